"""The base's slip (``max_slip``) against G's travel (``max_travel``): rocking about a corner
never moves the base, sliding moves it by Newmark's closed form, and a corner that slips as the
body falls past its slenderness angle alpha does not count (``kernels.extremes``)."""
import math

import numpy as np
import pytest

from kernels import codes
from kernels.api import run_scene
from scenes import G, const, pulse, scene

SLENDER = (0.2, 1.0)  # B, H [m]: alpha = 0.197 rad


def _allowance(r, b, h):
    """The most that rotation by up to max |theta| about a corner moves G."""
    theta = min(r.max_abs_theta, 0.5 * math.pi)
    return b * (1.0 - math.cos(theta)) + h * math.sin(theta)


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_a_rocking_overturn_does_not_slip(sign):
    """A slender body knocked over by a 3 west pulse with mu = 2: while |theta| <= alpha it only
    rocks (every history sample is in rotation), so its base never slipped, though G travels
    further than rotation explains as it falls (the floor moves under it)."""
    B, H = SLENDER
    c = const(B, H)
    r = run_scene(scene(B, H, mu=2.0, horizontal=pulse(sign * 3.0 * G * B / H, 0.4),
                        t_end=5.0, dt_out=1e-3), history=True)
    assert r.status == "overturned"
    hist = r.history
    standing = np.abs(hist["theta"]) <= c.alpha
    assert np.all(hist["mode"][standing & (hist["theta"] != 0)] == codes.ROTATION)
    assert r.max_slip < 1e-12
    assert r.max_travel - _allowance(r, c.b, c.h) > 0.01   # G's travel alone would say "slid"
    # the floor pushes right (sign +1): the body falls left, theta > 0, G ends at x < 0
    assert r.overturn_direction == sign and np.sign(hist["x"][-1]) == -sign


@pytest.mark.parametrize("u0, mu", [(1.0, 0.3), (0.5, 0.2)])
def test_a_slide_moves_the_base_by_its_closed_form(u0, mu):
    """A slender body (b/h = 0.5 > mu, so it does not tip) pushed at u0 on a still floor slides
    u0^2 / (2 mu g) and stops upright: its base and G move alike."""
    r = run_scene(scene(0.3, 0.6, mu=mu, initial={"x_dot": u0}, t_end=1.0))
    assert r.status == "ok" and r.max_abs_theta == 0.0
    closed = u0 ** 2 / (2.0 * mu * G)
    assert r.max_slip == pytest.approx(closed, rel=1e-9)
    assert r.max_travel == pytest.approx(closed, rel=1e-9)


def test_free_rocking_leaves_the_base_in_place():
    """Rocking from theta0 = alpha/2 with mu = 10 and Housner's impact: the pivot changes from
    corner to corner, the footprint stays; G, which starts tilted, travels at least
    b (1 - cos theta0) + h sin theta0 on its way to theta = 0."""
    B, H = 0.1, 0.3
    c = const(B, H)
    theta0 = 0.5 * c.alpha
    r = run_scene(scene(B, H, initial={"theta": theta0}, t_end=2.0))
    assert r.impact_count > 3
    assert r.max_slip < 1e-12
    assert r.max_travel >= c.b * (1 - math.cos(theta0)) + c.h * math.sin(theta0) > 0.02
