"""The annual rate of overturning at a site: a lognormal fragility on a hazard curve.

The risk integral (Cornell & Krawinkler 2000; docs/probability.md §9), summed over the segments of
the tabulated curve, between levels x_i < x_{i+1} of which the curve is a power law
λ(x) = λ_i (x/x_i)^(−k_i) (log–log interpolation):

    λ_O = ∫ P(O | x) |dλ/dx| dx = Σ_i C_i + F(x_n) λ(x_n)                                  (1)

With u = ln x, F(u) = Φ((u − μ)/β), μ = ln θ, each segment [a, b] integrates in closed form
(integration by parts, then completing the square):

    C_i = F(a) λ(a) − F(b) λ(b)
          + λ(a) exp(−k (μ − a) + k² β² / 2) [Φ((b − μ)/β + kβ) − Φ((a − μ)/β + kβ)]       (2)

so the sum is exact for the interpolated curve; a step fragility (β = 0) gives
C_i = λ(max(a, μ)) − λ(b) when μ < b.  On a power law over all x, (1) is
λ_O = k0 θ^(−k) exp(k²β²/2) (Cornell et al. 2002).  The ends of the curve:

* **above** its last level x_n, the shaking is counted with the fragility of x_n: the term
  F(x_n) λ(x_n) of (1), included (a lower bound of the tail, which is at most λ(x_n));
* **below** its first level, nothing is included; the estimate of what is left out extends
  the first segment's power law to x → 0: −F(x_1) λ(x_1) + λ(x_1) exp(−k(μ − a) + k²β²/2)
  Φ((a − μ)/β + kβ) (2 with a → −∞), stated as a share of λ_O.

The probability in T years is 1 − exp(−λ_O T) (Poisson), the return period 1/λ_O.  The 95 %
interval carries the fragility's bootstrap replicates of (ln θ, β) (``fit.LognormalFit``)
through (1): percentiles of λ_O over them.  The contributions C_i, with the share above x_n,
are the disaggregation of λ_O by IM level.  When more than ``BEYOND_SHARE`` of λ_O comes from
above x_n (or θ > x_n), or the estimate below x_1 exceeds it, the curve is too short for the
fragility (:attr:`Risk.beyond_above`, :attr:`Risk.beyond_below`).

**No overturning at any stripe** (0 of n_j at x_1 < … < x_m) identifies no fragility but
bounds it.  With c the confidence, p = 1 − (1 − c)^(1/N) is the one-sided upper bound of a
probability from 0 of N trials (Clopper & Pearson 1934).  A non-decreasing fragility is at
least F(x_j) at every stripe above x_j, so with independent motions (synthetic, each its own
seed) the 0 of N_j = Σ_(i ≥ j) n_i motions at x_j and above bound F(x_j) by p_j (N = N_j);
with the same records at every stripe only the stripe's own n_j do (N = n_j).  The fragility
is then at most q_j = min_(i ≥ j) p_i on (x_(j−1), x_j] (x_0 the curve's first level) and at
most 1 above x_m, so that

    λ_O ≤ λ_up = Σ_j q_j [λ(x_(j−1)) − λ(x_j)] + λ(x_m)                                    (3)

a bound at confidence c: a fragility with λ_O > λ_up has F(x_i) > p_i at some stripe i, and
0 overturned has then a chance of at most (1 − F(x_i))^N < 1 − c (:func:`none_overturned`).
"""
from dataclasses import dataclass

import numpy as np

from .hazard_curve import HazardCurve, poe_from_rate

BEYOND_SHARE = 0.05  # a share of λ_O from beyond the curve's ends that the report cautions of


def _log_ndtr_difference(lower, upper):
    """ln(Φ(upper) − Φ(lower)) for upper ≥ lower, without cancellation in either tail."""
    from scipy.special import log_ndtr

    lower, upper = np.broadcast_arrays(lower, upper)
    right = lower > 0  # both in the upper tail: Φ(−lower) − Φ(−upper)
    hi = np.where(right, log_ndtr(-lower), log_ndtr(upper))
    lo = np.where(right, log_ndtr(-upper), log_ndtr(lower))
    with np.errstate(divide="ignore", invalid="ignore"):
        return hi + np.log1p(-np.exp(lo - hi))


def _tilted(log_rate, a, k, mu, beta, lower, upper):
    """λ(a) exp(−k(μ − a) + k²β²/2) [Φ(upper) − Φ(lower)], in logs against overflow."""
    with np.errstate(over="ignore", invalid="ignore"):
        return np.exp(log_rate - k * (mu - a) + 0.5 * (k * beta) ** 2
                      + _log_ndtr_difference(lower, upper))


def segment_contributions(curve, log_theta, beta):
    """C_i of (2) for every segment of ``curve``, broadcast over fragilities.

    Parameters
    ----------
    curve : HazardCurve
    log_theta, beta : array_like, shape S
        ln of the median (in the curve's SI units) and the dispersion; β = 0 is a step.

    Returns
    -------
    ndarray, shape S + (n − 1,)
    """
    from scipy.special import ndtr

    mu = np.asarray(log_theta, dtype=float)[..., None]
    beta = np.asarray(beta, dtype=float)[..., None]
    u = np.log(curve.levels)
    log_rate = np.log(curve.rates)
    a, b, k = u[:-1], u[1:], curve.slopes()
    step = beta <= 0
    safe_beta = np.where(step, 1.0, beta)
    fa, fb = ndtr((a - mu) / safe_beta), ndtr((b - mu) / safe_beta)
    smooth = (fa * curve.rates[:-1] - fb * curve.rates[1:]
              + _tilted(log_rate[:-1], a, k, mu, safe_beta,
                        (a - mu) / safe_beta + k * safe_beta,
                        (b - mu) / safe_beta + k * safe_beta))
    start = np.clip(mu, a, b)  # a step: the rate between max(a, μ) and b
    stepped = np.exp(log_rate[:-1] - k * (start - a)) - curve.rates[1:]
    stepped = np.where(mu < b, stepped, 0.0)
    return np.maximum(np.where(step, stepped, smooth), 0.0)


def fragility_at(x, log_theta, beta):
    """F(x) = Φ((ln x − ln θ)/β), a step at θ for β = 0; broadcast."""
    from scipy.special import ndtr

    log_theta, beta = np.asarray(log_theta, dtype=float), np.asarray(beta, dtype=float)
    z = (np.log(x) - log_theta) / np.where(beta > 0, beta, 1.0)
    return np.where(beta > 0, ndtr(z), (np.log(x) >= log_theta).astype(float))


def tail_above(curve, log_theta, beta):
    """F(x_n) λ(x_n): the shaking above the curve's last level, with the fragility there."""
    return fragility_at(curve.levels[-1], log_theta, beta) * curve.rates[-1]


def tail_below(curve, log_theta, beta):
    """What the part of the curve below its first level would add, the first segment's power
    law extended to x → 0 (module docstring); not included in λ_O."""
    mu, beta = np.asarray(log_theta, dtype=float), np.asarray(beta, dtype=float)
    a, k = np.log(curve.levels[0]), curve.slopes()[0]
    step = beta <= 0
    safe_beta = np.where(step, 1.0, beta)
    fa = fragility_at(curve.levels[0], mu, beta)
    smooth = -fa * curve.rates[0] + _tilted(np.log(curve.rates[0]), a, k, mu, safe_beta,
                                            -np.inf, (a - mu) / safe_beta + k * safe_beta)
    stepped = np.where(mu < a, np.exp(np.log(curve.rates[0]) - k * (mu - a))
                       - curve.rates[0], 0.0)
    return np.maximum(np.where(step, stepped, smooth), 0.0)


def annual_rate(curve, log_theta, beta):
    """λ_O of (1), broadcast over fragilities."""
    return segment_contributions(curve, log_theta, beta).sum(-1) + \
        tail_above(curve, log_theta, beta)


def hazard_density(curve, x):
    """|dλ/d ln x| = k_i λ(x) at ``x`` inside the curve (per unit ln x) [1/yr]."""
    x = np.asarray(x, dtype=float)
    segment = np.clip(np.searchsorted(curve.levels, x, side="right") - 1, 0,
                      curve.levels.size - 2)
    return curve.slopes()[segment] * curve.rate(x)


def integrand(curve, x, log_theta, beta):
    """F(x) |dλ/d ln x| = F(x) k_i λ(x) at ``x`` inside the curve (per unit ln x) [1/yr]."""
    return fragility_at(x, log_theta, beta) * hazard_density(curve, x)


@dataclass(frozen=True)
class Risk:
    """The risk of one body at one site.

    Attributes
    ----------
    annual_rate : float
        λ_O [1/yr], (1).
    years : float
    probability : float
        1 − exp(−λ_O years).
    return_period : float
        1/λ_O [yr].
    rate_interval, probability_interval : tuple of float
        Percentile intervals at ``confidence`` over the fragility's bootstrap replicates;
        (NaN, NaN) without replicates.
    confidence : float
    contributions : ndarray, shape (n,)
        C_i of each segment of the curve and, last, the term above its last level [1/yr];
        they sum to λ_O.
    lower, upper : ndarray, shape (n,)
        The IM bounds of each contribution (the last one's upper bound is inf).
    share_above, share_below : float
        The term above the curve's last level (included) and the estimate below its first
        level (not included), as shares of λ_O.
    median, beta : float
        The fragility used (median in the curve's SI units); NaN for a bound.
    replicates : int
        Bootstrap replicates that entered the intervals.
    last_rate : float
        λ(x_n), the rate of the shaking above the curve's last level [1/yr].
    bound : str or None
        Set when ``annual_rate`` and ``probability`` are one-sided upper bounds, not
        estimates (:func:`none_overturned`): what they bound, in words.
    staircase : tuple of ndarray or None
        With ``bound``: the stripe levels and the q_j of the bounding fragility (3).
    """

    annual_rate: float
    years: float
    probability: float
    return_period: float
    rate_interval: tuple
    probability_interval: tuple
    confidence: float
    contributions: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    share_above: float
    share_below: float
    median: float
    beta: float
    replicates: int = 0
    last_rate: float = np.nan
    bound: str = None
    staircase: tuple = None

    @property
    def shares(self):
        """The contributions as shares of λ_O (summing to 1)."""
        return self.contributions / self.annual_rate

    @property
    def rate_at_most(self):
        """λ_O if every shaking above the curve's last level overturned the body: the
        most that the part above the curve can add [1/yr]."""
        return self.annual_rate - self.contributions[-1] + self.last_rate

    @property
    def beyond_above(self):
        """Whether the fragility reaches past the curve's last level: θ above it, or more
        than ``BEYOND_SHARE`` of λ_O from above it (an estimate, not a bound)."""
        return self.bound is None and (self.median > self.lower[-1]
                                       or self.share_above > BEYOND_SHARE)

    @property
    def open_above(self):
        """Whether the part above the curve's last level could add more than 1 % to λ_O
        (the fragility there below 1)."""
        return self.beyond_above and self.rate_at_most > 1.01 * self.annual_rate

    @property
    def beyond_below(self):
        """Whether the estimate below the curve's first level (not included) exceeds
        ``BEYOND_SHARE`` of λ_O."""
        return self.share_below > BEYOND_SHARE


def risk(curve, median, beta, years=50.0, replicates=None, confidence=0.95):
    """:class:`Risk` of a lognormal fragility (``median`` in the curve's SI units, ``beta``)
    on ``curve``; ``replicates``: bootstrap (ln θ, β) rows, shape (R, 2), for the interval."""
    if not isinstance(curve, HazardCurve):
        raise TypeError("`curve` must be a HazardCurve")
    if not (median > 0 and beta >= 0 and np.isfinite(median) and np.isfinite(beta)):
        raise ValueError(f"the fragility needs median > 0 and beta >= 0, got median "
                         f"{median!r}, beta {beta!r}")
    log_theta = np.log(median)
    contributions = np.append(segment_contributions(curve, log_theta, beta),
                              tail_above(curve, log_theta, beta))
    rate = float(contributions.sum())
    below = float(tail_below(curve, log_theta, beta))
    nan2 = (np.nan, np.nan)
    rate_interval, probability_interval, count = nan2, nan2, 0
    if replicates is not None and len(replicates):
        replicates = np.asarray(replicates, dtype=float)
        rates = annual_rate(curve, replicates[:, 0], replicates[:, 1])
        rates = rates[np.isfinite(rates)]
        count = int(rates.size)
        if count:
            tail = 50.0 * (1.0 - confidence)
            lo, hi = np.percentile(rates, [tail, 100.0 - tail])
            rate_interval = (float(lo), float(hi))
            probability_interval = tuple(float(p) for p in poe_from_rate([lo, hi], years))
    with np.errstate(divide="ignore", invalid="ignore"):
        share_above = float(contributions[-1] / rate) if rate > 0 else np.nan
        share_below = below / rate if rate > 0 else np.nan
    return Risk(rate, float(years), float(poe_from_rate(rate, years)),
                1.0 / rate if rate > 0 else np.inf, rate_interval, probability_interval,
                confidence, contributions, curve.levels.copy(),
                np.append(curve.levels[1:], np.inf), share_above, share_below,
                float(median), float(beta), count, float(curve.rates[-1]))


def stripe_bounds(n, confidence=0.95, independent=True):
    """q_j of (3): the one-sided upper bounds p_j = 1 − (1 − c)^(1/N_j) of P(O | x_j) from
    0 of ``n`` overturned (N_j the motions at x_j and above when ``independent``, else n_j),
    each lowered to the least of those above it."""
    n = np.asarray(n, dtype=float)
    trials = np.cumsum(n[::-1])[::-1] if independent else n
    p = -np.expm1(np.log1p(-confidence) / trials)
    return np.minimum.accumulate(p[::-1])[::-1]


def bounding_fragility(x, staircase):
    """The staircase (stripe levels, q_j) of (3) at ``x``: q_j on (x_(j−1), x_j], 1 above
    the last stripe."""
    levels, q = staircase
    return np.append(q, 1.0)[np.searchsorted(levels, x, side="left")]


def none_overturned(curve, levels, n, years=50.0, confidence=0.95, independent=True):
    """:class:`Risk` whose rate and probability are the bounds (3) of a body that never
    overturned: 0 of ``n`` at the stripe ``levels`` (ascending, inside the curve; stripes
    with n = 0 left out), their motions ``independent`` or the same records at each.  The
    contributions are those of the bounding staircase F ≤ q_j per segment of the curve
    (steps at the curve's first level and at each stripe)."""
    levels, n = np.asarray(levels, dtype=float), np.asarray(n, dtype=float)
    levels, n = levels[n > 0], n[n > 0]
    q = stripe_bounds(n, confidence, independent)
    weights = np.diff(np.concatenate([[0.0], q, [1.0]]))  # rises of the staircase
    steps = np.log(np.concatenate([curve.levels[:1], levels]))
    pieces = np.column_stack([segment_contributions(curve, steps, np.zeros(steps.size)),
                              tail_above(curve, steps, np.zeros(steps.size))])
    contributions = weights @ pieces
    rate = float(contributions.sum())
    probability = float(poe_from_rate(rate, years))
    motions = (f"{n[0]:g} motions at each stripe" if np.all(n == n[0]) else
               f"{', '.join(f'{v:g}' for v in n)} motions at the stripes")
    bound = f"none overturned in {motions}: one-sided {100 * confidence:g} % bound"
    return Risk(rate, float(years), probability, 1.0 / rate, (0.0, rate), (0.0, probability),
                confidence, contributions, curve.levels.copy(),
                np.append(curve.levels[1:], np.inf), float(contributions[-1] / rate), np.nan,
                np.nan, np.nan, 0, float(curve.rates[-1]), bound, (levels, q))
