"""``sweep.io.files``: tables written with the digits that mean something."""
import csv
import math

import numpy as np
import pytest

from sweep.io.files import csv_value, write_csv


@pytest.mark.parametrize("value, text", [
    (0.1 + 0.6, "0.7"),              # 0.7000000000000001: float noise dropped
    (70 * 0.01, "0.7"),              # "70 cm" in metres
    (np.float64(0.1) + np.float64(0.2), "0.3"),
    (1 / 3, "0.333333"),             # a computed ratio: 6 significant digits
    (0.05, "0.05"), (35.25, "35.25"), (9.80665 * 0.4, "3.92266"), (1e-7 / 3, "3.33333e-08"),
    (None, ""), (True, "True"), (3, "3"), ("stone 1", "stone 1"), (math.inf, "inf"),
])
def test_csv_values(value, text):
    assert csv_value(value) == text


def test_write_csv_rows_as_written(tmp_path):
    path = write_csv(tmp_path / "t.csv", [{"body": "stone", "B_m": 0.1 + 0.6, "mu": None},
                                          {"body": "lantern", "B_m": 0.4, "slides": True}])
    assert path.read_text().splitlines() == ["body,B_m,mu,slides", "stone,0.7,,",
                                             "lantern,0.4,,True"]
    with open(path, newline="") as f:
        assert [row["B_m"] for row in csv.DictReader(f)] == ["0.7", "0.4"]
