"""The likelihood of a site's levels and their posterior.

A part of ``sweep.probability.site`` (docs/probability.md section 6).

o_ijm in {0, 1} says whether body i overturned under member m of the ensemble scaled to level
x_j; the bodies seen overturned (set O) bound the shaking from below, those left standing (set
S) from above.

* **Site likelihood.**  The observation as a whole is reproduced by member m at level x_j when
  c_jm = prod_{i in O} o_ijm prod_{i in S} (1 - o_ijm) = 1.  The likelihood of x_j is the
  ensemble average L(x_j) = mean_m c_jm, taken directly from the simulations: the bodies
  shaken by the same motion are not independent, and the product of their marginal
  probabilities is not the likelihood (docs/probability.md section 6).
* **Posterior.**  Prior uniform in ln x over the levels; L linear in ln x between them, and 0
  at and below West's level of the most demanding overturned body, a_o = (B/H) g, below which
  no body rocks without vertical motion (a knot added there).  The posterior density in ln x
  is L normalised; its quantiles at the stated probabilities are the site's PGA bounds.  The
  PGV bounds are quantiles of the same posterior carried over to each member's PGV (its
  PGV/PGA is fixed by the record; ln PGV is linear in ln x between levels), so they hold for
  the ensemble's mix of PGV/PGA.  Where the likelihood is not 0 at the lowest (highest)
  level, the posterior is cut there by the range of levels, not by the bodies:
  ``cut_below`` and ``cut_above`` say so.
* **Support.**  The posterior is only as good as the simulations that reproduce every
  observation (c_jm = 1).  With one such simulation its shape is the triangle of the linear
  interpolation between the two levels around it, and its percentiles restate the spacing of
  the levels: with 12 levels and with 24 they differ by a factor 1.5.  The estimate says how
  many simulations, at how many levels, carry the likelihood (:class:`Support`), and gives no
  percentiles below :data:`MIN_MATCHES` simulations or :data:`MIN_LEVELS` levels; it says
  where more levels would help (between the levels around those with L > 0) and that more
  members would.

SI units throughout.
"""
import math
from dataclasses import dataclass

import numpy as np

# The fewest simulations reproducing every body, and the fewest levels with L > 0, that give
# posterior percentiles: fewer, and the percentiles restate the spacing of the levels.
MIN_MATCHES = 5
MIN_LEVELS = 3


def consistency(overturned, observed):
    """c_jm = prod_{i in O} o_ijm prod_{i in S} (1 - o_ijm): member m at level j reproduces
    every observation.

    Parameters
    ----------
    overturned : ndarray, shape (bodies, levels, members)
        o_ijm: 1 overturned, 0 standing, NaN failed.
    observed : array_like of bool, shape (bodies,)
        True for the bodies seen overturned.

    Returns
    -------
    ndarray, shape (levels, members)
        1 or 0; NaN where a body's simulation failed.
    """
    o = np.asarray(overturned, dtype=float)
    seen = np.asarray(observed, dtype=bool)[:, None, None]
    return np.prod(np.where(seen, o, 1.0 - o), axis=0)


def likelihood(consistent):
    """L(x_j) = mean over the members of c_jm, failed cells left out; and the members
    counted at each level.  NaN where none counts."""
    c = np.asarray(consistent, dtype=float)
    counted = np.sum(np.isfinite(c), axis=1)
    with np.errstate(invalid="ignore"):
        return np.nansum(c, axis=1) / counted, counted


def with_floor(u, values, floor):
    """Knots ``u`` and ``values`` (along axis 0) with a knot at ``floor`` of value 0 added when
    it lies strictly between two knots: the quantity is 0 there (West's level).  ``values``
    may have more axes (members); their knot is 0 too."""
    u = np.asarray(u, dtype=float)
    values = np.asarray(values, dtype=float)
    if floor is None or not u[0] < floor < u[-1] or np.any(u == floor):
        return u, values
    k = int(np.searchsorted(u, floor))
    return np.insert(u, k, floor), np.insert(values, k, 0.0, axis=0)


@dataclass(frozen=True)
class Pieces:
    """A density in ln x, linear between knots, carried over to a measure w (ln PGA or
    ln PGV) linear in ln x between the same knots: one trapezoid per member and segment.

    ``w0``, ``w1``: ends of each piece in w; ``d0``, ``d1``: density at its ends per unit
    ln x; ``du``: its width in ln x.  Mass of a piece: du (d0 + d1)/2.
    """

    w0: np.ndarray
    w1: np.ndarray
    d0: np.ndarray
    d1: np.ndarray
    du: np.ndarray

    @classmethod
    def build(cls, u, density, measure):
        """Pieces from knots ``u`` (K,), ``density`` (K, M) and ``measure`` w (K, M)."""
        du = np.diff(u)[:, None] * np.ones_like(density[1:])
        return cls(measure[:-1].ravel(), measure[1:].ravel(), density[:-1].ravel(),
                   density[1:].ravel(), du.ravel())

    @property
    def total(self):
        return float(np.sum(self.du * (self.d0 + self.d1)) / 2.0)

    def cdf(self, t):
        """Mass below ``t`` over the total (w increasing within each piece)."""
        f = np.clip((t - self.w0) / (self.w1 - self.w0), 0.0, 1.0)
        return float(np.sum(self.du * (self.d0 * f + (self.d1 - self.d0) * f * f / 2.0))
                     / self.total)

    def quantiles(self, probabilities):
        """The w at which the cdf reaches each probability (exact: within a bracket of
        breakpoints the cdf is a quadratic, solved by Brent's method)."""
        from scipy.optimize import brentq

        edges = np.unique(np.concatenate([self.w0, self.w1]))
        at = np.array([self.cdf(t) for t in edges])
        out = []
        for q in probabilities:
            k = int(np.searchsorted(at, q))
            if k == 0:
                out.append(edges[0])
            elif k == len(edges) or at[k] == q:
                out.append(edges[min(k, len(edges) - 1)])
            else:
                out.append(brentq(lambda t: self.cdf(t) - q, edges[k - 1], edges[k],
                                  xtol=1e-13, rtol=1e-14))
        return np.array(out, dtype=float)


@dataclass(frozen=True)
class Posterior:
    """The posterior of the level (PGA) given every observation at a site.

    Attributes
    ----------
    knots : ndarray, shape (K,)
        PGA [m/s^2] of the levels and of the West knot.
    density : ndarray, shape (K,)
        Posterior density per unit ln PGA at the knots (linear in ln PGA between them).
    pga, pgv : ndarray, shape (Q,)
        Quantiles [m/s^2, m/s] at the probabilities.
    cut_below, cut_above : bool
        The likelihood is not 0 at the lowest (highest) level: the lower (upper) quantiles
        are set by the range of levels, not by the observations.
    """

    knots: np.ndarray
    density: np.ndarray
    pga: np.ndarray
    pgv: np.ndarray
    cut_below: bool
    cut_above: bool


def posterior(levels, consistent, pgv, probabilities, floor=None):
    """The posterior of the level given the observations, and its quantiles.

    Parameters
    ----------
    levels : ndarray, shape (J,)
        PGA levels x_j [m/s^2], increasing.
    consistent : ndarray, shape (J, M)
        c_jm (:func:`consistency`); NaN for failed cells, which take the average of the
        others at their level (they neither add nor remove evidence).
    pgv : ndarray, shape (J, M)
        PGV of member m at level j [m/s].
    probabilities : sequence of float
    floor : float, optional
        West's level [m/s^2] of the most demanding overturned body: the likelihood is 0 at
        and below it.

    Returns
    -------
    Posterior or None
        None when no member reproduces the observations at any level.
    """
    u = np.log(np.asarray(levels, dtype=float))
    c = np.asarray(consistent, dtype=float)
    mean, _ = likelihood(c)
    if not np.nansum(mean) > 0:
        return None
    c = np.where(np.isfinite(c), c, np.nan_to_num(mean)[:, None])
    knots, density = with_floor(u, c, None if floor is None else math.log(floor))
    ln_pga = np.repeat(knots[:, None], c.shape[1], axis=1)
    ln_pgv = np.column_stack([np.interp(knots, u, np.log(pgv[:, m]))
                              for m in range(c.shape[1])])
    by_pga = Pieces.build(knots, density, ln_pga)
    by_pgv = Pieces.build(knots, density, ln_pgv)
    return Posterior(knots=np.exp(knots), density=density.sum(axis=1) / by_pga.total,
                     pga=np.exp(by_pga.quantiles(probabilities)),
                     pgv=np.exp(by_pgv.quantiles(probabilities)),
                     cut_below=bool(mean[0] > 0), cut_above=bool(mean[-1] > 0))


@dataclass(frozen=True)
class Support:
    """What carries the likelihood of a site.

    Attributes
    ----------
    matches : int
        Simulations (member, level) that reproduce every observation (c_jm = 1).
    cells : int
        Simulations counted (failed ones left out).
    levels : int
        Levels at which the likelihood is not 0; ``of_levels``: the levels simulated.
    between : tuple of float or None
        (low, high) [m/s^2]: the levels around those with L > 0, where more levels would
        resolve the posterior; None when no level has L > 0.
    """

    matches: int
    cells: int
    levels: int
    of_levels: int
    between: tuple

    @property
    def sufficient(self):
        """Enough to give percentiles (:data:`MIN_MATCHES`, :data:`MIN_LEVELS`)."""
        return self.matches >= MIN_MATCHES and self.levels >= MIN_LEVELS

    def text(self):
        """'3 of 48 simulations (at 2 of 12 levels)'."""
        return (f"{self.matches} of {self.cells} simulation{'s' if self.cells != 1 else ''} "
                f"(at {self.levels} of {self.of_levels} level{'s' if self.of_levels != 1 else ''})")


def support(levels, consistent):
    """The :class:`Support` of the likelihood of ``consistent`` (J, M) at ``levels`` (J,)."""
    c = np.asarray(consistent, dtype=float)
    hit = np.nansum(c, axis=1) > 0
    where = np.flatnonzero(hit)
    between = None if where.size == 0 else (float(levels[max(where[0] - 1, 0)]),
                                            float(levels[min(where[-1] + 1, len(levels) - 1)]))
    return Support(int(np.nansum(c)), int(np.sum(np.isfinite(c))), int(hit.sum()), len(levels),
                   between)


def support_advice(sup):
    """Why the percentiles are withheld, and what to do (or '' when they are given)."""
    if sup.sufficient:
        return ""
    low, high = sup.between
    return (f"only {sup.text()} reproduce every body; percentiles need at least "
            f"{MIN_MATCHES} simulations at {MIN_LEVELS} levels, else they restate the spacing "
            f"of the levels: add levels between {low * 100:.0f} and {high * 100:.0f} gal, or "
            "more motions")
