"""Where the first event of a taken step lies.

This kernel's counterpart of scipy's ``find_active_events`` and ``handle_events``.

Each event function is tested at the step's end or, when the step holds a turning point
(omega or a vertical velocity changes sign), at a third, two thirds and the end: an event
function that dips below zero and back inside one step is then still seen if the dip spans
a third of it; without a turning point theta and the gaps are monotone in the step.  A sign
change is located on the dense output by Brent's method.  A function that entered the step
at zero (a corner that has just left the floor) is located as the root of g(x)/x, which
has the same roots and is positive from the start where g rises; one that has not risen
at x = RISE_X of the sample (it left with zero rate) is first searched for a positive peak.
``polish`` puts the located event on its root with the step's own accuracy.
"""
from ._jit import jit
from .codes import ROTATION_JUMP, SLIDE, TRANSLATION_JUMP
from .events import angle_event, angle_value, event_value, event_values, n_events
from .integrate import dense
from .motion import to_full
from .roots import brent, peak_above_zero
from .tolerances import EVENT_XTOL, PEAK_XTOL, POLISH_DELTA, POLISH_MAX, RISE_X

SAMPLES = (1.0 / 3.0, 2.0 / 3.0, 1.0)     # step fractions tested when it holds a turn
END_ONLY = (1.0, 1.0, 1.0)                # ... and when it does not


@jit(inline="always")
def _value_of(k, mode, t, z, ctx, scene, rec, q, g):
    """Event function k at the compact state z (q, g: scratch for the full state and the
    event values); theta alone where the event needs no more (z[0] is theta there)."""
    if angle_event(k, mode):
        return angle_value(k, z[0], ctx, scene)
    to_full(mode, z, ctx, scene.body, q)
    return event_value(k, mode, t, q, ctx, scene, rec, g)


@jit(inline="always")
def _value_at(x, args):
    """Event function k at the fraction x of the step (args = (k, step, ctx, scene, rec, z,
    q, g): scratch for the compact and the full state and the event values)."""
    k, step, ctx, scene, rec, z, q, g = args
    dense(step, x, z)
    return _value_of(k, step.mode, step.t + x * step.dt, z, ctx, scene, rec, q, g)


@jit(inline="always")
def _slope_at(x, args):
    """Event function k at the fraction x divided by x: for a function that entered the
    step at zero, positive from the start while it rises, with the same roots after it."""
    return _value_at(x, args) / x


_locate = brent(_value_at)
_locate_rising = brent(_slope_at)
_peak = peak_above_zero(_value_at)


@jit(inline="always")
def _root_after_zero(args, xs, gs):
    """The first root in (0, xs] of event function k that entered the step at zero and is
    gs <= 0 at xs; 0 if it never rises above zero."""
    xl = RISE_X * xs
    hl = _slope_at(xl, args)
    if hl > 0.0:
        return _locate_rising(args, xl, xs, hl, gs / xs, EVENT_XTOL)
    xl, gl = _peak(args, 0.0, xs, PEAK_XTOL)      # not risen yet: it left with zero rate
    if gl > 0.0:
        return _locate(args, xl, xs, gl, gs, EVENT_XTOL)
    return 0.0                                    # it left zero the wrong way: the event is now


@jit(inline="always")
def first_event(step, ctx, scene, rec, values, scratch):
    """(k, x): the mode's event that fires first inside ``step`` and the step fraction where
    it does; k = -1 if none does, and then ``values.last`` holds the event values at the
    step's end.  ``values.old`` holds them at the step's start."""
    mode, z, z_new = step.mode, step.z, step.z_new
    g_old, g_new, g_last = values.old, values.new, values.last
    z_x, q_x, g_x = scratch.z, scratch.q, scratch.g
    ne = n_events(mode)
    for k in range(ne):
        g_last[k] = g_old[k]
    xa = 0.0
    x_e = 2.0
    k_e = -1
    turning = mode == TRANSLATION_JUMP or mode == ROTATION_JUMP or \
        (mode != SLIDE and z[1] * z_new[1] <= 0.0)
    for xs in SAMPLES if turning else END_ONLY:
        if xs == xa:
            break
        dense(step, xs, z_x)
        to_full(mode, z_x, ctx, scene.body, q_x)
        event_values(mode, step.t + xs * step.dt, q_x, ctx, scene, rec, g_new)
        for k in range(ne):
            if g_new[k] > 0.0:
                continue
            args = (k, step, ctx, scene, rec, z_x, q_x, g_x)
            if g_last[k] > 0.0:
                xr = _locate(args, xa, xs, g_last[k], g_new[k], EVENT_XTOL)
            else:                    # entered the step at zero (so xa = 0)
                xr = _root_after_zero(args, xs, g_new[k])
            if xr < x_e:
                x_e = xr
                k_e = k
        if k_e >= 0:
            break
        xa = xs
        for k in range(ne):
            g_last[k] = g_new[k]
    return k_e, x_e


@jit
def polish(k, step, ctx, scene, rec, scratch):
    """Newton's step on event k from the end of ``step`` (taken exactly to the event):
    move step.z_new along its slope f by d and return d.  The event was found on the dense
    output, one order less exact than the step; this puts it on its root with the step's
    own accuracy.  A correction of POLISH_MAX of the step or more is not taken."""
    mode, z, dt = step.mode, step.z_new, step.dt
    f = step.K[step.end]
    t = step.t + dt
    zbuf, q, g = scratch.z, scratch.q, scratch.g
    g0 = _value_of(k, mode, t, z, ctx, scene, rec, q, g)
    delta = POLISH_DELTA * dt
    for j in range(step.n):
        zbuf[j] = z[j] + delta * f[j]
    slope = (_value_of(k, mode, t + delta, zbuf, ctx, scene, rec, q, g) - g0) / delta
    d = -g0 / slope if slope != 0.0 else 0.0
    if not abs(d) < POLISH_MAX * dt:
        return 0.0
    for j in range(step.n):
        z[j] += d * f[j]
    return d
