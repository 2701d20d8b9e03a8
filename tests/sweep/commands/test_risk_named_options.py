"""Named options of a risk file (docs/options.md) and isolated platforms under the stripes.

Each option is its base scene with some dotted paths replaced; every option sees the same
motions (seeds seed + j·motions + i, the same scenario), so an option equal to the base scene
has the P of the base file run alone, bit for bit; a friction pendulum that never slides
leaves its platform the floor; a friction pendulum's displacement demand solves
P[D > d* in T] = target on a brute-force integral written here; bad options are refused with
their dotted paths and exit status 2."""
import contextlib
import csv
import io
import json

import numpy as np
import pytest
import xarray as xr
import yaml
from scipy import stats

from sweep.probability import stripes
from sweep.risk import main

G = 9.80665
K0, K = 2e-3, 2.5  # λ(x) = K0 x^-K, x in m/s²
CURVE_G = np.geomspace(0.01, 5.0, 30)
LEVELS = [1.0, 1.8, 3.2, 5.6]  # m/s²
MOTIONS, SEED, TARGET = 6, 7, 0.05
BUILDING = {"period": "0.6 s", "damping": "5 %", "height_ratio": 0.667}
PENDULUM = {"kind": "friction_pendulum", "radius": "1.5 m", "mu": 0.06}


def _base():
    return {"body": {"B": "15 cm", "H": "60 cm"}, "contact": {"mu": 0.8},
            "solver": {"max_events": 100000},
            "excitation": {"horizontal": {"kind": "floor", "building": BUILDING}}}


def _isolated(isolator):
    return {"excitation.horizontal": {"kind": "isolated", "isolator": isolator,
                                      "under": {"kind": "floor", "building": BUILDING}}}


OPTIONS = {"as it stands": {}, "friction pendulum": _isolated(PENDULUM),
           "stuck pendulum": _isolated({**PENDULUM, "mu": 50.0}),
           "ground floor": {"excitation.horizontal": "none"}}


def _risk_file(folder, name, scene, **extra):
    folder.mkdir(exist_ok=True)
    (folder / "curve.txt").write_text("pga_g,annual_rate\n" + "".join(
        f"{x!r},{K0 * (x * G) ** -K!r}\n" for x in CURVE_G.tolist()))
    path = folder / f"{name}.yaml"
    path.write_text(yaml.safe_dump(json.loads(json.dumps({  # no YAML aliases
        "name": name, "hazard": {"file": {"path": "curve.txt", "format": "columns",
                                          "im": "pga", "units": "g"}},
        "scene": scene, "target": TARGET, "replicates": 30,
        "stripes": {"levels": [f"{x} m/s^2" for x in LEVELS], "motions": MOTIONS,
                    "seed": SEED, "vs30": "760 m/s",
                    "scenario": {"magnitude": 6.5, "distance": "20 km"}}, **extra})),
        sort_keys=False))
    return path


def _json(path, capsys, *args):
    assert main([str(path), "--json", *args]) == 0
    return json.loads(capsys.readouterr().out)


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    folder = tmp_path_factory.mktemp("named")
    path = _risk_file(folder, "named", _base(), options=OPTIONS)
    return folder, path


@pytest.fixture(scope="module")
def document(run):
    folder, path = run
    table = folder / "options.csv"
    out = io.StringIO()  # capsys is function-scoped: the module's run is read here
    with contextlib.redirect_stdout(out):
        assert main([str(path), "--json", "--csv", str(table), "--options",
                     str(folder / "options.png")]) == 0
    return json.loads(out.getvalue()), list(csv.DictReader(table.open()))


def test_every_option_is_listed_by_its_name(document):
    doc, rows = document
    assert doc["options"] == list(OPTIONS)
    assert [b["option"] for b in doc["bodies"]] == list(OPTIONS)
    assert [r["option"] for r in rows] == list(OPTIONS)


def test_every_option_sees_the_same_motions(run, document):
    folder, _ = run
    expected = [SEED + j * MOTIONS + i for j in range(len(LEVELS)) for i in range(MOTIONS)]
    for k in range(len(OPTIONS)):
        seeds = []
        for j in range(len(LEVELS)):
            study = yaml.safe_load((folder / "results" / "named" /
                                    f"named_option{k}_stripe{j}.yaml").read_text())
            axis = next(a for a in study["grid"] if a.endswith("seed"))
            seeds += study["grid"][axis]
            motion = study["scene"]["excitation"]["horizontal"]
            while motion.get("kind") != "synthetic":  # down to the ground motion
                motion = motion.get("ground") or motion["under"]
            assert (motion["magnitude"], motion["distance"]) == (6.5, 20000.0)
        assert seeds == expected


def test_an_option_equal_to_the_base_is_the_base_run_alone(run, document, capsys):
    folder, _ = run
    alone = _json(_risk_file(folder, "alone", _base()), capsys)["bodies"][0]
    option = document[0]["bodies"][0]
    assert option["probability"] == alone["probability"]
    assert option["interval"] == alone["interval"]
    assert option["fragility"]["stripes"]["overturned"] == \
        alone["fragility"]["stripes"]["overturned"]


def test_a_pendulum_that_never_slides_leaves_the_floor(document):
    """μ = 50: the push never exceeds μg, the platform moves with the floor: the same
    outcomes as the body on the floor, and no displacement."""
    bodies = {b["option"]: b for b in document[0]["bodies"]}
    assert bodies["stuck pendulum"]["fragility"]["stripes"]["overturned"] == \
        bodies["as it stands"]["fragility"]["stripes"]["overturned"]
    assert bodies["stuck pendulum"]["isolator_demand"]["displacement"] is None
    assert bodies["stuck pendulum"]["isolator_demand"]["stripes"]["moving"] == \
        [0.0] * len(LEVELS)


def test_the_isolator_demand_has_the_target_probability(run, document):
    """The per-stripe fit is scipy's lognormal of the stripes' displacements; d* makes
    1 − exp(−λ_D T) the target, λ_D integrated here by the trapezoid rule in ln x."""
    folder, _ = run
    found = {b["option"]: b for b in document[0]["bodies"]}["friction pendulum"][
        "isolator_demand"]
    k = list(OPTIONS).index("friction pendulum")
    medians, betas = [], []
    for j in range(len(LEVELS)):
        with xr.open_dataset(folder / "results" / "named" /
                             f"named_option{k}_stripe{j}.nc") as ds:
            d = ds["isolator_max_displacement"].values.ravel()
        s, _, scale = stats.lognorm.fit(d[d > 0], floc=0)
        medians.append(scale)
        betas.append(s)
    assert found["stripes"]["median"] == pytest.approx(medians, rel=1e-6)
    assert found["stripes"]["beta"] == pytest.approx(betas, rel=1e-6)
    u = np.linspace(np.log(CURVE_G[0] * G), np.log(CURVE_G[-1] * G), 200001)
    x = np.exp(u)
    ln_m = np.interp(u, np.log(LEVELS), np.log(medians))
    beta = np.interp(u, np.log(LEVELS), betas)
    p = stats.norm.sf((np.log(found["displacement"]) - ln_m) / beta)
    rate = np.trapezoid(p * K * K0 * x ** -K, u) + p[-1] * K0 * x[-1] ** -K
    assert 1 - np.exp(-rate * found["years"]) == pytest.approx(TARGET, rel=2e-3)


def test_the_csv_and_the_figure_carry_the_demand(run, document):
    folder, _ = run
    rows = {r["option"]: r for r in document[1]}
    bodies = {b["option"]: b for b in document[0]["bodies"]}
    assert float(rows["friction pendulum"]["isolator_demand"]) == pytest.approx(
        bodies["friction pendulum"]["isolator_demand"]["displacement"], rel=1e-5)
    assert rows["as it stands"]["isolator_demand"] == ""
    assert (folder / "options.png").stat().st_size > 0


def test_isolated_stripes_go_in_at_the_deepest_under():
    stripe = stripes.Stripe(2.0, [3], [6.5], [2e4])
    on_ground = {"body": {"B": "15 cm", "H": "60 cm"}, "excitation": {"horizontal": {
        "kind": "isolated", "isolator": PENDULUM}}}
    study = stripes.study_dict(stripe, on_ground, 760.0, None, "s", "s.nc")
    under = study["scene"]["excitation"]["horizontal"]["under"]
    assert (under["kind"], under["seed"], under["pga"]) == ("synthetic", 3, "2.0 m/s^2")
    assert list(study["grid"]) == ["excitation.horizontal.under.seed"]
    assert stripes.placement(on_ground).startswith("the ground under the isolated platform")
    floor = {**on_ground, "excitation": {"horizontal": {
        "kind": "isolated", "isolator": PENDULUM,
        "under": {"kind": "floor", "building": BUILDING}}}}
    study = stripes.study_dict(stripe, floor, 760.0, None, "s", "s.nc")
    under = study["scene"]["excitation"]["horizontal"]["under"]
    assert under["building"] == BUILDING and under["ground"]["seed"] == 3
    assert list(study["grid"]) == ["excitation.horizontal.under.ground.seed"]
    assert "floor the isolated platform stands on" in stripes.placement(floor)


@pytest.mark.parametrize("extra, line", [
    ({"options": {"tall": {"body.B": "-1 cm"}}}, "options.tall.body.B: must be greater"),
    ({"options": {"iso": {"excitation.horizontal": {
        "kind": "isolated", "isolator": PENDULUM,
        "under": {"kind": "record", "name": "elcentro1940_ns"}}}}},
     "options.iso.excitation.horizontal.under: leave it out"),
    ({"options": {"iso": {"excitation.horizontal.isolator.radius": "0 m"}},
      "scene": {**_base(), "excitation": {"horizontal": {"kind": "isolated",
                                                         "isolator": PENDULUM}}}},
     "options.iso.excitation.horizontal.isolator.radius: must be greater than 0"),
    ({"options": {"a": {}}, "grid": {"contact.mu": [0.5, 0.8]}},
     "options: give either a grid or options, not both"),
    ({"options": {}}, "options: give at least one option"),
    ({"grid": {"body.G": [[0, "0.3 m"], ["0.02 m", "0.3 m"]]}},
     "grid.body.G: an axis takes one number or name per value, not a vector: compare such "
     "values as named options"),
])
def test_bad_options_are_refused_with_their_dotted_paths(tmp_path, capsys, extra, line):
    scene = extra.pop("scene", _base())
    path = _risk_file(tmp_path, "bad", scene, **extra)
    with pytest.raises(SystemExit) as exited:
        main([str(path)])
    assert exited.value.code == 2
    err = capsys.readouterr().err
    assert line in err
    assert "Traceback" not in err
    assert not (tmp_path / "results" / "bad" / "bad_option0_stripe0.nc").exists()


@pytest.mark.parametrize("axis, refused", [
    ("excitation.horizontal.isolator.mu", False),
    ("excitation.horizontal.under.building.height_ratio", False),
    ("excitation.horizontal.under.ground.seed", True),
])
def test_a_risk_map_may_vary_the_isolator_not_its_ground(tmp_path, axis, refused):
    from sweep.io.problems import FileProblems
    from sweep.io.risk_schema import load_risk

    scene = {**_base(), "excitation": {"horizontal": {
        "kind": "isolated", "isolator": PENDULUM,
        "under": {"kind": "floor", "building": BUILDING}}}}
    values = [1, 2] if axis.endswith("seed") else [0.3, 0.6]
    path = _risk_file(tmp_path, "map", scene, grid={axis: values})
    if not refused:
        assert load_risk(path).checked.grid == {axis: values}
        return
    with pytest.raises(FileProblems) as problems:
        load_risk(path)
    assert str(problems.value).startswith(f"grid.{axis}: sets {axis}: the stripes give")


def test_grid_bodies_are_named_in_words():
    """A grid's anchor, isolator and building axes read as a conservator says them, with their
    units; an axis without a word keeps its dotted path."""
    from sweep.probability.risk_report import describe_body

    values = {"B": 0.4, "H": 1.6, "mu": 0.6, "restraint.strength": 800.0,
              "excitation.horizontal.isolator.mu": 0.06,
              "excitation.horizontal.under.building.height_ratio": 0.667,
              "solver.max_events": 1000.0}
    units = {"restraint.strength": "N", "excitation.horizontal.isolator.mu": "1",
             "excitation.horizontal.under.building.height_ratio": "1"}
    assert describe_body(values, units) == (
        "B 40 cm × H 160 cm (b/h 0.25), μ 0.6, anchor 800 N, isolator μ 0.06, "
        "floor height ratio 0.667, solver.max_events 1000")
