"""The rocking-only block written with ``scipy.integrate.solve_ivp``: what a user would write.

Mode 3 of PHYSICS.md 1.2 (rocking about a corner, no slip, no lift-off) integrated by DOP853
with event location, Housner's impact omega+ = eta omega- (PHYSICS 2.1) at every return to
theta = 0, rest until |a_x| > (b/h)(g + a_y) (PHYSICS 1.3).  Plain numpy/scipy, independent of
``kernels``: the tests use it (through ``tests/naive.py``) as the event-by-event reference, the
work-precision benchmark as the program our kernel is compared with.  Floor motions
``sine``, ``sweep`` and ``record`` are written from DESIGN.md section 4.

Units SI, g = 9.80665 m/s^2; theta > 0 is rotation about the left corner, driven by a_x > 0.
"""
import math

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

G = 9.80665


def body_constants(B, H, i2=None):
    """(b, h, r, alpha, i2, eta, p) of a uniform (or given i2) rectangle B x H (PHYSICS 1.1)."""
    b, h = 0.5 * B, 0.5 * H
    r = math.hypot(b, h)
    alpha = math.atan2(b, h)
    i2 = r * r / 3.0 if i2 is None else i2
    eta = 1.0 - 2.0 * b * b / (i2 + r * r)
    p = math.sqrt(G * r / (i2 + r * r))
    return b, h, r, alpha, i2, eta, p


def sine(amplitude, frequency, phase=0.0):
    """a(t) = amplitude sin(2 pi frequency t + phase)."""
    omega = 2.0 * math.pi * frequency
    return lambda t: amplitude * math.sin(omega * t + phase)


def sweep(amplitude, f_start, f_stop, duration, phase=0.0):
    """Constant-acceleration log sweep: a = A sin(2 pi f_start (e^(k t) - 1)/k + phase),
    k = ln(f_stop/f_start)/duration, zero after ``duration`` (DESIGN.md 4)."""
    k = math.log(f_stop / f_start) / duration

    def a(t):
        if not 0.0 <= t < duration:
            return 0.0
        return amplitude * math.sin(2.0 * math.pi * f_start * math.expm1(k * t) / k + phase)
    return a


def record(samples, dt, scale=1.0):
    """Linear interpolation of a sampled record (sample k at k dt), zero outside it."""
    times = dt * np.arange(len(samples))
    values = scale * np.asarray(samples, dtype=float)
    return lambda t: float(np.interp(t, times, values, left=0.0, right=0.0))


def _zero(t):
    return 0.0


def housner_rocking(B, H, a_x=_zero, a_y=_zero, theta0=0.0, omega0=0.0, t_end=10.0,
                    a_x_breaks=(), theta_over=math.pi / 2, rtol=1e-11, atol=1e-13,
                    max_step=0.01, zeno_omega=1e-9, max_impacts=100_000, t_start=0.0):
    """Rocking-only response (no slip, no jump) with Housner's impact law.

    Starts at ``t_start``; at rest (theta0 = omega0 = 0) until |a_x| > (b/h)(g + a_y) (the rest
    exit is found by brentq on a fine scan), then integrates theta'' of PHYSICS 1.2 (3) side
    by side, one half-cycle per ``solve_ivp`` call, with a terminal event at theta = 0.  An
    impact whose post-impact |omega| is below ``zeno_omega`` while the floor cannot lift the
    body closes to rest (the classical Zeno closure).  ``max_step`` bounds solve_ivp's step (the tests' 0.01 s
    keeps a step from jumping over a brief return to theta = 0; ``math.inf`` is scipy's
    default).

    Returns a dict: impact_times, omega_before, omega_after (lists), overturned (bool),
    t_overturn, t_rest (start of the final rest, or None), steps (accepted solve_ivp steps),
    nfev (right-hand-side calls).
    """
    b, h, r, alpha, i2, eta, p = body_constants(B, H)
    k = r / (i2 + r * r)
    beta = b / h

    def rocking(side):
        def rhs(t, y):
            phi = alpha * side - y[0]
            return [y[1], -k * ((G + a_y(t)) * math.sin(phi) - a_x(t) * math.cos(phi))]
        return rhs

    def excess(t):
        return abs(a_x(t)) - beta * (G + a_y(t))

    def rest_exit(t0):
        # scan at 1/400 s (far below any half-period used in the tests), then brentq
        ts = np.arange(t0, t_end + 1e-3, 2.5e-3)
        ts = np.unique(np.concatenate([ts, [bk for bk in a_x_breaks if t0 <= bk <= t_end]]))
        f_prev = excess(ts[0])
        if f_prev > 0.0:
            return ts[0]
        for ta, tb in zip(ts[:-1], ts[1:]):
            f = excess(tb)
            if f > 0.0:
                return brentq(excess, ta, tb, xtol=1e-15, rtol=4 * np.finfo(float).eps)
        return math.inf

    out = dict(impact_times=[], omega_before=[], omega_after=[], overturned=False,
               t_overturn=None, t_rest=None, steps=0, nfev=0)
    t, theta, omega = t_start, theta0, omega0
    resting = theta == 0.0 and omega == 0.0
    while t < t_end and len(out["impact_times"]) < max_impacts:
        if resting:
            out["t_rest"] = t
            t = rest_exit(t)
            if t >= t_end:
                break
            out["t_rest"] = None
            resting = False
            theta, omega = 0.0, 0.0
            side = math.copysign(1.0, a_x(t))
        else:
            side = math.copysign(1.0, theta if theta != 0.0 else omega)

        def impact(t_, y, side=side):
            return side * y[0]
        impact.terminal, impact.direction = True, -1

        def overturn(t_, y):
            return theta_over - abs(y[0])
        overturn.terminal, overturn.direction = True, -1

        sol = solve_ivp(rocking(side), (t, t_end), [theta, omega], method="DOP853",
                        events=(impact, overturn), rtol=rtol, atol=atol, max_step=max_step)
        out["steps"] += sol.t.size - 1
        out["nfev"] += sol.nfev
        if sol.status == -1:
            raise RuntimeError(sol.message)
        if sol.t_events[1].size:
            out["overturned"] = True
            out["t_overturn"] = float(sol.t_events[1][0])
            break
        if not sol.t_events[0].size:
            break
        t = float(sol.t_events[0][0])
        omega_minus = float(sol.y_events[0][0][1])
        omega = eta * omega_minus
        theta = 0.0
        out["impact_times"].append(t)
        out["omega_before"].append(omega_minus)
        out["omega_after"].append(omega)
        if abs(omega) < zeno_omega and excess(t) <= 0.0:
            resting = True
    return out
