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

STEADY_A, STEADY_F = 0.5 * G, 4.0          # docs/design.md 10: 1.5 west at 4 Hz, 10 s, 79 impacts


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
    rest exit (docs/physics.md 1.2 (3), 1.3)."""
    a_x = lambda t: STEADY_A * math.sin(2 * math.pi * 4.0 * t)
    a_y = lambda t: 0.3 * G * math.sin(2 * math.pi * 3.0 * t)
    ref = naive.housner_rocking(0.1, 0.3, a_x=a_x, a_y=a_y, t_end=5.0)
    r = run_scene(scene(horizontal=sine(STEADY_A, 4.0), vertical=sine(0.3 * G, 3.0),
                        t_end=5.0, rtol=1e-10, atol=1e-12))
    assert r.mode_time["slide_rotation"] == 0.0 and r.mode_time["rotation_jump"] == 0.0
    _compare(r, ref, atol_t=1e-8)


def _random_rocking(rng):
    """A random slender block (b/h 0.1-0.6) under 1.1-3 times its West acceleration at
    1-6 Hz, 8 s: (B, H, amplitude, frequency)."""
    H = rng.uniform(0.2, 2.0)
    B = H * rng.uniform(0.1, 0.6)
    return B, H, rng.uniform(1.1, 3.0) * B / H * G, rng.uniform(1.0, 6.0)


def _check_random(n_scenes, seed):
    rng = np.random.default_rng(seed)
    compared = 0
    for n in range(n_scenes):
        B, H, A, f = _random_rocking(rng)
        ref = naive.housner_rocking(B, H, a_x=lambda t: A * math.sin(2 * math.pi * f * t),
                                    t_end=8.0)
        # tight tolerances: some of these scenes amplify an early error 1e4-fold by t = 8 s
        r = run_scene(scene(B, H, horizontal=sine(A, f), t_end=8.0, rtol=1e-12, atol=1e-14))
        assert r.overturned == ref["overturned"], n
        if r.mode_time["slide_rotation"] or r.mode_time["rotation_jump"]:
            continue         # the pivot slipped or lifted (near overturning): not Housner's model
        _compare(r, ref, atol_t=1e-7, rtol_w=1e-6)
        if r.overturned:
            assert r.t_overturn == pytest.approx(ref["t_overturn"], abs=1e-7)
        compared += 1
    assert compared >= n_scenes // 2


def test_random_rocking_scenes():
    """12 random harmonic rocking scenes, event by event within 1e-7 s."""
    _check_random(12, 8)


@pytest.mark.slow
def test_random_rocking_scenes_many():
    """200 random harmonic rocking scenes, event by event within 1e-7 s."""
    _check_random(200, 9)
