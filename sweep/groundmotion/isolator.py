"""The absolute acceleration of a platform on a friction pendulum, from the motion under it.

The platform slides on a sphere of radius R with Coulomb friction mu.  Its displacement u
relative to what is under it (acceleration a) obeys, with omega^2 = g/R,

    sliding:  u'' + omega^2 u = -a - mu g sgn(u')
    stuck:    u' = 0 while |a + omega^2 u| <= mu g

and the platform's absolute acceleration is -omega^2 u - mu g sgn(u') while it slides, a while
it sticks, so at most g (mu + D/R) for a largest displacement D (Zayas, Low & Mahin 1990).
The body's reaction on the platform is neglected (docs/isolation.md).

The input is read linearly between its samples, on which the sliding equation is linear and
solved in closed form; the stop instants (u' = 0: the root of the closed-form velocity) and
the slip instants (|a + omega^2 u| reaching mu g: a linear equation) are located exactly
within each segment.  The output is sampled on a uniform grid ``substeps`` times finer than the
input's (at most ``STEP`` of a period), exact at its samples; the jump of up to 2 mu g at a stop
falls between two of them.  After the input the platform slides until it sticks
(``ring_down``).

Reference: Zayas, V.A., Low, S.S. & Mahin, S.A. (1990), A simple pendulum technique for
achieving seismic isolation, Earthquake Spectra 6(2), 317-333.
"""
import math
from collections import namedtuple

import numpy as np

from kernels.codes import G

Pendulum = namedtuple("Pendulum", "radius mu")
Pendulum.__doc__ = "A friction pendulum: radius of the sphere [m], friction coefficient."
Response = namedtuple("Response", "acceleration dt max_displacement")
Response.__doc__ = ("The platform's absolute acceleration [m/s^2] at the times k dt, and the "
                    "largest |u| [m].")
STEP = 1.0 / 200.0  # output step, as a fraction of the pendulum's period, at most
EPS = 1e-6  # time [1/omega] under which a root of the velocity is the slide's start


def substeps(dt, pendulum):
    """Output samples per input step: the output step is at most ``STEP`` of the period."""
    period = 2.0 * math.pi * math.sqrt(pendulum.radius / G)
    return max(1, math.ceil(dt / (STEP * period)))


def _free_and_forced(u, v, sign, a0, slope, w2, mu):
    """The slide towards ``sign`` from (u, v) under a0 + slope t is
    p0 + p1 t + c cos(w t) + d sin(w t): (w, p0, p1, c, d)."""
    w = math.sqrt(w2)
    p0 = -(a0 + mu * G * sign) / w2
    p1 = -slope / w2
    return w, p0, p1, u - p0, (v - p1) / w


def _slide(u, v, sign, a0, slope, tau, w2, mu):
    """State (u, v) after sliding ``tau`` towards ``sign`` under a0 + slope t, exact."""
    w, p0, p1, c, d = _free_and_forced(u, v, sign, a0, slope, w2, mu)
    cs, sn = math.cos(w * tau), math.sin(w * tau)
    return p0 + p1 * tau + c * cs + d * sn, p1 - c * w * sn + d * w * cs


def _stop_time(u, v, sign, a0, slope, h, w2, mu):
    """First instant in (EPS/omega, h] at which the velocity of the slide returns to zero,
    or None: the roots of p1 + M cos(w t + phi) = 0 of the closed form."""
    w, _, p1, c, d = _free_and_forced(u, v, sign, a0, slope, w2, mu)
    m = w * math.hypot(c, d)
    if m == 0.0 or abs(p1) > m:
        return None
    phi = math.atan2(c, d)
    base = math.acos(min(1.0, max(-1.0, -p1 / m)))
    best = None
    for root in (base, -base):
        t = (root - phi) / w
        t += 2.0 * math.pi / w * math.ceil((EPS - w * t) / (2.0 * math.pi))
        if t <= h and (best is None or t < best):
            best = t
    return best


def _slip_time(f0, slope, h, limit):
    """First instant in (0, h] at which |f0 + slope t| exceeds ``limit``, or None."""
    if slope == 0.0:
        return None
    t = (math.copysign(limit, slope) - f0) / slope
    return t if 0.0 <= t <= h else None


def _segment(state, a0, a1, h, w2, mu):
    """Advance ``state`` = [u, v, sign (0: stuck), max |u|] over a segment of length h with
    a linear input from a0 to a1, locating every stop and slip inside."""
    u, v, sign, peak = state
    slope = (a1 - a0) / h
    tau = 0.0
    while tau < h:
        a = a0 + slope * tau
        if sign == 0:
            f = a + w2 * u
            if abs(f) > mu * G:
                sign = -math.copysign(1.0, f)
                continue
            t = _slip_time(f, slope, h - tau, mu * G)
            if t is None:
                break
            tau += t
            sign = -math.copysign(1.0, slope)
            continue
        t = _stop_time(u, v, sign, a, slope, h - tau, w2, mu)
        if t is None:
            u, v = _slide(u, v, sign, a, slope, h - tau, w2, mu)
            peak = max(peak, abs(u))
            break
        u, _ = _slide(u, v, sign, a, slope, t, w2, mu)
        v, tau = 0.0, tau + t
        peak = max(peak, abs(u))
        f = a0 + slope * tau + w2 * u
        sign = 0 if abs(f) <= mu * G else -math.copysign(1.0, f)
    return [u, v, sign, peak]


def _platform(state, a, w2, mu):
    u, _, sign, _ = state
    return a if sign == 0 else -w2 * u - mu * G * sign


def ring_down(pendulum, displacement):
    """Time [s] for a pendulum sliding freely from ``displacement`` to stick: each half period
    takes 2 mu R off the amplitude; without friction, ten periods."""
    period = 2.0 * math.pi * math.sqrt(pendulum.radius / G)
    if pendulum.mu == 0.0:
        return 10.0 * period
    return (displacement / (2.0 * pendulum.mu * pendulum.radius) + 1.0) * period / 2.0


def response(samples, dt, pendulum):
    """The platform's :class:`Response` over an acceleration ``samples`` [m/s^2] at the times
    k dt, read linearly between them, from rest; followed by the free slide after them."""
    w2, mu = G / pendulum.radius, pendulum.mu
    samples = np.append(samples, 0.0)  # the input falls to rest over one step
    n = substeps(dt, pendulum)
    h = dt / n
    fine = np.interp(np.arange((len(samples) - 1) * n + 1) * h,
                     dt * np.arange(len(samples)), samples)
    state = [0.0, 0.0, 0 if abs(fine[0]) <= mu * G else -math.copysign(1.0, fine[0]), 0.0]
    out = [_platform(state, fine[0], w2, mu)]
    for a0, a1 in zip(fine[:-1], fine[1:]):
        state = _segment(state, a0, a1, h, w2, mu)
        out.append(_platform(state, a1, w2, mu))
    free = math.ceil(ring_down(pendulum, abs(state[0])) / h)
    for _ in range(free):
        state = _segment(state, 0.0, 0.0, h, w2, mu)
        out.append(_platform(state, 0.0, w2, mu))
    return Response(np.asarray(out), h, state[3])
