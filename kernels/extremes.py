"""The extremes a scene reports: max |theta|, slip, travel and lift, inside steps too.

Max |theta|, the base's slip along the floor, G's travel |x - x0| and max lift (the gap under
the lowest corner in flight), observed at the ends of steps and at the turning points inside
them, where a rate (omega, u, the lowest corner's V_y) changes sign.

The base's slip is that of its footprint (``footprint``): where the middle of the base would
be, were the body set down flat about the corner it stands on.  Rocking about a corner leaves
the footprint in place, so a body that rocks, even to overturning, without its corner slipping
has no slip; sliding moves it, and so does a jump that lands elsewhere.  It is observed while
the body touches the floor and stands within its slenderness angle, |theta| <= alpha, so a
corner that slips as the body falls past alpha does not count.  In slide and slide rotation
the contact slips one way until an event ends the mode, so the footprint moves monotonically
within a step and the step ends are its turning points.
"""
import math

from ._jit import jit
from .codes import IOMEGA, ITHETA, IU, IX, IY, ROTATION_JUMP, TRANSLATION_JUMP
from .integrate import dense
from .motion import corner, corner_velocity, half_base, to_full
from .roots import regula_falsi
from .tolerances import TURN_XTOL

# entries of the scene's ``extremes``: the first three have rates (``_rate``); BASE_REF is
# the footprint first observed (NaN until the body touches the floor)
MAX_THETA, MAX_TRAVEL, MAX_LIFT, MAX_SLIP, BASE_REF = range(5)
N_EXTREMES = 5


@jit(inline="always")
def footprint(q, body):
    """(x_f, standing): the footprint x_f = x_c - s b_s of the base (where G would be, set
    down flat), from the contact corner s = -sgn(theta) at x_c = x + r_cx, i.e.
    x + sgn(theta) (b_s (1 - cos theta) + h sin |theta|); standing is |theta| <= alpha_s =
    atan(b_s/h)."""
    theta = q[ITHETA]
    b = half_base(-theta, body)
    h = body.h
    c = math.cos(theta)
    sn = abs(math.sin(theta))
    x_f = q[IX] + math.copysign(b * (1.0 - c) + h * sn, theta)
    return x_f, h * sn <= b * c


@jit
def observe(mode, q, body, extremes):
    """Update the extremes with the full state q."""
    extremes[MAX_THETA] = max(extremes[MAX_THETA], abs(q[ITHETA]))
    extremes[MAX_TRAVEL] = max(extremes[MAX_TRAVEL], abs(q[IX]))
    if mode == TRANSLATION_JUMP or mode == ROTATION_JUMP:
        gap = q[IY] + min(corner(-1.0, q[ITHETA], body)[1], corner(1.0, q[ITHETA], body)[1])
        extremes[MAX_LIFT] = max(extremes[MAX_LIFT], gap)
        return
    x_f, standing = footprint(q, body)
    if standing:
        if math.isnan(extremes[BASE_REF]):
            extremes[BASE_REF] = x_f
        extremes[MAX_SLIP] = max(extremes[MAX_SLIP], abs(x_f - extremes[BASE_REF]))


@jit
def _rate(j, q, body):
    """Rate of extreme j: theta (omega), x (u), lift (V_y of the lowest corner)."""
    if j == MAX_THETA:
        return q[IOMEGA]
    if j == MAX_TRAVEL:
        return q[IU]
    s = -1.0 if corner(-1.0, q[ITHETA], body)[1] < corner(1.0, q[ITHETA], body)[1] else 1.0
    return corner_velocity(q, s, body)[1]


@jit(inline="always")
def _rate_at(x, args):
    """Rate of extreme j at the fraction x of the step (args = (j, step, ctx, body, z, q):
    scratch for the compact and the full state)."""
    j, step, ctx, body, z, q = args
    dense(step, x, z)
    to_full(step.mode, z, ctx, body, q)
    return _rate(j, q, body)


_turning_point = regula_falsi(_rate_at)


@jit(inline="always")
def observe_turns(step, q0, q1, ctx, body, scratch, extremes):
    """Observe the extremes inside a step from q0 to q1: where a rate changes sign, its root
    on the dense output is one."""
    mode = step.mode
    z, q = scratch.z, scratch.q
    for j in range(3 if mode == TRANSLATION_JUMP or mode == ROTATION_JUMP else 2):
        fa = _rate(j, q0, body)
        fb = _rate(j, q1, body)
        if fa * fb >= 0.0:
            continue
        x = _turning_point((j, step, ctx, body, z, q), 0.0, 1.0, fa, fb, TURN_XTOL)
        dense(step, x, z)
        to_full(mode, z, ctx, body, q)
        observe(mode, q, body, extremes)
