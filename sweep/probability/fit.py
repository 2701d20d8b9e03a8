"""Fragility functions fitted by maximum likelihood (docs/probability.md section 4).

Lognormal fragility P(x) = Φ(ln(x/θ)/β): a probit GLM of the outcome on ln x, P = Φ(b0 + b1
ln x), so θ = exp(−b0/b1) and β = 1/b1 (Baker 2015, Earthquake Spectra 31).  The data are
binary outcomes (k = 0 or 1 of n = 1 at x) or stripes (k of n at level x), or both.

Intervals of θ and β, two methods:

* ``"bootstrap"`` (default): bias-corrected and accelerated (BCa) intervals over replicates
  that resample the ensemble members with replacement, each member with all its levels (a
  cluster bootstrap, ``sweep.probability.bootstrap``).  A study scales the same members to
  every level, so a member's outcomes at different levels are correlated; the binomial
  likelihood counts them as independent, and its curvature (the delta method) then
  understates the uncertainty.  Without member labels every trial is its own member.  A
  replicate whose levels separate (no overturning below a gap, all overturned above it) enters
  with β = 0 and θ the geometric middle of the gap, the limit of its maximum-likelihood
  estimate; a replicate with no overturning, all overturned or one level cannot be fitted and
  is counted in ``unfitted_replicates``.
* ``"delta"``: Wald intervals of ln θ and ln β from the GLM's covariance (delta method),
  exponentiated: valid when every trial is independent.

When the data cannot determine θ and β (no trial, fewer than two distinct levels, no
overturning, all overturned, separated levels) or the fitted slope falls with x, the fit
returns NaN with a status code and its reason, never an exception or a warning.  The
two-parameter surface P = Φ(b0 + b1 ln PGA + b2 ln PGV) (Purvance, Anooshehpoor & Brune 2008,
EESD 37) is :func:`fit_surface`.  statsmodels and scipy are imported when a fit is made.
"""
import warnings
from dataclasses import dataclass

import numpy as np

from . import bootstrap
from .intervals import normal_quantile, validate_confidence

# status of a fit: codes, names (CF flag_meanings) and the reasons said to the user
(FITTED, NO_DATA, TOO_FEW_LEVELS, NONE_OVERTURNED, ALL_OVERTURNED, SEPARATED,
 NOT_CONVERGED, DECREASING) = range(8)
FIT_STATUS_NAMES = ("fitted", "no_data", "too_few_levels", "none_overturned",
                    "all_overturned", "separated", "not_converged", "decreasing")
FIT_REASONS = (
    "fitted",
    "no trial with a positive intensity measure",
    "fewer than 2 distinct intensity levels (3 for a surface)",
    "no member overturned at any level",
    "every member overturned at every level",
    "the levels separate: no member overturned at a level below one at which a member "
    "stood, so the maximum-likelihood beta is 0",
    "the maximum-likelihood iterations did not converge",
    "the fitted probability falls as the intensity grows: not a fragility function",
)
INTERVALS = ("bootstrap", "delta")
DEFAULT_REPLICATES = 1000  # bootstrap replicates: a 2.5 % tail from ~25 values


@dataclass(frozen=True)
class LognormalFit:
    """A lognormal fragility P(x) = Φ(ln(x/θ)/β) fitted to outcomes.

    Attributes
    ----------
    theta, beta : float
        Median θ (units of x) and dispersion β; NaN when not identifiable.
    theta_interval, beta_interval : tuple of float
        (lower, upper) at ``confidence``; NaN when not identifiable.
    confidence : float
    interval : str
        ``"bootstrap"`` or ``"delta"`` (module docstring).
    points : int
        Trials used (positive, finite x).
    levels : int
        Distinct values of x among them.
    status : int
        ``FITTED`` or the code of why not; ``reason`` says it in words.
    reason : str
    coefficients : ndarray, shape (2,)
        Probit coefficients (b0, b1) of P = Φ(b0 + b1 ln x).
    covariance : ndarray, shape (2, 2)
        Their covariance from the GLM's Fisher information.
    replicates : ndarray, shape (m, 2) or None
        Bootstrap (ln θ, β) of the replicates that entered the intervals.
    unfitted_replicates : int
        Bootstrap replicates left out (no overturning, all overturned, one level, not
        converged).
    log_levels : ndarray or None
        The distinct ln x of the data, through which :meth:`band` draws a separated
        replicate.
    """

    theta: float
    beta: float
    theta_interval: tuple
    beta_interval: tuple
    confidence: float
    interval: str
    points: int
    levels: int
    status: int
    reason: str
    coefficients: np.ndarray
    covariance: np.ndarray
    replicates: np.ndarray = None
    unfitted_replicates: int = 0
    log_levels: np.ndarray = None

    @property
    def identifiable(self):
        return self.status == FITTED

    def probability(self, x):
        """The fitted P(x) (NaN when not identifiable)."""
        with np.errstate(divide="ignore"):
            return _phi((np.log(np.asarray(x, dtype=float)) - np.log(self.theta)) / self.beta)

    def band(self, x):
        """Pointwise (lower, upper) confidence band of P(x): percentiles of the bootstrap
        curves at each x (:func:`replicate_curves`; smooth where BCa's correction of a curve
        of 0s and 1s is not), or Φ(η ± z se(η)) with η = b0 + b1 ln x by the delta method."""
        x = np.asarray(x, dtype=float)
        if not self.identifiable or (self.interval == "bootstrap"
                                     and not len(self.replicates)):
            return np.full(x.shape, np.nan), np.full(x.shape, np.nan)
        with np.errstate(divide="ignore"):
            log_x = np.log(x)
        if self.interval == "bootstrap":
            curves = replicate_curves(log_x, self.replicates, self.log_levels)
            tail = 50.0 * (1.0 - self.confidence)
            return tuple(np.percentile(curves, [tail, 100.0 - tail], axis=-1))
        eta = self.coefficients[0] + self.coefficients[1] * log_x
        design = np.stack([np.ones_like(log_x), log_x], axis=-1)
        se = np.sqrt(np.einsum("...i,ij,...j->...", design, self.covariance, design))
        z = normal_quantile(self.confidence)
        return _phi(eta - z * se), _phi(eta + z * se)


@dataclass(frozen=True)
class SurfaceFit:
    """P = Φ(b0 + b1 ln PGA + b2 ln PGV) fitted to outcomes (PGA in m/s², PGV in m/s).

    Attributes
    ----------
    coefficients : ndarray, shape (3,)
        (b0, b1, b2); NaN when not identifiable.
    covariance : ndarray, shape (3, 3)
    points : int
        Trials used (positive, finite PGA and PGV).
    status : int
    reason : str
    """

    coefficients: np.ndarray
    covariance: np.ndarray
    points: int
    status: int
    reason: str

    @property
    def identifiable(self):
        return self.status == FITTED

    def probability(self, pga, pgv):
        """The fitted surface at ``pga`` [m/s²] and ``pgv`` [m/s] (broadcast)."""
        b0, b1, b2 = self.coefficients
        return _phi(b0 + b1 * np.log(pga) + b2 * np.log(pgv))


def _phi(z):
    from scipy.special import ndtr
    return ndtr(z)


def _lognormal_cdf(log_x, log_theta, beta):
    """Φ((ln x − ln θ)/β), with β = 0 the step at θ (1/2 on it)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        z = (log_x - log_theta) / beta
    step = np.where(log_x > log_theta, 1.0, np.where(log_x < log_theta, 0.0, 0.5))
    return np.where(beta > 0, _phi(z), step)


def replicate_curves(log_x, replicates, log_levels=None):
    """P at ``log_x`` of each bootstrap replicate (ln θ, β), shape ``log_x.shape + (R,)``.

    A replicate whose levels separate (β = 0) is a step somewhere between two levels
    ``log_levels``, where its data do not place it: its curve is drawn through its values
    at the levels (0 below the step, 1 above, 1/2 on it) joined linearly in ln x, so that
    the band has no wall at a step.
    """
    log_x = np.asarray(log_x, dtype=float)
    curves = _lognormal_cdf(log_x[..., None], replicates[:, 0], replicates[:, 1])
    steps = replicates[:, 1] == 0
    if steps.any() and log_levels is not None and np.size(log_levels) > 1:
        at_levels = _lognormal_cdf(np.asarray(log_levels)[:, None], replicates[steps, 0], 0.0)
        curves[..., steps] = np.stack([np.interp(log_x, log_levels, values)
                                       for values in at_levels.T], axis=-1)
    return curves


def _used_rows(x, k, n):
    """The rows with n > 0 and a positive finite x (after checking 0 <= k <= n, whole)."""
    if np.any(k < 0) or np.any(k > n) or np.any(k != np.round(k)) or np.any(n != np.round(n)):
        raise ValueError("`k` and `n` must be whole numbers with 0 <= k <= n")
    return (n > 0) & np.isfinite(x) & (x > 0)


def data_status(log_x, k, n):
    """Whether outcomes can determine a lognormal fragility: ``FITTED`` or why not.

    Separation (complete or quasi-complete): the highest level with a standing member is not
    above the lowest level with an overturned one; the likelihood then grows without bound as
    β → 0.
    """
    if n.sum() == 0:
        return NO_DATA
    if np.unique(log_x[n > 0]).size < 2:
        return TOO_FEW_LEVELS
    if k.sum() == 0:
        return NONE_OVERTURNED
    if k.sum() == n.sum():
        return ALL_OVERTURNED
    if log_x[n - k > 0].max() <= log_x[k > 0].min():
        return SEPARATED
    return FITTED


def separation_reason(log_x, k, n):
    """How levels (``log_x``, k of n) separate, in words true of them: a gap between the
    highest level where a member stood and the lowest where one overturned, or one level
    with both, with none overturned below it and all above it (where there are levels);
    ``FIT_REASONS[SEPARATED]`` when they do not separate so (statsmodels found it)."""
    if data_status(log_x, k, n) != SEPARATED:
        return FIT_REASONS[SEPARATED]
    used = n > 0
    standing, overturned = log_x[used & (n > k)].max(), log_x[k > 0].min()
    if standing < overturned:
        return ("the levels separate: none overturned up to a level, all overturned above "
                "it, so the maximum-likelihood beta is 0")
    said = ["only one level had members overturned and standing"]
    if np.any(used & (log_x < standing)):
        said.append("none overturned below it")
    if np.any(used & (log_x > standing)):
        said.append("all overturned above it")
    return ", ".join(said) + ": the levels separate there, so the maximum-likelihood beta is 0"


def _probit_glm(design, k, n):
    """statsmodels' probit GLM of k of n on ``design``: (coefficients, covariance, status)."""
    import statsmodels.api as sm
    from statsmodels.genmod.families import Binomial
    from statsmodels.genmod.families.links import Probit
    from statsmodels.tools.sm_exceptions import PerfectSeparationWarning

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        model = sm.GLM(np.column_stack([k, n - k]), design, family=Binomial(link=Probit()))
        try:
            result = model.fit()
        except (np.linalg.LinAlgError, ValueError):
            result = None
    separated = any(issubclass(w.category, PerfectSeparationWarning) for w in caught)
    if result is None or separated or not result.converged \
            or not np.all(np.isfinite(result.params)):
        nan = np.full(design.shape[1], np.nan)
        return nan, np.full((nan.size, nan.size), np.nan), \
            SEPARATED if separated else NOT_CONVERGED
    return np.asarray(result.params), np.asarray(result.cov_params()), FITTED


def fit_lognormal(x, k, n=1, members=None, *, confidence=0.95, interval="bootstrap",
                  replicates=DEFAULT_REPLICATES, seed=0):
    """Fit P(x) = Φ(ln(x/θ)/β) by maximum likelihood to k of n overturned at x.

    Parameters
    ----------
    x : array_like, shape (N,)
        Intensity measure of each row (level or cell), any positive unit.  Rows with x <= 0,
        non-finite x or n = 0 are left out.
    k, n : array_like of int, shape (N,)
        Overturned and trials of each row (binary outcomes: k in {0, 1}, n = 1).
    members : array_like, shape (N,), optional
        The ensemble member of each row, for the bootstrap over members (module docstring);
        omitted: every trial is independent.
    confidence : float
        Coverage of the intervals of θ and β.
    interval : {"bootstrap", "delta"}
    replicates : int
        Bootstrap replicates.
    seed : int or numpy.random.Generator
        Randomness of the bootstrap.

    Returns
    -------
    LognormalFit

    References
    ----------
    Baker, J. W. (2015), Earthquake Spectra 31, 579-599; docs/probability.md section 4.
    """
    validate_confidence(confidence)
    if interval not in INTERVALS:
        raise ValueError(f"`interval` must be one of {', '.join(INTERVALS)}, got {interval!r}")
    x, k, n = np.broadcast_arrays(*(np.asarray(a, dtype=float).ravel() for a in (x, k, n)))
    if members is not None and np.size(members) != x.size:
        raise ValueError(f"`members` has {np.size(members)} labels for {x.size} rows")
    used = _used_rows(x, k, n)
    log_x, k, n = np.log(x[used]), k[used], n[used]
    levels, row_level = np.unique(log_x, return_inverse=True)
    k_level = np.bincount(row_level, k, minlength=levels.size)
    n_level = np.bincount(row_level, n, minlength=levels.size)
    common = dict(confidence=confidence, interval=interval, points=int(n.sum()),
                  levels=int(levels.size))
    status = data_status(levels, k_level, n_level)
    if status == FITTED:
        design = np.column_stack([np.ones_like(levels), levels])
        coefficients, covariance, status = _probit_glm(design, k_level, n_level)
        if status == FITTED and coefficients[1] <= 0:
            status = DECREASING
    if status != FITTED:
        nan2 = (np.nan, np.nan)
        reason = separation_reason(levels, k_level, n_level) if status == SEPARATED else \
            FIT_REASONS[status]
        return LognormalFit(np.nan, np.nan, nan2, nan2, status=status,
                            reason=reason, coefficients=np.full(2, np.nan),
                            covariance=np.full((2, 2), np.nan), **common)
    b0, b1 = coefficients
    theta, beta = np.exp(-b0 / b1), 1.0 / b1
    if interval == "delta":
        theta_interval, beta_interval = _delta_intervals(coefficients, covariance, confidence)
        return LognormalFit(float(theta), float(beta), theta_interval, beta_interval,
                            status=FITTED, reason=FIT_REASONS[FITTED],
                            coefficients=coefficients, covariance=covariance, **common)
    if members is None:
        patterns = bootstrap.trial_patterns(k_level, n_level)
    else:
        _, row_member = np.unique(np.asarray(members).ravel()[used], return_inverse=True)
        patterns = bootstrap.member_patterns(row_member.ravel(), row_level, k, n, levels.size)
    resampled, fitted = _estimates(levels, *bootstrap.resample(
        patterns, replicates, np.random.default_rng(seed)), coefficients)
    resampled, unfitted = resampled[fitted], int(replicates - fitted.sum())
    jackknife, fitted = _estimates(levels, *bootstrap.leave_one_out(patterns), coefficients)
    jackknife, weights = jackknife[fitted], patterns.count[fitted]
    bounds = bootstrap.bca_interval(
        [np.log(theta), beta], resampled.T, jackknife.T, weights, confidence)
    theta_interval = tuple(float(v) for v in np.exp([bounds[0][0], bounds[1][0]]))
    beta_interval = (float(bounds[0][1]), float(bounds[1][1]))
    return LognormalFit(float(theta), float(beta), theta_interval, beta_interval,
                        status=FITTED, reason=FIT_REASONS[FITTED], coefficients=coefficients,
                        covariance=covariance, replicates=resampled,
                        unfitted_replicates=unfitted, log_levels=levels, **common)


def _delta_intervals(coefficients, covariance, confidence):
    """Wald intervals of ln θ = −b0/b1 and ln β = −ln b1, exponentiated."""
    b0, b1 = coefficients
    gradients = np.array([[-1.0 / b1, b0 / b1 ** 2],  # d ln θ / d(b0, b1)
                          [0.0, -1.0 / b1]])  # d ln β / d(b0, b1)
    se = np.sqrt(np.einsum("ij,jk,ik->i", gradients, covariance, gradients))
    z = normal_quantile(confidence)
    centre = np.array([-b0 / b1, -np.log(b1)])
    lower, upper = np.exp(centre - z * se), np.exp(centre + z * se)
    return (lower[0], upper[0]), (lower[1], upper[1])


def _estimates(log_x, k, n, start):
    """(ln θ, β) of replicates (rows of k, n over levels ``log_x``), separated ones at their
    limit (module docstring), NaN where unfitted; and the mask of the fitted rows."""
    has_n, has_k, has_standing = n > 0, k > 0, n - k > 0
    highest_standing = np.where(has_standing, log_x, -np.inf).max(axis=1)
    lowest_overturned = np.where(has_k, log_x, np.inf).min(axis=1)
    spread = (np.where(has_n, log_x, -np.inf).max(axis=1)
              > np.where(has_n, log_x, np.inf).min(axis=1))
    can_fit = spread & has_k.any(axis=1) & has_standing.any(axis=1)
    separated = can_fit & (highest_standing <= lowest_overturned)
    regular = can_fit & ~separated
    estimates = np.full((k.shape[0], 2), np.nan)
    coefficients, converged = bootstrap.probit_coefficients(log_x, k[regular], n[regular],
                                                            start)
    b0, b1 = coefficients.T
    with np.errstate(divide="ignore", invalid="ignore"):
        estimates[regular] = np.column_stack([-b0 / b1, 1.0 / b1])
    estimates[separated] = np.column_stack([
        0.5 * (highest_standing[separated] + lowest_overturned[separated]),
        np.zeros(separated.sum())])
    fitted = separated.copy()
    fitted[regular] = converged & (b1 > 0)
    return estimates, fitted


def fit_surface(pga, pgv, k, n=1):
    """Fit P = Φ(b0 + b1 ln PGA + b2 ln PGV) by maximum likelihood (a probit GLM).

    Parameters
    ----------
    pga, pgv : array_like, shape (N,)
        Peak ground acceleration [m/s²] and velocity [m/s] of each row; rows with a
        non-positive or non-finite value, or n = 0, are left out.
    k, n : array_like of int, shape (N,)
        Overturned and trials of each row.

    Returns
    -------
    SurfaceFit

    References
    ----------
    Purvance, M. D., Anooshehpoor, A. & Brune, J. N. (2008), Earthquake Eng. Struct. Dyn. 37.
    """
    pga, pgv, k, n = np.broadcast_arrays(
        *(np.asarray(a, dtype=float).ravel() for a in (pga, pgv, k, n)))
    used = _used_rows(pga, k, n) & np.isfinite(pgv) & (pgv > 0)
    design = np.column_stack([np.ones(used.sum()), np.log(pga[used]), np.log(pgv[used])])
    k, n = k[used], n[used]
    if n.sum() == 0:
        status = NO_DATA
    elif np.linalg.matrix_rank(design) < 3:
        status = TOO_FEW_LEVELS
    elif k.sum() == 0:
        status = NONE_OVERTURNED
    elif k.sum() == n.sum():
        status = ALL_OVERTURNED
    else:
        status = FITTED
    coefficients, covariance = np.full(3, np.nan), np.full((3, 3), np.nan)
    if status == FITTED:
        coefficients, covariance, status = _probit_glm(design, k, n)
    return SurfaceFit(coefficients, covariance, int(n.sum()), status, FIT_REASONS[status])
