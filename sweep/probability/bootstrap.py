"""The bootstrap over ensemble members, fitted all at once, with BCa intervals.

Resampling, the probit fit of many replicates at once, and bias-corrected and accelerated (BCa)
intervals.

A member is one motion of the ensemble with its outcomes at every level (its k and n per
level).  Members with the same outcomes form a *pattern* with a ``count``: a replicate draws
as many members as the ensemble has, with replacement, i.e. a multinomial count per pattern;
the jackknife leaves out one member at a time, one fit per pattern.  BCa intervals (Efron
1987, J. Am. Stat. Assoc. 82; Davison & Hinkley 1997, section 5.3) correct the percentile
interval for the median bias of the estimate and for its skewness (acceleration from the
jackknife).
"""
from collections import namedtuple

import numpy as np

MAX_ITERATIONS = 100  # Fisher scoring of the replicates (from the full fit: 3-10 iterations)
MAX_HALVINGS = 30  # step halvings of one iteration while the log-likelihood decreases
STEP_TOLERANCE = 1e-10  # converged: every coefficient moved less than this (relative + absolute)
LOG_SQRT_2PI = 0.5 * np.log(2.0 * np.pi)

Patterns = namedtuple("Patterns", "k n count")
Patterns.__doc__ = """Distinct members: ``k``, ``n`` per level, shape (P, levels); ``count``,
shape (P,), the members of each."""


def member_patterns(row_member, row_level, k, n, n_levels):
    """The patterns of labelled members from rows (member index, level index, k, n)."""
    k_member = np.zeros((row_member.max() + 1, n_levels))
    n_member = np.zeros_like(k_member)
    np.add.at(k_member, (row_member, row_level), k)
    np.add.at(n_member, (row_member, row_level), n)
    rows, count = np.unique(np.hstack([k_member, n_member]), axis=0, return_counts=True)
    return Patterns(rows[:, :n_levels], rows[:, n_levels:], count)


def trial_patterns(k_level, n_level):
    """The patterns when every trial is its own member: at each level an overturned trial
    (count k) and a standing one (count n − k)."""
    levels = np.arange(k_level.size)
    one = np.zeros((2 * k_level.size, k_level.size))
    one[2 * levels, levels] = one[2 * levels + 1, levels] = 1.0
    k = np.zeros_like(one)
    k[2 * levels, levels] = 1.0
    count = np.ravel(np.column_stack([k_level, n_level - k_level]))
    keep = count > 0
    return Patterns(k[keep], one[keep], count[keep].astype(np.int64))


def resample(patterns, replicates, rng):
    """k and n per level of ``replicates`` resamplings of the members, shape (replicates,
    levels) each."""
    members = int(patterns.count.sum())
    draws = rng.multinomial(members, patterns.count / members, size=replicates).astype(float)
    return draws @ patterns.k, draws @ patterns.n


def leave_one_out(patterns):
    """k and n per level without one member of each pattern, shape (P, levels) each."""
    count = patterns.count[:, None]
    return ((count * patterns.k).sum(0) - patterns.k,
            (count * patterns.n).sum(0) - patterns.n)


def _log_likelihood(log_x, k, n, coefficients):
    from scipy.special import log_ndtr
    eta = coefficients[:, :1] + coefficients[:, 1:] * log_x
    return np.sum(k * log_ndtr(eta) + (n - k) * log_ndtr(-eta), axis=1)


def probit_coefficients(log_x, k, n, start):
    """Maximum-likelihood (b0, b1) of P = Φ(b0 + b1 ln x) for many replicates at once.

    The estimate of a probit GLM, for arrays of replicates: Fisher scoring from ``start`` with
    step halving while the log-likelihood decreases (it is concave in (b0, b1)).

    Parameters
    ----------
    log_x : ndarray, shape (levels,)
    k, n : ndarray, shape (replicates, levels)
    start : array_like, shape (2,)

    Returns
    -------
    coefficients : ndarray, shape (replicates, 2)
    converged : ndarray of bool, shape (replicates,)
    """
    from scipy.special import log_ndtr

    coefficients = np.tile(np.asarray(start, dtype=float), (k.shape[0], 1))
    converged = np.zeros(k.shape[0], dtype=bool)
    log_likelihood = _log_likelihood(log_x, k, n, coefficients)
    for _ in range(MAX_ITERATIONS):
        active = np.flatnonzero(~converged)
        if not active.size:
            break
        c, ka, na = coefficients[active], k[active], n[active]
        eta = c[:, :1] + c[:, 1:] * log_x
        log_pdf = -0.5 * eta ** 2 - LOG_SQRT_2PI
        ratio_up = np.exp(log_pdf - log_ndtr(eta))  # φ(η)/Φ(η)
        ratio_down = np.exp(log_pdf - log_ndtr(-eta))  # φ(η)/Φ(−η)
        score = ka * ratio_up - (na - ka) * ratio_down  # d log-likelihood / d η
        weight = na * ratio_up * ratio_down  # Fisher information per unit η
        gradient = np.stack([score.sum(1), (score * log_x).sum(1)], axis=1)
        i00, i01, i11 = weight.sum(1), (weight * log_x).sum(1), (weight * log_x ** 2).sum(1)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = np.stack([i11 * gradient[:, 0] - i01 * gradient[:, 1],
                             i00 * gradient[:, 1] - i01 * gradient[:, 0]], axis=1) \
                / (i00 * i11 - i01 ** 2)[:, None]
        old = log_likelihood[active]
        trial = c + step
        new = _log_likelihood(log_x, ka, na, trial)
        for _ in range(MAX_HALVINGS):
            worse = ~(new >= old - 1e-12 * np.abs(old))  # NaN counts as worse
            if not worse.any():
                break
            step[worse] *= 0.5
            trial[worse] = c[worse] + step[worse]
            new[worse] = _log_likelihood(log_x, ka[worse], na[worse], trial[worse])
        coefficients[active], log_likelihood[active] = trial, new
        converged[active] = np.all(np.abs(step) <= STEP_TOLERANCE * (1.0 + np.abs(trial)),
                                   axis=1)
    return coefficients, converged & np.all(np.isfinite(coefficients), axis=1)


def bca_interval(estimate, replicates, jackknife, weights, confidence):
    """The BCa interval of a statistic, vectorized over leading axes.

    Parameters
    ----------
    estimate : array_like, shape S
        The statistic on the data.
    replicates : ndarray, shape S + (B,)
        Its bootstrap replicates.
    jackknife : ndarray, shape S + (P,)
        Its leave-one-member-out values, one per pattern.
    weights : ndarray, shape (P,)
        The members of each pattern.
    confidence : float

    Returns
    -------
    lower, upper : ndarray, shape S
        NaN without replicates.

    References
    ----------
    Efron, B. (1987), Better bootstrap confidence intervals, J. Am. Stat. Assoc. 82, 171-185.
    """
    from scipy.special import ndtr, ndtri

    estimate = np.asarray(estimate, dtype=float)[..., None]
    count = replicates.shape[-1]
    if count == 0:
        return np.full(estimate.shape[:-1], np.nan), np.full(estimate.shape[:-1], np.nan)
    below = (np.sum(replicates < estimate, axis=-1)
             + 0.5 * np.sum(replicates == estimate, axis=-1)) / count
    bias = ndtri(np.clip(below, 0.5 / count, 1.0 - 0.5 / count))  # z0
    with np.errstate(divide="ignore", invalid="ignore"):  # no jackknife value: a = 0
        deviation = np.sum(weights * jackknife, axis=-1, keepdims=True) / np.sum(weights) \
            - jackknife
        spread = np.sum(weights * deviation ** 2, axis=-1)
        acceleration = np.where(spread > 0, np.sum(weights * deviation ** 3, axis=-1)
                                / (6.0 * spread ** 1.5), 0.0)
    z = ndtri(0.5 + 0.5 * confidence)
    ordered = np.sort(replicates, axis=-1)
    bounds = []
    for z_tail in (-z, z):
        shifted = bias + z_tail
        denominator = 1.0 - acceleration * shifted
        with np.errstate(divide="ignore", invalid="ignore"):
            adjusted = ndtr(bias + shifted / denominator)
        # a skew so strong that the correction turns over: the widest interval, not a flip
        probability = np.where(denominator > 0, adjusted, 0.0 if z_tail < 0 else 1.0)
        bounds.append(_quantile_sorted(ordered, probability))
    return tuple(bounds)


def _quantile_sorted(ordered, probability):
    """Linear-interpolation quantile (numpy's default) of sorted rows at one ``probability``
    per row."""
    position = np.clip(probability, 0.0, 1.0)[..., None] * (ordered.shape[-1] - 1)
    below = np.floor(position).astype(np.int64)
    above = np.minimum(below + 1, ordered.shape[-1] - 1)
    low, high = (np.take_along_axis(ordered, i, axis=-1) for i in (below, above))
    with np.errstate(invalid="ignore"):  # inf - inf where a row runs to infinity
        value = np.where(low == high, low, low + (position - below) * (high - low))
    return value[..., 0]
