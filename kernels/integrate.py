"""One step of either integrator on a mode's compact state, and its dense output.

``step`` has one signature for both methods.  ``ADAPTIVE``: Dormand-Prince 5(4), FSAL, the
error estimate returned as the scaled RMS norm (accept when <= 1).  ``FIXED``: classical RK4,
error norm 0.  In both, K[0] holds f(t, z) on entry and K[6] holds f(t + h, z_new) on exit,
which the next step reuses and the dense output needs.  Stage times are capped at ``t_lim``
so that the floor is always evaluated on the near side of a discontinuity of its motion.
"""
import math

from ._jit import jit
from .codes import ADAPTIVE
from .motion import rhs
from .tableaus import DP_A, DP_B, DP_C, DP_E, DP_ORDER, DP_P, RK4_A, RK4_B, RK4_C

SAFETY = 0.9          # step-size controller (Hairer, Norsett & Wanner II.4)
MIN_FACTOR = 0.2      # never shrink the step by more than this factor at once
MAX_FACTOR = 10.0     # never grow it by more than this factor at once
PI_BETA = 0.04        # weight of the last accepted error (PI control)


@jit
def step(method, mode, n, t, z, h, t_lim, par, rec, ctx, body, K, ztmp, z_new,
         rtol, atol):
    """Advance z by h; fill z_new and K; return the error norm (0 for the fixed step)."""
    b, h_, i2, mu_k, mu_edge_k = body
    if method == ADAPTIVE:
        for s in range(1, 6):
            for k in range(n):
                acc = 0.0
                for j in range(s):
                    acc += DP_A[s, j] * K[j, k]
                ztmp[k] = z[k] + h * acc
            rhs(mode, min(t + DP_C[s] * h, t_lim), ztmp, par, rec, ctx, b, h_, i2, mu_k,
                mu_edge_k, K[s])
        for k in range(n):
            acc = 0.0
            for j in range(6):
                acc += DP_B[j] * K[j, k]
            z_new[k] = z[k] + h * acc
        rhs(mode, min(t + h, t_lim), z_new, par, rec, ctx, b, h_, i2, mu_k, mu_edge_k, K[6])
        err2 = 0.0
        for k in range(n):
            e = 0.0
            for j in range(7):
                e += DP_E[j] * K[j, k]
            sc = atol + rtol * max(abs(z[k]), abs(z_new[k]))
            e = h * e / sc
            err2 += e * e
        return math.sqrt(err2 / n)
    for s in range(1, 4):
        for k in range(n):
            ztmp[k] = z[k] + h * RK4_A[s, s - 1] * K[s - 1, k]
        rhs(mode, min(t + RK4_C[s] * h, t_lim), ztmp, par, rec, ctx, b, h_, i2, mu_k,
            mu_edge_k, K[s])
    for k in range(n):
        z_new[k] = z[k] + h * (RK4_B[0] * K[0, k] + RK4_B[1] * K[1, k]
                               + RK4_B[2] * K[2, k] + RK4_B[3] * K[3, k])
    rhs(mode, min(t + h, t_lim), z_new, par, rec, ctx, b, h_, i2, mu_k, mu_edge_k, K[6])
    return 0.0


@jit
def dense(method, n, z, z_new, K, h, x, out):
    """State at the fraction x of the last step (0 <= x <= 1): DP5's quartic interpolant
    (scipy's RK45 P matrix) or, for RK4, the cubic Hermite interpolant."""
    if method == ADAPTIVE:
        x2 = x * x
        x3 = x2 * x
        x4 = x3 * x
        for k in range(n):
            acc = 0.0
            for j in range(7):
                acc += K[j, k] * (DP_P[j, 0] * x + DP_P[j, 1] * x2 + DP_P[j, 2] * x3
                                  + DP_P[j, 3] * x4)
            out[k] = z[k] + h * acc
        return
    x2 = x * x
    x3 = x2 * x
    h00 = 2.0 * x3 - 3.0 * x2 + 1.0
    h10 = x3 - 2.0 * x2 + x
    h01 = -2.0 * x3 + 3.0 * x2
    h11 = x3 - x2
    for k in range(n):
        out[k] = h00 * z[k] + h * h10 * K[0, k] + h01 * z_new[k] + h * h11 * K[6, k]


@jit
def next_step_size(h, err, err_old):
    """Step-size proposal after a step with error norm err; err_old is that of the last
    accepted step.  Accepted steps take the PI controller of Hairer, Norsett & Wanner
    (II.4, DOPRI5 with beta = 0.04), which damps the alternation of accepted and rejected
    steps that the plain controller shows; a rejected step only shrinks."""
    if err == 0.0:
        return h * MAX_FACTOR
    if err > 1.0:
        return h * max(MIN_FACTOR, SAFETY * err ** (-1.0 / DP_ORDER))
    fac = SAFETY * err ** (PI_BETA * 0.75 - 1.0 / DP_ORDER) * err_old ** PI_BETA
    return h * min(MAX_FACTOR, max(MIN_FACTOR, fac))
