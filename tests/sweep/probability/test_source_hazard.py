"""The hazard of the package's sources against independent values: the Gutenberg-Richter
density against its integral, a characteristic source against ν(1 − Φ((ln x − μ)/σ)) with
pygmm's μ and σ, a Gutenberg-Richter point source against a Monte Carlo integration over
magnitudes written here (inverse CDF, pygmm called for each sample), the disaggregation
against the curve it splits; area sources against a brute-force sum over 0.5 km cells and
their draws against the areal density; OpenQuake's truncation (scipy's truncnorm) and
a-value (TruncatedGRMFD's bin rates); sources deeper than the models' range warned, and
deeper than any crust refused."""
import json
import math

import numpy as np
import pygmm
import pytest
import yaml
from scipy.integrate import quad
from scipy.stats import norm, truncnorm

from sweep.io.problems import InputWarning
from sweep.io.risk_schema import SourceHazard
from sweep.probability import risk_inputs
from sweep.probability import source_hazard as sh
from sweep.risk import main

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
    """λ(x) and the mean Rrup of the disaggregation of a 40 x 40 km area (steps of at most
    2 km) against an integration over magnitude and position written here: randomized
    (scrambled) Sobol points, magnitudes by inverse CDF, positions uniform in the rectangle,
    pygmm per point; four scrambles give the standard error.  Tolerance: 4 standard errors
    and 0.5 % (four scrambles estimate the standard error itself loosely)."""
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


def _gr_bins(m_min, m_max, dm, b=1.0):
    """Centres and probabilities of the bins of width ``dm`` of the truncated exponential
    density, from its CDF written here."""
    edges = np.arange(m_min, m_max + 1e-9, dm)
    beta = b * math.log(10.0)
    cdf = -np.expm1(-beta * (edges - m_min)) / -math.expm1(-beta * (m_max - m_min))
    return 0.5 * (edges[1:] + edges[:-1]), np.diff(cdf)


def _cells_hazard(levels, rate, east_km, north_km, depth_km, dm, cell_km=0.5, step_km=0.25):
    """λ(x) of a rectangle by brute force: the mean over 0.5 km square cells (their centres)
    of P(IM > x), pygmm's μ and σ tabulated every 0.25 km of Rjb and interpolated linearly.
    Its own error, against 0.2 km cells and a 0.1 km table: at most 0.13 % at 0.5-2 g."""
    mags, p = _gr_bins(5.0, 7.0, dm)
    x = np.arange(east_km[0] + cell_km / 2, east_km[1], cell_km)
    y = np.arange(north_km[0] + cell_km / 2, north_km[1], cell_km)
    rjb = np.hypot(*np.meshgrid(x, y)).ravel()
    table = np.arange(0.0, rjb.max() + step_km, step_km)
    out = np.zeros(len(levels))
    for m, pm in zip(mags, p):
        mu, sigma = np.array([_bssa14_pga(m, r, depth_km) for r in table]).T
        eps = (np.log(levels)[:, None] - np.interp(rjb, table, mu)) / np.interp(rjb, table,
                                                                               sigma)
        out += rate * pm * norm.sf(eps).mean(axis=1)
    return out


@pytest.mark.parametrize("east_km, north_km, spacing", [
    ((-50, 50), (-50, 50), None),      # the site in the middle
    ((-50, 50), (-50, 50), 10e3),      # the same with the documented spacing: a bound
    ((2, 102), (-3, 97), None),        # the site 2 km west of the area, near its corner
    ((20, 120), (10, 110), None)])     # the site outside, off a corner
def test_area_source_against_cells(east_km, north_km, spacing):
    """A 100 x 100 km area at 10 km depth, M 5-7, against the brute-force sum over 0.5 km
    cells written here, at 0.5, 1 and 2 g: within 0.3 % (the reference's own error is up to
    0.13 %; 10 km cells gave −15, −38 and −61 % around the site, 2 km cells −0.4 % to −2.5 %
    beside it)."""
    levels = np.array([0.5, 1.0, 2.0]) * G
    area = sh.area_source(sh.Recurrence(0.05, 5.0, 7.0), np.array(east_km) * 1e3,
                          np.array(north_km) * 1e3, spacing, 10e3)
    package = sh.SourceModel([area], 760.0, "BSSA14", "pga", dm=0.25).rates(levels)
    expected = _cells_hazard(levels, 0.05, east_km, north_km, 10.0, 0.25)
    np.testing.assert_allclose(package, expected, rtol=3e-3)


def _disc_in_square(radius, half):
    """Area of a disc of ``radius`` centred in a square of half-side ``half`` (radius between
    half and half √2): the disc less its four circular segments beyond the sides."""
    segment = radius ** 2 * math.acos(half / radius) - half * math.sqrt(radius ** 2 - half ** 2)
    return math.pi * radius ** 2 - 4.0 * segment


def test_area_draws_follow_the_areal_density_and_the_disaggregation():
    """At a level every earthquake exceeds, the drawn epicentral distances of a 100 x 100 km
    area around the site follow the uniform density over the area: the share within 30 km is
    π 30²/100², within 60 km the disc's part inside the square over its area (4 standard
    errors of a binomial share); at 1 g, the drawn mean Rrup is the disaggregation's (4
    standard errors)."""
    depth = 10e3
    model = sh.SourceModel([sh.area_source(sh.Recurrence(0.05, 5.0, 7.0), (-50e3, 50e3),
                                           (-50e3, 50e3), None, depth)],
                           760.0, "BSSA14", "pga", dm=0.25)
    count = 4000
    drawn = model.draw(1e-6, count, np.random.default_rng(3))
    rjb = np.sqrt(drawn[:, 1] ** 2 - depth ** 2)
    for radius, share in ((30e3, math.pi * 30e3 ** 2 / 100e3 ** 2),
                          (60e3, _disc_in_square(60e3, 50e3) / 100e3 ** 2)):
        se = math.sqrt(share * (1 - share) / count)
        assert abs(np.mean(rjb <= radius) - share) < 4 * se
    strong = model.draw(G, count, np.random.default_rng(4))[:, 1]
    mean_distance = model.disaggregate([G], [0.0, 200e3]).mean_distance[0]
    assert abs(strong.mean() - mean_distance) < 4 * strong.std() / math.sqrt(count)


def _source_entry(recurrence, depth="8 km", **extra):
    return SourceHazard.model_validate({
        "model": "BSSA14", "im": "pga", "vs30": "760 m/s", **extra,
        "sources": [{"kind": "point", "distance": "10 km", "depth": depth,
                     "recurrence": recurrence}]})


def test_truncation_is_openquakes_truncated_normal():
    """``truncation_level: 3`` against scipy's truncnorm(−3, 3).sf(ε) per magnitude bin, with
    pygmm's μ and σ, summed here: at 1 g; and 0 at 2 g, where every bin's ε exceeds 3."""
    model = risk_inputs.source_model(_source_entry(
        {"rate": 0.02, "m_min": 5.5, "m_max": 7.5}, truncation_level=3))
    mags, p = _gr_bins(5.5, 7.5, sh.DM)
    mu, sigma = np.array([_bssa14_pga(m, 10.0, 8.0) for m in mags]).T
    for level in (G, 2 * G):
        eps = (math.log(level) - mu) / sigma
        expected = np.sum(0.02 * p * truncnorm.sf(eps, -3, 3))
        assert model.rates([level])[0] == pytest.approx(expected, rel=1e-10, abs=0)
    assert np.all((math.log(2 * G) - mu) / sigma > 3)
    assert model.rates([2 * G])[0] == 0.0


@pytest.mark.parametrize("m_max", [6.0, 7.0])
def test_a_value_is_openquakes_truncated_gutenberg_richter(m_max):
    """``a: 4`` as OpenQuake's TruncatedGRMFD: bins of 0.05 from m_min with rates
    10^(a − b m_lo) − 10^(a − b m_hi), each at its centre, written here (ΔM = 1 and 2)."""
    a, b, m_min = 4.0, 1.0, 5.0
    model = risk_inputs.source_model(_source_entry({"a": a, "b": b, "m_min": m_min,
                                                    "m_max": m_max}))
    lo = np.arange(m_min, m_max - 1e-9, sh.DM)
    rates = 10.0 ** (a - b * lo) - 10.0 ** (a - b * (lo + sh.DM))
    mu, sigma = np.array([_bssa14_pga(m, 10.0, 8.0) for m in lo + sh.DM / 2]).T
    for level in (0.1 * G, G):
        expected = np.sum(rates * norm.sf((math.log(level) - mu) / sigma))
        assert model.rates([level])[0] == pytest.approx(expected, rel=1e-10)


def test_a_value_of_a_characteristic_source_is_the_rate_above_m_min():
    model = risk_inputs.source_model(_source_entry({"a": 4.0, "b": 1.0, "m_min": 6.0,
                                                    "characteristic": True}))
    mu, sigma = _bssa14_pga(6.0, 10.0, 8.0)
    assert model.rates([G])[0] == pytest.approx(1e-2 * norm.sf((math.log(G) - mu) / sigma),
                                                rel=1e-10)


def test_a_source_deeper_than_the_models_range_is_warned():
    with pytest.warns(InputWarning, match=r"hazard\.source\.sources\[0\]\.depth: deeper than "
                                          r"the ground-motion model's range"):
        risk_inputs.source_model(_source_entry({"rate": 0.02, "m_min": 5.5, "m_max": 7.5},
                                               depth="25 km"))


def _depth_risk_file(tmp_path, depth):
    path = tmp_path / "risk.yaml"
    entry = {"model": "BSSA14", "im": "pga", "vs30": "760 m/s",
             "levels": {"start": "0.02 g", "stop": "2 g", "num": 10},
             "sources": [{"kind": "area", "east": ["-20 km", "20 km"],
                          "north": ["-20 km", "20 km"], "depth": depth,
                          "recurrence": {"rate": 0.02, "m_min": 5.5, "m_max": 7.0}}]}
    path.write_text(yaml.safe_dump({"name": "deep", "hazard": {"source": entry},
                                    "fragility": {"median": "0.4 g", "beta": 0.3}}))
    return path


def test_the_risk_command_reports_the_depth_warning(tmp_path, capsys):
    status = main([str(_depth_risk_file(tmp_path, "30 km")), "--json"])
    out, err = capsys.readouterr()
    line = "hazard.source.sources[0].depth: deeper than the ground-motion model's range"
    assert status == 0
    assert f"warning: {line}" in err
    assert any(w.startswith(line) for w in json.loads(out)["warnings"])


def test_a_depth_below_any_crust_is_refused(tmp_path, capsys):
    with pytest.raises(SystemExit) as ended:
        main([str(_depth_risk_file(tmp_path, "1000 km")), "--json"])
    err = capsys.readouterr().err
    assert ended.value.code == 2
    assert "hazard.source.sources[0].depth: deeper than any crust (80 km)" in err
    assert "(got: '1000 km')" in err and "Traceback" not in err
