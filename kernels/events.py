"""Event functions of each mode and their location on the dense output.

Every event is written g(t, q) > 0 while the mode holds and fires when g reaches 0 from
above (PHYSICS.md 1.3): an impact (the body side theta*side, a corner gap), lift-off
(N_c), the onset of slip (mu_edge_s N_c - |F_c|), the end of slip (sigma V_cx), the
Painleve condition (D), overturning (theta_over - |theta|), flat sliding stopping
(sigma u) and the floor falling faster than gravity (g_e).  ``locate`` finds the root on
the step's dense output by Brent's method (xtol 1e-13 of the step fraction).
"""
import math

from ._jit import jit
from .codes import ROTATION, ROTATION_JUMP, SLIDE, SLIDE_ROTATION, TRANSLATION_JUMP
from .ground import G, ground
from .integrate import dense
from .motion import (CTX_S, CTX_SIGMA, IOMEGA, ITHETA, IU, IY, corner, corner_velocity,
                     rotation_dynamics, slide_rotation_dynamics, to_full)

# event indices per mode
EV_IMPACT, EV_LIFTOFF, EV_SLIP, EV_OVERTURN, EV_PAINLEVE = range(5)   # rotation modes
EV_STOP, EV_FREE_FALL = range(2)                                     # slide
EV_GAP_L, EV_GAP_R, EV_JUMP_OVERTURN = range(3)                      # jumps
MAX_EVENTS = 5


@jit
def n_events(mode):
    """Number of event functions of a mode."""
    if mode == ROTATION:
        return 4
    if mode == SLIDE_ROTATION:
        return 5
    if mode == SLIDE:
        return 2
    if mode == TRANSLATION_JUMP:
        return 1
    if mode == ROTATION_JUMP:
        return 3
    return 0


@jit
def event_values(mode, t, q, ctx, par, rec, body, mu_edge_s, theta_over, out):
    """Write the mode's event functions at (t, q) into out."""
    b, h, i2, mu_k, mu_edge_k = body
    s = ctx[CTX_S]
    if mode == ROTATION or mode == SLIDE_ROTATION:
        a_x, a_y = ground(t, par, rec)
        g_e = G + a_y
        out[EV_IMPACT] = -s * q[ITHETA]
        out[EV_OVERTURN] = theta_over - abs(q[ITHETA])
        if mode == ROTATION:
            thdd, F, N = rotation_dynamics(q[ITHETA], q[IOMEGA], s, a_x, g_e, b, h, i2)
            out[EV_LIFTOFF] = N
            out[EV_SLIP] = mu_edge_s * N - abs(F)
        else:
            sigma = ctx[CTX_SIGMA]
            thdd, udd, N, D = slide_rotation_dynamics(q[ITHETA], q[IOMEGA], s, sigma, a_x,
                                                      g_e, b, h, i2, mu_edge_k)
            out[EV_LIFTOFF] = N
            out[EV_SLIP] = sigma * corner_velocity(q, s, b, h)[0]
            out[EV_PAINLEVE] = D
    elif mode == SLIDE:
        out[EV_STOP] = ctx[CTX_SIGMA] * q[IU]
        out[EV_FREE_FALL] = G + ground(t, par, rec)[1]
    elif mode == TRANSLATION_JUMP:
        out[EV_GAP_L] = q[IY] - h
    elif mode == ROTATION_JUMP:
        out[EV_GAP_L] = q[IY] + corner(-1.0, q[ITHETA], b, h)[1]
        out[EV_GAP_R] = q[IY] + corner(1.0, q[ITHETA], b, h)[1]
        out[EV_JUMP_OVERTURN] = theta_over - abs(q[ITHETA])


@jit
def event_value(k, mode, t, q, ctx, par, rec, body, mu_edge_s, theta_over, gbuf):
    """Event function k alone; the rocking modes' impact and overturning need no forces."""
    if mode == ROTATION or mode == SLIDE_ROTATION:
        if k == EV_IMPACT:
            return -ctx[CTX_S] * q[ITHETA]
        if k == EV_OVERTURN:
            return theta_over - abs(q[ITHETA])
    event_values(mode, t, q, ctx, par, rec, body, mu_edge_s, theta_over, gbuf)
    return gbuf[k]


@jit
def _value_at(x, k, method, mode, n, t, z, z_new, K, h, ctx, par, rec, body, mu_edge_s,
              theta_over, zbuf, q, gbuf):
    dense(method, n, z, z_new, K, h, x, zbuf)
    to_full(mode, zbuf, ctx, body[0], body[1], q)
    return event_value(k, mode, t + x * h, q, ctx, par, rec, body, mu_edge_s, theta_over,
                       gbuf)


@jit
def locate(k, xa, xb, ga, gb, method, mode, n, t, z, z_new, K, h, ctx, par, rec, body,
           mu_edge_s, theta_over, zbuf, q, gbuf):
    """Step fraction in [xa, xb] where event k is zero (ga > 0 >= gb), by Brent's method."""
    xtol = 1e-13
    a, b_, fa, fb = xa, xb, ga, gb
    c, fc = a, fa
    d = e = b_ - a
    for _ in range(100):
        if fb * fc > 0.0:
            c, fc = a, fa
            d = e = b_ - a
        if abs(fc) < abs(fb):
            a, b_, c = b_, c, b_
            fa, fb, fc = fb, fc, fb
        tol = 2.0 * 2.2e-16 * abs(b_) + 0.5 * xtol
        m = 0.5 * (c - b_)
        if abs(m) <= tol or fb == 0.0:
            break
        if abs(e) >= tol and abs(fa) > abs(fb):
            s = fb / fa
            if a == c:
                p = 2.0 * m * s
                qq = 1.0 - s
            else:
                qq = fa / fc
                r = fb / fc
                p = s * (2.0 * m * qq * (qq - r) - (b_ - a) * (r - 1.0))
                qq = (qq - 1.0) * (r - 1.0) * (s - 1.0)
            if p > 0.0:
                qq = -qq
            else:
                p = -p
            if 2.0 * p < min(3.0 * m * qq - abs(tol * qq), abs(e * qq)):
                e = d
                d = p / qq
            else:
                d = m
                e = m
        else:
            d = m
            e = m
        a, fa = b_, fb
        if abs(d) > tol:
            b_ += d
        else:
            b_ += math.copysign(tol, m)
        fb = _value_at(b_, k, method, mode, n, t, z, z_new, K, h, ctx, par, rec, body,
                       mu_edge_s, theta_over, zbuf, q, gbuf)
    return b_


@jit
def peak(k, xa, xb, method, mode, n, t, z, z_new, K, h, ctx, par, rec, body, mu_edge_s,
         theta_over, zbuf, q, gbuf):
    """(x, g): the largest value of event k on [xa, xb] by golden-section search.

    Used when an event function entered the step at zero (a corner that has just left the
    floor): a return to zero inside the step shows as a positive peak before the end.
    """
    invphi = 0.6180339887498949
    a, b_ = xa, xb
    x1 = b_ - invphi * (b_ - a)
    x2 = a + invphi * (b_ - a)
    f1 = _value_at(x1, k, method, mode, n, t, z, z_new, K, h, ctx, par, rec, body,
                   mu_edge_s, theta_over, zbuf, q, gbuf)
    f2 = _value_at(x2, k, method, mode, n, t, z, z_new, K, h, ctx, par, rec, body,
                   mu_edge_s, theta_over, zbuf, q, gbuf)
    while b_ - a > 1e-10:
        if f1 > 0.0 or f2 > 0.0:
            break
        if f1 > f2:
            b_, x2, f2 = x2, x1, f1
            x1 = b_ - invphi * (b_ - a)
            f1 = _value_at(x1, k, method, mode, n, t, z, z_new, K, h, ctx, par, rec, body,
                           mu_edge_s, theta_over, zbuf, q, gbuf)
        else:
            a, x1, f1 = x1, x2, f2
            x2 = a + invphi * (b_ - a)
            f2 = _value_at(x2, k, method, mode, n, t, z, z_new, K, h, ctx, par, rec, body,
                           mu_edge_s, theta_over, zbuf, q, gbuf)
    if f1 >= f2:
        return x1, f1
    return x2, f2
