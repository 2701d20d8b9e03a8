"""Hazard of point and area sources with a truncated Gutenberg-Richter recurrence, and its
disaggregation by magnitude and distance (docs/probability.md §9).

The rate at which the intensity measure exceeds x at the site (Cornell 1968; McGuire 2004):

    λ(x) = Σ_sources ν Σ_m Σ_p P_m w_p [1 − Φ((ln x − μ(m, r_p)) / σ(m, r_p))]        (1)

ν the rate of earthquakes with M ≥ m_min, P_m the probability of magnitude bin m under the
truncated Gutenberg-Richter density (2), w_p the share of point p of the source (1 for a point
source; equal shares over the cells of an area), μ and σ the mean and standard deviation of
ln IM of a ground-motion model (``sweep.probability.gmpe``).  The truncated exponential
density of magnitude, β = b ln 10 (Cosentino, Ficarra & Luzio 1977):

    f(m) = β exp(−β (m − m_min)) / (1 − exp(−β (m_max − m_min))),  m_min ≤ m ≤ m_max       (2)

P_m is the exact mass of f in each bin (a difference of the CDF), the magnitude taken at the
bin's centre.  A ``characteristic`` recurrence puts rate ν on one magnitude.  The
disaggregation at level x is each (magnitude bin, distance bin)'s share of the sum (1)
(Bazzurro & Cornell 1999, BSSA 89), its mean magnitude and distance.  Distances are Rjb
(epicentral) for the model and Rrup = sqrt(Rjb² + depth²) in the disaggregation and the
synthetic motions.  Over an area, the model is evaluated at the distinct distances (to 0.1 km)
or, with more than ``MAX_DISTANCES`` of them, interpolated linearly in ln(Rjb + 1 km) between
``MAX_DISTANCES`` distances.  SI units: m, m/s, m/s² (or m/s for PGV), 1/yr.
"""
from collections import namedtuple
from dataclasses import dataclass

import numpy as np

from . import gmpe
from .hazard_curve import HazardCurve

DM = 0.05  # width of the magnitude bins of (1)
MAX_DISTANCES = 40  # distinct distances of an area evaluated by the model (else interpolated)
DISTANCE_ROUND = 100.0  # m: distances of an area's points equal to this are one distance


@dataclass(frozen=True)
class Recurrence:
    """Earthquakes of a source: ``rate`` ν [1/yr] of M ≥ ``m_min``, truncated
    Gutenberg-Richter with ``b`` up to ``m_max``; or ``characteristic``: rate ν of M = m_min."""

    rate: float
    m_min: float
    m_max: float = None
    b: float = 1.0
    characteristic: bool = False

    @classmethod
    def from_a_value(cls, a, b, m_min, m_max):
        """Gutenberg-Richter log10 N(M ≥ m) = a − b m: ν = 10^(a − b m_min)."""
        return cls(10.0 ** (a - b * m_min), m_min, m_max, b)

    @property
    def beta(self):
        return self.b * np.log(10.0)

    def cdf(self, m):
        """P(M ≤ m) of the truncated density (2)."""
        m = np.clip(np.asarray(m, dtype=float), self.m_min, self.m_max)
        span = -np.expm1(-self.beta * (self.m_max - self.m_min))
        return -np.expm1(-self.beta * (m - self.m_min)) / span

    def pdf(self, m):
        """f(m) of (2), 0 outside [m_min, m_max]."""
        m = np.asarray(m, dtype=float)
        span = -np.expm1(-self.beta * (self.m_max - self.m_min))
        inside = (m >= self.m_min) & (m <= self.m_max)
        return np.where(inside, self.beta * np.exp(-self.beta * (m - self.m_min)) / span, 0.0)

    def bins(self, dm=DM):
        """Magnitude bins: (centres, edges, probabilities) (the last bin may be narrower)."""
        if self.characteristic:
            return (np.array([self.m_min]), np.array([self.m_min, self.m_min]),
                    np.array([1.0]))
        count = max(1, int(np.ceil((self.m_max - self.m_min) / dm - 1e-9)))
        edges = np.minimum(self.m_min + dm * np.arange(count + 1), self.m_max)
        return 0.5 * (edges[1:] + edges[:-1]), edges, np.diff(self.cdf(edges))


@dataclass(frozen=True)
class Source:
    """A source: its recurrence, its points (Rjb [m] of each from the site, their shares
    ``weights`` summing to 1, and the half-size ``cell`` [m] of an area's square cells, 0 for
    a point), the depth [m] and the mechanism."""

    recurrence: Recurrence
    rjb: np.ndarray
    weights: np.ndarray
    depth: float
    mechanism: str = "SS"
    cell: float = 0.0
    xy: np.ndarray = None  # (P, 2) east, north [m] of the points from the site


def point_source(recurrence, distance, depth, mechanism="SS"):
    """A point at epicentral ``distance`` [m] from the site, at ``depth`` [m]."""
    return Source(recurrence, np.array([float(distance)]), np.array([1.0]), float(depth),
                  mechanism, 0.0, np.array([[float(distance), 0.0]]))


def area_source(recurrence, east, north, spacing, depth, mechanism="SS"):
    """A rectangle ``east`` = (x0, x1), ``north`` = (y0, y1) [m] around the site, cut into
    square cells of side ``spacing`` [m] (fewer, larger cells if the side does not divide);
    the rate is shared equally between the cells, each a point at its centre."""
    centres = []
    for lo, hi in (east, north):
        n = max(1, int(round((hi - lo) / spacing)))
        centres.append(lo + (hi - lo) * (np.arange(n) + 0.5) / n)
    x, y = (a.ravel() for a in np.meshgrid(*centres, indexing="ij"))
    return Source(recurrence, np.hypot(x, y), np.full(x.size, 1.0 / x.size), float(depth),
                  mechanism, 0.5 * spacing, np.column_stack([x, y]))


Disaggregation = namedtuple("Disaggregation", "levels magnitudes distance_edges "
                                              "contributions mean_magnitude mean_distance")
Disaggregation.__doc__ = """λ(x) split by magnitude bin and Rrup bin at each level:
``contributions`` [1/yr], shape (levels, magnitudes, distance bins), summing over the last two
axes to λ(x); ``mean_magnitude`` and ``mean_distance`` [m] per level (weighted by the
contributions, the exact Rrup of each point)."""


class SourceModel:
    """The sources around a site with a Vs30 [m/s] and a ground-motion model: the hazard
    curve (1) of an IM and its disaggregation.

    The medians and sigmas of every (magnitude bin, point) are computed once
    (:meth:`terms`); :meth:`exceedance` is then P(IM > x | m, p) times the rate of each.
    """

    def __init__(self, sources, vs30, model="BSSA14", im="pga", dm=DM):
        self.sources, self.vs30, self.model, self.im, self.dm = sources, vs30, model, im, dm
        self._terms = [self._source_terms(s) for s in sources]

    def _source_terms(self, source):
        centres, _, probabilities = source.recurrence.bins(self.dm)
        rjb = np.round(source.rjb / DISTANCE_ROUND) * DISTANCE_ROUND
        distinct, index = np.unique(rjb, return_inverse=True)
        if distinct.size <= MAX_DISTANCES:
            ln_median, sigma = gmpe.predict_grid(self.model, self.im, centres, distinct,
                                                 source.depth, self.vs30, source.mechanism)
            ln_median, sigma = ln_median[:, index], sigma[:, index]
        else:
            grid = np.expm1(np.linspace(np.log1p(distinct[0] / 1e3),
                                        np.log1p(distinct[-1] / 1e3), MAX_DISTANCES)) * 1e3
            g_median, g_sigma = gmpe.predict_grid(self.model, self.im, centres, grid,
                                                  source.depth, self.vs30, source.mechanism)
            u, ug = np.log1p(source.rjb / 1e3), np.log1p(grid / 1e3)
            ln_median = np.array([np.interp(u, ug, row) for row in g_median])
            sigma = np.array([np.interp(u, ug, row) for row in g_sigma])
        rate = source.recurrence.rate * probabilities[:, None] * source.weights[None, :]
        rrup = np.hypot(source.rjb, source.depth)
        return centres, rrup, ln_median, sigma, rate

    def exceedance(self, levels):
        """[(magnitudes, rrup, rates)] per source: rates [1/yr] of (m, p) events exceeding
        each level, shape (levels, M, P)."""
        from scipy.special import ndtr

        log_x = np.log(np.asarray(levels, dtype=float))[:, None, None]
        out = []
        for centres, rrup, ln_median, sigma, rate in self._terms:
            out.append((centres, rrup, rate * ndtr((ln_median - log_x) / sigma)))
        return out

    def rates(self, levels):
        """λ(x) of (1) at ``levels``, shape (levels,)."""
        return sum(r.sum(axis=(1, 2)) for _, _, r in self.exceedance(levels))

    def curve(self, levels):
        """The :class:`HazardCurve` at ``levels`` (levels never exceeded dropped), with its
        disaggregation."""
        levels = np.asarray(levels, dtype=float)
        rates = self.rates(levels)
        keep = rates > 0
        return HazardCurve(self.im, levels[keep], rates[keep], self.describe(),
                           source_model=self)

    def disaggregate(self, levels, distance_edges):
        """:class:`Disaggregation` at ``levels`` over the magnitude bins and Rrup bins of
        ``distance_edges`` [m] (events beyond the last edge in the last bin)."""
        levels = np.asarray(levels, dtype=float)
        centres = np.unique(np.concatenate([t[0] for t in self._terms]))
        edges = np.asarray(distance_edges, dtype=float)
        total = np.zeros((levels.size, centres.size, edges.size - 1))
        weighted_m = np.zeros(levels.size)
        weighted_r = np.zeros(levels.size)
        for magnitudes, rrup, rates in self.exceedance(levels):
            m_index = np.searchsorted(centres, magnitudes)
            r_index = np.clip(np.searchsorted(edges, rrup, side="right") - 1, 0, edges.size - 2)
            for i, mi in enumerate(m_index):
                np.add.at(total, (slice(None), mi, r_index), rates[:, i, :])
            weighted_m += np.einsum("lmp,m->l", rates, magnitudes)
            weighted_r += np.einsum("lmp,p->l", rates, rrup)
        lam = total.sum(axis=(1, 2))
        with np.errstate(invalid="ignore", divide="ignore"):
            return Disaggregation(levels, centres, edges, total, weighted_m / lam,
                                  weighted_r / lam)

    def draw(self, level, count, rng):
        """``count`` (magnitude, Rrup [m]) of earthquakes drawn in proportion to their share
        of λ(level): a (magnitude bin, point) by its rate of exceeding ``level``, then the
        magnitude uniform within its bin and, over an area, the point uniform within its
        cell.  Shape (count, 2)."""
        shares, events = [], []
        for source, (magnitudes, rrup, rates) in zip(self.sources,
                                                     self.exceedance([level])):
            _, edges, _ = source.recurrence.bins(self.dm)
            for i in range(magnitudes.size):
                for p in range(rrup.size):
                    shares.append(rates[0, i, p])
                    events.append((source, edges[i], edges[i + 1], p))
        shares = np.asarray(shares)
        picks = rng.choice(shares.size, size=count, p=shares / shares.sum())
        out = np.empty((count, 2))
        for k, pick in enumerate(picks):
            source, lo, hi, p = events[pick]
            out[k, 0] = rng.uniform(lo, hi) if hi > lo else lo
            x, y = source.xy[p]
            if source.cell > 0:
                x, y = x + rng.uniform(-source.cell, source.cell), \
                    y + rng.uniform(-source.cell, source.cell)
            out[k, 1] = np.hypot(np.hypot(x, y), source.depth)
        return out

    def describe(self):
        kinds = ", ".join(
            f"{'point' if s.rjb.size == 1 else f'area of {s.rjb.size} points'} at depth "
            f"{s.depth / 1e3:g} km, "
            + (f"characteristic M {s.recurrence.m_min:g}" if s.recurrence.characteristic else
               f"M {s.recurrence.m_min:g}-{s.recurrence.m_max:g} b {s.recurrence.b:g}")
            + f" nu {s.recurrence.rate:g}/yr" for s in self.sources)
        return f"{self.model}, Vs30 {self.vs30:g} m/s: {kinds}"
