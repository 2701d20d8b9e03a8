"""Rest without stepping: the next instant at which the floor can move a resting body.

A body at rest leaves rest when |a_x| > mu_s g_e, |a_x| > (b/h) g_e or g_e < 0
(PHYSICS.md 1.3), i.e. when phi(t) = |a_x| - kappa g_e > 0 with kappa = min(mu_s, b/h).
The floor is scanned in intervals that hold at most one extremum of a smooth component
(1/8 of its period) and never cross a break of the motion; where a sampled slope bound
allows phi to rise above zero inside an interval, its peak is found by golden-section
search, so a short excursion above the threshold between two samples is not missed.  The crossing itself is located by bisection to 1e-13 s.
"""
import math

from ._jit import jit
from .ground import G, ground, ground_end, next_break, scan_step


@jit
def _phi(t, kappa, par, rec):
    a_x, a_y = ground(t, par, rec)
    return abs(a_x) - kappa * (G + a_y)


@jit
def _crossing(ta, tb, kappa, par, rec):
    """Time in (ta, tb] with phi > 0 just after phi <= 0 (phi(ta) <= 0 < phi(tb))."""
    while tb - ta > 1e-13 * max(1.0, abs(tb)):
        tm = 0.5 * (ta + tb)
        if tm <= ta or tm >= tb:
            break
        if _phi(tm, kappa, par, rec) > 0.0:
            tb = tm
        else:
            ta = tm
    return tb


@jit
def _peak(ta, tb, kappa, par, rec):
    """(t, phi) at the largest phi on [ta, tb], stopping as soon as phi > 0 is seen."""
    invphi = 0.6180339887498949
    x1 = tb - invphi * (tb - ta)
    x2 = ta + invphi * (tb - ta)
    f1 = _phi(x1, kappa, par, rec)
    f2 = _phi(x2, kappa, par, rec)
    while tb - ta > 1e-10 * max(1.0, tb) and f1 <= 0.0 and f2 <= 0.0:
        if f1 > f2:
            tb, x2, f2 = x2, x1, f1
            x1 = tb - invphi * (tb - ta)
            f1 = _phi(x1, kappa, par, rec)
        else:
            ta, x1, f1 = x1, x2, f2
            x2 = ta + invphi * (tb - ta)
            f2 = _phi(x2, kappa, par, rec)
    if f1 >= f2:
        return x1, f1
    return x2, f2


@jit
def rest_exit(t, t_stop, kappa, par, rec):
    """First time in [t, t_stop) at which the floor can move a body at rest; inf if none.

    Evaluations of the floor motion just before a break use its left-hand value.
    """
    if _phi(t, kappa, par, rec) > 0.0:
        return t
    t_stop = min(t_stop, ground_end(par))
    ta = t
    phi_a = _phi(ta, kappa, par, rec)
    while ta < t_stop:
        tb = min(ta + scan_step(ta, par), next_break(ta, par), t_stop)
        tl = tb - 1e-12 if tb < t_stop else tb          # left-hand value at a break
        phi_b = _phi(tl, kappa, par, rec)
        if phi_b > 0.0:
            return _crossing(ta, tl, kappa, par, rec)
        tm = 0.5 * (ta + tl)
        phi_m = _phi(tm, kappa, par, rec)
        if phi_m > 0.0:
            return _crossing(ta, tm, kappa, par, rec)
        # a peak inside the interval could rise above zero between the samples: bound it
        # by the largest sample plus the sampled slope times the whole interval
        slope = 2.0 * max(abs(phi_m - phi_a), abs(phi_b - phi_m)) / (tl - ta)
        if max(phi_a, phi_m, phi_b) + slope * (tl - ta) > 0.0:
            tp, phi_p = _peak(ta, tl, kappa, par, rec)
            if phi_p > 0.0:
                return _crossing(ta, tp, kappa, par, rec)
        ta = tb
        phi_a = _phi(ta, kappa, par, rec)
        if phi_a > 0.0:
            return ta
    return math.inf
