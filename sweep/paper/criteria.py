"""Closed-form overturning criteria of Ishiyama (1982), Eqs. (1)-(21), in SI units.

Every function takes the full breadth ``B`` and height ``H`` [m] of a rectangular body (b = B/2,
h = H/2) and, where the paper uses it, the radius of gyration ``i_g`` about G [m]; ``i_g=None``
means a uniform rectangle (i^2 = r^2/3).  Energies are per unit mass.  Inputs may be numpy arrays.
Equation numbers are the paper's (Ishiyama 1982); symbols as docs/physics.md 1.1.
``G``, :func:`body_constants`, West's acceleration (Eq. 1, :func:`west_acceleration`) and the
single-shock velocity v_H (Eqs. 9/10, :func:`single_shock_velocity`) are the body's scales that
the units of scene files need too: they are defined in ``sweep.bodies``, below ``io``, and
imported here under the same names.
"""
from collections import namedtuple

import numpy as np

from ..bodies import G, BodyConstants, body_constants, single_shock_velocity, west_acceleration

V_FACTOR = 0.4  # Ishiyama's empirical lower limit of the normalized velocity (point P)
POINT_P = (V_FACTOR, 1.0)  # (v/v_H, a/((B/H) g)) of the paper's point P

IshiyamaLimits = namedtuple("IshiyamaLimits", "a_o v_o d_o T_c")
IshiyamaLimits.__doc__ = """Lower limits a_o [m/s^2], v_o [m/s], d_o [m] and the period T_c [s]."""

# Eq. (1), West's acceleration (b/h) g: west_acceleration, from sweep.bodies.


def mononobe_coefficients(k_x, k_y):
    """Mononobe's combined seismic coefficients K, K' = k_x/(1 -+ k_y), Eq. (2).

    Parameters
    ----------
    k_x, k_y : float or ndarray
        Horizontal and vertical seismic coefficients (accelerations / g).

    Returns
    -------
    K, K_prime : float or ndarray
        K with the vertical acceleration lowering the effective gravity to g(1 - k_y), K' with
        it raising it to g(1 + k_y).  Rocking starts when the coefficient exceeds b/h.
    """
    k_x, k_y = np.asarray(k_x, float), np.asarray(k_y, float)
    return k_x / (1.0 - k_y), k_x / (1.0 + k_y)


def kirkpatrick_acceleration(B, H, t_1, i_g=None, g=G):
    """Acceleration amplitude of a half-sine pulse of duration ``t_1`` that overturns, Eq. (3).

    a = alpha g sqrt(1 + (i^2 + r^2)/(g r) (pi/t_1)^2) [m/s^2]; small-alpha (linearized) result.
    """
    c = body_constants(B, H, i_g, g)
    return c.alpha * g * np.sqrt(1.0 + (np.pi / np.asarray(t_1, float) / c.p) ** 2)


def housner_overturn_time(B, H, a, i_g=None, g=G):
    """Duration t_o of a constant acceleration ``a`` that overturns the body, Eq. (4) [s].

    cosh(p t_o) = 1 + 1/(2 x (x - 1)) with x = a/(g alpha) and p = sqrt(g r/(i^2 + r^2)): after the
    acceleration stops the body still escapes (small-alpha, linearized).  The printed exponent
    sqrt(g alpha/(i^2 + r^2)) has the dimension 1/sqrt(m s^2); p is the form the derivation
    gives (the linearized escape condition e^(p t_o) = x/(x - 1) of docs/physics.md A8, whose
    cosh is the right-hand side above).  NaN when a <= g alpha (the body never overturns).
    """
    c = body_constants(B, H, i_g, g)
    x = np.asarray(a, float) / (g * c.alpha)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(x > 1.0, np.arccosh(1.0 + 1.0 / (2.0 * x * (x - 1.0))) / c.p, np.nan)


def potential_energy(B, H, g=G):
    """Energy per unit mass to lift G over the base edge, g r (1 - cos alpha), Eq. (5) [J/kg]."""
    c = body_constants(B, H, None, g)
    return g * c.r * (1.0 - np.cos(c.alpha))


def kinetic_energy(B, H, omega, i_g=None):
    """Kinetic energy per unit mass about a base edge, (i^2 + r^2) omega^2/2, Eq. (6) [J/kg]."""
    c = body_constants(B, H, i_g)
    return 0.5 * (c.i2 + c.r ** 2) * np.square(omega)


def overturning_angular_velocity(B, H, i_g=None, g=G):
    """Angular velocity about a base edge that just lifts G over it, Eq. (7) [rad/s]."""
    c = body_constants(B, H, i_g, g)
    return np.sqrt(2.0 * g * c.r * (1.0 - np.cos(c.alpha)) / (c.i2 + c.r ** 2))


def shock_angular_velocity(B, H, v, i_g=None):
    """Angular velocity after a translation at ``v`` is stopped at a base edge, Eq. (8) [rad/s].

    Angular momentum about the edge is conserved: v h = (i^2 + r^2) omega.
    """
    c = body_constants(B, H, i_g)
    return np.asarray(v, float) * c.h / (c.i2 + c.r ** 2)


# Eqs. (9)/(10), the single-shock velocity v_H: single_shock_velocity, from sweep.bodies.


def single_shock_velocity_small_angle(B, H, g=G):
    """Small-alpha form of Eq. (10) for a uniform rectangle, v^2 = 4 g b alpha/3, Eq. (11) [m/s]."""
    c = body_constants(B, H, None, g)
    return np.sqrt(4.0 * g * c.b * c.alpha / 3.0)


def omori_displacement(B, H, i_g=None):
    """Omori's floor displacement 2d (twice the amplitude) that overturns, Eqs. (12)/(13) [m].

    2d = b (i^2 + r^2)/h^2; for a uniform rectangle (``i_g=None``) 4 r^2 b/(3 h^2), which is
    Eq. (13) with the h^2 that Eq. (12) gives (the transcription prints h, which would make 2d an
    area).  The paper notes that the formula has not been verified.
    """
    c = body_constants(B, H, i_g)
    return c.b * (c.i2 + c.r ** 2) / c.h ** 2


def ishiyama_acceleration(B, H, g=G):
    """Lower limit a_o = (B/H) g of the peak floor acceleration to overturn, Eq. (14) [m/s^2]."""
    return west_acceleration(B, H, g)


def ishiyama_velocity(B, H, i_g=None, g=G):
    """Lower limit v_o = 0.4 v_H of the peak floor velocity to overturn, Eqs. (15)/(16) [m/s]."""
    return V_FACTOR * single_shock_velocity(B, H, i_g, g)


def ishiyama_velocity_approx(B, H):
    """Slender-body rule v_o ~ 10 B/sqrt(H) [cm/s with B, H in cm], Eq. (17); returned in m/s.

    In SI the rule reads v_o = B/sqrt(H) (B, H in m, v_o in m/s).
    """
    B_cm, H_cm = 100.0 * np.asarray(B, float), 100.0 * np.asarray(H, float)
    return 0.01 * 10.0 * B_cm / np.sqrt(H_cm)


def ishiyama_displacement(B, H, i_g=None, g=G):
    """Lower limit d_o = v_o^2/a_o of the peak floor displacement to overturn, Eq. (18) [m].

    The relation behind it is that of a sinusoid, v^2 = a d (the transcription prints
    v_o^2 = a_o^2 d_o, which is not homogeneous in units).
    """
    return ishiyama_velocity(B, H, i_g, g) ** 2 / ishiyama_acceleration(B, H, g)


def ishiyama_displacement_approx(B):
    """Slender-body rule d_o ~ B/10, Eq. (19) [m].

    The small-alpha limit of Eq. (18) is d_o = (0.32/3) B = 0.1067 B, in any units.
    """
    return np.asarray(B, float) / 10.0


def critical_period(B, H, i_g=None, g=G):
    """Period T_c = 2 pi v_o/a_o at point P of the normalized plane, Eq. (20) [s].

    The paper prints T_c = 2 pi a_o/v_o = 2 pi v_o/d_o, which has the dimension of a frequency
    (docs/physics.md A11).  The period at which a sinusoid of acceleration amplitude a_o has
    velocity amplitude v_o is 2 pi v_o/a_o = 2 pi d_o/v_o, and that is what is returned.
    """
    return 2.0 * np.pi * ishiyama_velocity(B, H, i_g, g) / ishiyama_acceleration(B, H, g)


def critical_period_approx(H):
    """Slender-body rule T_c ~ sqrt(H)/16 [s with H in cm], Eq. (21); returned in s for H in m.

    The transcription of the paper reads sqrt(H/16); the small-alpha limit of Eq. (20),
    T_c = 0.8 pi sqrt(2H/(3g)) = 0.0655 sqrt(H) [cm, s], shows the intended form is sqrt(H)/16.
    """
    return np.sqrt(100.0 * np.asarray(H, float)) / 16.0


def ishiyama_limits(B, H, i_g=None, g=G):
    """The lower limits a_o, v_o, d_o and the period T_c of Eqs. (14), (15), (18), (20)."""
    a_o = ishiyama_acceleration(B, H, g)
    v_o = ishiyama_velocity(B, H, i_g, g)
    return IshiyamaLimits(a_o=a_o, v_o=v_o, d_o=v_o ** 2 / a_o, T_c=2.0 * np.pi * v_o / a_o)


def normalized_plane(A, f, B, H, i_g=None, g=G):
    """Coordinates of a sinusoid in the paper's plane (Figs. 6-11).

    Parameters
    ----------
    A : float or ndarray
        Acceleration amplitude [m/s^2].
    f : float or ndarray
        Frequency [Hz].

    Returns
    -------
    x, y : float or ndarray
        Normalized acceleration A/((b/h) g) and normalized velocity (A/(2 pi f))/v_H; Ishiyama's
        point P is (1, 0.4).
    """
    A = np.asarray(A, float)
    return (A / west_acceleration(B, H, g),
            A / (2.0 * np.pi * np.asarray(f, float)) / single_shock_velocity(B, H, i_g, g))
