"""``sweep.probability.intervals``: Wilson's score interval against the formula worked by
hand, the exact interval against scipy's ``binomtest``, the edges k = 0 and k = n, and the
coverage of both over many simulated binomials.

Coverage tolerance: S simulated binomials give an observed coverage with the binomial sd
√(0.95 · 0.05 / S) (0.0015 at S = 20,000); we accept 3 sd.  Wilson's coverage oscillates
around the nominal value as p varies (Brown, Cai & DasGupta 2001, Stat. Sci. 16), so it is
checked averaged over p ~ U(0.05, 0.95) (0.9515 at n = 50, summing the binomial pmf); the
exact interval never covers less than nominal.
"""
import numpy as np
import pytest
from scipy.stats import binomtest

from sweep.probability.intervals import (exact_interval, proportion_interval,
                                         wilson_interval)

NOMINAL = 0.95
SIMULATED = 20_000


@pytest.mark.parametrize("k, n, lower, upper", [
    # z = 1.959964; k = 3, n = 10: p = 0.3, centre = (0.3 + z²/20)/(1 + z²/10) = 0.355507,
    # half-width = z √(0.021 + z²/400)/(1 + z²/10) = 0.247715
    (3, 10, 0.1077913, 0.6032219),
    # k = 47, n = 120: p = 0.391667, centre = 0.395027, half-width = 0.086035
    (47, 120, 0.3089920, 0.4810622),
])
def test_wilson_matches_the_formula_by_hand(k, n, lower, upper):
    bounds = wilson_interval(k, n)
    np.testing.assert_allclose(bounds, (lower, upper), atol=5e-7)
    scipy = binomtest(k, n).proportion_ci(confidence_level=NOMINAL, method="wilson")
    np.testing.assert_allclose(bounds, (scipy.low, scipy.high), rtol=1e-12)


def test_exact_matches_binomtest_elementwise():
    k = np.array([[0, 1, 5], [7, 10, 2]])
    n = np.array([[10, 10, 10], [12, 10, 40]])
    lower, upper = exact_interval(k, n, 0.9)
    assert lower.shape == upper.shape == k.shape
    for index in np.ndindex(k.shape):
        ci = binomtest(int(k[index]), int(n[index])).proportion_ci(confidence_level=0.9)
        assert (lower[index], upper[index]) == pytest.approx((ci.low, ci.high), rel=1e-12)


@pytest.mark.parametrize("method", ["wilson", "exact"])
@pytest.mark.parametrize("n", [1, 7, 50, 1000])
def test_edges_stay_inside_zero_one(method, n):
    lower, upper = proportion_interval([0, n], [n, n], method=method)
    assert lower[0] == 0.0 and 0.0 < upper[0] < 1.0
    assert 0.0 < lower[1] < 1.0 and upper[1] == 1.0
    lower, upper = proportion_interval(np.arange(n + 1), n, method=method)
    assert np.all((0.0 <= lower) & (lower <= np.arange(n + 1) / n))
    assert np.all((np.arange(n + 1) / n <= upper) & (upper <= 1.0))


@pytest.mark.parametrize("method", ["wilson", "exact"])
def test_no_trials_give_nan(method):
    lower, upper = proportion_interval([0, 2], [0, 4], method=method)
    assert np.isnan(lower[0]) and np.isnan(upper[0])
    assert np.isfinite([lower[1], upper[1]]).all()


def test_bad_arguments_raise():
    with pytest.raises(ValueError, match="0 <= k <= n"):
        wilson_interval(5, 4)
    with pytest.raises(ValueError, match="confidence"):
        exact_interval(1, 4, confidence=1.0)
    with pytest.raises(ValueError, match="method"):
        proportion_interval(1, 4, method="wald")


def _coverage(method, n, p):
    k = np.random.default_rng(2024).binomial(n, p)
    lower, upper = proportion_interval(k, n, method=method)
    return np.mean((lower <= p) & (p <= upper))


def test_coverage_over_simulated_binomials():
    tolerance = 3 * np.sqrt(NOMINAL * (1 - NOMINAL) / SIMULATED)
    p = np.random.default_rng(7).uniform(0.05, 0.95, SIMULATED)
    assert abs(_coverage("wilson", 50, p) - NOMINAL) <= tolerance
    assert _coverage("exact", 50, p) >= NOMINAL - tolerance
    for p_fixed in (0.02, 0.3, 0.5):  # the exact interval at any single p, small n too
        for n in (10, 50):
            assert _coverage("exact", n, np.full(SIMULATED, p_fixed)) >= NOMINAL - tolerance
