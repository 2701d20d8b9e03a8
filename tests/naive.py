"""Slow, obviously correct reference versions of single kernel modes (STUMPY's ``naive.py``).

Plain numpy/scipy, written from docs/physics.md and docs/design.md section 4 alone, independent of
``kernels``; the tests compare the kernel with them event by event, and the work-precision
benchmark (``benchmarks/``, which imports this module) runs the same programs against it:

* ``housner_rocking``: the rocking-only model (mode 3 of docs/physics.md 1.2: rocking about a
  corner, no slip, no lift-off) integrated by ``scipy.integrate.solve_ivp`` (DOP853, with event
  location), Housner's impact omega+ = eta omega- (docs/physics.md 2.1) at every return to theta =
  0, rest until |a_x| > (b/h)(g + a_y) (docs/physics.md 1.3); floor motions ``sine``, ``sweep`` and
  ``record``.  It is what a user would write with scipy.
* ``free_rocking_impact_times`` and ``zeno_time``: free rocking from rest at theta0 by
  quadrature of the energy integral and the amplitude map of docs/physics.md A4;
* ``rigid_plastic_slide``: flat stick-slip sliding (mode 2) under a_x(t), Newmark's
  rigid-plastic block (docs/physics.md A6), integrated piecewise with solve_ivp.

Units SI, g = 9.80665 m/s^2; theta > 0 is rotation about the left corner, driven by a_x > 0.
"""
import math

import numpy as np
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq

G = 9.80665


def body_constants(B, H, i2=None):
    """(b, h, r, alpha, i2, eta, p) of a uniform (or given i2) rectangle B x H (docs/physics.md
    1.1)."""
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
    k = ln(f_stop/f_start)/duration, zero after ``duration`` (docs/design.md 4)."""
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
    exit is found by brentq on a fine scan), then integrates theta'' of docs/physics.md 1.2 (3)
    side by side, one half-cycle per ``solve_ivp`` call, with a terminal event at theta = 0.  An
    impact whose post-impact |omega| is below ``zeno_omega`` while the floor cannot lift the body
    closes to rest (the classical Zeno closure).  ``max_step`` bounds solve_ivp's step (the tests'
    0.01 s keeps a step from jumping over a brief return to theta = 0; ``math.inf`` is scipy's
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


# --- references without an event-driven integrator ------------------------------------------

def _quarter_time(theta_n, alpha, p):
    """Time from rest at theta_n to theta = 0 in free rocking (energy integral).

    omega(theta)^2 = 2 p^2 (cos(alpha - theta_n) - cos(alpha - theta)) = 4 p^2 sin(alpha -
    (theta_n + theta)/2) sin((theta_n - theta)/2); the substitution theta = theta_n (1 - u^2)
    removes the inverse-square-root end singularity.
    """
    def integrand(u):
        half = 0.5 * theta_n * u * u
        s_over_u2 = math.sin(half) / (u * u) if half > 0.0 else 0.5 * theta_n
        return theta_n / (p * math.sqrt(math.sin(alpha - theta_n + half) * s_over_u2))
    return quad(integrand, 0.0, 1.0, epsabs=0.0, epsrel=1e-13, limit=200)[0]


def _next_amplitude(theta_n, alpha, eta):
    """Amplitude after one impact: E(theta) = cos(alpha - theta) - cos(alpha) shrinks by eta^2."""
    def energy(theta):
        return 2.0 * math.sin(alpha - 0.5 * theta) * math.sin(0.5 * theta)
    target = eta * eta * energy(theta_n)
    return brentq(lambda th: energy(th) - target, 0.0, theta_n, xtol=1e-300,
                  rtol=4 * np.finfo(float).eps)


def free_rocking_impact_times(B, H, theta0, n):
    """First n impact times of free rocking from rest at theta0 (docs/physics.md A4 method).

    Half-cycle times by quadrature, amplitude map
    cos(alpha - theta_{n+1}) = cos(alpha) + eta^2 [cos(alpha - theta_n) - cos(alpha)].
    """
    b, h, r, alpha, i2, eta, p = body_constants(B, H)
    times = []
    t = _quarter_time(theta0, alpha, p)
    amp = theta0
    for _ in range(n):
        times.append(t)
        amp = _next_amplitude(amp, alpha, eta)
        t += 2.0 * _quarter_time(amp, alpha, p)
    return np.array(times)


def zeno_time(B, H, theta0):
    """Accumulation time of the impacts of free rocking from rest at theta0 (docs/physics.md A4).

    Sums the half-cycles until the amplitude is below 1e-12 alpha, then adds the geometric
    tail: for small amplitudes theta_{n+1} = eta^2 theta_n and the half-cycle time, which
    scales like sqrt(theta), shrinks by eta (relative error of the tail O(theta/alpha)).
    """
    b, h, r, alpha, i2, eta, p = body_constants(B, H)
    t = _quarter_time(theta0, alpha, p)
    amp = theta0
    while amp > 1e-12 * alpha:
        amp = _next_amplitude(amp, alpha, eta)
        t += 2.0 * _quarter_time(amp, alpha, p)
    return t + 2.0 * _quarter_time(amp, alpha, p) * eta / (1.0 - eta)


def rigid_plastic_slide(a_x, mu, t_end, breaks=(), rtol=1e-12, atol=1e-14, mu_stick=None):
    """Newmark's rigid-plastic sliding block on a horizontal floor (docs/physics.md 1.2 (2), A6).

    Kinetic friction mu, static mu_stick (default mu), no rocking.  Stick -> slip when
    |a_x| > mu_stick g; slip -> stick when u = 0 and |a_x| <= mu_stick g, else the slip
    reverses.  ``breaks`` are the instants where a_x jumps (integration never crosses them).
    Returns (t, x) on a dense grid and max |x|: relative displacement of the block.
    """
    mu_stick = mu if mu_stick is None else mu_stick

    def excess(t):
        return abs(a_x(t)) - mu_stick * G

    stops = sorted(set([bk for bk in breaks if 0.0 < bk < t_end] + [t_end]))
    scan = np.unique(np.concatenate([np.arange(0.0, t_end, 1e-3), stops]))
    t, x, u = 0.0, 0.0, 0.0
    ts, xs = [0.0], [0.0]
    sliding = False
    sigma = 0.0
    while t < t_end:
        if not sliding:                      # stuck: find the next instant |a_x| > mu_stick g
            if excess(t) <= 0.0:
                t_next = None
                ta = t
                for tb in scan[scan > t]:
                    tl = tb - 1e-13 if tb in stops else tb   # left value at a jump
                    if excess(tl) > 0.0:
                        t_next = brentq(excess, ta, tl, xtol=1e-15)
                        break
                    if excess(tb) > 0.0:
                        t_next = tb
                        break
                    ta = tb
                if t_next is None:
                    break
                t = t_next
            sigma = -math.copysign(1.0, a_x(t + 1e-13))      # a_x > 0 drags it left
            sliding = True
        t_seg = min(s for s in stops if s > t)

        def rhs(t_, y, sigma=sigma, t_seg=t_seg):
            return [y[1], -a_x(min(t_, t_seg - 1e-13)) - mu * G * sigma]

        def stop(t_, y, sigma=sigma):
            return sigma * y[1]
        stop.terminal, stop.direction = True, -1
        sol = solve_ivp(rhs, (t, t_seg), [x, u], method="DOP853", events=stop, rtol=rtol,
                        atol=atol, max_step=1e-3, dense_output=True)
        tt = np.linspace(t, sol.t[-1], 2001)
        ts.extend(tt[1:].tolist())
        xs.extend(sol.sol(tt)[0][1:].tolist())
        t = float(sol.t[-1])
        x, u = float(sol.y[0][-1]), float(sol.y[1][-1])
        if sol.t_events[0].size:             # the slip stopped: stick, or slip back
            u = 0.0
            sliding = False
    xs = np.array(xs)
    return np.array(ts), xs, float(np.max(np.abs(xs)))


def floor_motion(ground):
    """A callable a(t) [m/s^2] of a resolved ground component (kernels/api.py) for the scipy
    program, and the instants [s] where it is not smooth (window edges, record samples)."""
    kind = ground["kind"]
    if kind == "none":
        return (lambda t: 0.0), ()
    if kind == "sine":
        a = sine(ground["amplitude"], ground["frequency"], ground["phase"])
        kinks = ()
    elif kind == "sweep":
        if ground["hold"] != "acceleration" or ground["law"] != "log":
            raise ValueError("the scipy sweep holds the acceleration on a log law")
        a = sweep(ground["amplitude"], ground["f_start"], ground["f_stop"],
                                ground["duration"], ground["phase"])
        kinks = ()
    elif kind == "record":
        samples = ground["samples"]
        a = record(samples, ground["dt"], ground["scale"])
        kinks = tuple(ground["dt"] * np.arange(len(samples)))
    else:
        raise ValueError(f"no scipy floor motion of kind {kind!r}")
    start = ground["start"]
    end = math.inf if ground["duration"] is None else start + ground["duration"]
    if start == 0.0 and end == math.inf:
        return a, kinks
    return ((lambda t: a(t - start) if start <= t < end else 0.0),
            tuple(start + k for k in kinks) + (start,) + ((end,) if end < math.inf else ()))
