"""The kernel against ``naive.housner_rocking`` (scipy DOP853, rtol 1e-11), event by event.

Rocking-only scenes (mu = 10, e_x = e_y = 0, so no slip, no jump, Housner's impact): every
impact time and post-impact omega is compared, with an err_msg naming the impact index and
time (nbkode's lockstep pattern).
"""
import math

import numpy as np
import pytest

import naive
from kernels.api import run_scene
from scenes import G, const, scene, sine

STEADY_A, STEADY_F = 0.5 * G, 4.0          # DESIGN 10: 1.5 west at 4 Hz, 10 s, 79 impacts


def _compare(r, ref, atol_t, rtol_w=1e-7):
    t, t_ref = np.array(r.impact_times), np.array(ref["impact_times"])
    assert t.size == t_ref.size, (t.size, t_ref.size)
    w, w_ref = np.array(r.omega_after), np.array(ref["omega_after"])
    for k in range(t.size):
        np.testing.assert_allclose(t[k], t_ref[k], rtol=0, atol=atol_t,
                                   err_msg=f"impact {k} at t = {t_ref[k]:.9f} s")
        np.testing.assert_allclose(w[k], w_ref[k], rtol=rtol_w, atol=1e-12,
                                   err_msg=f"omega after impact {k} at t = {t_ref[k]:.9f} s")


@pytest.fixture(scope="module")
def steady_reference():
    return naive.housner_rocking(
        0.1, 0.3, a_x=lambda t: STEADY_A * math.sin(2 * math.pi * STEADY_F * t), t_end=10.0)


def test_steady_rocking(steady_reference):
    """B = 0.1, H = 0.3, a_x = 0.5 g sin(2 pi 4 t), 10 s: 79 impacts within 1e-7 s."""
    assert len(steady_reference["impact_times"]) == 79
    r = run_scene(scene(horizontal=sine(STEADY_A, STEADY_F), t_end=10.0))
    assert r.status == "ok" and not r.overturned
    assert r.mode_time["slide_rotation"] == 0.0 and r.mode_time["rotation_jump"] == 0.0
    _compare(r, steady_reference, atol_t=1e-7)
    # the rest exit: |a_x| = (b/h) g at t = asin(2/3)/(8 pi)
    assert r.mode_time["rest"] == pytest.approx(math.asin(2 / 3) / (8 * math.pi), abs=1e-12)


def test_steady_rocking_tight(steady_reference):
    """With rtol 1e-12 the kernel meets the reference to its own accuracy (1e-10 s)."""
    r = run_scene(scene(horizontal=sine(STEADY_A, STEADY_F), t_end=10.0, rtol=1e-12,
                        atol=1e-14))
    _compare(r, steady_reference, atol_t=1e-10, rtol_w=1e-9)


def test_free_rocking():
    """Free rocking from 0.5 alpha: the first 60 impacts (to t = 1.7834 s) within 1e-9 s."""
    c = const(0.1, 0.3)
    ref = naive.housner_rocking(0.1, 0.3, theta0=0.5 * c.alpha, t_end=1.7834)
    r = run_scene(scene(initial={"theta": 0.5 * c.alpha}, t_end=1.7834, rtol=1e-12,
                        atol=1e-14))
    _compare(r, ref, atol_t=1e-9, rtol_w=1e-9)


def test_rocking_with_vertical_motion():
    """a_x = 0.5 g sin(2 pi 4 t) with a_y = 0.3 g sin(2 pi 3 t): g_e enters theta'' and the
    rest exit (PHYSICS 1.2 (3), 1.3)."""
    a_x = lambda t: STEADY_A * math.sin(2 * math.pi * 4.0 * t)
    a_y = lambda t: 0.3 * G * math.sin(2 * math.pi * 3.0 * t)
    ref = naive.housner_rocking(0.1, 0.3, a_x=a_x, a_y=a_y, t_end=5.0)
    r = run_scene(scene(horizontal=sine(STEADY_A, 4.0), vertical=sine(0.3 * G, 3.0),
                        t_end=5.0, rtol=1e-10, atol=1e-12))
    assert r.mode_time["slide_rotation"] == 0.0 and r.mode_time["rotation_jump"] == 0.0
    _compare(r, ref, atol_t=1e-8)
