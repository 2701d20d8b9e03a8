"""What bodies seen at a site tell of its shaking, in probability (docs/probability.md section 6).

Every body of a site is simulated under an ensemble of motions (records, or synthetic motions
of a scenario), each motion scaled to a set of PGA levels x_j.  o_ijm in {0, 1} says whether
body i overturned under member m scaled to x_j.  The bodies seen overturned (set O) bound the
shaking from below, those left standing (set S) from above:

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
* **Per body.**  Fragility P_i(x_j) = fraction of the members that overturned it, with a 95 %
  Wilson interval; with the same knot at its own a_o.  An overturned body bounds x from below:
  x_lo(q) is the lowest x with P_i(x) = q (overturning below it had probability < q).  A
  standing body bounds x from above: x_hi(q) is the highest x with 1 - P_i(x) = q (above it,
  it survives with probability < q): the precarious-rock argument (Brune 1996; Purvance,
  Anooshehpoor & Brune 2008, EESD 37).  Both are
  interpolated in ln x; a bound outside the levels is said so (``beyond``: ``below`` the
  lowest level, ``above`` the highest).
* **(PGA, PGV) map.**  Each (member, level) is a point (PGA, PGV) of the scaled motion; its
  indicator c_jm.  The probability that a motion of (PGA, PGV) is consistent with every
  observation is the Gaussian-kernel (Nadaraya-Watson) average of c in (ln PGA, ln PGV/PGA),
  bandwidths the spacing of ln x and max(that, 1.06 sigma M^-1/5) (sigma: the spread of
  ln PGV/PGA over the M members), left blank where the kernel weights sum to less than
  :data:`MAP_SUPPORT`.  The region at level q is where it is at least q.  A probit surface
  cannot hold a band bounded on both sides (overturned below, standing above): hence the
  kernel average.
* **Sliding.**  A body whose friction coefficient (given, or the ensemble's default) is below
  B/H slides before it rocks (Ishiyama 1982, conclusion 1): it is kept out of the likelihood,
  not simulated, and listed with the reason.  A body that slid (``slid`` = 1) in most of the
  simulations at the two levels around its 50 % bound is flagged.

The simulations (one study per distinct body, run or reused: ``site_studies``) give o_ijm;
the text and JSON of an estimate are ``site_report``'s.  SI units throughout.
"""
import math
from collections import namedtuple
from dataclasses import dataclass, field

import numpy as np

from ..paper import criteria
from .site_studies import (friction, member_labels, simulated_time, sliding_reason, specimen,
                           specimen_key)

MAP_POINTS = 121  # grid points along each axis of the (PGA, PGV) map
MAP_SUPPORT = 0.5  # the map is blank where the kernel weights (1 at a point) sum below this
SILVERMAN = 1.06  # normal-reference factor of the bandwidth in ln PGV/PGA
SLID_MOST = 0.5  # a body is flagged when more than this fraction of the cells near its bound slid
# The fewest simulations reproducing every body, and the fewest levels with L > 0, that give
# posterior percentiles: fewer, and the percentiles restate the spacing of the levels.
MIN_MATCHES = 5
MIN_LEVELS = 3
WILSON_CONFIDENCE = 0.95

Bound = namedtuple("Bound", "value beyond")
Bound.__doc__ = """A bound [SI]: ``value``, or None when it lies above the highest level;
``beyond`` None inside the levels, ``"below"`` when it is at or below the lowest level (then
``value`` is that level), ``"above"`` when no level reaches it."""



# --- the likelihood and the posterior ---------------------------------------------------------

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


# --- one body ---------------------------------------------------------------------------------

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


# --- the (PGA, PGV) map -----------------------------------------------------------------------

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


# --- a site -----------------------------------------------------------------------------------

@dataclass(frozen=True)
class SiteEstimate:
    """What the bodies of one site tell under the ensemble (see the module).

    Attributes
    ----------
    site : io.bodies_schema.Site
    ensemble : io.bodies_schema.Ensemble
    members : list of str
        Labels of the motions.
    bodies : list of BodyEstimate
        The bodies that rock (kept in the likelihood), in the file's order.
    excluded : list of (str, str)
        Name and reason of the bodies kept out (they slide).
    likelihood : ndarray, shape (J,)
        L(x_j); ``counted``: the members counted at each level.
    posterior : Posterior or None
    reason : str
        Why there is no posterior ('' when there is one).
    west_floor : float or None
        a_o of the most demanding overturned body [m/s^2].
    map : ConsistencyMap or None
    support : Support or None
        What carries the likelihood (None: no body rocks).
    failed_cells : int
    t_end : float
        Simulated time [s].
    datasets : list of str
        The datasets read, one per body that rocks.
    """

    site: object
    ensemble: object
    members: list
    bodies: list
    excluded: list
    likelihood: np.ndarray
    counted: np.ndarray
    posterior: Posterior
    reason: str
    west_floor: float
    map: ConsistencyMap
    support: Support
    failed_cells: int
    t_end: float
    datasets: list = field(default_factory=list)

    @property
    def quantiles(self):
        """The posterior's (pga, pgv) at the probabilities, or None when there is no
        posterior or too little :class:`Support` for percentiles."""
        if self.posterior is None or not self.support.sufficient:
            return None
        return self.posterior.pga, self.posterior.pgv


def _cells(ds, name):
    """A variable of a specimen's dataset as float (levels, members), NaN where failed."""
    values = ds[name].transpose("pga", ...).values.astype(float)
    return np.where(values < 0, np.nan, values)


def estimate_site(site, ensemble, datasets):
    """The probabilistic estimate of one site from the datasets of its specimens.

    Parameters
    ----------
    site : io.bodies_schema.Site
    ensemble : io.bodies_schema.Ensemble
    datasets : dict of str to xarray.Dataset
        {specimen key: dataset} (``site_studies.ensemble_datasets``), with dimensions
        ``pga`` and the members' (``record`` or ``seed``).

    Returns
    -------
    SiteEstimate
    """
    excluded, rocking = [], []
    for body in site.bodies:
        reason = sliding_reason(body, ensemble)
        if reason is None:
            rocking.append(body)
        else:
            excluded.append((body.name, reason))
    levels = np.asarray(ensemble.levels)
    common = {"site": site, "ensemble": ensemble, "members": member_labels(ensemble),
              "excluded": excluded, "t_end": simulated_time(ensemble)}
    if not rocking:
        return SiteEstimate(**common, bodies=[], likelihood=np.full(levels.size, np.nan),
                            counted=np.zeros(levels.size, int), posterior=None,
                            reason="no body that rocks: every body slides (mu < B/H)",
                            west_floor=None, map=None, support=None, failed_cells=0)
    keys = [specimen_key(specimen(b, ensemble)) for b in rocking]
    overturned = np.stack([_cells(datasets[k], "overturned") for k in keys])
    slid = np.stack([_cells(datasets[k], "slid") for k in keys])
    bodies = [body_estimate(b, ensemble, o, s) for b, o, s in zip(rocking, overturned, slid)]
    consistent = consistency(overturned, [b.overturned for b in rocking])
    mean, counted = likelihood(consistent)
    pgv = _cells(datasets[keys[0]], "pgv")
    pga = np.broadcast_to(levels[:, None], pgv.shape).copy()
    floor = max((b.west for b in bodies if b.overturned), default=None)
    post = posterior(levels, consistent, pgv, ensemble.probabilities, floor)
    reason = "" if post is not None else (
        "no member reproduces every observation at any level: the bodies seen contradict "
        "each other under this ensemble (or the levels miss the band where they agree)")
    return SiteEstimate(**common, bodies=bodies, likelihood=mean, counted=counted,
                        posterior=post, reason=reason, west_floor=floor,
                        support=support(levels, consistent),
                        map=consistency_map(levels, pga, pgv, consistent,
                                            ensemble.probabilities),
                        failed_cells=int(np.sum(~np.isfinite(overturned))),
                        datasets=[str(datasets[k].encoding.get("source", k)) for k in keys])
