"""``sweep.simulate``: one scene from Python, from a dict in file units or a file path."""
import math

import pytest

import sweep

# PHYSICS A4: B x H = 10 x 30 cm released from theta0 = 0.5 alpha, Housner impacts
A4_FIRST_IMPACTS = (0.19368, 0.47162, 0.68867)

FREE_ROCKING = {"body": {"B": "10 cm", "H": "30 cm"},
                "contact": {"mu": 10, "e_x": 0.0, "e_y": 0.0},
                "initial": {"theta": "0.5 alpha"},
                "solver": {"t_end": 0.8}}


def test_simulate_twice_from_a_dict():
    """The package-level function stays callable after its first use, and a dict with
    units gives the A4 impact times."""
    first = sweep.simulate(FREE_ROCKING)
    second = sweep.simulate(FREE_ROCKING)
    assert first.impact_times == second.impact_times
    assert first.impact_times[:3] == pytest.approx(A4_FIRST_IMPACTS, abs=1e-5)
    assert first.status == "ok" and not first.overturned


def test_simulate_history_is_a_dataset():
    """history=True gives an xarray Dataset whose theta starts at 0.5 alpha."""
    r = sweep.simulate(FREE_ROCKING, history=True)
    theta0 = float(r.history["theta"].isel(time=0))
    assert theta0 == pytest.approx(0.5 * math.atan(1 / 3), rel=1e-12)
