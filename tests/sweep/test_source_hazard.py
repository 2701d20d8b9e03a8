"""The hazard of the package's sources against independent values: the Gutenberg-Richter
density against its integral, a characteristic source against ν(1 − Φ((ln x − μ)/σ)) with
pygmm's μ and σ, a Gutenberg-Richter point source against a Monte Carlo integration over
magnitudes written here (inverse CDF, pygmm called for each sample), and the disaggregation
against the curve it splits."""
import math

import numpy as np
import pygmm
import pytest
from scipy.integrate import quad
from scipy.stats import norm

from sweep.probability import source_hazard as sh

G = 9.80665
GR = sh.Recurrence(rate=0.05, m_min=5.0, m_max=7.5, b=1.0)


def _bssa14_pga(m, rjb_km, depth_km, vs30=760.0):
    """ln median PGA [ln m/s²] and sigma straight from pygmm."""
    model = pygmm.BooreStewartSeyhanAtkinson2014(pygmm.Scenario(
        mag=m, dist_jb=rjb_km, dist_rup=math.hypot(rjb_km, depth_km), v_s30=vs30,
        mechanism="SS"))
    return math.log(model.pga * G), model.ln_std_pga


def test_gutenberg_richter_density_integrates_to_one_and_bins_hold_its_mass():
    total, _ = quad(GR.pdf, 4.0, 8.0, points=[5.0, 7.5])
    assert total == pytest.approx(1.0, abs=1e-10)
    centres, edges, p = GR.bins(0.1)
    assert p.sum() == pytest.approx(1.0, abs=1e-12)
    assert p[3] == pytest.approx(quad(GR.pdf, edges[3], edges[4])[0], rel=1e-10)
    # a-value: log10 N(M >= m) = a - b m
    assert sh.Recurrence.from_a_value(3.7, 1.0, 5.0, 7.5).rate == pytest.approx(10 ** -1.3)


def test_characteristic_source_is_one_lognormal_exceedance():
    nu, m, r, depth = 0.01, 6.5, 20e3, 8e3
    model = sh.SourceModel([sh.point_source(sh.Recurrence(nu, m, characteristic=True), r,
                                            depth)], 760.0, "BSSA14", "pga")
    mu, sigma = _bssa14_pga(m, 20.0, 8.0)
    levels = np.array([0.5, 2.0, 6.0])
    expected = nu * norm.sf((np.log(levels) - mu) / sigma)
    np.testing.assert_allclose(model.rates(levels), expected, rtol=1e-12)


@pytest.mark.parametrize("name, cls", [("ASK14", pygmm.AbrahamsonSilvaKamai2014),
                                       ("CB14", pygmm.CampbellBozorgnia2014),
                                       ("CY14", pygmm.ChiouYoungs2014)])
def test_other_models_by_name(name, cls):
    """A characteristic source of each model against pygmm called here on a vertical point
    rupture (Rjb = Rx = epicentral distance, Rrup = hypocentral distance, 1 km wide)."""
    model = sh.SourceModel([sh.point_source(sh.Recurrence(0.01, 6.0, characteristic=True),
                                            12e3, 6e3)], 400.0, name, "sa(0.5)")
    gm = cls(pygmm.Scenario(mag=6.0, dist_jb=12.0, dist_rup=math.hypot(12.0, 6.0),
                            dist_x=12.0, v_s30=400.0, mechanism="SS", depth_hyp=6.0,
                            depth_tor=6.0, dip=90.0, width=1.0))
    mu = math.log(gm.interp_spec_accels([0.5])[0] * G)
    sigma = gm.interp_ln_stds([0.5])[0]
    assert model.rates([2.0])[0] == pytest.approx(0.01 * norm.sf((math.log(2.0) - mu) / sigma),
                                                  rel=1e-10)


def test_gutenberg_richter_point_source_against_monte_carlo():
    """λ(x) and the mean magnitude of the disaggregation against sampling M by the inverse
    CDF of the truncated density, to 3 standard errors of the sampling."""
    depth, r = 8e3, 15e3
    model = sh.SourceModel([sh.point_source(GR, r, depth)], 760.0, "BSSA14", "pga", dm=0.02)
    rng = np.random.default_rng(1)
    u = rng.uniform(size=600)
    beta = GR.b * math.log(10.0)
    m = GR.m_min - np.log1p(-u * -math.expm1(-beta * (GR.m_max - GR.m_min))) / beta
    mu, sigma = np.array([_bssa14_pga(mi, 15.0, 8.0) for mi in m]).T
    for level in (1.0, 4.0):
        exceed = GR.rate * norm.sf((math.log(level) - mu) / sigma)
        se = exceed.std(ddof=1) / math.sqrt(m.size)
        assert abs(model.rates([level])[0] - exceed.mean()) < 3 * se
        mean_m = np.sum(exceed * m) / exceed.sum()
        weights = exceed / exceed.sum()
        se_m = math.sqrt(np.sum(weights ** 2 * (m - mean_m) ** 2))  # ratio estimator
        d = model.disaggregate([level], [0.0, 50e3])
        assert abs(d.mean_magnitude[0] - mean_m) < 3 * se_m
        assert d.mean_distance[0] == pytest.approx(math.hypot(r, depth))


def test_disaggregation_of_an_area_sums_to_the_curve():
    area = sh.area_source(GR, (-40e3, 40e3), (-30e3, 50e3), 20e3, 10e3)
    assert area.weights.sum() == pytest.approx(1.0)
    model = sh.SourceModel([area, sh.point_source(GR, 5e3, 5e3)], 500.0, "BSSA14", "pga")
    levels = np.array([0.3, 1.5, 5.0])
    d = model.disaggregate(levels, [0.0, 10e3, 20e3, 40e3, 80e3])
    np.testing.assert_allclose(d.contributions.sum(axis=(1, 2)), model.rates(levels),
                               rtol=1e-12)
    assert np.all(np.diff(d.mean_magnitude) > 0)  # stronger shaking: larger earthquakes


def test_draws_follow_the_disaggregation():
    model = sh.SourceModel([sh.point_source(GR, 15e3, 8e3)], 760.0, "BSSA14", "pga")
    drawn = model.draw(4.0, 400, np.random.default_rng(0))
    d = model.disaggregate([4.0], [0.0, 50e3])
    assert np.all((drawn[:, 0] >= GR.m_min) & (drawn[:, 0] <= GR.m_max))
    assert np.allclose(drawn[:, 1], math.hypot(15e3, 8e3))
    se = drawn[:, 0].std() / math.sqrt(len(drawn))
    assert abs(drawn[:, 0].mean() - d.mean_magnitude[0]) < 4 * se


def test_area_source_against_quasi_monte_carlo():
    """λ(x) and the mean Rrup of the disaggregation of a 40 x 40 km area (2 km cells) against
    an integration over magnitude and position written here: randomized (scrambled) Sobol
    points, magnitudes by inverse CDF, positions uniform in the rectangle, pygmm per point;
    four scrambles give the standard error.  Tolerance: 4 standard errors and the cells'
    discretization (0.5 % at these levels, measured against 1 km cells)."""
    from scipy.stats import qmc

    recurrence = sh.Recurrence(0.05, 5.0, 7.0, 1.0)
    model = sh.SourceModel([sh.area_source(recurrence, (20e3, 60e3), (-20e3, 20e3), 2e3, 10e3)],
                           760.0, "BSSA14", "pga")
    levels = np.array([0.05, 0.2]) * G
    beta = math.log(10.0)
    estimates = []
    for scramble in range(4):
        s = qmc.Sobol(3, scramble=True, seed=scramble).random(256)
        m = 5.0 - np.log1p(-s[:, 0] * -math.expm1(-2.0 * beta)) / beta
        x, y = 20.0 + 40.0 * s[:, 1], -20.0 + 40.0 * s[:, 2]
        rjb = np.hypot(x, y)
        mu, sigma = np.array([_bssa14_pga(mi, ri, 10.0) for mi, ri in zip(m, rjb)]).T
        exceed = recurrence.rate * norm.sf((np.log(levels)[:, None] - mu) / sigma)
        rrup = np.hypot(rjb, 10.0) * 1e3
        estimates.append(np.concatenate([exceed.mean(1), (exceed * rrup).sum(1)
                                         / exceed.sum(1)]))
    estimates = np.array(estimates)
    mean, se = estimates.mean(0), estimates.std(0, ddof=1) / 2.0
    d = model.disaggregate(levels, [0.0, 100e3])
    package = np.concatenate([model.rates(levels), d.mean_distance])
    assert np.all(np.abs(package - mean) <= 4 * se + 0.005 * np.abs(mean))
