"""``kernels.api``: what a result says was cut (the impact log) or changed (restitution).

Counts are checked against the kernel's own impact count and against a plastic scene run
without clamping; the steady-rocking scene (DESIGN 10: 1.5 west at 4 Hz, 10 s) has 79 impacts.
"""
import numpy as np

from kernels import codes
from kernels.api import not_run, run_scene
from scenes import G, scene, sine

STEADY = {"horizontal": sine(0.5 * G, 4.0), "t_end": 10.0}


def test_impact_log_truncated_against_the_kernel_count():
    full = run_scene(scene(**STEADY))
    cut = run_scene(scene(**STEADY), max_log=10)
    assert full.impact_count == len(full.impact_times) == 79 and not full.impact_log_truncated
    assert "truncated" not in full.message
    assert cut.impact_count == full.impact_count and cut.impact_log_truncated
    assert cut.impact_times == full.impact_times[:10]
    assert cut.omega_after == full.omega_after[:10]
    assert cut.message.endswith("; impact log truncated at 10 of 79 impacts")


def test_every_impact_clamped_is_said_and_equals_plastic():
    """e_x = e_y = 1 gains energy at every rocking impact: each is clamped to the plastic law,
    so the scene is the plastic one (e_x = e_y = 0) bit for bit, and the message says so."""
    plastic = run_scene(scene(**STEADY))
    clamped = run_scene(scene(e_x=1.0, e_y=1.0, **STEADY))
    assert plastic.energy_clamps == 0
    assert clamped.status == "ok" and clamped.energy_clamps == clamped.impact_count == 79
    assert clamped.impact_times == plastic.impact_times
    assert clamped.omega_after == plastic.omega_after
    assert clamped.message == (codes.STATUS_MESSAGES[codes.OK] + "; all 79 impacts had their "
                               "restitution clamped to gain no energy (check e_x, e_y)")
    assert plastic.message == codes.STATUS_MESSAGES[codes.OK]


def test_default_restitution_is_never_clamped():
    r = run_scene(scene(mu=0.8, e_x=-0.8, e_y=0.2, **STEADY))
    assert r.impact_count > 0 and r.energy_clamps == 0


def test_rows_of_scenes_that_never_ran():
    rows = not_run(2)
    assert rows.shape == (2, codes.N_RES)
    assert (rows[:, codes.R_STATUS] == codes.INVALID_SCENE).all()
    counts = [codes.R_IMPACTS, codes.R_STEPS, codes.R_EVENTS, codes.R_ENERGY_CLAMPS,
              codes.R_DIRECTION]
    assert (rows[:, counts] == 0).all()
    rest = np.setdiff1d(np.arange(codes.N_RES), counts + [codes.R_STATUS])
    assert np.isnan(rows[:, rest]).all()
