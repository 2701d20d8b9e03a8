"""Reference solutions that need no event-driven integrator, written from PHYSICS.md alone.

* ``free_rocking_impact_times`` and ``zeno_time``: free rocking from rest at theta0 by
  quadrature of the energy integral and the amplitude map of PHYSICS A4;
* ``rigid_plastic_slide``: flat stick-slip sliding (mode 2) under a_x(t), Newmark's
  rigid-plastic block (PHYSICS A6), integrated piecewise with solve_ivp.

Units SI; theta > 0 is rotation about the left corner.
"""
import math

import numpy as np
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq

from .scipy_rocking import G, body_constants


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
    """First n impact times of free rocking from rest at theta0 (PHYSICS A4 method).

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
    """Accumulation time of the impacts of free rocking from rest at theta0 (PHYSICS A4).

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


def rigid_plastic_slide(a_x, mu, t_end, breaks=(), rtol=1e-12, atol=1e-14):
    """Newmark's rigid-plastic sliding block on a horizontal floor (PHYSICS 1.2 (2), A6).

    Static = kinetic friction mu and no rocking (mu < b/h).  Stick -> slip when
    |a_x| > mu g; slip -> stick when u = 0 and |a_x| <= mu g, else the slip reverses.
    ``breaks`` are the instants where a_x jumps (integration never crosses them).
    Returns (t, x) on a dense grid and max |x|: relative displacement of the block.
    """
    def excess(t):
        return abs(a_x(t)) - mu * G

    stops = sorted(set([bk for bk in breaks if 0.0 < bk < t_end] + [t_end]))
    scan = np.unique(np.concatenate([np.arange(0.0, t_end, 1e-3), stops]))
    t, x, u = 0.0, 0.0, 0.0
    ts, xs = [0.0], [0.0]
    sliding = False
    sigma = 0.0
    while t < t_end:
        if not sliding:                      # stuck: find the next instant |a_x| > mu g
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
