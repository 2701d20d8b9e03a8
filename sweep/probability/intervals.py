"""Confidence intervals of a binomial proportion p from k successes in n trials.

Wilson's score interval (Wilson 1927, J. Am. Stat. Assoc. 22) and the exact interval of
Clopper & Pearson (1934, Biometrika 26), both vectorized over arrays of ``k`` and ``n``.  Both
stay inside [0, 1] and are sensible at k = 0 and k = n (docs/probability.md section 3).  n = 0
gives NaN.
"""
from statistics import NormalDist

import numpy as np

METHODS = ("wilson", "exact")


def normal_quantile(confidence):
    """z = Φ⁻¹(1 − a/2) of a two-sided interval at ``confidence`` = 1 − a."""
    validate_confidence(confidence)
    return NormalDist().inv_cdf(0.5 + 0.5 * confidence)


def validate_confidence(confidence):
    """Raise ``ValueError`` unless 0 < ``confidence`` < 1."""
    if not 0.0 < confidence < 1.0:
        raise ValueError(f"`confidence` must lie strictly between 0 and 1, got {confidence}")


def _counts(k, n):
    """``k`` and ``n`` as broadcast integer arrays, checked 0 <= k <= n."""
    k, n = np.broadcast_arrays(np.asarray(k), np.asarray(n))
    if np.any(k != np.round(k)) or np.any(n != np.round(n)):
        raise ValueError("`k` and `n` must be whole numbers")
    k, n = k.astype(np.int64), n.astype(np.int64)
    if np.any(k < 0) or np.any(k > n):
        raise ValueError("`k` must satisfy 0 <= k <= n")
    return k, n


def wilson_interval(k, n, confidence=0.95):
    """Wilson's score interval of p from ``k`` of ``n``.

    centre = (p̂ + z²/2n) / (1 + z²/n),
    half-width = z √(p̂(1 − p̂)/n + z²/4n²) / (1 + z²/n),  p̂ = k/n.

    Parameters
    ----------
    k, n : array_like of int
        Successes and trials, broadcast together; 0 <= k <= n.
    confidence : float
        Coverage of the interval, 0 < confidence < 1.

    Returns
    -------
    lower, upper : ndarray of float
        The bounds, NaN where n = 0.

    References
    ----------
    Wilson, E. B. (1927), J. Am. Stat. Assoc. 22, 209-212; docs/probability.md section 3.
    """
    k, n = _counts(k, n)
    z = normal_quantile(confidence)
    with np.errstate(divide="ignore", invalid="ignore"):
        nf = n.astype(float)
        p = k / nf
        denominator = 1.0 + z * z / nf
        centre = (p + z * z / (2.0 * nf)) / denominator
        half = z * np.sqrt(p * (1.0 - p) / nf + z * z / (4.0 * nf * nf)) / denominator
    # centre - half is 0 at k = 0 and centre + half is 1 at k = n, up to rounding
    lower = np.where(k == 0, 0.0, np.clip(centre - half, 0.0, 1.0))
    upper = np.where(k == n, 1.0, np.clip(centre + half, 0.0, 1.0))
    empty = n == 0
    return np.where(empty, np.nan, lower)[()], np.where(empty, np.nan, upper)[()]


def exact_interval(k, n, confidence=0.95):
    """Clopper-Pearson's exact interval of p from ``k`` of ``n``, as
    ``scipy.stats.binomtest(k, n).proportion_ci(confidence)``.

    Each distinct (k, n) pair is computed once by ``binomtest``, so arrays of many cells with
    a few ensemble sizes cost a few calls.  Parameters and returns as :func:`wilson_interval`.

    References
    ----------
    Clopper, C. J. & Pearson, E. S. (1934), Biometrika 26, 404-413.
    """
    from scipy.stats import binomtest

    k, n = _counts(k, n)
    validate_confidence(confidence)
    pairs, index = np.unique(np.stack([k.ravel(), n.ravel()], axis=1), axis=0,
                             return_inverse=True)
    bounds = np.full((len(pairs), 2), np.nan)
    for row, (k_one, n_one) in enumerate(pairs):
        if n_one > 0:
            ci = binomtest(int(k_one), int(n_one)).proportion_ci(confidence_level=confidence)
            bounds[row] = ci.low, ci.high
    index = index.reshape(-1)
    return bounds[index, 0].reshape(k.shape)[()], bounds[index, 1].reshape(k.shape)[()]


def proportion_interval(k, n, confidence=0.95, method="wilson"):
    """The interval of ``method`` (``"wilson"`` or ``"exact"``) of p from ``k`` of ``n``."""
    if method not in METHODS:
        raise ValueError(f"`method` must be one of {', '.join(METHODS)}, got {method!r}")
    interval = wilson_interval if method == "wilson" else exact_interval
    return interval(k, n, confidence)
