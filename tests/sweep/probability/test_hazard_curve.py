"""Hazard curve files: OpenQuake CSV, USGS JSON and two columns, read into annual rates in SI
units, checked against values computed here by hand (Poisson: λ = −ln(1 − P)/T)."""
import json
import math

import numpy as np
import pytest

from sweep.io.imt import normalize_im
from sweep.probability import hazard_curve as hc
from sweep.probability import hazard_files as hf

G = 9.80665


def test_openquake_csv_levels_in_g_and_poe_to_rate(tmp_path):
    path = tmp_path / "hazard_curve-mean-PGA_0.csv"
    path.write_text("#,,,,\"generated_by='OpenQuake engine 3.16.0', start_date='2024-01-01', "
                    "checksum=1, kind='mean', investigation_time=50.0, imt='PGA'\"\n"
                    "lon,lat,depth,poe-0.05,poe-0.1,poe-0.2,poe-0.4,poe-0.8\n"
                    "10.0,45.0,0.0,1.0,0.5,0.1,0.01,0.0\n")
    curve = hf.read_openquake_csv(path)
    assert curve.im == "pga"
    np.testing.assert_allclose(curve.levels, [0.1 * G, 0.2 * G, 0.4 * G])  # P = 1, P = 0 dropped
    np.testing.assert_allclose(curve.rates, [math.log(2) / 50, -math.log(0.9) / 50,
                                             -math.log(0.99) / 50], rtol=1e-14)


def test_openquake_round_trip(tmp_path):
    levels = np.geomspace(0.5, 20.0, 12)
    curve = hc.HazardCurve("sa(0.3)", levels, 1e-2 * (levels / 0.5) ** -2.2)
    back = hf.read_openquake_csv(hf.write_openquake_csv(tmp_path / "c.csv", curve, 50.0))
    assert back.im == "sa(0.3)"
    np.testing.assert_allclose(back.levels, curve.levels, rtol=1e-7)
    np.testing.assert_allclose(back.rates, curve.rates, rtol=1e-7)


def test_usgs_json_total_component_pgv_in_cm_s(tmp_path):
    path = tmp_path / "usgs.json"
    path.write_text(json.dumps({"status": "success", "response": [
        {"metadata": {"imt": {"value": "PGA"}, "xvalues": [0.1, 0.2]},
         "data": [{"component": "Total", "yvalues": [1e-2, 1e-3]}]},
        {"metadata": {"imt": {"value": "PGV"}, "xvalues": [5.0, 10.0, 20.0]},
         "data": [{"component": "Grid", "yvalues": [1.0, 1.0, 1.0]},
                  {"component": "Total", "yvalues": [2e-2, 4e-3, 5e-4]}]}]}))
    curve = hf.read_usgs_json(path, "pgv")
    np.testing.assert_allclose(curve.levels, [0.05, 0.1, 0.2])
    np.testing.assert_allclose(curve.rates, [2e-2, 4e-3, 5e-4])
    assert hf.read_usgs_json(path).im == "pga"
    assert normalize_im("SA0P2") == "sa(0.2)"


def test_two_columns_poe_and_rates_agree(tmp_path):
    rates = np.array([1e-2, 2e-3, 1e-4])
    (tmp_path / "r.txt").write_text("im,annual_rate\n50,1e-2\n100,2e-3\n300,1e-4\n")
    poe = hc.poe_from_rate(rates, 50.0)
    (tmp_path / "p.txt").write_text("".join(f"{x} {float(p)!r}\n"
                                            for x, p in zip([50, 100, 300], poe)))
    a = hf.read_columns(tmp_path / "r.txt", "pga", "gal")
    b = hf.read_columns(tmp_path / "p.txt", "pga", "cm/s^2", "poe", 50.0)
    np.testing.assert_allclose(a.levels, [0.5, 1.0, 3.0])
    np.testing.assert_allclose(b.rates, a.rates, rtol=1e-12)


@pytest.mark.parametrize("rates, message", [
    ([1e-3, 2e-3, 1e-4], "never increases"),
    ([1e-3, -1e-4, 1e-5], "must be positive"),
])
def test_a_curve_that_is_not_one_is_refused(rates, message):
    with pytest.raises(hc.HazardFileError, match=message):
        hc.HazardCurve("pga", [1.0, 2.0, 3.0], rates)


def test_log_log_interpolation_is_exact_on_a_power_law():
    levels = np.array([0.5, 2.0, 8.0])
    curve = hc.HazardCurve("pga", levels, 3e-3 * levels ** -1.7)
    assert curve.rate(1.0) == pytest.approx(3e-3, rel=1e-12)
    assert curve.level_at_rate(3e-3) == pytest.approx(1.0, rel=1e-12)
    assert np.isnan(curve.rate(10.0))
