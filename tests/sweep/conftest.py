"""Fixtures of the package's tests; makes ``study_helpers`` (next to this file) and the test
modules of its subfolders (one per subpackage, some importing from another) importable."""
import sys
from pathlib import Path

import pytest

_HERE = Path(__file__).resolve().parent
for _folder in (_HERE, *sorted({p.parent for p in _HERE.glob("*/test_*.py")})):
    if str(_folder) not in sys.path:
        sys.path.insert(0, str(_folder))

from study_helpers import make_study  # noqa: E402


@pytest.fixture
def small_study():
    """4 x 3 cells of short sines: amplitude in West's units x frequency."""
    return make_study({"amplitude": {"values": [0.5, 1.5, 2.5, 3.0], "unit": "west"},
                       "frequency": [1.5, 3.0, 8.0]})


@pytest.fixture(autouse=True)
def _close_figures():
    """Figures a test draws are closed after it (pyplot keeps them otherwise)."""
    yield
    if "matplotlib.pyplot" in sys.modules:
        sys.modules["matplotlib.pyplot"].close("all")


@pytest.fixture(scope="module")
def study():
    """4 x 3 x 2 cells (amplitude, frequency, b/h) for the part-file and merge tests; a module
    that needs another ``study`` defines its own."""
    from sweep.runner.cell_checks import load_study
    return load_study(make_study({
        "amplitude": {"values": [0.5, 1.5, 2.5, 3.0], "unit": "west"},
        "frequency": [1.5, 3.0, 8.0], "b_over_h": [0.333, 0.2]}))


@pytest.fixture(scope="module")
def whole(study):
    """All cells of ``study`` in one chunk."""
    import numpy as np

    from sweep.runner.cells import run_chunk
    return run_chunk(study, np.arange(study.n_cells))
