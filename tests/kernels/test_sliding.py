"""Flat sliding, Newmark's rigid-plastic block (docs/physics.md 1.2 (2) and anchor A6).

B = H = 0.3 m (b/h = 1 above every mu used, so the block slides without rocking); max_slip
is how far the base moved along the floor, here G's travel |x - x0| as well.
"""
import math

import pytest

import naive
from kernels.api import run_scene
from scenes import G, pulse, scene, sine

# A6: rectangular pulse A [g], mu, t_d [s] -> slip [m]
PULSES = [(0.5, 0.2, 0.5, 0.919373), (1.0, 0.3, 0.2, 0.457644)]
# A6: a_x = A sin(4 pi t) for 2 s, mu = 0.2: A [mu g] -> max slip [m]
HARMONIC = [(1.05, 1.3437e-4), (1.5, 1.0029e-2), (3.0, 1.0592e-1)]


@pytest.mark.parametrize("A, mu, t_d, anchor", PULSES)
def test_newmark_pulse(A, mu, t_d, anchor):
    """slip = A t_d^2 (A - mu g)/(2 mu g); the block stops at t_d A/(mu g)."""
    closed = A * G * t_d ** 2 * (A - mu) / (2 * mu)
    assert closed == pytest.approx(anchor, abs=5e-7)
    r = run_scene(scene(0.3, 0.3, mu=mu, horizontal=pulse(A * G, t_d), t_end=3.0))
    assert r.status == "ok"
    assert r.max_slip == pytest.approx(closed, rel=1e-9)
    assert r.max_abs_theta == 0.0 and r.mode_time["rotation"] == 0.0
    assert r.t_rest == pytest.approx(t_d * A / mu, rel=1e-9)
    assert r.mode_time["slide"] == pytest.approx(t_d * A / mu, rel=1e-9)


@pytest.mark.parametrize("A, anchor", HARMONIC)
def test_harmonic_sliding(A, anchor):
    """Stick-slip under A sin(4 pi t): max slip to 1e-3 (anchor) and 1e-6 (naive solve_ivp)."""
    mu = 0.2
    amp = A * mu * G
    r = run_scene(scene(0.3, 0.3, mu=mu, horizontal=sine(amp, 2.0), t_end=2.0))
    assert r.status == "ok" and r.max_abs_theta == 0.0
    assert r.max_slip == pytest.approx(anchor, rel=1e-3)
    ref = naive.rigid_plastic_slide(lambda t: amp * math.sin(4 * math.pi * t), mu, 2.0)[2]
    assert r.max_slip == pytest.approx(ref, rel=1e-6)


def test_slide_under_constant_acceleration():
    """A constant a_x = 0.5 g > mu g on a mu = 0.2 block from rest: x = -(a_x - mu g) t^2/2."""
    r = run_scene(scene(0.3, 0.3, mu=0.2, horizontal=pulse(0.5 * G, 10.0), t_end=1.0,
                        dt_out=0.1), history=True)
    h = r.history
    assert (h["mode"] == 1).all()
    for t, x in zip(h["t"], h["x"]):
        assert x == pytest.approx(-0.3 * G * t * t / 2, rel=1e-12, abs=1e-15)
