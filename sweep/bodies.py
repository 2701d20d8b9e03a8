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
(i^2 = r^2/3).  Inputs may be numpy arrays; symbols as PHYSICS.md 1.1.
"""
from collections import namedtuple

import numpy as np

from kernels.codes import G  # standard gravity [m/s^2], the kernel's

BodyConstants = namedtuple("BodyConstants", "b h r alpha i2 p eta")
BodyConstants.__doc__ = """Derived constants of a rectangular body (PHYSICS.md 1.1, 2.1).

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
    PHYSICS.md 1.1 (notation) and 2.1 (eta).
    """
    b, h = 0.5 * np.asarray(B, float), 0.5 * np.asarray(H, float)
    r2 = b * b + h * h
    i2 = _i2(B, H, i_g)
    return BodyConstants(b=b, h=h, r=np.sqrt(r2), alpha=np.arctan2(b, h), i2=i2,
                         p=np.sqrt(g * np.sqrt(r2) / (i2 + r2)),
                         eta=1.0 - 2.0 * b * b / (i2 + r2))


def west_acceleration(B, H, g=G):
    """West's acceleration to initiate rocking, a = (b/h) g, Eq. (1) [m/s^2]."""
    return np.asarray(B, float) / np.asarray(H, float) * g


def single_shock_velocity(B, H, i_g=None, g=G):
    """Velocity v_H of a single horizontal shock that overturns the body, Eqs. (9)/(10) [m/s].

    v_H^2 = (2g/r)(i^2 + r^2)(1 - cos alpha)/cos^2 alpha; with ``i_g=None`` (i^2 + r^2 = 4r^2/3)
    this is Eq. (10).  It is the unit of the normalized velocity (the ``v_H`` unit of scene files).
    """
    c = body_constants(B, H, i_g, g)
    cos_a = np.cos(c.alpha)
    return np.sqrt(2.0 * g / c.r * (c.i2 + c.r ** 2) * (1.0 - cos_a) / cos_a ** 2)
