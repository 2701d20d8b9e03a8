"""Fixtures of the study-runner tests; makes ``study_helpers`` (next to this file) importable."""
import sys
from pathlib import Path

import pytest

_HERE = str(Path(__file__).resolve().parent)
if _HERE not in sys.path:
    sys.path.insert(0, _HERE)

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
