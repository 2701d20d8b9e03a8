"""One explicit Runge-Kutta step on a mode's compact state, its dense output, step-size control.

``step`` and ``fit_dense`` run the method's ``Tableau`` (``tableaus``) as a module constant,
so that its coefficients are constants of the compiled code, which skips the terms of zero
coefficients (a new method is a new tableau and a branch in both).  Stage
times are capped at ``t_lim`` so that the floor is always evaluated on the near side of a
discontinuity of its motion.  On entry K[0] holds f(t, z); on exit K[stages] holds
f(t + dt, z_new), which the next step reuses and the dense output needs.  ``fit_dense``
turns a taken step into the coefficients of its dense output once, so that each of the
many evaluations inside it (samples, event and turning-point roots) is a Horner scheme.
``dense`` is compiled into its callers (``inline="always"``); ``step`` is not: compiled
into the driver's two call sites it saves another 15 % of a steady-rocking scene but costs
10 s more of the first compile.
"""
import math

from ._jit import jit
from .codes import ADAPTIVE
from .motion import rhs
from .tableaus import DOPRI5, RK4

SAFETY = 0.9          # step-size controller (Hairer, Norsett & Wanner II.4)
MIN_FACTOR = 0.2      # never shrink the step by more than this factor at once
MAX_FACTOR = 10.0     # never grow it by more than this factor at once
PI_BETA = 0.04        # weight of the last accepted error (PI control)
FIRST_STEP = 1e-3     # the adaptive method's first trial step [s] (max_step if smaller)
DENSE_DEGREE = 4      # degree in the step fraction of the dense output (DOPRI5's)


@jit
def step(method, mode, n, t, z, dt, t_lim, ctx, scene, rec, K, z_stage, z_new):
    """Advance the compact state z (n entries) of ``mode`` by dt with the method's tableau.

    Fills z_new and the stages K; returns the error norm (scaled RMS of the embedded
    estimate, accept when <= 1), 0 for a tableau without one.
    """
    if method == ADAPTIVE:
        return _step(DOPRI5, mode, n, t, z, dt, t_lim, ctx, scene, rec, K, z_stage, z_new)
    return _step(RK4, mode, n, t, z, dt, t_lim, ctx, scene, rec, K, z_stage, z_new)


@jit(inline="always")
def _step(tab, mode, n, t, z, dt, t_lim, ctx, scene, rec, K, z_stage, z_new):
    """``step`` with the tableau tab, a module constant, so that its coefficients are
    constants of the compiled code; a zero coefficient adds nothing and is skipped."""
    A, B, C, E = tab.A, tab.B, tab.C, tab.E
    stages = tab.stages
    for s in range(1, stages):
        for k in range(n):
            acc = 0.0
            for j in range(s):
                if A[s, j] != 0.0:
                    acc += A[s, j] * K[j, k]
            z_stage[k] = z[k] + dt * acc
        rhs(mode, min(t + C[s] * dt, t_lim), z_stage, ctx, scene, rec, K[s])
    for k in range(n):
        acc = 0.0
        for j in range(stages):
            if B[j] != 0.0:
                acc += B[j] * K[j, k]
        z_new[k] = z[k] + dt * acc
    rhs(mode, min(t + dt, t_lim), z_new, ctx, scene, rec, K[stages])
    if E.size == 0:
        return 0.0
    rtol, atol = scene.solver.rtol, scene.solver.atol
    err2 = 0.0
    for k in range(n):
        e = 0.0
        for j in range(stages + 1):
            if E[j] != 0.0:
                e += E[j] * K[j, k]
        sc = atol + rtol * max(abs(z[k]), abs(z_new[k]))
        e = dt * e / sc
        err2 += e * e
    return math.sqrt(err2 / n)


@jit
def fit_dense(method, step):
    """Fill step.D with the dense output of a taken ``Step`` as a polynomial in the step
    fraction x, z(x) = z + x (D[0] + x (D[1] + x (D[2] + x D[3]))): from the interpolant P
    of the method's tableau, D[m] = dt sum_j P[j, m] K[j], or, without one, the cubic
    Hermite interpolant of the end values and slopes (D[3] = 0)."""
    if method == ADAPTIVE:
        _fit_interpolant(DOPRI5.P, step)
    else:
        _fit_hermite(step)


@jit(inline="always")
def _fit_interpolant(P, step):
    """D from the interpolant P, a module constant (zero coefficients skipped)."""
    K, D, n, dt = step.K, step.D, step.n, step.dt
    for k in range(n):                  # the loops over constants inside, to be unrolled
        for m in range(DENSE_DEGREE):
            acc = 0.0
            for j in range(P.shape[0]):
                if P[j, m] != 0.0:
                    acc += P[j, m] * K[j, k]
            D[m, k] = dt * acc


@jit(inline="always")
def _fit_hermite(step):
    """D of the cubic Hermite interpolant of the step's end values and slopes."""
    K, z, z_new, D, n, dt = step.K, step.z, step.z_new, step.D, step.n, step.dt
    K_end = K[step.end]
    for k in range(n):
        d0 = dt * K[0, k]
        d1 = dt * K_end[k]
        jump = z_new[k] - z[k]
        D[0, k] = d0
        D[1, k] = 3.0 * jump - 2.0 * d0 - d1
        D[2, k] = d0 + d1 - 2.0 * jump
        D[3, k] = 0.0


@jit(inline="always")
def dense(step, x, out):
    """State at the fraction x of a taken ``Step`` (0 <= x <= 1) whose ``fit_dense`` is
    done: Horner's scheme on its coefficients D."""
    D, z = step.D, step.z
    for k in range(step.n):
        out[k] = z[k] + x * (D[0, k] + x * (D[1, k] + x * (D[2, k] + x * D[3, k])))


@jit
def next_step_size(dt, err, err_old, order):
    """Step-size proposal after a step with error norm err; err_old is that of the last
    accepted step.  Accepted steps take the PI controller of Hairer, Norsett & Wanner
    (II.4, DOPRI5 with beta = 0.04), which damps the alternation of accepted and rejected
    steps that the plain controller shows; a rejected step only shrinks."""
    if err == 0.0:
        return dt * MAX_FACTOR
    if err > 1.0:
        return dt * max(MIN_FACTOR, SAFETY * err ** (-1.0 / order))
    fac = SAFETY * err ** (PI_BETA * 0.75 - 1.0 / order) * err_old ** PI_BETA
    return dt * min(MAX_FACTOR, max(MIN_FACTOR, fac))
