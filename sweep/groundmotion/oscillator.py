"""The damped SDOF oscillator under a ground acceleration, and Sa(T) of a motion.

Sa(T) is the pseudo-spectral acceleration of the single-degree-of-freedom oscillator of period
T.

u'' + 2 zeta omega u' + omega^2 u = p, u relative to the ground, from rest, with p = -a_g
piecewise linear between the samples, is integrated exactly by the recursion of Nigam &
Jennings (1969), Chopra (2017) section 5.2, Table 5.2.1.  It gives the floors of buildings
(``floor``) and the pseudo-spectral acceleration Sa(T, zeta) = omega^2 max |u| that a
motion is scaled to (``sa:`` of a scene's record or synthetic motion): after the record the
ground is still for one period, long enough for the free vibration to pass its first peak.
A period of 0 is a rigid oscillator, Sa = PGA.

References: Nigam, N.C. & Jennings, P.C. (1969), BSSA 59(2), 909-922.  Chopra, A.K. (2017),
Dynamics of Structures, 5th ed., Pearson, sections 5.2 and 6.6.
"""
import math

import numpy as np

from kernels._jit import jit

DAMPING = 0.05  # of the spectra of hazard curves and ground-motion models


@jit(runtime=True)
def _response(p, dt, omega, zeta):
    """u and u' at the samples of p: the recursion of Chopra (2017) Table 5.2.1."""
    k = omega * omega
    root = math.sqrt(1.0 - zeta * zeta)
    wd = omega * root
    e = math.exp(-zeta * omega * dt)
    s = math.sin(wd * dt)
    c = math.cos(wd * dt)
    z = zeta / root
    a = e * (z * s + c)
    b = e * s / wd
    cc = (2.0 * zeta / (omega * dt) + e * (((1.0 - 2.0 * zeta * zeta) / (wd * dt) - z) * s
                                            - (1.0 + 2.0 * zeta / (omega * dt)) * c)) / k
    d = (1.0 - 2.0 * zeta / (omega * dt) + e * ((2.0 * zeta * zeta - 1.0) / (wd * dt) * s
                                                 + 2.0 * zeta / (omega * dt) * c)) / k
    a1 = -e * omega / root * s
    b1 = e * (c - z * s)
    c1 = (-1.0 / dt + e * ((omega / root + z / dt) * s + c / dt)) / k
    d1 = (1.0 - e * (z * s + c)) / (k * dt)
    u = np.zeros(p.size)
    v = np.zeros(p.size)
    for i in range(p.size - 1):
        u[i + 1] = a * u[i] + b * v[i] + cc * p[i] + d * p[i + 1]
        v[i + 1] = a1 * u[i] + b1 * v[i] + c1 * p[i] + d1 * p[i + 1]
    return u, v


def response(p, dt, omega, zeta):
    """Relative displacement u [m] and velocity u' [m/s] at the samples of the piecewise-linear
    force per unit mass ``p`` [m/s^2] sampled every ``dt`` [s], from rest; ``omega``
    [rad/s] > 0, 0 <= ``zeta`` < 1."""
    return _response(np.ascontiguousarray(p, dtype=np.float64), float(dt), float(omega),
                     float(zeta))


def pseudo_acceleration(samples, dt, period, damping=DAMPING):
    """Sa(T, zeta) [m/s^2] = (2 pi/T)^2 max |u| of a ground acceleration [m/s^2] sampled every
    ``dt`` [s], followed by one ``period`` [s] of still ground; the PGA for T = 0."""
    a = np.asarray(samples, dtype=np.float64)
    if period == 0.0:
        return float(np.max(np.abs(a)))
    omega = 2.0 * math.pi / period
    ground = np.concatenate([a, np.zeros(math.ceil(period / dt) + 1)])
    u, _ = response(-ground, dt, omega, damping)
    return float(omega * omega * np.max(np.abs(u)))
