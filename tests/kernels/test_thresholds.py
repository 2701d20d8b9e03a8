"""Leaving rest (docs/physics.md 1.3 and anchor A2).

Rocking iff |a_x| > (b/h) g_e, sliding iff |a_x| > mu_s g_e, lift-off iff a_y < -g, and the
slide-rock window of Shenton's mu_req under a step of a_x.  Each case is run at 0.99x and
1.01x of its threshold.
"""
import math

import pytest

from kernels.api import run_scene
from scenes import G, const, pulse, scene, sine

T_END = 3.0


def _at_rest_throughout(r, t_end=T_END):
    return (r.status == "ok" and r.max_abs_theta == 0.0 and r.max_slip == 0.0
            and r.max_lift == 0.0 and r.mode_time["rest"] == t_end and not r.impact_times)


@pytest.mark.parametrize("factor", [0.99, 1.01])
def test_west_threshold(factor):
    """2 Hz sine at 0.99 (B/H) g: rest; at 1.01 (B/H) g: rocks (mu = 0.8 > b/h)."""
    r = run_scene(scene(mu=0.8, horizontal=sine(factor * G / 3, 2.0), t_end=T_END))
    if factor < 1:
        assert _at_rest_throughout(r)
    else:
        assert r.status == "ok" and r.mode_time["rotation"] > 0 and r.max_abs_theta > 0
        assert r.mode_time["slide"] == 0.0


@pytest.mark.parametrize("factor", [0.99, 1.01])
def test_sliding_threshold(factor):
    """B = H = 0.3 (b/h = 1 > mu = 0.3): 2 Hz sine at 0.99 / 1.01 mu g."""
    r = run_scene(scene(0.3, 0.3, mu=0.3, horizontal=sine(factor * 0.3 * G, 2.0), t_end=T_END))
    if factor < 1:
        assert _at_rest_throughout(r)
    else:
        assert r.mode_time["slide"] > 0 and r.max_slip > 0
        assert r.max_abs_theta == 0.0 and r.mode_time["rotation"] == 0.0


@pytest.mark.parametrize("a_y", [0.3 * G, -0.3 * G])
@pytest.mark.parametrize("factor", [0.99, 1.01])
def test_rocking_threshold_with_vertical(a_y, factor):
    """Constant a_y (a rectangular pulse longer than the run): rocking iff
    |a_x| > (b/h)(g + a_y)."""
    amp = factor * (G + a_y) / 3
    r = run_scene(scene(mu=0.8, horizontal=sine(amp, 2.0), vertical=pulse(a_y, 100.0),
                        t_end=T_END))
    if factor < 1:
        assert _at_rest_throughout(r)
    else:
        assert r.mode_time["rotation"] > 0 and r.max_abs_theta > 0
    if a_y < 0 and factor > 1:       # it rocks below West's a_y = 0 threshold (b/h) g
        assert amp < G / 3


@pytest.mark.parametrize("factor", [0.99, 1.01])
def test_sliding_threshold_with_vertical(factor):
    """Sliding iff |a_x| > mu_s (g + a_y), here with a_y = -0.3 g."""
    g_e = 0.7 * G
    r = run_scene(scene(0.3, 0.3, mu=0.3, horizontal=sine(factor * 0.3 * g_e, 2.0),
                        vertical=pulse(-0.3 * G, 100.0), t_end=T_END))
    if factor < 1:
        assert _at_rest_throughout(r)
    else:
        assert r.mode_time["slide"] > 0 and r.max_abs_theta == 0.0


@pytest.mark.parametrize("factor", [0.99, 1.01])
def test_lift_off_threshold(factor):
    """a_y = -factor g for 0.2 s: lift-off iff a_y < -g; the flat hop then lands at the
    ballistic time (relative acceleration (factor - 1) g up for 0.2 s, then g down)."""
    t_d = 0.2
    r = run_scene(scene(mu=0.8, vertical=pulse(-factor * G, t_d), t_end=1.0))
    if factor < 1:
        assert _at_rest_throughout(r, 1.0)
        return
    a = (factor - 1) * G
    y1, v1 = 0.5 * a * t_d ** 2, a * t_d
    t_land = t_d + (v1 + math.sqrt(v1 ** 2 + 2 * G * y1)) / G
    assert r.status == "ok" and r.mode_time["translation_jump"] > 0
    assert r.impact_times[0] == pytest.approx(t_land, abs=1e-9)
    assert r.t_rest == pytest.approx(t_land, abs=1e-9)
    assert r.max_abs_theta == 0.0 and r.omega_after[0] == 0.0


def test_hop_apex_height():
    """max_lift is 'the largest gap under the lowest point': the apex of the hop above,
    y1 + v1^2/(2 g), to 1e-9 relative."""
    t_d = 0.2
    r = run_scene(scene(mu=0.8, vertical=pulse(-1.01 * G, t_d), t_end=1.0))
    a = 0.01 * G
    y1, v1 = 0.5 * a * t_d ** 2, a * t_d
    assert r.max_lift == pytest.approx(y1 + v1 ** 2 / (2 * G), rel=1e-9)


def _mu_required(A, c):
    """Friction a pure rocking onset needs under a step a_x = A g, from Newton-Euler at
    theta = omega = 0 about the left corner (rho = (b, h)): theta'' (i^2 + r^2) = a_x h - g b,
    F = a_x - theta'' h, N = g + theta'' b (per unit mass)."""
    thdd = (A * G * c.h - G * c.b) / (c.i2 + c.r ** 2)
    return (A * G - thdd * c.h) / (G + thdd * c.b)


# A2 (b/h = 1/3): A -> mu_req
SHENTON = [(0.40, 0.349754), (0.5, 0.373494), (0.75, 0.428571), (1.0, 0.478261),
           (2.0, 0.636364)]


def test_shenton_table():
    """The A2 table (and its A -> infinity limit (1 + 4 beta^2)/(3 beta) = 1.444444) from
    Newton-Euler, and mu_req(beta) = beta."""
    c = const(0.1, 0.3)
    for A, mu in SHENTON:
        assert _mu_required(A, c) == pytest.approx(mu, abs=5e-7)
    assert _mu_required(1e9, c) == pytest.approx(1.444444, abs=1e-6)
    assert _mu_required(c.beta, c) == pytest.approx(c.beta, rel=1e-13)


@pytest.mark.parametrize("A, mu_req", SHENTON[1:])
@pytest.mark.parametrize("factor", [0.99, 1.01])
def test_shenton_onset(A, mu_req, factor):
    """A step a_x = A g from t = 0: mu_s = mu_edge_s = factor mu_req (kinetic equal, > b/h):
    slide rotation at onset below mu_req, rotation above (first 5 ms)."""
    mu = factor * mu_req
    assert mu > 1 / 3
    r = run_scene(scene(mu=mu, horizontal=pulse(A * G, 1.0), t_end=0.005))
    assert r.status == "ok" and r.max_abs_theta > 0
    if factor < 1:
        assert r.mode_time["slide_rotation"] == pytest.approx(0.005, abs=1e-12)
    else:
        assert r.mode_time["rotation"] == pytest.approx(0.005, abs=1e-12)
