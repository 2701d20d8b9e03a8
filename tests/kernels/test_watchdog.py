"""The per-cell wall-time budget: a watchdog thread stops a cell stuck in compiled code.

A fixed step of 1 us over 10^4 s would run for hours; with a budget of 0.5 s it ends with
status ``time_budget`` after about that long, and the cells before and after it in the same
chunk give the results they give without a budget.
"""
import time

import numpy as np
import pytest

from kernels import api, codes
from scenes import G, NO_JIT, scene, sine

pytestmark = pytest.mark.skipif(NO_JIT, reason="the budget needs compiled code off the GIL")

STEADY = scene(horizontal=sine(0.5 * G, 4.0), t_end=10.0)
ENDLESS = scene(horizontal=sine(0.5 * G, 4.0), t_end=1e4, method="fixed", dt=1e-6)


def _rows(*scenes):
    return np.array([api.scene_row(s, []) for s in scenes]), api.record_buffer([])


def test_a_cell_over_budget_is_stopped_and_the_next_runs():
    rows, rec = _rows(STEADY, ENDLESS, STEADY)
    alone = api.run_cells(rows[:1], rec)                     # also compiles
    t0 = time.perf_counter()
    results = api.run_cells(rows, rec, budget=0.5)
    wall = time.perf_counter() - t0
    assert 0.5 <= wall < 2.0
    assert results["status"].tolist() == [codes.OK, codes.TIME_BUDGET, codes.OK]
    assert 0.0 < results[1]["t_end"] < 1e4
    assert results[[0, 2]].tobytes() == np.concatenate([alone, alone]).tobytes()
    assert codes.TIME_BUDGET in codes.FAILED_STATUSES


def test_no_budget_changes_nothing():
    rows, rec = _rows(STEADY, scene(mu=0.8, e_x=-0.8, e_y=0.2, horizontal=sine(0.5 * G, 4.0)))
    assert api.run_cells(rows, rec, budget=60.0).tobytes() == api.run_cells(rows, rec).tobytes()


def test_bad_budget():
    rows, rec = _rows(STEADY)
    with pytest.raises(ValueError, match="`budget`"):
        api.run_cells(rows, rec, budget=-1.0)
