"""Rest without stepping: the next instant at which the floor can move a resting body.

A body at rest leaves rest when |a_x| > mu_s g_e, |a_x| > (b_s/h) g_e or g_e < 0
(docs/physics.md 1.3; s the corner the floor drives the body towards: b1 for a_x > 0, b2 for
a_x < 0), i.e. when phi(t) = max(a_x - kappa_+ g_e, -a_x - kappa_- g_e) > 0 with
kappa_+ = min(mu_s, b1/h) and kappa_- = min(mu_s, b2/h) (|a_x| - kappa g_e for a symmetric
body).  An anchored body (docs/anchors.md) is held until a tie must pull harder than its
strength T: phi(t) = max(a_x - (b1 g_e + T' B)/h, -a_x - (b2 g_e + T' B)/h), T' = T/m, the far
corner's tie with arm B = b1 + b2; it neither slides nor rocks before.
The floor is scanned in intervals that hold at most one extremum of a smooth component
(1/8 of its period) and never cross a break of the motion; where a sampled slope bound
allows phi to rise above zero inside an interval, its peak is found by golden-section
search, so a short excursion above the threshold between two samples is not missed.  The
crossing itself is located by bisection to ``REST_XTOL``.  ``rest_begin`` starts a scan and
``rest_interval`` takes one interval of it, so that the scene's loop can take one a pass.
"""
import math

from ._jit import jit
from .ground import G, ground, ground_end, next_break, scan_step
from .roots import bisect, peak_above_zero
from .tolerances import BREAK_GUARD, PEAK_XTOL, REST_XTOL


@jit
def rest_threshold(body, contact):
    """(kappa_+, kappa_-, c): rest ends when a_x > kappa_+ g_e + c or -a_x > kappa_- g_e + c;
    c = 0 for a free body."""
    return min(contact.mu_s, body.b1 / body.h), min(contact.mu_s, body.b2 / body.h), 0.0


@jit
def anchored_threshold(body, tie):
    """(kappa_+, kappa_-, c) of a body held by its anchor's ties of strength T' = ``tie``
    per unit mass: the tie of the far corner gives way at a_x h = b_s g_e + T' (b1 + b2)
    (docs/anchors.md (1))."""
    return body.b1 / body.h, body.b2 / body.h, tie * (body.b1 + body.b2) / body.h


@jit
def _phi(t, args):
    """max(a_x - kappa_+ g_e - c, -a_x - kappa_- g_e - c) at t (args = (kappa, floor,
    rec)); rest ends where it is > 0."""
    kappa, floor, rec = args
    a_x, a_y = ground(t, floor, rec)
    g_e = G + a_y
    return max(a_x - kappa[0] * g_e - kappa[2], -a_x - kappa[1] * g_e - kappa[2])


_crossing = bisect(_phi)
_peak = peak_above_zero(_phi)


@jit
def rest_begin(t, t_stop, kappa, floor, rec):
    """The start of the scan of a rest that begins at t: (t_e, phi, t_scan), with t_e = t if
    the floor moves the body at t already (else inf), phi its value at t and t_scan the end
    of the scan, min(t_stop, the end of the floor motion)."""
    phi = _phi(t, (kappa, floor, rec))
    return (t if phi > 0.0 else math.inf), phi, min(t_stop, ground_end(floor))


@jit
def rest_interval(ta, phi_a, t_scan, kappa, floor, rec):
    """One interval [ta, tb] of the scan (phi_a: phi at ta): (t_e, tb, phi_b), with t_e the
    first time in it at which the floor can move the body, else inf and then phi_b = phi at
    tb, where the next interval starts; none before t_scan once tb >= t_scan.

    Evaluations of the floor motion just before a break use its left-hand value.
    """
    args = (kappa, floor, rec)
    tb = min(ta + scan_step(ta, floor), next_break(ta, floor), t_scan)
    tl = tb - BREAK_GUARD if tb < t_scan else tb              # left-hand value at a break
    phi_b = _phi(tl, args)
    if phi_b > 0.0:
        return _crossing(args, ta, tl, REST_XTOL), tb, phi_b
    tm = 0.5 * (ta + tl)
    phi_m = _phi(tm, args)
    if phi_m > 0.0:
        return _crossing(args, ta, tm, REST_XTOL), tb, phi_b
    # a peak inside the interval could rise above zero between the samples: bound it by the
    # largest sample plus the sampled slope times the whole interval
    slope = 2.0 * max(abs(phi_m - phi_a), abs(phi_b - phi_m)) / (tl - ta)
    if max(phi_a, phi_m, phi_b) + slope * (tl - ta) > 0.0:
        tp, phi_p = _peak(args, ta, tl, PEAK_XTOL)
        if phi_p > 0.0:
            return _crossing(args, ta, tp, REST_XTOL), tb, phi_b
    phi_b = _phi(tb, args)
    return (tb if phi_b > 0.0 else math.inf), tb, phi_b


@jit
def rest_scanning(t_e, ta, t_scan):
    """Whether a scan at ta that has found t_e goes on to its next interval."""
    return t_e == math.inf and ta < t_scan


@jit
def rest_exit(t, t_stop, kappa, floor, rec):
    """First time in [t, t_stop) at which the floor can move a body at rest; inf if none:
    the scan of ``rest_begin`` and ``rest_interval`` in one call (``driver.run_scene`` takes
    one interval a pass of its loop)."""
    t_e, phi_a, t_scan = rest_begin(t, t_stop, kappa, floor, rec)
    ta = t
    while rest_scanning(t_e, ta, t_scan):
        t_e, ta, phi_a = rest_interval(ta, phi_a, t_scan, kappa, floor, rec)
    return t_e
