"""The floor: the engine's adaptive tableau in a compact rocking-only loop.

What the engine's generality costs is measured against this loop, which knows only rocking on
a floor moving as a sine or a log sweep of acceleration (the throughput map's): theta'' of
docs/physics.md 1.2 (3) about the pivot corner, Housner's impact
omega+ = eta omega- at theta = 0 (docs/physics.md 2.1 with e_x = e_y = 0 and a pivot that never
slips), rest until |a_x| > (b/h) g, and nothing else — no sliding, flight, events of other
modes, extremes, history or Zeno bookkeeping beyond the classical closure (and, with
``zeno_dt``, the map's: an impact within zeno_dt of the one before ends in rest).  It runs the very
tableau (``kernels.tableaus.tableau(ADAPTIVE)``) and step-size controller
(``kernels.integrate.next_step_size``) of the engine, locates impacts on the tableau's dense
output by the Illinois method and returns what the work-precision scenes compare: impact times,
omega after each, the overturning time.
"""
import math

import numpy as np
from numba import njit

from kernels.codes import ADAPTIVE
from kernels.integrate import next_step_size
from kernels.tableaus import tableau
from tests.naive import G, body_constants

ZENO_OMEGA = 1e-9       # rad/s: an impact slower than this ends in rest (as tests.naive)
FIRST_STEP = 1e-4       # s
MAX_STEP = 0.01         # s, as the tests' scipy program
MIN_STEP = 1e-13        # s: below it the loop gives up (never reached on the bench scenes)
REST_SCAN = 2.5e-3      # s between tests of the rest exit before bisection
ERR_FLOOR = 1e-4
RISE_SAMPLES = 16       # samples of a step that starts at an impact, to bracket the next one


@njit(cache=True)
def _accel(t, amp, omega_f, phase, rate):
    """a_x(t): a sine of angular frequency omega_f (rate 0), or a log sweep from it whose
    frequency grows as exp(rate t) (the kernel's ``ground.sweep_phase``)."""
    if rate == 0.0:
        return amp * math.sin(omega_f * t + phase)
    return amp * math.sin(omega_f * (math.exp(rate * t) - 1.0) / rate + phase)


@njit(cache=True)
def _rhs(t, theta, omega, side, k, alpha, amp, omega_f, phase, rate, out):
    phi = alpha * side - theta
    out[0] = omega
    out[1] = -k * (G * math.sin(phi) - _accel(t, amp, omega_f, phase, rate) * math.cos(phi))


@njit(cache=True)
def _dense(y, K, P, dt, x, stages, j):
    """Component j of the dense output at fraction x of the step."""
    acc = 0.0
    for s in range(stages + 1):
        xp, poly = x, 0.0
        for m in range(P.shape[1]):
            poly += P[s, m] * xp
            xp *= x
        acc += K[s, j] * poly
    return y[j] + dt * acc


@njit(cache=True)
def _rest_exit(t0, t_end, beta, amp, omega_f, phase, rate):
    """First t >= t0 with |a_x(t)| > beta g (scan, then bisection), or inf."""
    def excess(t):
        return abs(_accel(t, amp, omega_f, phase, rate)) - beta * G
    if excess(t0) > 0.0:
        return t0
    ta = t0
    while ta < t_end:
        tb = min(ta + REST_SCAN, t_end)
        if excess(tb) > 0.0:
            for _ in range(200):
                tm = 0.5 * (ta + tb)
                if tm <= ta or tm >= tb:
                    break
                if excess(tm) > 0.0:
                    tb = tm
                else:
                    ta = tm
            return tb
        ta = tb
    return math.inf


@njit(cache=True)
def _run(C, A, B, E, P, order, stages, b, h, i2, amp, omega_f, phase, rate, theta0, t_end,
         rtol, atol, zeno_dt, times, omegas):
    """The loop; returns (number of impacts, t_overturn or NaN, accepted steps)."""
    r = math.hypot(b, h)
    alpha = math.atan2(b, h)
    k = r / (i2 + r * r)
    eta = 1.0 - 2.0 * b * b / (i2 + r * r)
    beta = b / h
    K = np.zeros((stages + 1, 2))
    y = np.zeros(2)
    y_new = np.zeros(2)
    z = np.zeros(2)
    t, n, steps, t_last = 0.0, 0, 0, -math.inf
    y[0], y[1] = theta0, 0.0
    resting = theta0 == 0.0
    side = 1.0 if theta0 >= 0.0 else -1.0
    dt, err_old = FIRST_STEP, ERR_FLOOR
    if not resting:
        _rhs(t, y[0], y[1], side, k, alpha, amp, omega_f, phase, rate, K[0])
    while t < t_end and n < times.size:
        if resting:
            t = _rest_exit(t, t_end, beta, amp, omega_f, phase, rate)
            if t >= t_end:
                break
            resting = False
            y[0], y[1] = 0.0, 0.0
            side = 1.0 if _accel(t, amp, omega_f, phase, rate) > 0.0 else -1.0  # theta's sign
            dt, err_old = FIRST_STEP, ERR_FLOOR
            _rhs(t, y[0], y[1], side, k, alpha, amp, omega_f, phase, rate, K[0])
        dt = min(dt, MAX_STEP, t_end - t)
        for s in range(1, stages):
            for j in range(2):
                acc = 0.0
                for m in range(s):
                    acc += A[s, m] * K[m, j]
                z[j] = y[j] + dt * acc
            _rhs(t + C[s] * dt, z[0], z[1], side, k, alpha, amp, omega_f, phase, rate, K[s])
        for j in range(2):
            acc = 0.0
            for s in range(stages):
                acc += B[s] * K[s, j]
            y_new[j] = y[j] + dt * acc
        _rhs(t + dt, y_new[0], y_new[1], side, k, alpha, amp, omega_f, phase, rate, K[stages])
        err = 0.0
        for j in range(2):
            acc = 0.0
            for s in range(stages + 1):
                acc += E[s] * K[s, j]
            scale = atol + rtol * max(abs(y[j]), abs(y_new[j]))
            err += (dt * acc / scale) ** 2
        err = math.sqrt(err / 2.0)
        dt_next = next_step_size(dt, err, err_old, order)
        if err > 1.0:
            if dt_next < MIN_STEP:
                break
            dt = dt_next
            continue
        err_old = max(err, ERR_FLOOR)
        steps += 1
        if abs(y_new[0]) >= 0.5 * math.pi:                # overturned within the step
            xa, xb = 0.0, 1.0
            for _ in range(100):
                xm = 0.5 * (xa + xb)
                if abs(_dense(y, K, P, dt, xm, stages, 0)) >= 0.5 * math.pi:
                    xb = xm
                else:
                    xa = xm
            return n, t + xb * dt, steps
        if side * y_new[0] < 0.0:                          # theta crossed 0: an impact
            xa, xb = 0.0, 1.0
            fa, fb = side * y[0], side * y_new[0]
            if fa == 0.0:            # the step starts at an impact: bracket past it
                for m in range(1, RISE_SAMPLES):
                    f = side * _dense(y, K, P, dt, m / RISE_SAMPLES, stages, 0)
                    if f > 0.0:
                        xa, fa = m / RISE_SAMPLES, f
                        break
                if fa == 0.0:        # never rose: the bounce closes at once (rest)
                    resting = True
                    y[0], y[1] = 0.0, 0.0
                    continue
            for _ in range(100):                           # Illinois on the dense output
                xm = (xa * fb - xb * fa) / (fb - fa)
                fm = side * _dense(y, K, P, dt, xm, stages, 0)
                if fm == 0.0 or (xb - xa) * dt < 1e-16:
                    break
                if (fm < 0.0) == (fa < 0.0):
                    xa, fa = xm, fm
                    fb *= 0.5
                else:
                    xb, fb = xm, fm
                    fa *= 0.5
            t_hit = t + xm * dt
            closing = t_hit - t_last < zeno_dt
            t_last = t_hit
            omega_minus = _dense(y, K, P, dt, xm, stages, 1)
            times[n] = t_hit
            omegas[n] = eta * omega_minus
            n += 1
            t, y[0], y[1] = t_hit, 0.0, eta * omega_minus
            side = -side
            excess = abs(_accel(t, amp, omega_f, phase, rate)) - beta * G
            if closing or (abs(y[1]) < ZENO_OMEGA and excess <= 0.0):
                resting = True
                y[1] = 0.0
                continue
            _rhs(t, y[0], y[1], side, k, alpha, amp, omega_f, phase, rate, K[0])
            # the next half-cycle lasts about 2 |omega+| / |theta''|: no step jumps over it
            dt = min(dt_next, abs(y[1]) / max(abs(K[0, 1]), 1e-300))
            continue
        t += dt
        y[0], y[1] = y_new[0], y_new[1]
        for j in range(2):
            K[0, j] = K[stages, j]
        dt = dt_next
    return n, math.nan, steps


def takes(resolved):
    """True for a scene the floor loop models: a still floor, a sine of acceleration, or a
    log sweep of acceleration from t = 0 to the end."""
    ground = resolved["excitation"]["horizontal"]
    if ground.get("hold", "acceleration") != "acceleration" or ground.get("start", 0.0):
        return False
    if ground["kind"] == "sweep":
        return ground.get("law") == "log" and ground["duration"] >= resolved["solver"]["t_end"]
    return ground["kind"] in ("none", "sine")


def run(resolved, rtol, atol, max_impacts=100_000, zeno_dt=0.0):
    """The floor loop on a resolved rocking-only scene (``takes``: a still floor, a sine or a
    log sweep, uniform body, theta0 given in ``initial.theta``): the dict of
    ``scenes.Outcome.of_scipy``.  ``zeno_dt`` > 0: an impact that soon after the one before
    ends in rest (the kernel's Zeno closure, as the map's cells use it)."""
    body = resolved["body"]
    b, h, _, _, i2, _, _ = body_constants(body["B"], body["H"])
    ground = resolved["excitation"]["horizontal"]
    if not takes(resolved):
        raise ValueError("the floor loop takes a still floor, a sine or a log sweep of "
                         "acceleration only")
    amp, omega_f, phase, rate = 0.0, 0.0, 0.0, 0.0
    if ground["kind"] == "sine":
        amp, omega_f = ground["amplitude"], 2.0 * math.pi * ground["frequency"]
    elif ground["kind"] == "sweep":
        amp, omega_f = ground["amplitude"], 2.0 * math.pi * ground["f_start"]
        rate = math.log(ground["f_stop"] / ground["f_start"]) / ground["duration"]
    if ground["kind"] != "none":
        phase = ground.get("phase") or 0.0
    tab = tableau(ADAPTIVE)
    times, omegas = np.zeros(max_impacts), np.zeros(max_impacts)
    n, t_over, steps = _run(tab.C, tab.A, tab.B, tab.E, tab.P, tab.order, tab.stages, b, h,
                            i2, amp, omega_f, phase, rate, resolved["initial"]["theta"],
                            resolved["solver"]["t_end"], rtol, atol, zeno_dt, times, omegas)
    return {"impact_times": times[:n].tolist(), "omega_after": omegas[:n].tolist(),
            "t_overturn": None if math.isnan(t_over) else t_over, "steps": steps}
