"""``python -m sweep.risk`` says its results plainly: a fragility that reaches past the hazard
curve (a caution with the range it leaves), a body that never overturned (a one-sided bound,
judged against the target and drawn on the map), ``--nrml`` of a known fragility, results of
two risk files of one name kept apart, and figures that read (a band without walls, sparse
labels over many decades, whole titles, bodies named by their parameters)."""
import json
import math

import numpy as np
import pytest
import yaml
from scipy.stats import norm

from sweep.io.problems import InputWarning
from sweep.probability import nrml
from sweep.probability import risk as risk_integral
from sweep.probability.fit import fit_lognormal
from sweep.probability.hazard_curve import HazardCurve
from sweep.risk import main

from risk_cases import G, K, K0, SOURCE


def _power_law(x):
    return K0 * np.asarray(x, dtype=float) ** -K


def _curve_file(tmp_path, levels_g, name="curve.txt"):
    path = tmp_path / name
    levels_g = np.asarray(levels_g, dtype=float)
    path.write_text("pga_g,annual_rate\n" + "".join(
        f"{float(x)!r},{float(r)!r}\n" for x, r in zip(levels_g, _power_law(levels_g * G))))
    return path


def _json(capsys):
    return json.loads(capsys.readouterr().out)


# --- the curve's ends -----------------------------------------------------------------------

def test_a_fragility_past_the_curve_is_cautioned_with_its_range(tmp_path, capsys):
    """A curve to 0.284 g, θ = 0.925 g: λ_O is the closed form of the power law cut at x_n
    (k0 θ^-k e^(k²β²/2) Φ(z_n + kβ)), the part above it at most λ(x_n), and the caution says
    so in the JSON's warnings."""
    path = _curve_file(tmp_path, np.geomspace(0.005, 0.284, 20))
    assert main(["--hazard", str(path), "--im", "pga", "--units", "g", "--median", "0.925g",
                 "--beta", "0.3", "--json"]) == 0
    report = _json(capsys)
    body = report["bodies"][0]
    theta, beta, last = 0.925 * G, 0.3, 0.284 * G
    z = math.log(last / theta) / beta
    within = K0 * theta ** -K * math.exp(0.5 * (K * beta) ** 2) * norm.cdf(z + K * beta)
    assert body["annual_rate"] == pytest.approx(within, rel=1e-6)
    above = norm.cdf(z) * _power_law(last)
    assert body["deaggregation"]["share_above_curve"] == pytest.approx(
        above / within, rel=1e-6)
    assert body["deaggregation"]["rate_above_curve_at_most"] == pytest.approx(
        _power_law(last), rel=1e-6)
    [said] = [w for w in report["warnings"] if "last level" in w]
    most = within - above + _power_law(last)
    assert f"{100 * above / within:.3g} %" in said and f"{most:.3g}/yr" in said
    assert "give a hazard curve to higher levels" in said


def test_a_curve_past_the_fragility_has_no_caution(tmp_path, capsys):
    path = _curve_file(tmp_path, np.geomspace(0.005, 8.0, 200))
    assert main(["--hazard", str(path), "--im", "pga", "--units", "g", "--median", "0.4g",
                 "--beta", "0.3", "--json"]) == 0
    report = _json(capsys)
    assert report["bodies"][0]["deaggregation"]["share_above_curve"] < 0.05
    assert not [w for w in report["warnings"] if "rate of overturning" in w]


def test_a_curve_that_starts_too_high_is_cautioned(tmp_path, capsys):
    """The first segment's power law extended below 0.3 g adds more than 5 % (its share,
    1 − Φ(z_1 + kβ)/… of the closed form): said, not included."""
    path = _curve_file(tmp_path, np.geomspace(0.3, 20.0, 100))
    assert main(["--hazard", str(path), "--im", "pga", "--units", "g", "--median", "0.3g",
                 "--beta", "0.4", "--json"]) == 0
    report = _json(capsys)
    theta, beta, first = 0.3 * G, 0.4, 0.3 * G
    whole = K0 * theta ** -K * math.exp(0.5 * (K * beta) ** 2)
    z = math.log(first / theta) / beta
    below = whole * norm.cdf(z + K * beta) - norm.cdf(z) * _power_law(first)
    share = report["bodies"][0]["deaggregation"]["share_below_curve_not_included"]
    assert share == pytest.approx(below / (whole - below), rel=1e-4)
    assert any("below the hazard curve's first level" in w for w in report["warnings"])


# --- a body that never overturned ----------------------------------------------------------

def _bound_in_the_test(levels, n, confidence, independent, rate=_power_law, first=None):
    """λ_up = Σ_j q_j [λ(x_(j−1)) − λ(x_j)] + λ(x_m), q_j = min_(i≥j) p_i, p_i = 1 − (1 −
    c)^(1/N_i) with N_i the motions at x_i and above (independent) or at x_i only."""
    n = np.asarray(n, dtype=float)
    trials = np.array([n[j:].sum() for j in range(n.size)]) if independent else n
    p = 1.0 - (1.0 - confidence) ** (1.0 / trials)
    q = np.array([p[j:].min() for j in range(p.size)])
    edges = np.concatenate([[first], levels])
    return sum(q[j] * (rate(edges[j]) - rate(edges[j + 1])) for j in range(n.size)) \
        + rate(levels[-1])


@pytest.mark.parametrize("n, independent", [([10, 10, 10, 10], True),
                                            ([12, 5, 9, 7], True),
                                            ([12, 5, 9, 7], False)])
def test_never_overturned_bound_against_its_formula(n, independent):
    curve = HazardCurve("pga", np.geomspace(0.1, 30.0, 60), _power_law(np.geomspace(0.1, 30.0,
                                                                                    60)))
    levels = np.array([1.0, 2.0, 4.0, 8.0])
    r = risk_integral.none_overturned(curve, levels, n, 50.0, 0.95, independent)
    expected = _bound_in_the_test(levels, n, 0.95, independent, first=0.1)
    assert r.annual_rate == pytest.approx(expected, rel=1e-12)
    assert r.probability == pytest.approx(1.0 - math.exp(-50.0 * expected), rel=1e-12)
    assert r.contributions.sum() == pytest.approx(expected, rel=1e-12)
    assert r.bound.endswith("one-sided 95 % bound")


@pytest.mark.parametrize("independent", [True, False])
def test_a_fragility_above_the_bound_would_rarely_give_none(independent):
    """What the bound means: a non-decreasing fragility raised just above the staircase at
    one stripe j (and so at every stripe above) has λ_O above the bound, and under it 0 of n
    at every stripe has a chance below 1 − c: the product over the stripes of (1 − F)^n
    with independent motions, at most the least one's with the same records; for the records
    the bound is tight (the chance is just under 1 − c)."""
    first, levels, n = 0.1, np.array([1.0, 2.0, 4.0, 8.0]), np.array([8, 6, 8, 8])
    curve = HazardCurve("pga", np.geomspace(first, 30.0, 60), _power_law(np.geomspace(
        first, 30.0, 60)))
    bound = risk_integral.none_overturned(curve, levels, n, 50.0, 0.95,
                                          independent).annual_rate
    q = risk_integral.stripe_bounds(n, 0.95, independent)
    edges = np.concatenate([[first], levels])
    chances = []
    for j in range(levels.size):
        fragility = np.maximum(q, np.where(np.arange(q.size) >= j, q[j] + 1e-9, 0.0))
        rate = sum(fragility[i] * (_power_law(edges[i]) - _power_law(edges[i + 1]))
                   for i in range(q.size)) + _power_law(levels[-1])
        assert rate > bound
        none = (1.0 - fragility) ** n
        chances.append(np.prod(none) if independent else none.min())
    assert max(chances) < 0.05
    if not independent:
        assert max(chances) > 0.05 * (1 - 1e-6)


def _risk_file(tmp_path, name="risk.yaml", **sections):
    path = tmp_path / name
    path.write_text(yaml.safe_dump({"name": "t", "hazard": {"source": SOURCE}, **sections}))
    return path


@pytest.fixture(scope="module")
def safe_grid(tmp_path_factory):
    """Slender and cubic blocks (b/h 0.25, 1; B 15, 30 cm) under 2 stripes of 3 motions at
    0.2 and 0.4 g: a cube cannot rock below 1 g, so it never overturns."""
    folder = tmp_path_factory.mktemp("grid")
    path = _risk_file(folder, scene={"body": {"B": "15 cm", "H": "60 cm"},
                                     "contact": {"mu": 0.8}},
                      stripes={"levels": ["2 m/s^2", "4 m/s^2"], "motions": 3},
                      grid={"B": ["15 cm", "30 cm"], "b_over_h": [0.25, 1.0]}, target=0.5,
                      replicates=20)
    return folder, path


def test_a_body_never_overturned_gets_its_bound(safe_grid, capsys):
    folder, path = safe_grid
    assert main([str(path), "--json"]) == 0
    report = _json(capsys)
    cube = report["bodies"][1]  # B 15 cm, b/h 1
    assert cube["fragility"]["stripes"]["overturned"] == [0, 0]
    levels = np.array(cube["fragility"]["stripes"]["levels"])
    hazard = report["hazard"]

    def rate(x):  # log-log interpolation of the curve, written here
        return np.exp(np.interp(np.log(x), np.log(hazard["levels"]),
                                np.log(hazard["annual_rates"])))
    expected = _bound_in_the_test(levels, [3, 3], 0.95, True, rate, hazard["levels"][0])
    assert cube["annual_rate"] is None and cube["probability"] is None
    assert cube["annual_rate_upper_bound"] == pytest.approx(expected, rel=1e-9)
    bound_p = 1.0 - math.exp(-50.0 * expected)
    assert cube["probability_upper_bound"] == pytest.approx(bound_p, rel=1e-9)
    assert cube["bound"] == "none overturned in 3 motions at each stripe: one-sided 95 % bound"
    assert cube["meets_target"] is (bound_p <= 0.5) is True
    assert any("none overturned at any stripe" in w for w in report["warnings"])


def test_the_bound_in_the_text_and_the_map(safe_grid, capsys, tmp_path):
    import matplotlib
    matplotlib.use("Agg")

    from sweep.io.risk_schema import load_risk
    from sweep.plots.risk import figure_map
    from sweep.probability import risk_report
    from sweep.probability.risk_inputs import checked_hazard

    folder, path = safe_grid
    assert main([str(path)]) == 0
    text = capsys.readouterr().out
    cube = "B 15 cm × H 15 cm (b/h 1), μ 0.8"  # b/h keeps B: H = 15 cm / 1
    assert f"{cube}:" in text and "annual rate of overturning ≤" in text
    meeting = text.split("bodies meeting the target")[1]
    assert cube in meeting
    spec = load_risk(path, hazard=checked_hazard)
    with pytest.warns(InputWarning, match="none overturned at any stripe"):
        outcome = risk_report.compute(spec, folder / "results" / "t")
    fig = figure_map(outcome)
    bound = outcome.risks[0, 1].probability
    labels = [t.get_text() for t in fig.axes[0].texts]
    bounded = [i for i in np.ndindex(*outcome.shape) if outcome.risks[i].bound is not None]
    assert (0, 1) in bounded and (1, 1) in bounded  # the cubes
    assert labels.count(f"≤ {100 * bound:.2g} %") == len(bounded) and "n/a" not in labels
    stars = [line for line in fig.axes[0].lines if line.get_marker() == "*"]
    starred = set(zip(*(np.round(a, 9) for a in stars[0].get_data())))
    assert {(0.15, 1.0), (0.3, 1.0)} <= starred  # their bounds meet 50 %
    assert "μ 0.8" in fig.get_suptitle()


# --- the separation said as it is ------------------------------------------------------------

@pytest.mark.parametrize("k, says, never", [
    ([0, 0, 0, 4], ["none overturned below it"], "all overturned"),
    ([0, 0, 8, 8], ["none overturned up to a level", "all overturned above it"], "one level"),
    ([0, 3, 8, 8], ["only one level", "none overturned below it", "all overturned above it"],
     "up to a level"),
])
def test_a_separation_is_said_as_the_data_are(k, says, never):
    fit = fit_lognormal([1.0, 2.0, 3.0, 4.0], k, 8, replicates=20)
    assert all(part in fit.reason for part in says)
    assert never not in fit.reason


# --- --nrml of a known fragility ------------------------------------------------------------

def test_nrml_of_a_given_fragility_reads_back(tmp_path, capsys):
    path = _curve_file(tmp_path, np.geomspace(0.005, 20.0, 100))
    xml = tmp_path / "given.xml"
    assert main(["--hazard", str(path), "--im", "pga", "--units", "g", "--median", "0.4g",
                 "--beta", "0.3", "--nrml", str(xml), "--json"]) == 0
    assert _json(capsys)["written"] == [str(xml)]
    [back] = nrml.read_fragility_model(xml).values()
    assert back.median == pytest.approx(0.4 * G, rel=1e-9)
    assert back.beta == pytest.approx(0.3, rel=1e-9)


def test_nrml_of_a_risk_files_fragility(tmp_path, capsys):
    _curve_file(tmp_path, np.geomspace(0.005, 20.0, 100))
    path = tmp_path / "risk.yaml"
    path.write_text(yaml.safe_dump({
        "name": "k", "hazard": {"file": {"path": "curve.txt", "format": "columns",
                                          "im": "pga", "units": "g"}},
        "fragility": {"median": "0.5 g", "beta": 0.45}}))
    xml = tmp_path / "known.xml"
    assert main([str(path), "--nrml", str(xml)]) == 0
    [back] = nrml.read_fragility_model(xml).values()
    assert (back.median, back.beta) == (pytest.approx(0.5 * G, rel=1e-9),
                                         pytest.approx(0.45, rel=1e-9))


# --- results of one name ----------------------------------------------------------------------

def test_two_risk_files_of_one_name_are_kept_apart(tmp_path, capsys):
    _curve_file(tmp_path, np.geomspace(0.005, 20.0, 100))
    paths = []
    for stem, median in (("a", "0.3 g"), ("b", "0.6 g")):
        paths.append(tmp_path / f"{stem}.yaml")
        paths[-1].write_text(yaml.safe_dump({
            "name": "shared", "hazard": {"file": {"path": "curve.txt", "format": "columns",
                                                  "im": "pga", "units": "g"}},
            "fragility": {"median": median, "beta": 0.3}}))
    marker = tmp_path / "results" / "shared" / "risk_file.txt"
    assert main([str(paths[0])]) == 0
    assert marker.read_text().strip() == str(paths[0].resolve())
    capsys.readouterr()
    with pytest.raises(SystemExit) as ended:
        main([str(paths[1])])
    assert ended.value.code == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err
    [line] = [t for t in err.splitlines() if "rename" in t]
    assert str(paths[0].resolve()) in line and "--force" in line
    assert main([str(paths[1]), "--force"]) == 0
    assert marker.read_text().strip() == str(paths[1].resolve())


# --- figures ------------------------------------------------------------------------------------

def test_band_is_pointwise_quantiles_without_walls():
    """Stripes that let many bootstrap replicates separate: the band at each x is the numpy
    percentiles of the replicates' curves built here (a step drawn through its values at the
    levels, joined linearly in ln x), monotone, and never steeper than the steepest
    replicate; drawn as steps, it would jump by more."""
    levels = np.array([1.0, 2.0, 3.0, 4.0])
    fit = fit_lognormal(levels, [0, 2, 6, 8], 8, replicates=300, seed=1)
    reps = fit.replicates
    steps = reps[:, 1] == 0
    assert steps.sum() >= 10  # the case at hand
    x = np.geomspace(0.5, 8.0, 2001)
    log_x = np.log(x)
    curves = np.empty((x.size, len(reps)))
    smooth = ~steps
    curves[:, smooth] = norm.cdf((log_x[:, None] - reps[smooth, 0]) / reps[smooth, 1])
    for j in np.flatnonzero(steps):
        at_levels = np.where(np.log(levels) > reps[j, 0], 1.0,
                             np.where(np.log(levels) < reps[j, 0], 0.0, 0.5))
        curves[:, j] = np.interp(log_x, np.log(levels), at_levels)
    lower, upper = fit.band(x)
    np.testing.assert_allclose(lower, np.percentile(curves, 2.5, axis=1), atol=1e-12)
    np.testing.assert_allclose(upper, np.percentile(curves, 97.5, axis=1), atol=1e-12)
    h = np.diff(log_x)[0]
    steepest = max(1.0 / (reps[smooth, 1].min() * math.sqrt(2 * math.pi)),
                   1.0 / np.diff(np.log(levels)).min())
    for side in (lower, upper):
        assert np.all(np.diff(side) >= -1e-12)
        assert np.abs(np.diff(side)).max() <= steepest * h * (1 + 1e-9)
    walls = np.where(log_x[:, None] > reps[:, 0], 1.0,
                     np.where(log_x[:, None] < reps[:, 0], 0.0, 0.5))
    walls[:, smooth] = curves[:, smooth]
    assert np.abs(np.diff(np.percentile(walls, 97.5, axis=1))).max() > 10 * steepest * h


def _drawn(fig):
    """The Agg renderer of ``fig``, drawn (its ``figure`` attribute set to it)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    FigureCanvasAgg(fig).draw()
    renderer = fig.canvas.get_renderer()
    renderer.figure = fig
    return renderer


def _overlap(boxes):
    return any(a.overlaps(b) for i, a in enumerate(boxes) for b in boxes[i + 1:])


def test_hazard_axes_over_nine_decades_label_sparsely():
    import matplotlib
    matplotlib.use("Agg")

    from sweep.plots.risk import figure_body
    from sweep.probability import risk_report

    levels = np.geomspace(0.001 * G, 5 * G, 40)
    rates = np.geomspace(0.5, 4e-9, 40)
    outcome = risk_report.known(HazardCurve("pga", levels, rates), 0.5 * G, 0.4, 50.0)
    renderer = _drawn(figure_body(outcome))
    ax = renderer.figure.axes[0]
    for axis, (low, high) in ((ax.xaxis, ax.get_xlim()), (ax.yaxis, ax.get_ylim())):
        labels = [t for t, at in zip(axis.get_ticklabels(), axis.get_ticklocs())
                  if t.get_text() and low <= at <= high]
        boxes = [t.get_window_extent(renderer) for t in labels]
        assert 3 <= len(labels) <= 8 and not _overlap(boxes)


def test_titles_say_the_extrapolation_whole(tmp_path):
    import matplotlib
    matplotlib.use("Agg")

    from sweep.plots.risk import figure_body
    from sweep.probability import risk_report

    levels = np.geomspace(0.005, 0.284, 20) * G
    with pytest.warns(InputWarning, match="give a hazard curve to higher levels"):
        outcome = risk_report.known(HazardCurve("pga", levels, _power_law(levels)),
                                    0.925 * G, 0.3, 50.0)
    fig = figure_body(outcome)
    titles = [ax.get_title() for ax in fig.axes if ax.get_title()]
    assert not any("…" in t for t in titles)
    assert any("give a curve to higher levels" in t for t in titles)
    renderer = _drawn(fig)
    for ax in fig.axes:
        box = ax.title.get_window_extent(renderer)
        assert box.x0 >= 0 and box.x1 <= fig.bbox.width
