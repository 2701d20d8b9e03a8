"""Rocking under a rectangular acceleration pulse (docs/physics.md anchor A8).

Linearized escape condition for a block released from rest by a_x = a for t1:
(a - g alpha) e^{p t1} >= a, i.e. a_min/(g alpha) = 1/(1 - e^{-p t1}).  For a slender block
(B = 0.05, H = 1.0, alpha = 0.05) the nonlinear kernel must agree within 1 %; found by
bisection on the amplitude, overturning declared at |theta| >= pi/2 within 20 s.
"""
import math

import pytest

from kernels.api import run_scene
from scenes import G, const, pulse, scene

B, H = 0.05, 1.0
# A8: p t1 -> a_min/(g alpha)
ESCAPE = [(0.341, 3.4608), (0.682, 2.0226), (1.364, 1.3434), (3.410, 1.0342)]


def _overturns(ratio, t1):
    c = const(B, H)
    r = run_scene(scene(B, H, horizontal=pulse(ratio * G * c.alpha, t1), t_end=20.0))
    assert r.status in ("ok", "overturned")
    return r.overturned


@pytest.mark.parametrize("pt1, anchor", ESCAPE)
def test_escape_threshold(pt1, anchor):
    assert 1 / (1 - math.exp(-pt1)) == pytest.approx(anchor, abs=5e-4)
    t1 = pt1 / const(B, H).p
    lo, hi = 0.97 * anchor, 1.03 * anchor
    assert not _overturns(lo, t1) and _overturns(hi, t1)
    for _ in range(9):                       # bracket 6 % wide -> 1.2e-4 relative
        mid = 0.5 * (lo + hi)
        if _overturns(mid, t1):
            hi = mid
        else:
            lo = mid
    assert 0.5 * (lo + hi) == pytest.approx(anchor, rel=0.01)
