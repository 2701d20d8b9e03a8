"""g and the scales of a rectangular body, defined once, at the bottom of ``sweep``.

The units of scene files (``west``, ``v_H``, ``alpha``: ``sweep.io.units``), the record
formats in g (``sweep.io.formats``), the normalized results of a cell (``sweep.runner.cells``)
and the paper's criteria (``sweep.paper.criteria``) all measure a body by the same few numbers.
They live here, in a module of their own below ``groundmotion`` and ``io`` that imports only
numpy and the kernel's ``G`` (from ``kernels.codes``, which loads no numba), so that every layer
can import them without reaching up to ``paper``; a body's scales are not ground motions, hence
not in ``groundmotion``.  ``sweep.paper.criteria`` imports them under the same names:
:func:`west_acceleration` is the paper's Eq. (1), :func:`single_shock_velocity` its
Eqs. (9)/(10).

Every function takes the full breadth ``B`` and height ``H`` [m] (b = B/2, h = H/2) and, where
it uses it, the radius of gyration ``i_g`` about G [m]; ``i_g=None`` means a uniform rectangle
(i^2 = (B^2 + H^2)/12).  Inputs may be numpy arrays; symbols as docs/physics.md 1.1.  A body whose
G is off the middle (``centre`` = (x_G, y_G) from the middle of the base, docs/bodies.md) has
its constants per side (:func:`body_sides`); where one number is asked for (``west``, ``v_H``,
``alpha``), the smaller side's governs: the body tips or overturns first that way.
"""
from collections import namedtuple

import numpy as np

from kernels.codes import G  # standard gravity [m/s^2], the kernel's

BodyConstants = namedtuple("BodyConstants", "b h r alpha i2 p eta")
BodyConstants.__doc__ = """Derived constants of a rectangular body (docs/physics.md 1.1, 2.1).

b, h : half-breadth, half-height [m]; r : corner-centroid distance [m]; alpha : slenderness
angle atan(b/h) [rad]; i2 : i^2 [m^2]; p : frequency parameter sqrt(g r/(i^2 + r^2)) [1/s];
eta : Housner's angular-velocity ratio per impact 1 - 2b^2/(i^2 + r^2) [-]."""


def _i2(B, H, i_g):
    """Squared radius of gyration about G; uniform rectangle when ``i_g`` is None."""
    if i_g is None:
        return (np.square(B) + np.square(H)) / 12.0  # r^2/3 with r^2 = (B^2 + H^2)/4
    return np.square(i_g)


def body_constants(B, H, i_g=None, g=G):
    """Constants b, h, r, alpha, i^2, p and Housner's eta of a rectangular body.

    Parameters
    ----------
    B, H : float or ndarray
        Full breadth and height [m].
    i_g : float or ndarray, optional
        Radius of gyration about G [m]; default uniform rectangle, i^2 = r^2/3.
    g : float
        Gravity [m/s^2].

    Returns
    -------
    BodyConstants

    References
    ----------
    docs/physics.md 1.1 (notation) and 2.1 (eta).
    """
    b, h = 0.5 * np.asarray(B, float), 0.5 * np.asarray(H, float)
    r2 = b * b + h * h
    i2 = _i2(B, H, i_g)
    return BodyConstants(b=b, h=h, r=np.sqrt(r2), alpha=np.arctan2(b, h), i2=i2,
                         p=np.sqrt(g * np.sqrt(r2) / (i2 + r2)),
                         eta=1.0 - 2.0 * b * b / (i2 + r2))


BodySides = namedtuple("BodySides", "b1 b2 h R1 R2 alpha_1 alpha_2 i2 p1 p2 eta_1 eta_2")
BodySides.__doc__ = """Constants of a body per corner, 1 left (-x), 2 right (+x) (docs/bodies.md).

b1, b2 : horizontal distances from G to the corners [m]; h : height of G [m]; R1, R2 : distances
from G to the corners [m]; alpha_1, alpha_2 : atan(b_i/h) [rad]; i2 : i^2 [m^2]; p1, p2 :
sqrt(g R_i/(i^2 + R_i^2)) [1/s]; eta_1, eta_2 : angular-velocity ratio of an impact that makes
corner i the pivot, 1 - b_i (b1 + b2)/(i^2 + R_i^2) [-]."""


def body_sides(B, H, centre=None, i_g=None, g=G):
    """Per-corner constants of a body with G at ``centre`` = (x_G, y_G) from the middle of the
    base (default (0, H/2)): b1 = B/2 + x_G, b2 = B/2 - x_G, h = y_G.  Returns BodySides."""
    B, H = np.asarray(B, float), np.asarray(H, float)
    x, h = (0.0, 0.5 * H) if centre is None else (float(centre[0]), float(centre[1]))
    b1, b2 = 0.5 * B + x, 0.5 * B - x
    i2 = _i2(B, H, i_g)
    R1, R2 = np.hypot(b1, h), np.hypot(b2, h)
    return BodySides(b1=b1, b2=b2, h=h, R1=R1, R2=R2, alpha_1=np.arctan2(b1, h),
                     alpha_2=np.arctan2(b2, h), i2=i2,
                     p1=np.sqrt(g * R1 / (i2 + R1 * R1)), p2=np.sqrt(g * R2 / (i2 + R2 * R2)),
                     eta_1=1.0 - b1 * B / (i2 + R1 * R1), eta_2=1.0 - b2 * B / (i2 + R2 * R2))


def west_acceleration(B, H, g=G, centre=None):
    """West's acceleration to initiate rocking, a = (b/h) g, Eq. (1) [m/s^2]; with G at
    ``centre``, the smaller side's g min(b1, b2)/h."""
    if centre is None:
        return np.asarray(B, float) / np.asarray(H, float) * g
    c = body_sides(B, H, centre)
    return np.minimum(c.b1, c.b2) / c.h * g


def _shock_velocity(R, alpha, i2, g):
    """v_H about a corner at distance R and angle alpha: Eq. (9)."""
    cos_a = np.cos(alpha)
    return np.sqrt(2.0 * g / R * (i2 + R ** 2) * (1.0 - cos_a) / cos_a ** 2)


def single_shock_velocity(B, H, i_g=None, g=G, centre=None):
    """Velocity v_H of a single horizontal shock that overturns the body, Eqs. (9)/(10) [m/s].

    v_H^2 = (2g/r)(i^2 + r^2)(1 - cos alpha)/cos^2 alpha; with ``i_g=None`` (i^2 + r^2 = 4r^2/3)
    this is Eq. (10).  It is the unit of the normalized velocity (the ``v_H`` unit of scene files).
    With G at ``centre``, the smaller of the two sides' (R_i, alpha_i).
    """
    if centre is None:
        c = body_constants(B, H, i_g, g)
        return _shock_velocity(c.r, c.alpha, c.i2, g)
    c = body_sides(B, H, centre, i_g, g)
    return np.minimum(_shock_velocity(c.R1, c.alpha_1, c.i2, g),
                      _shock_velocity(c.R2, c.alpha_2, c.i2, g))


def slenderness(B, H, centre=None):
    """The slenderness angle alpha = atan(B/H) [rad]; with G at ``centre``, the smaller side's
    min(alpha_1, alpha_2)."""
    if centre is None:
        return np.arctan2(0.5 * np.asarray(B, float), 0.5 * np.asarray(H, float))
    c = body_sides(B, H, centre)
    return np.minimum(c.alpha_1, c.alpha_2)


def describe(B, H, centre=None, i_g=None):
    """The body as the JSON echoes it, in both forms: B, H, G = [x_G, y_G] (default
    [0, H/2]), i_g (``i_g_default``: the uniform rectangle's sqrt((B^2 + H^2)/12)), and the rock
    literature's alpha_1, alpha_2 [rad], R_1, R_2 [m]."""
    c = body_sides(B, H, centre, i_g)
    x = 0.0 if centre is None else float(centre[0])
    return {"B": float(B), "H": float(H), "G": [x, float(c.h)], "i_g": float(np.sqrt(c.i2)),
            "i_g_default": i_g is None, "alpha_1": float(c.alpha_1),
            "alpha_2": float(c.alpha_2), "R_1": float(c.R1), "R_2": float(c.R2)}
