"""The extremes a scene reports: max |theta|, max slip |x - x0| and max lift (the gap under
the lowest corner in flight), observed at the ends of steps and at the turning points
inside them, where a rate (omega, u, the lowest corner's V_y) changes sign.
"""
from ._jit import jit
from .codes import IOMEGA, ITHETA, IU, IX, IY, ROTATION_JUMP, TRANSLATION_JUMP
from .integrate import dense
from .motion import corner, corner_velocity, to_full
from .roots import regula_falsi
from .tolerances import TURN_XTOL

MAX_THETA, MAX_SLIP, MAX_LIFT = range(3)     # entries of the scene's ``extremes``
N_EXTREMES = 3


@jit
def observe(mode, q, body, extremes):
    """Update the extremes with the full state q."""
    b, h = body.b, body.h
    extremes[MAX_THETA] = max(extremes[MAX_THETA], abs(q[ITHETA]))
    extremes[MAX_SLIP] = max(extremes[MAX_SLIP], abs(q[IX]))
    if mode == TRANSLATION_JUMP or mode == ROTATION_JUMP:
        gap = q[IY] + min(corner(-1.0, q[ITHETA], b, h)[1], corner(1.0, q[ITHETA], b, h)[1])
        extremes[MAX_LIFT] = max(extremes[MAX_LIFT], gap)


@jit
def _rate(j, q, body):
    """Rate of extreme j: theta (omega), x (u), lift (V_y of the lowest corner)."""
    if j == MAX_THETA:
        return q[IOMEGA]
    if j == MAX_SLIP:
        return q[IU]
    b, h = body.b, body.h
    s = -1.0 if corner(-1.0, q[ITHETA], b, h)[1] < corner(1.0, q[ITHETA], b, h)[1] else 1.0
    return corner_velocity(q, s, b, h)[1]


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
