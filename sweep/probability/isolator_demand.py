"""The isolator's displacement demand at a site, exceeded with a target's probability.

From the stripes' largest displacements of an isolator (``isolator_max_displacement``
of their datasets, docs/isolation.md), the rate at which the platform's displacement D exceeds
d, on the hazard curve λ(x) (the total probability theorem of PBEE, Cornell & Krawinkler 2000;
the demand hazard of Jalayer & Cornell 2009, eq. 3):

    λ_D(d) = ∫ P(D > d | x) |dλ(x)|  (+ P(D > d | x_n) λ(x_n) above the curve's last level)

P(D > d | x) per stripe j: the share q_j of motions that moved the platform (D > 0: a friction
pendulum sticks while the push stays below μg) times a lognormal of those that did, median m_j
and dispersion β_j fitted by maximum likelihood (``scipy.stats.lognorm.fit`` with loc 0; one
moving motion, or equal ones: a step, β 0).  Between stripes q, ln m and β are interpolated
linearly in ln x; below the lowest stripe and above the highest they are held at the end
stripe's (the share of λ_D(d*) from there is reported, and cautioned above 5 %).  The integral
is a midpoint rule in ln x, 16 nodes per segment of the log–log curve.  The demand d* solves
λ_D(d*) = −ln(1 − target)/years, P[D > d* in years] = target (Poisson).  SI units.
"""
from dataclasses import dataclass

import numpy as np

NODES = 16  # midpoint nodes per segment of the hazard curve
OUTSIDE_SHARE = 0.05  # a share of λ_D(d*) from outside the stripes that the report cautions of


@dataclass(frozen=True)
class StripeDisplacements:
    """Per stripe: ``levels`` [SI IM], ``moving`` q_j (share with D > 0), ``median`` m_j [m]
    and ``beta`` β_j of the moving ones (NaN where none moved), ``motions`` (finite D)."""

    levels: np.ndarray
    moving: np.ndarray
    median: np.ndarray
    beta: np.ndarray
    motions: np.ndarray


@dataclass(frozen=True)
class IsolatorDemand:
    """The displacement ``displacement`` [m] exceeded with probability ``probability`` in
    ``years`` (None where the stripes cannot reach it: ``reason``), its annual rate, the
    share of that rate from shaking outside the stripes' range, and the per-stripe fit."""

    displacement: float
    probability: float
    years: float
    rate: float
    share_outside: float
    stripes: StripeDisplacements
    reason: str = None


def fit_stripes(levels, displacements):
    """:class:`StripeDisplacements` of ``displacements`` [m], shape (stripes, motions); NaN
    (a failed cell, an isolator without one) left out."""
    from scipy.stats import lognorm

    moving, median, beta, motions = (np.full(len(levels), np.nan) for _ in range(4))
    for j, row in enumerate(np.asarray(displacements, dtype=float)):
        row = row[np.isfinite(row)]
        motions[j] = row.size
        positive = row[row > 0]
        if row.size:
            moving[j] = positive.size / row.size
        if positive.size == 1 or (positive.size > 1 and np.ptp(positive) == 0):
            median[j], beta[j] = positive[0], 0.0
        elif positive.size > 1:
            s, _, scale = lognorm.fit(positive, floc=0)
            median[j], beta[j] = scale, s
    return StripeDisplacements(np.asarray(levels, dtype=float), moving, median, beta, motions)


def _exceedance(stripes, x, d):
    """P(D > d | x) at IM levels ``x``: q, ln m and β interpolated in ln x, held beyond the
    ends."""
    from scipy.special import ndtr

    u = np.log(stripes.levels)
    q = np.interp(np.log(x), u, np.nan_to_num(stripes.moving))
    known = np.isfinite(stripes.median)
    if not known.any():
        return np.zeros_like(x)
    log_m = np.interp(np.log(x), u[known], np.log(stripes.median[known]))
    beta = np.interp(np.log(x), u[known], stripes.beta[known])
    z = (log_m - np.log(d)) / np.where(beta > 0, beta, 1.0)
    return q * np.where(beta > 0, ndtr(z), (log_m > np.log(d)).astype(float))


def _nodes(curve):
    """Midpoints in ln x of :data:`NODES` pieces of every segment of ``curve``, and the rate
    λ drops over each piece."""
    u = np.log(curve.levels)
    edges = np.concatenate([np.linspace(a, b, NODES + 1)[:-1] for a, b in zip(u[:-1], u[1:])]
                           + [u[-1:]])
    rates = curve.rate(np.exp(edges))
    return np.exp(0.5 * (edges[:-1] + edges[1:])), rates[:-1] - rates[1:]


def exceedance_rate(curve, stripes, d):
    """λ_D(d) [1/yr] (module docstring), and the share of it from outside the stripes'
    range."""
    x, drops = _nodes(curve)
    terms = np.append(_exceedance(stripes, x, d) * drops,
                      _exceedance(stripes, curve.levels[-1:], d) * curve.rates[-1])
    rate = float(terms.sum())
    outside = np.append((x < stripes.levels[0]) | (x > stripes.levels[-1]),
                        curve.levels[-1] > stripes.levels[-1])
    return rate, float(terms[outside].sum() / rate) if rate > 0 else np.nan


def demand(curve, stripes, years, target):
    """The :class:`IsolatorDemand` d* with P[D > d* in ``years``] = ``target``."""
    from scipy.optimize import brentq

    wanted = -np.log1p(-target) / years
    known = stripes.median[np.isfinite(stripes.median)]

    def none(reason):
        return IsolatorDemand(None, target, years, wanted, np.nan, stripes, reason)

    if not known.size:
        return none("the platform never moved in the stripes")
    lo, hi = np.log(known.min()) - 10.0, np.log(known.max()) + 10.0
    if exceedance_rate(curve, stripes, np.exp(lo))[0] < wanted:
        return none("the platform moves less often than the target's probability")
    if exceedance_rate(curve, stripes, np.exp(hi))[0] > wanted:
        return none("beyond the stripes' displacements")
    log_d = brentq(lambda v: exceedance_rate(curve, stripes, np.exp(v))[0] - wanted,
                   lo, hi, xtol=1e-10)
    rate, outside = exceedance_rate(curve, stripes, np.exp(log_d))
    return IsolatorDemand(float(np.exp(log_d)), target, years, rate, outside, stripes)


def said(found):
    """The demand in words: ``0.231 m exceeded with 2 % in 50 years`` (or why none)."""
    within = f"{100 * found.probability:.3g} % in {found.years:g} years"
    if found.displacement is None:
        return f"none at {within}: {found.reason}"
    return f"{found.displacement:.3g} m exceeded with {within}"


def record(found):
    """The JSON of a demand (``isolator_demand``): displacement [m], its probability, years,
    annual rate, the share from outside the stripes, the per-stripe fit, the reason for
    none."""
    stripes = found.stripes

    def listed(values):
        return [None if not np.isfinite(v) else float(v) for v in values]

    return {"displacement": found.displacement, "probability": found.probability,
            "years": found.years, "annual_rate": found.rate,
            "share_outside_stripes": None if not np.isfinite(found.share_outside)
            else found.share_outside, "reason": found.reason,
            "stripes": {"levels": stripes.levels.tolist(), "moving": listed(stripes.moving),
                        "median": listed(stripes.median), "beta": listed(stripes.beta),
                        "motions": listed(stripes.motions)}}
