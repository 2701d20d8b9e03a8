"""The (PGA, PGV) map of a site (``sweep.probability.site``, docs/probability.md section 6).

Each (member, level) is a point (PGA, PGV) of the scaled motion; its indicator c_jm
(``site_posterior.consistency``).  The probability that a motion of (PGA, PGV) is consistent
with every observation is the Gaussian-kernel (Nadaraya-Watson) average of c in
(ln PGA, ln PGV/PGA), bandwidths the spacing of ln x and max(that, 1.06 sigma M^-1/5) (sigma:
the spread of ln PGV/PGA over the M members), left blank where the kernel weights sum to less
than :data:`MAP_SUPPORT`.  The region at level q is where it is at least q.  A probit surface
cannot hold a band bounded on both sides (overturned below, standing above): hence the kernel
average.

SI units throughout.
"""
from dataclasses import dataclass

import numpy as np

MAP_POINTS = 121  # grid points along each axis of the (PGA, PGV) map
MAP_SUPPORT = 0.5  # the map is blank where the kernel weights (1 at a point) sum below this
SILVERMAN = 1.06  # normal-reference factor of the bandwidth in ln PGV/PGA


@dataclass(frozen=True)
class ConsistencyMap:
    """The probability that a motion of (PGA, PGV) reproduces every observation.

    Attributes
    ----------
    pga, pgv : ndarray, shape (A,), (V,)
        The map's axes [m/s^2, m/s], log-spaced over the simulated points.
    probability : ndarray, shape (V, A)
        Kernel average of the indicator; NaN where the points are too few (see the module).
    bandwidth : tuple of float
        In ln PGA and in ln PGV/PGA.
    points_pga, points_pgv, consistent : ndarray, shape (J, M)
        The simulated points and their indicator c_jm (NaN: failed).
    regions : tuple
        At each probability q: ``(pga_min, pga_max, pgv_min, pgv_max)`` of the map where the
        probability is at least q, or None where it never is.
    """

    pga: np.ndarray
    pgv: np.ndarray
    probability: np.ndarray
    bandwidth: tuple
    points_pga: np.ndarray
    points_pgv: np.ndarray
    consistent: np.ndarray
    regions: tuple


def bandwidths(levels, pga, pgv):
    """Kernel bandwidths in ln PGA (the spacing of ln x) and in ln PGV/PGA (Silverman's
    normal reference over the members' mean ln PGV/PGA, no narrower than the first)."""
    h_pga = float(np.median(np.diff(np.log(levels))))
    ratio = np.nanmean(np.log(pgv / pga), axis=0)
    spread = float(np.std(ratio, ddof=1)) if ratio.size > 1 else 0.0
    return h_pga, max(h_pga, SILVERMAN * spread * ratio.size ** -0.2)


def consistency_map(levels, pga, pgv, consistent, probabilities, points=MAP_POINTS):
    """The :class:`ConsistencyMap` of the points (pga, pgv) with indicators ``consistent``,
    all of shape (J, M)."""
    h_a, h_r = bandwidths(levels, pga, pgv)
    keep = np.isfinite(consistent)
    s_i, r_i = np.log(pga[keep]), np.log(pgv[keep] / pga[keep])
    c_i = consistent[keep]
    axis_a = np.geomspace(np.min(pga), np.max(pga), points)
    axis_v = np.geomspace(np.min(pgv), np.max(pgv), points)
    s = np.log(axis_a)[None, :, None]
    r = np.log(axis_v)[:, None, None] - s
    weight = np.exp(-0.5 * ((s - s_i) / h_a) ** 2 - 0.5 * ((r - r_i) / h_r) ** 2)
    total = weight.sum(axis=2)
    with np.errstate(invalid="ignore", divide="ignore"):
        probability = np.where(total >= MAP_SUPPORT, (weight * c_i).sum(axis=2) / total, np.nan)
    regions = []
    for q in probabilities:
        inside = probability >= q
        if not inside.any():
            regions.append(None)
            continue
        rows, cols = np.nonzero(inside)
        regions.append((axis_a[cols.min()], axis_a[cols.max()], axis_v[rows.min()],
                        axis_v[rows.max()]))
    return ConsistencyMap(axis_a, axis_v, probability, (h_a, h_r), pga, pgv, consistent,
                          tuple(regions))
