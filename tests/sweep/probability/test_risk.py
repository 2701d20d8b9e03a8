"""The risk integral against closed forms and conservation, and the NRML fragility model's
conversion between (median, β) and OpenQuake's (mean, stddev)."""
import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.stats import norm

from sweep.probability import nrml
from sweep.probability import risk as risk_integral
from sweep.probability.hazard_curve import HazardCurve, poe_from_rate, rate_from_poe

K0, K = 2e-4, 2.8  # λ(x) = K0 x^-K, x in m/s²
THETA, BETA = 4.0, 0.45


def _power_law(levels):
    levels = np.asarray(levels, dtype=float)
    return HazardCurve("pga", levels, K0 * levels ** -K)


def test_power_law_hazard_and_lognormal_fragility_give_cornell_2002():
    """λ_O = k0 θ^-k exp(k²β²/2) (Cornell et al. 2002), on a fine and on a coarse curve."""
    exact = K0 * THETA ** -K * math.exp(0.5 * (K * BETA) ** 2)
    for count in (400, 12):
        curve = _power_law(np.geomspace(THETA / 60, THETA * 60, count))
        r = risk_integral.risk(curve, THETA, BETA)
        assert r.annual_rate == pytest.approx(exact, rel=1e-3)
        assert r.probability == pytest.approx(1 - math.exp(-50 * exact), rel=1e-3)
        assert r.return_period == pytest.approx(1 / exact, rel=1e-3)


def test_each_segment_against_quadrature_of_the_interpolated_curve():
    levels = np.array([0.3, 1.0, 2.0, 5.0, 9.0])
    curve = HazardCurve("pga", levels, [1e-2, 3e-3, 8e-4, 5e-5, 1e-6])
    slopes = curve.slopes()
    c = risk_integral.segment_contributions(curve, math.log(THETA), BETA)
    for i in range(4):
        def f(u, i=i):
            return norm.cdf((u - math.log(THETA)) / BETA) * slopes[i] * curve.rate(math.exp(u))
        expected, _ = quad(f, math.log(levels[i]), math.log(levels[i + 1]), epsrel=1e-12)
        assert c[i] == pytest.approx(expected, rel=1e-9)


def test_step_fragility_gives_the_rate_at_its_median():
    curve = HazardCurve("pga", [0.5, 1.5, 3.0, 7.0], [1e-2, 2e-3, 4e-4, 1e-5])
    r = risk_integral.risk(curve, 2.2, 0.0)
    assert r.annual_rate == pytest.approx(float(curve.rate(2.2)), rel=1e-12)


def test_disaggregation_sums_to_the_rate_and_tails_are_stated():
    curve = _power_law(np.geomspace(1.0, 10.0, 15))  # cut short: both tails matter
    r = risk_integral.risk(curve, THETA, BETA)
    assert r.contributions.sum() == pytest.approx(r.annual_rate, rel=1e-12)
    assert r.shares.sum() == pytest.approx(1.0, rel=1e-12)
    assert r.contributions[-1] == pytest.approx(norm.cdf(math.log(10 / THETA) / BETA)
                                                * K0 * 10.0 ** -K, rel=1e-12)
    # the estimate below the curve extends its power law: with it the total is exact
    # but for the tail above, counted with F(x_max) instead of F(x) for x > x_max
    above_exact, _ = quad(lambda u: norm.cdf((u - math.log(THETA)) / BETA) * K * K0
                          * math.exp(-K * u), math.log(10.0), math.log(1e4))
    exact = K0 * THETA ** -K * math.exp(0.5 * (K * BETA) ** 2)
    total = r.annual_rate * (1 + r.share_below) - r.contributions[-1] + above_exact
    assert total == pytest.approx(exact, rel=1e-9)


def test_curves_as_rates_or_poes_give_the_same_rate():
    levels = np.geomspace(0.2, 20.0, 20)
    rates = K0 * levels ** -K
    via_poe = HazardCurve("pga", levels, rate_from_poe(poe_from_rate(rates, 50.0), 50.0))
    assert risk_integral.risk(via_poe, THETA, BETA).annual_rate == pytest.approx(
        risk_integral.risk(HazardCurve("pga", levels, rates), THETA, BETA).annual_rate,
        rel=1e-10)


def test_a_larger_hazard_never_lowers_the_rate():
    levels = np.geomspace(0.2, 20.0, 20)
    base = K0 * levels ** -K
    bump = np.where(levels > 3.0, 1.5, 1.0) * base  # more strong shaking, still decreasing
    bump = np.minimum.accumulate(np.maximum(bump, base))
    lo = risk_integral.risk(HazardCurve("pga", levels, base), THETA, BETA).annual_rate
    hi = risk_integral.risk(HazardCurve("pga", levels, bump), THETA, BETA).annual_rate
    assert hi > lo


def test_interval_carries_the_bootstrap_replicates():
    curve = _power_law(np.geomspace(0.1, 200.0, 60))
    rng = np.random.default_rng(0)
    replicates = np.column_stack([math.log(THETA) + 0.1 * rng.standard_normal(500),
                                  np.abs(BETA + 0.05 * rng.standard_normal(500))])
    r = risk_integral.risk(curve, THETA, BETA, replicates=replicates)
    closed = K0 * np.exp(replicates[:, 0]) ** -K * np.exp(0.5 * (K * replicates[:, 1]) ** 2)
    np.testing.assert_allclose(r.rate_interval, np.percentile(closed, [2.5, 97.5]), rtol=1e-3)
    assert r.rate_interval[0] < r.annual_rate < r.rate_interval[1]


@pytest.mark.parametrize("median, beta", [(3.9, 0.3), (0.25, 0.8), (12.0, 0.05)])
def test_nrml_mean_stddev_round_trip(tmp_path, median, beta):
    mean, stddev = nrml.mean_stddev(median, beta)
    # the moments of a lognormal, by quadrature
    density = lambda x: norm.pdf(math.log(x / median) / beta) / (beta * x)  # noqa: E731
    upper = median * math.exp(12 * beta)
    assert mean == pytest.approx(quad(lambda x: x * density(x), 0, upper,
                                      points=[median])[0], rel=1e-7)
    second = quad(lambda x: x * x * density(x), 0, upper, points=[median])[0]
    assert stddev == pytest.approx(math.sqrt(second - mean ** 2), rel=1e-6)
    path = nrml.write_fragility_model(tmp_path / "f.xml", [("b1", median, beta)], "pga")
    back = nrml.read_fragility_model(path)["b1"]
    assert back.im == "pga"
    assert back.median == pytest.approx(median, rel=1e-10)
    assert back.beta == pytest.approx(beta, rel=1e-10)
    assert 'shape="logncdf"' in path.read_text() and 'imt="PGA"' in path.read_text()


def test_separated_stripes_give_a_step_in_the_gap():
    from sweep.probability.stripe_results import separated_risk

    curve = HazardCurve("pga", [0.5, 1.5, 3.0, 7.0], [1e-2, 2e-3, 4e-4, 1e-5])
    levels = np.array([1.0, 2.0, 4.0])
    r = separated_risk(curve, levels, np.array([0, 0, 5]), np.array([5, 5, 5]), 50.0, 0.95)
    assert r.annual_rate == pytest.approx(float(curve.rate(math.sqrt(2.0 * 4.0))), rel=1e-12)
    assert r.rate_interval == pytest.approx((float(curve.rate(4.0)), float(curve.rate(2.0))))
