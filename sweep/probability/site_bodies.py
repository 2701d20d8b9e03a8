"""What one body of a site tells of its shaking.

A part of ``sweep.probability.site`` (docs/probability.md section 6).

Fragility P_i(x_j) = fraction of the members that overturned it, with a 95 % Wilson interval;
0 at and below its own West level a_o = (B/H) g (a knot, as in ``site_posterior``).  An
overturned body bounds x from below: x_lo(q) is the lowest x with P_i(x) = q (overturning below
it had probability < q).  A standing body bounds x from above: x_hi(q) is the highest x with
1 - P_i(x) = q (above it, it survives with probability < q): the precarious-rock argument
(Brune 1996; Purvance, Anooshehpoor & Brune 2008, EESD 37).  Both are interpolated in ln x; a
bound outside the levels is said so (``beyond``: ``below`` the lowest level, ``above`` the
highest).

A body that slid (``slid`` = 1) in most of the simulations at the two levels around its 50 %
bound is flagged.  SI units throughout.
"""
import math
from collections import namedtuple
from dataclasses import dataclass

import numpy as np

from ..paper import criteria
from .site_posterior import with_floor
from .site_studies import friction

SLID_MOST = 0.5  # a body is flagged when more than this fraction of the cells near its bound slid
WILSON_CONFIDENCE = 0.95

Bound = namedtuple("Bound", "value beyond")
Bound.__doc__ = """A bound [SI]: ``value``, or None when it lies above the highest level;
``beyond`` None inside the levels, ``"below"`` when it is at or below the lowest level (then
``value`` is that level), ``"above"`` when no level reaches it."""


def _crossing(u, p, q, first):
    """Where ``p`` (at knots ``u``) crosses ``q``, interpolated in u.

    ``first``: the lowest u at which p reaches q (a fragility rising through q: a lower
    bound); else the highest u at which p still reaches q (a survival falling through q: an
    upper bound), so that p stays below q above it.  Returns ``(u or None, beyond, (k0, k1))``
    with ``beyond`` as in :class:`Bound` and the knots bracketing the crossing (None above).
    """
    p = np.asarray(p, dtype=float)
    if first:
        reached = np.flatnonzero(p >= q)
        if reached.size == 0:
            return None, "above", None
        k = int(reached[0])
        if k == 0:
            return u[0], "below", (0, 0)
        t = (q - p[k - 1]) / (p[k] - p[k - 1])
        return u[k - 1] + t * (u[k] - u[k - 1]), None, (k - 1, k)
    held = np.flatnonzero(p >= q)  # p is the survival here: the last knot where it holds
    if held.size == 0:
        return u[0], "below", (0, 0)
    k = int(held[-1])
    if k == len(u) - 1:
        return None, "above", None
    t = (p[k] - q) / (p[k] - p[k + 1])
    return u[k] + t * (u[k + 1] - u[k]), None, (k, k + 1)


def body_bound(levels, fragility, q, overturned, west=None):
    """The bound on the level that one body gives at probability ``q``.

    Parameters
    ----------
    levels : ndarray, shape (J,)
        PGA levels [m/s^2], increasing.
    fragility : ndarray, shape (J,)
        P_i(x_j), the fraction of members that overturned the body.
    q : float
    overturned : bool
        Seen overturned: the lower bound x_lo(q), the lowest x with P_i(x) = q; seen
        standing: the upper bound x_hi(q), the highest x with 1 - P_i(x) = q.
    west : float, optional
        The body's a_o = (B/H) g: P_i is 0 at and below it (a knot of value 0).

    Returns
    -------
    Bound
    """
    counted = np.isfinite(fragility)  # a level whose every simulation failed says nothing
    u, p = with_floor(np.log(levels)[counted], np.asarray(fragility)[counted],
                      None if west is None else math.log(west))
    if overturned:
        x, beyond, _ = _crossing(u, p, q, first=True)
    else:
        x, beyond, _ = _crossing(u, 1.0 - p, q, first=False)
    return Bound(None if x is None else float(math.exp(x)), beyond)


@dataclass(frozen=True)
class BodyEstimate:
    """One body of a site under the ensemble.

    Attributes
    ----------
    name : str
    overturned : bool
        As seen.
    B, H, mu : float
        Size [m] and the friction coefficient simulated.
    mu_given : bool
        ``mu`` is the body's own, not the ensemble's default.
    west : float
        a_o = (B/H) g [m/s^2].
    fragility, lower, upper : ndarray, shape (J,)
        P_i(x_j) and its 95 % Wilson interval.
    members : ndarray of int, shape (J,)
        Members counted at each level (failed cells left out).
    bounds : tuple of Bound
        At each probability: x_lo(q) for an overturned body, x_hi(q) for a standing one.
    slid : float
        Fraction of the cells at the two levels around the 50 % bound in which the body slid
        (NaN without such a bound).
    """

    name: str
    overturned: bool
    B: float
    H: float
    mu: float
    mu_given: bool
    west: float
    fragility: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    members: np.ndarray
    bounds: tuple
    slid: float

    @property
    def slid_near_bound(self):
        """True when the body slid in most of the simulations near its bound."""
        return bool(self.slid > SLID_MOST)


def body_estimate(body, ensemble, overturned, slid):
    """A :class:`BodyEstimate` from the body's outcomes.

    Parameters
    ----------
    body : io.bodies_schema.Body
    ensemble : io.bodies_schema.Ensemble
    overturned, slid : ndarray, shape (J, M)
        1/0 per level and member, NaN for failed cells.
    """
    from .intervals import wilson_interval

    levels = np.asarray(ensemble.levels)
    k = np.nansum(overturned, axis=1)
    n = np.sum(np.isfinite(overturned), axis=1)
    with np.errstate(invalid="ignore"):
        p = k / n
    lower, upper = wilson_interval(k, n, WILSON_CONFIDENCE)
    west = float(criteria.west_acceleration(body.B, body.H))
    bounds = tuple(body_bound(levels, p, q, body.overturned, west)
                   for q in ensemble.probabilities)
    u = np.log(levels)
    target = p if body.overturned else 1.0 - p
    _, _, bracket = _crossing(u, target, 0.5, first=body.overturned)
    near = np.nan if bracket is None else float(np.nanmean(slid[list(set(bracket))]))
    return BodyEstimate(name=body.name, overturned=body.overturned, B=body.B, H=body.H,
                        mu=friction(body, ensemble), mu_given=body.mu is not None, west=west,
                        fragility=p, lower=np.asarray(lower, float),
                        upper=np.asarray(upper, float), members=n, bounds=bounds, slid=near)
