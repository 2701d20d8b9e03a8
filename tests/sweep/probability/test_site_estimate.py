"""What bodies at a site tell in probability (sweep.probability.site, python -m sweep.estimate):
the likelihood and posterior against closed forms on hand-made outcomes, the joint likelihood
against the product of marginals, a deterministic ensemble, West's level in a real ensemble,
sliding bodies kept out, and the command (formats, JSON, CSV, figures, errors, reuse)."""
import csv
import json
import math
import time

import matplotlib.pyplot as plt
import numpy as np
import pytest
import xarray as xr
import yaml

from sweep import estimate
from sweep.io.bodies_schema import load_survey
from sweep.plots.site import figure_site
from sweep.probability import site, site_bodies, site_posterior, site_report, site_studies
from study_helpers import cli

G = 9.80665
RECORDS = ["elcentro1940_ns", "elcentro1940_ew", "taft1952_ew_s69e"]


# --- (1) the posterior in closed form ---------------------------------------------------------

# levels x = e^0 .. e^3; one body seen overturned; member 1 overturns it from x = e^1 up,
# member 2 from e^2 up: L = (0, 1/2, 1, 1), linear in u = ln x between levels.
U = np.arange(4.0)
ONE_BODY = np.array([[[0, 0], [1, 0], [1, 1], [1, 1]]], dtype=float)
RATIOS = np.array([0.1, 0.2])  # PGV/PGA of the two members [s]


def test_posterior_of_two_members_by_hand():
    consistent = site_posterior.consistency(ONE_BODY, [True])
    np.testing.assert_array_equal(site_posterior.likelihood(consistent)[0], [0, 0.5, 1, 1])
    post = site_posterior.posterior(np.exp(U), consistent, np.exp(U)[:, None] * RATIOS,
                                    [0.05, 0.5, 0.95])
    # Z = int L du = 1/4 + 3/4 + 1 = 2: masses 1/8, 3/8, 1/2 on the three segments.
    # 5 %: u^2/8 = 0.05 on the first; 50 %: 1/8 + (u/2 + u^2/4)/2 = 1/2 -> u = 1 on the
    # second (u = 2 in all); 95 %: 1/2 + u/2 = 0.95 -> u = 0.9 on the third.
    np.testing.assert_allclose(np.log(post.pga), [math.sqrt(0.4), 2.0, 2.9], rtol=1e-10)
    np.testing.assert_allclose(post.density, [0, 0.25, 0.5, 0.5], rtol=1e-12)
    assert not post.cut_below and post.cut_above
    # PGV: member 1 at ln v = u + ln 0.1 carries mass 5/2, member 2 at u + ln 0.2 mass 3/2.
    # Median at t = ln 0.1 + tau: 1/2 + (tau - 1) + y^2/2 = 2 with y = tau - ln 2 - 1, so
    # y = -1 + sqrt(4 - 2 ln 2).
    tau = -1 + math.sqrt(4 - 2 * math.log(2)) + math.log(2) + 1
    assert post.pgv[1] == pytest.approx(0.1 * math.exp(tau), rel=1e-10)


def test_body_bounds_by_hand():
    x, p = np.exp(U), np.array([0, 0.5, 1, 1])
    # overturned: P crosses 0.05 at u = 0.1, 0.5 at u = 1, 0.95 at u = 1.9
    lows = [site_bodies.body_bound(x, p, q, overturned=True) for q in (0.05, 0.5, 0.95)]
    np.testing.assert_allclose(np.log([b.value for b in lows]), [0.1, 1.0, 1.9], rtol=1e-12)
    # standing: survival 1 - P falls through 0.05 at u = 1.9, through 0.95 at u = 0.1
    highs = [site_bodies.body_bound(x, p, q, overturned=False) for q in (0.05, 0.95)]
    np.testing.assert_allclose(np.log([b.value for b in highs]), [1.9, 0.1], rtol=1e-12)
    # West's knot at u = 0.5: P = 0 there, so 5 % is reached at u = 0.5 + 0.1 * 0.5
    floored = site_bodies.body_bound(x, p, 0.05, overturned=True, west=math.exp(0.5))
    assert math.log(floored.value) == pytest.approx(0.55, rel=1e-12)
    # outside the levels: said so
    rare = np.array([0, 0, 0, 0.5])
    bound, Bound = site_bodies.body_bound, site_bodies.Bound
    assert bound(x, rare, 0.95, overturned=True) == Bound(None, "above")
    assert bound(x, rare, 0.05, overturned=False) == Bound(None, "above")
    assert bound(x, np.ones(4), 0.5, overturned=True) == Bound(1.0, "below")


# --- (2) joint likelihood, not the product of marginals ---------------------------------------

def test_joint_likelihood_is_not_the_product_of_marginals():
    """Two identical bodies under the same motions overturn together (perfect correlation):
    one seen overturned and one standing can never be reproduced (L = 0), though the product
    of their marginals P (1 - P) is not 0; both overturned give L = P, not P^2."""
    rng = np.random.default_rng(1)
    threshold = rng.uniform(1.0, 5.0, size=40)  # each member's overturning level
    levels = np.linspace(0.5, 6.0, 12)
    o = (levels[:, None] >= threshold[None, :]).astype(float)
    pair = np.stack([o, o])
    p = o.mean(axis=1)
    mixed, _ = site_posterior.likelihood(site_posterior.consistency(pair, [True, False]))
    both, _ = site_posterior.likelihood(site_posterior.consistency(pair, [True, True]))
    np.testing.assert_array_equal(mixed, 0.0)
    assert np.max(p * (1 - p)) > 0.2
    np.testing.assert_allclose(both, p)
    assert np.max(np.abs(both - p * p)) > 0.2
    assert site_posterior.posterior(levels, site_posterior.consistency(pair, [True, False]),
                                    o + 1.0, [0.5]) is None


# --- (3) a deterministic ensemble -------------------------------------------------------------

def _fake_dataset(overturned, pgv):
    """A specimen's dataset as the runner writes it: (pga, record)."""
    dims = ("pga", "record")
    return xr.Dataset({"overturned": (dims, overturned.astype("int8")),
                       "slid": (dims, np.zeros_like(overturned, dtype="int8")),
                       "pgv": (dims, pgv)})


def test_identical_members_give_zero_one_and_bracketing_bounds():
    """Three identical members: each body's fragility is 0 or 1, and every bound, body's or
    site's, lies between the two levels that bracket its step."""
    survey = load_survey({"site": "s", "bodies": [
        {"name": "fallen", "B": "20 cm", "H": "80 cm", "overturned": True},
        {"name": "stood", "B": "30 cm", "H": "60 cm", "overturned": False}],
        "ensemble": {"motions": {"record": RECORDS},
                     "levels": {"pga": {"start": "1 m/s^2", "stop": "16 m/s^2", "num": 9}}}})
    ens = survey.ensemble
    levels = np.array(ens.levels)
    step = {"fallen": 3, "stood": 6}  # first level index at which each body overturns
    datasets = {}
    for body in survey.sites[0].bodies:
        o = np.repeat((np.arange(levels.size) >= step[body.name])[:, None], 3, axis=1)
        key = site_studies.specimen_key(site_studies.specimen(body, ens))
        datasets[key] = _fake_dataset(o, 0.1 * levels[:, None] * np.ones(3))
    result = site.estimate_site(survey.sites[0], ens, datasets)
    for body in result.bodies:
        assert set(np.unique(body.fragility)) == {0.0, 1.0}
        k = step[body.name]
        lo, hi = levels[k - 1], levels[k]
        for bound in body.bounds:
            assert lo <= bound.value <= hi and bound.beyond is None
    # consistent at levels 3, 4, 5 only: the posterior lives on [x_2, x_6]
    np.testing.assert_array_equal(result.likelihood, [0, 0, 0, 1, 1, 1, 0, 0, 0])
    assert np.all((result.posterior.pga >= levels[2]) & (result.posterior.pga <= levels[6]))
    assert not result.posterior.cut_below and not result.posterior.cut_above
    # 3 members x 3 levels reproduce both bodies: enough for percentiles
    assert result.support == site_posterior.Support(9, 27, 3, 9, (levels[2], levels[6]))
    assert result.quantiles is not None


def _survey_of_steps(fallen, stood, levels=9):
    """Survey of one body seen overturned and one standing, three identical-shaped members,
    each overturning the bodies from the level indices ``fallen[m]`` and ``stood[m]`` up."""
    survey = load_survey({"site": "s", "bodies": [
        {"name": "fallen", "B": "20 cm", "H": "80 cm", "overturned": True},
        {"name": "stood", "B": "30 cm", "H": "60 cm", "overturned": False}],
        "ensemble": {"motions": {"record": RECORDS},
                     "levels": {"pga": {"start": "1 m/s^2", "stop": "16 m/s^2",
                                        "num": levels}}}})
    ens = survey.ensemble
    x = np.array(ens.levels)
    datasets = {}
    for body, steps in zip(survey.sites[0].bodies, (fallen, stood)):
        o = np.arange(x.size)[:, None] >= np.array(steps)[None, :]
        datasets[site_studies.specimen_key(site_studies.specimen(body, ens))] = _fake_dataset(
            o, 0.1 * x[:, None] * np.ones(3))
    return survey, x, site.estimate_site(survey.sites[0], ens, datasets)


def test_percentiles_on_one_matching_simulation_are_withheld():
    """Member 0 reproduces both bodies at level 3 alone (the fallen body goes over from level
    3, the standing one from 4); the other two members never: 1 of 27 simulations, at 1 of 9
    levels.  The posterior is the interpolation's triangle on [x_2, x_4], whose percentiles
    are the level spacing: none are given, in the text, the JSON or the CSV, and the advice
    names the levels around x_3."""
    survey, x, result = _survey_of_steps(fallen=(3, 5, 7), stood=(4, 5, 7))
    np.testing.assert_array_equal(result.likelihood, [0, 0, 0, 1 / 3, 0, 0, 0, 0, 0])
    assert result.support == site_posterior.Support(1, 27, 1, 9, (x[2], x[4]))
    assert not result.support.sufficient and result.quantiles is None
    assert result.posterior is not None  # the density is still there to be drawn
    text = site_report.format_text(result)
    assert "1 of 27 simulations (at 1 of 9 levels)" in text
    assert "Percentiles withheld" in text
    assert f"add levels between {x[2] * 100:.0f} and {x[4] * 100:.0f} gal" in " ".join(
        text.split())
    summary = site_report.summary(result)
    assert summary["posterior"]["pga"] is None and summary["posterior"]["pgv"] is None
    assert summary["support"]["simulations_reproducing"] == 1
    assert summary["support"]["sufficient"] is False
    fig = figure_site(result)
    texts = [t.get_text() for ax in fig.axes for t in ax.texts]
    assert any("percentiles withheld" in t and "1 of 27 simulations" in t for t in texts)
    assert not any(t.startswith(("5%\n", "50%\n", "95%\n")) for t in texts)
    plt.close(fig)
    # five matches at three levels are enough: member 0 at levels 3-5, member 1 at 5-6
    _, _, enough = _survey_of_steps(fallen=(3, 5, 7), stood=(6, 7, 7))
    assert (enough.support.matches, enough.support.levels) == (5, 4)
    assert enough.quantiles is not None and "Percentiles withheld" not in site_report.format_text(
        enough)


# --- (4) West's level in a real ensemble ------------------------------------------------------

def _bodies_file(folder, **ensemble):
    raw = {"sites": [
        {"name": "yard", "latitude": 35.0, "longitude": 139.5, "bodies": [
            {"name": "slim", "B": "20 cm", "H": "80 cm", "overturned": True},
            {"name": "stout", "B": "30 cm", "H": "60 cm", "overturned": False},
            {"name": "slab", "B": "50 cm", "H": "55 cm", "overturned": True, "mu": 0.5}]},
        {"name": "field", "bodies": [
            {"name": "slim", "B": "20 cm", "H": "80 cm", "overturned": False}]}],
        "ensemble": {"motions": {"record": RECORDS},
                     "levels": {"pga": {"start": "1 m/s^2", "stop": "12 m/s^2", "num": 6}},
                     "t_end": "8 s", **ensemble}}
    path = folder / "yard.yaml"
    path.write_text(yaml.safe_dump(raw, sort_keys=False))
    return path


@pytest.fixture(scope="module")
def yard(tmp_path_factory):
    """The real ensemble (2 bodies that rock x 3 records x 6 levels, 8 s) and its estimate."""
    folder = tmp_path_factory.mktemp("yard")
    path = _bodies_file(folder)
    survey = load_survey(path)
    datasets = site_studies.ensemble_datasets(survey, site_studies.results_folder(path))
    return path, survey, [site.estimate_site(s, survey.ensemble, datasets)
                          for s in survey.sites]


def test_no_overturning_below_west_and_bounds_above_it(yard):
    _, survey, (first, _) = yard
    levels = np.array(survey.ensemble.levels)
    for body in first.bodies:
        a_o = body.B / body.H * G
        assert body.west == pytest.approx(a_o, rel=1e-12)
        np.testing.assert_array_equal(body.fragility[levels < a_o], 0.0)
        assert body.fragility[-1] > 0  # the range reaches overturning
    slim = first.bodies[0]
    assert slim.overturned
    assert all(b.value is not None and b.value >= slim.west for b in slim.bounds)
    assert np.all(first.posterior.pga >= slim.west)


# --- (5) sliding bodies kept out ---------------------------------------------------------------

def test_sliding_bodies_are_kept_out_and_said_so(yard):
    _, survey, (first, _) = yard
    assert [b.name for b in first.bodies] == ["slim", "stout"]
    (name, reason), = first.excluded
    assert name == "slab" and "mu = 0.5 < B/H = 0.909" in reason
    assert all("mu0.5" not in key for key in site_studies.site_specimens(survey))  # not simulated
    # the deterministic part: the slab (a_o = 0.91 g) would set the PGA limit; it does not
    result = estimate.estimate(survey.sites[0].bodies)
    assert result["lower_limits"]["pga"]["body"] == "slim"
    assert result["excluded"][0]["name"] == "slab"
    assert "slides rather than rocks" in estimate.format_text(result)


def test_the_ensemble_default_friction_can_exclude_too():
    survey = load_survey({"site": "s", "bodies": [
        {"name": "squat", "B": "40 cm", "H": "50 cm", "overturned": True}],
        "ensemble": {"motions": {"record": RECORDS}, "contact": {"mu": 0.5},
                     "levels": {"pga": [1.0, 2.0]}}})
    reason = site_studies.sliding_reason(survey.sites[0].bodies[0], survey.ensemble)
    assert "the ensemble's default" in reason
    # the deterministic part keeps it (its mu is not known)
    result = estimate.estimate(survey.sites[0].bodies)
    assert result["lower_limits"]["pga"]["body"] == "squat" and result["excluded"] == []


# --- (6) the command --------------------------------------------------------------------------

def _run(argv, capsys):
    status = estimate.main([str(a) for a in argv])
    out = capsys.readouterr()
    return status, out.out, out.err


def test_command_json_csv_and_figures(yard, tmp_path, capsys):
    path, _, _ = yard
    results = site_studies.results_folder(path)
    stamps = {p.name: p.stat().st_mtime_ns for p in results.glob("*.nc")}
    assert len(stamps) == 2
    status, out, _ = _run([path, "--json", "--csv", tmp_path / "t.csv", "-o",
                           tmp_path / "f.png"], capsys)
    assert status == 0
    assert {p.name: p.stat().st_mtime_ns for p in results.glob("*.nc")} == stamps  # reused
    data = json.loads(out)
    yard_json, field_json = data["sites"]
    assert (yard_json["site"], yard_json["latitude"]) == ("yard", 35.0)
    assert yard_json["excluded"][0]["name"] == "slab"
    assert yard_json["ensemble"]["excluded"][0]["name"] == "slab"
    side = yard_json["side_by_side"]["pga"]
    assert side["deterministic_lower_limit"] == pytest.approx(0.25 * G)
    assert len(side["posterior_quantiles"]) == 3
    assert field_json["lower_limits"] is None and field_json["ensemble"]["bodies"]
    with open(tmp_path / "t.csv") as f:
        rows = list(csv.DictReader(f))
    assert [(r["site"], r["body"]) for r in rows] == [
        ("yard", "slim"), ("yard", "stout"), ("yard", "slab"), ("field", "slim")]
    assert rows[0]["latitude"] == "35" and rows[0]["bound"] == "lower"
    assert (rows[0]["B_m"], rows[0]["H_m"]) == ("0.2", "0.8")  # 20 cm, 80 cm: no float noise
    assert rows[2]["bound"] == "" and "slides" in rows[2]["excluded"]
    assert (tmp_path / "f_yard.png").stat().st_size > 10_000
    assert (tmp_path / "f_field.png").stat().st_size > 10_000
    status, text, _ = _run([path], capsys)
    assert status == 0 and "Kept out: slab" in text and "deterministic" in text


def test_a_second_run_reuses_the_datasets(tmp_path, capsys, monkeypatch):
    """Bodies rocking through whole records (t_end from the motions): the first run
    simulates, the second reads what it wrote and simulates no cell."""
    from sweep.runner import cells
    simulated, run = [], cells.ChunkRunner.__call__

    def counted(self, study, ids):
        simulated.append(len(ids))
        return run(self, study, ids)
    monkeypatch.setattr(cells.ChunkRunner, "__call__", counted)
    path = tmp_path / "rocking.yaml"
    path.write_text(yaml.safe_dump({"site": "yard", "bodies": [
        {"name": "slim", "B": "20 cm", "H": "80 cm", "overturned": True},
        {"name": "stout", "B": "30 cm", "H": "60 cm", "overturned": False}],
        "ensemble": {"motions": {"record": RECORDS},
                     "levels": {"pga": {"start": "3 m/s^2", "stop": "12 m/s^2", "num": 6}}}}))
    start = time.perf_counter()
    status, first, said = _run([path], capsys)
    simulating = time.perf_counter() - start
    assert status == 0 and "2 of 2 bodies simulated" in said
    assert sum(simulated) > 0
    simulated.clear()
    stamps = {p.name: p.stat().st_mtime_ns for p in site_studies.results_folder(path).glob("*.nc")}
    start = time.perf_counter()
    status, second, said = _run([path], capsys)
    reading = time.perf_counter() - start
    assert status == 0 and said == "" and second == first
    assert {p.name: p.stat().st_mtime_ns
            for p in site_studies.results_folder(path).glob("*.nc")} == stamps
    print(f"reuse: {reading:.2f} s, simulation: {simulating:.2f} s")
    assert simulated == []


def test_command_old_format_and_write_study(tmp_path, capsys):
    old = tmp_path / "old.yaml"
    old.write_text("site: village\nbodies:\n  - {name: stone, B: 30 cm, H: 90 cm, "
                   "overturned: true}\n")
    status, out, _ = _run([old, "--json"], capsys)
    data = json.loads(out)
    assert status == 0 and data["site"] == "village" and data["ensemble"] is None
    assert data["lower_limits"]["pga"]["value"] == pytest.approx(G / 3)
    path = _bodies_file(tmp_path)
    status, out, _ = _run([path, "--write-study", tmp_path / "studies"], capsys)
    assert status == 0
    written = sorted(p.name for p in (tmp_path / "studies").iterdir())
    assert written == ["B20cm_H80cm_mu0.6.yaml", "B30cm_H60cm_mu0.6.yaml"]
    study = yaml.safe_load((tmp_path / "studies" / written[0]).read_text())
    assert list(study["grid"]) == ["pga", "record"] and study["scene"]["solver"]["t_end"] == 8
    assert not list(tmp_path.glob("results/*/*.nc"))  # nothing run


def test_command_bad_files_exit_2_with_every_problem(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text(yaml.safe_dump({
        "sites": [{"name": "a", "latitude": 91, "bodies": [
            {"B": "30 cm", "H": "90 cm", "overturned": True},
            {"B": "30 kg", "H": "90 cm", "overturned": "yes"}]}],
        "ensemble": {"motions": {"record": ["elcentro1940_ns", "nowhere.AT2"]},
                     "levels": {"pga": {"start": "1 m/s^2", "stop": "2 west", "num": 1}},
                     "probabilities": [0.5, 1.5]}}))
    out = cli([bad, "--json"], cwd=tmp_path, module="sweep.estimate")
    assert out.returncode == 2 and out.stdout == ""
    assert "Traceback" not in out.stderr
    for path in ("sites[0].latitude", "sites[0].bodies[1].B", "sites[0].bodies[1].overturned",
                 "ensemble.motions.record[1]", "ensemble.levels.pga.stop",
                 "ensemble.levels.pga.num", "ensemble.probabilities[1]"):
        assert f"  {path}: " in out.stderr, path
    assert not (tmp_path / "results").exists()
    no_ensemble = tmp_path / "plain.yaml"
    no_ensemble.write_text("bodies:\n  - {B: 30 cm, H: 90 cm, overturned: true}\n")
    out = cli([no_ensemble, "-o", tmp_path / "f.png"], cwd=tmp_path, module="sweep.estimate")
    assert out.returncode == 2 and "ensemble: required by -o/--output" in out.stderr


def test_a_study_that_does_not_run_to_its_end_is_an_exception(tmp_path, monkeypatch):
    """The site estimate runs a study with ``launch.run_file`` and gets how it ended as an
    exception: refused or failed as ``RunFailed``, Ctrl-C as ``KeyboardInterrupt``."""
    from sweep.runner import launch, mpi
    from study_helpers import make_study, write_study

    path = write_study(tmp_path / "s.yaml", {**make_study({"amplitude": [1.0]}),
                                             "output": str(tmp_path / "s.nc")})
    seen = []

    def ends(error):
        def run_file(comm, study, options):
            seen.append((study, options))
            raise error
        return run_file

    for error, status in ((launch.Refused(), 2), (mpi.JobFailure("boom"), 1)):
        monkeypatch.setattr(launch, "run_file", ends(error))
        with pytest.raises(site_studies.RunFailed, match=f"ended with status {status}$"):
            site_studies._run_study(path)
    monkeypatch.setattr(launch, "run_file", ends(KeyboardInterrupt()))
    with pytest.raises(KeyboardInterrupt):
        site_studies._run_study(path)
    study, options = seen[0]
    assert study == str(path) and options.quiet and not options.force
    assert options.command_line() == f"python -m sweep.run {path} --quiet"
