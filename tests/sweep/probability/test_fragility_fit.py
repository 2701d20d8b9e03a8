"""``sweep.probability.fit``: the lognormal fit recovers a known median and dispersion, its
95 % intervals cover them as often as they claim, and data that cannot determine a fit give
NaN with a reason instead of an exception or a warning.

Outcomes are drawn from P(x) = Φ(ln(x/θ)/β) with θ = 3 m/s² and β = 0.4 at 10 levels
spanning P = 0.01 to 0.99, 50 members each, in two ways: independent trials at each level,
and members reused at every level (member m overturns at x when x exceeds its capacity
θ exp(β ε_m), ε_m ~ N(0, 1): the same marginal P(x), with a member's outcomes correlated
across levels, as when a study scales the same records to every level).

Coverage tolerance: over R repetitions the observed coverage of an interval with true coverage
0.95 has the binomial sd √(0.95 · 0.05 / R) (0.0154 at R = 200, 0.0069 at R = 1000); we
accept 3 sd, and for the bootstrap a shortfall of 0.025 besides: bootstrap intervals from 50
members run somewhat below nominal (measured over 1000 repetitions: 0.926-0.945, the lowest
for β with reused members), as small-sample bootstrap intervals do (Davison & Hinkley 1997,
chapter 5).
"""
import warnings

import numpy as np
import pytest
from scipy.special import ndtr

from sweep.probability import bootstrap
from sweep.probability.fit import (ALL_OVERTURNED, DECREASING, FITTED, NONE_OVERTURNED,
                                   SEPARATED, TOO_FEW_LEVELS, fit_lognormal, fit_surface)

THETA, BETA = 3.0, 0.4
LEVELS = THETA * np.exp(BETA * np.linspace(-2.3, 2.3, 10))  # P from 0.011 to 0.989
MEMBERS = 50
NOMINAL = 0.95
BOOTSTRAP_SHORTFALL = 0.025  # allowed below nominal for the bootstrap (module docstring)
MAXIMUM_LIKELIHOOD_BIAS = 0.005  # relative, allowed besides the noise of an average


def _outcomes(rng, reused):
    """(levels, members) arrays of x, overturned (0/1) and member labels."""
    x = np.broadcast_to(LEVELS[:, None], (LEVELS.size, MEMBERS))
    if reused:
        capacity = THETA * np.exp(BETA * rng.standard_normal(MEMBERS))
        overturned = x > capacity[None, :]
    else:
        overturned = rng.random(x.shape) < ndtr(np.log(x / THETA) / BETA)
    members = np.broadcast_to(np.arange(MEMBERS), x.shape)
    return x, overturned.astype(float), members


def _repeat(repetitions, reused, interval, seed):
    """Estimates and whether each interval covered the truth, over ``repetitions`` data sets."""
    rng = np.random.default_rng(seed)
    estimates, covered = [], []
    for _ in range(repetitions):
        x, overturned, members = _outcomes(rng, reused)
        fit = fit_lognormal(x, overturned, 1, members, interval=interval, seed=rng)
        assert fit.status == FITTED
        estimates.append((fit.theta, fit.beta))
        covered.append((fit.theta_interval[0] <= THETA <= fit.theta_interval[1],
                        fit.beta_interval[0] <= BETA <= fit.beta_interval[1]))
    return np.array(estimates), np.mean(covered, axis=0)


def _tolerance(repetitions):
    """3 binomial sd of a coverage observed over ``repetitions``."""
    return 3.0 * np.sqrt(NOMINAL * (1.0 - NOMINAL) / repetitions)


def _assert_nominal(coverage, repetitions, interval):
    """Coverage within 3 sd of nominal, and within the stated shortfall below it for the
    bootstrap."""
    below = _tolerance(repetitions) + (BOOTSTRAP_SHORTFALL if interval == "bootstrap" else 0.0)
    assert np.all(coverage >= NOMINAL - below), coverage
    assert np.all(coverage <= NOMINAL + _tolerance(repetitions)), coverage


@pytest.mark.parametrize("interval", ["delta", "bootstrap"])
@pytest.mark.parametrize("repetitions", [
    200, pytest.param(1000, marks=pytest.mark.slow)])
def test_recovers_theta_and_beta_and_covers(interval, repetitions):
    """Independent trials: the estimates average to the generating values and both interval
    methods cover them at the nominal rate.

    Averages of ln θ and β within 3 standard errors of the mean, plus 0.5 % of θ and β for
    the O(1/n) bias of maximum likelihood (measured over 1000 repetitions: under 0.05 % for
    θ, -0.7 % to +0.1 % for β)."""
    estimates, coverage = _repeat(repetitions, reused=False, interval=interval, seed=11)
    log_theta, beta = np.log(estimates[:, 0]), estimates[:, 1]
    standard_error = np.array([log_theta.std(), beta.std()]) / np.sqrt(repetitions)
    bias = np.abs([log_theta.mean() - np.log(THETA), beta.mean() - BETA])
    allowed = 3 * standard_error + MAXIMUM_LIKELIHOOD_BIAS * np.array([1.0, BETA])
    assert np.all(bias <= allowed), (bias, standard_error)
    _assert_nominal(coverage, repetitions, interval)


@pytest.mark.parametrize("repetitions", [
    200, pytest.param(1000, marks=pytest.mark.slow)])
def test_bootstrap_covers_when_members_are_reused(repetitions):
    """Members reused at every level: the bootstrap over members still covers θ and β at
    the nominal rate, while the delta method, which counts every cell as independent,
    covers θ far less often (the reason the bootstrap is the default)."""
    _, coverage = _repeat(repetitions, reused=True, interval="bootstrap", seed=12)
    _assert_nominal(coverage, repetitions, "bootstrap")
    _, delta = _repeat(repetitions, reused=True, interval="delta", seed=12)
    assert delta[0] < NOMINAL - _tolerance(repetitions), delta


def test_stripes_and_binary_outcomes_give_the_same_fit():
    """k of n at each level is the same likelihood as the n binary outcomes."""
    x, overturned, members = _outcomes(np.random.default_rng(3), reused=False)
    binary = fit_lognormal(x, overturned, interval="delta")
    stripes = fit_lognormal(LEVELS, overturned.sum(axis=1), MEMBERS, interval="delta")
    assert binary.theta == pytest.approx(stripes.theta, rel=1e-9)
    assert binary.beta == pytest.approx(stripes.beta, rel=1e-9)
    assert binary.points == stripes.points == LEVELS.size * MEMBERS
    assert binary.levels == stripes.levels == LEVELS.size


def test_replicate_fits_agree_with_the_glm():
    """The batched Fisher scoring of the bootstrap finds statsmodels' GLM estimate."""
    x, overturned, _ = _outcomes(np.random.default_rng(4), reused=False)
    glm = fit_lognormal(x, overturned, interval="delta")
    k = overturned.sum(axis=1)[None, :]
    coefficients, converged = bootstrap.probit_coefficients(
        np.log(LEVELS), k, np.full_like(k, MEMBERS), start=[0.0, 1.0])
    assert converged.all()
    np.testing.assert_allclose(coefficients[0], glm.coefficients, rtol=1e-6)


def test_confidence_band_contains_the_fit_and_the_truth():
    x, overturned, members = _outcomes(np.random.default_rng(5), reused=True)
    fit = fit_lognormal(x, overturned, 1, members)
    lower, upper = fit.band(LEVELS)
    assert np.all(lower <= fit.probability(LEVELS)) and np.all(fit.probability(LEVELS) <= upper)
    assert np.all((0.0 <= lower) & (upper <= 1.0))


@pytest.mark.parametrize("x, k, n, status", [
    ([1.0, 2.0, 3.0], [0, 0, 0], [10, 10, 10], NONE_OVERTURNED),
    ([1.0, 2.0, 3.0], [10, 10, 10], [10, 10, 10], ALL_OVERTURNED),
    ([1.0, 2.0, 3.0, 4.0], [0, 0, 10, 10], [10, 10, 10, 10], SEPARATED),  # complete
    ([1.0, 2.0, 3.0], [0, 4, 10], [10, 10, 10], SEPARATED),  # quasi-complete: one mixed level
    ([2.0, 2.0], [3, 5], [10, 10], TOO_FEW_LEVELS),
    ([1.0, 2.0, 3.0, 4.0], [9, 6, 4, 1], [10, 10, 10, 10], DECREASING),
])
@pytest.mark.parametrize("interval", ["bootstrap", "delta"])
def test_unidentifiable_fit_is_nan_with_a_reason(x, k, n, status, interval):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no statsmodels or numpy warning reaches the user
        fit = fit_lognormal(x, k, n, interval=interval)
    assert fit.status == status and not fit.identifiable
    assert np.isnan([fit.theta, fit.beta, *fit.theta_interval, *fit.beta_interval]).all()
    assert fit.reason and fit.reason != "fitted"
    assert np.isnan(fit.probability([1.0, 2.0])).all()


def test_rows_without_trials_or_positive_x_are_left_out():
    fit = fit_lognormal([0.0, np.nan, 1.0, 2.0, 3.0, 4.0], [5, 5, 1, 3, 6, 0],
                        [10, 10, 10, 10, 10, 0], interval="delta")
    assert fit.points == 30 and fit.levels == 3 and fit.status == FITTED


def test_bad_counts_raise():
    with pytest.raises(ValueError, match="0 <= k <= n"):
        fit_lognormal([1.0, 2.0], [3, 1], [2, 2])
    with pytest.raises(ValueError, match="members"):
        fit_lognormal([1.0, 2.0], [1, 1], [2, 2], members=[0])


def test_surface_recovers_known_coefficients():
    """P = Φ(b0 + b1 ln PGA + b2 ln PGV) from 4000 cells at random (PGA, PGV): each
    estimate within 4 of its standard errors of the generating value."""
    rng = np.random.default_rng(6)
    truth = np.array([-1.0, 2.0, 1.2])
    pga = np.exp(rng.uniform(np.log(0.5), np.log(10.0), 4000))
    pgv = pga * np.exp(rng.normal(np.log(0.08), 0.5, pga.size))
    overturned = rng.random(pga.size) < ndtr(truth[0] + truth[1] * np.log(pga)
                                             + truth[2] * np.log(pgv))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fit = fit_surface(pga, pgv, overturned)
    assert fit.identifiable and fit.points == pga.size
    se = np.sqrt(np.diag(fit.covariance))
    assert np.all(np.abs(fit.coefficients - truth) <= 4 * se), (fit.coefficients, se)


def test_separated_surface_is_flagged():
    rng = np.random.default_rng(7)
    pga, pgv = np.exp(rng.normal(size=(2, 200)))
    overturned = np.log(pga) + np.log(pgv) > 0.0  # a line separates them exactly
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fit = fit_surface(pga, pgv, overturned)
    assert fit.status == SEPARATED and np.isnan(fit.coefficients).all()
    assert fit_surface(pga, np.ones(200), overturned).status == TOO_FEW_LEVELS
