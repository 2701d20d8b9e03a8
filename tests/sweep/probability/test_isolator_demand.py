"""The isolator's displacement demand at a site against closed forms: on a power-law hazard
λ(x) = k0 x^-k with a lognormal demand of median a x and constant β, the rate of D > d is
λ_D(d) = k0 (d/a)^-k exp(k²β²/2) (the integral of Cornell et al. 2002 with d/a for θ), so that
d* of P[D > d* in T] = p is a (k0 exp(k²β²/2) / λ*)^(1/k), λ* = −ln(1 − p)/T; a share q of
motions moving scales λ_D by q; the per-stripe fit is scipy's lognormal maximum likelihood."""
import numpy as np
import pytest
from scipy import stats

from sweep.probability import isolator_demand as demand
from sweep.probability.hazard_curve import HazardCurve

K0, K = 1e-3, 2.2  # λ(x) = K0 x^-K, x in m/s²
A, BETA = 0.05, 0.45  # the median displacement a x [m] and its dispersion
YEARS, TARGET = 50.0, 0.02
LEVELS = np.geomspace(1e-3, 1e3, 120)  # a curve long enough that its ends do not matter


def _curve():
    return HazardCurve("pga", LEVELS, K0 * LEVELS ** -K)


def _stripes(levels, moving=1.0):
    levels = np.asarray(levels, dtype=float)
    n = levels.size
    return demand.StripeDisplacements(levels, np.full(n, moving), A * levels,
                                      np.full(n, BETA), np.full(n, 10.0))


def _closed_form_rate(d, moving=1.0):
    return moving * K0 * (d / A) ** -K * np.exp(0.5 * (K * BETA) ** 2)


@pytest.mark.parametrize("d", [0.05, 0.3, 1.0])
def test_exceedance_rate_is_the_closed_form(d):
    rate, outside = demand.exceedance_rate(_curve(), _stripes(LEVELS), d)
    assert rate == pytest.approx(_closed_form_rate(d), rel=2e-3)
    assert outside == 0.0  # stripes at every level of the curve


def test_demand_at_the_target_is_the_closed_form():
    wanted = -np.log1p(-TARGET) / YEARS
    expected = A * (K0 * np.exp(0.5 * (K * BETA) ** 2) / wanted) ** (1 / K)
    found = demand.demand(_curve(), _stripes(LEVELS), YEARS, TARGET)
    assert found.displacement == pytest.approx(expected, rel=2e-3)
    assert found.rate == pytest.approx(wanted, rel=1e-6)


def test_a_share_moving_scales_the_rate():
    rate, _ = demand.exceedance_rate(_curve(), _stripes(LEVELS, 0.4), 0.2)
    assert rate == pytest.approx(_closed_form_rate(0.2, 0.4), rel=2e-3)


def test_few_stripes_interpolate_a_proportional_median_exactly_and_say_the_share_outside():
    """ln m is linear in ln x: three stripes interpolate it exactly between them; beyond them
    the held median is not the closed form, and the share from there is the closed form's
    integral outside [x_1, x_3] over the whole."""
    levels = [1.0, 3.0, 9.0]
    d = 0.15  # d/a = 3: the median crosses d inside the stripes
    rate, outside = demand.exceedance_rate(_curve(), _stripes(levels), d)
    x = np.geomspace(1e-3, 1e3, 200001)
    u = np.log(x)
    p = stats.norm.sf((np.log(d) - np.log(A * np.clip(x, 1.0, 9.0))) / BETA)
    density = K * K0 * x ** -K  # |dλ/d ln x|
    inside = (x >= 1.0) & (x <= 9.0)
    total = np.trapezoid(p * density, u)
    assert rate == pytest.approx(total, rel=3e-3)
    assert outside == pytest.approx(np.trapezoid(np.where(inside, 0, p * density), u) / total,
                                    rel=1e-2)


def test_the_stripe_fit_is_scipys_maximum_likelihood_with_the_still_motions_apart():
    rng = np.random.default_rng(3)
    moving = rng.lognormal(np.log(0.1), 0.5, 8)
    row = np.concatenate([moving, [0.0, 0.0, np.nan]])  # two still, one failed
    fitted = demand.fit_stripes([2.0], row[None, :])
    assert fitted.moving[0] == pytest.approx(8 / 10)
    assert fitted.motions[0] == 10
    assert fitted.median[0] == pytest.approx(np.exp(np.log(moving).mean()), rel=1e-4)
    assert fitted.beta[0] == pytest.approx(np.log(moving).std(), rel=1e-3)


def test_a_platform_that_never_moved_has_no_demand():
    fitted = demand.fit_stripes([1.0, 2.0], np.zeros((2, 5)))
    found = demand.demand(_curve(), fitted, YEARS, TARGET)
    assert found.displacement is None and "never moved" in found.reason
