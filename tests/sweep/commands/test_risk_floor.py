"""A risk file's body on a building's floor: the stripes keep the building and put their
motions under it as its ground; every other motion, and a scene that is not a scene, is
refused with one line and exit status 2; ``sweep.fragility --im ground_pga`` fits a floor
study against the ground's levels.

The expected values are computed here: the same floor scenes simulated one by one
(``sweep.runner.simulate``), a lognormal fitted by maximum likelihood with scipy, and the risk
integral on the power-law curve by quadrature."""
import json
import math

import numpy as np
import pytest
import xarray as xr
import yaml
from scipy import integrate, optimize, stats

from sweep import fragility as fragility_cli
from sweep.probability.fragility import FragilityError, fragility
from sweep.risk import main
from sweep.runner.simulate import simulate

G = 9.80665
K0, K = 2e-3, 2.5  # λ(x) = K0 x^-K, x in m/s²
CURVE_G = np.geomspace(0.01, 5.0, 30)  # levels of the curve file [g]
BUILDING = {"period": "0.6 s", "damping": "5 %", "height_ratio": 0.667}  # 4th of 6 floors
FLOOR = {"kind": "floor", "building": BUILDING}
BODY = {"body": {"B": "15 cm", "H": "60 cm"}, "contact": {"mu": 0.8},
        "solver": {"max_events": 100000}}
LEVELS = [1.0, 1.8, 3.2, 5.6]  # m/s²: stripes that neither never nor always overturn
MOTIONS, SEED, MAGNITUDE, DISTANCE, VS30 = 6, 0, 6.5, "20 km", "760 m/s"


def _risk_file(tmp_path, scene, **sections):
    curve = tmp_path / "curve.txt"
    curve.write_text("pga_g,annual_rate\n" + "".join(
        f"{x!r},{K0 * (x * G) ** -K!r}\n" for x in CURVE_G.tolist()))
    path = tmp_path / "risk.yaml"
    path.write_text(yaml.safe_dump({
        "name": "t", "hazard": {"file": {"path": "curve.txt", "format": "columns",
                                         "im": "pga", "units": "g"}},
        "scene": scene, **sections}))
    return path


def _stripes(**given):
    return {"levels": [f"{x} m/s^2" for x in LEVELS], "motions": MOTIONS, "seed": SEED,
            "scenario": {"magnitude": MAGNITUDE, "distance": DISTANCE}, "vs30": VS30,
            **given}


def _floor_scene(ground):
    return {**BODY, "excitation": {"horizontal": {**FLOOR, "ground": ground}}}


def _lognormal_mle(x, k, n):
    """(θ, β) maximising the binomial likelihood of Φ(ln(x/θ)/β) (scipy)."""
    x, k, n = (np.asarray(a, dtype=float) for a in (x, k, n))

    def nll(p):
        z = (np.log(x) - p[0]) / math.exp(p[1])
        return -np.sum(k * stats.norm.logcdf(z) + (n - k) * stats.norm.logsf(z))

    start = [np.log(np.sum(x * n) / n.sum()), math.log(0.4)]
    best = optimize.minimize(nll, start, method="Nelder-Mead",
                             options={"xatol": 1e-10, "fatol": 1e-13, "maxiter": 20000})
    return math.exp(best.x[0]), math.exp(best.x[1])


def _rate(theta, beta):
    """λ_O on the curve's power law: ∫ F |dλ| from its first to its last level, plus the
    shaking above its last level at the fragility there (docs/risk.md (3))."""
    lo, hi = np.log(CURVE_G[[0, -1]] * G)

    def integrand(u):
        return stats.norm.cdf((u - math.log(theta)) / beta) * K * K0 * math.exp(-K * u)

    inside, _ = integrate.quad(integrand, lo, hi, epsabs=0, epsrel=1e-11, limit=200)
    return inside + stats.norm.cdf((hi - math.log(theta)) / beta) * K0 * math.exp(-K * hi)


def test_floor_stripes_give_the_risk_of_the_floor_scenes_fitted_here(tmp_path, capsys):
    """Each stripe is the building's floor over a synthetic ground scaled to the level: its
    counts are those of the same floor scenes simulated here; the risk is that of the
    lognormal fitted here to them, integrated here on the same curve."""
    path = _risk_file(tmp_path, {**BODY, "excitation": {"horizontal": FLOOR}},
                      stripes=_stripes(), years=50, replicates=20)
    assert main([str(path), "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    body = report["bodies"][0]
    assert report["placement"].startswith("the ground of a building")  # said, not dropped
    assert "period" in report["placement"]
    overturned = []
    for j, level in enumerate(LEVELS):
        overturned.append(sum(bool(simulate(_floor_scene({
            "kind": "synthetic", "model": "boore2003", "magnitude": MAGNITUDE,
            "distance": DISTANCE, "vs30": VS30, "seed": SEED + j * MOTIONS + i,
            "pga": f"{level} m/s^2"})).overturned) for i in range(MOTIONS)))
    assert body["fragility"]["stripes"]["overturned"] == overturned
    assert body["fragility"]["status"] == "fitted"
    theta, beta = _lognormal_mle(LEVELS, overturned, [MOTIONS] * len(LEVELS))
    assert body["fragility"]["median"] == pytest.approx(theta, rel=1e-5)
    assert body["fragility"]["beta"] == pytest.approx(beta, rel=1e-5)
    rate = _rate(theta, beta)
    assert body["annual_rate"] == pytest.approx(rate, rel=1e-4)
    assert body["probability"] == pytest.approx(1 - math.exp(-50 * rate), rel=1e-4)

    study = yaml.safe_load((tmp_path / "results" / "t" / "t_stripe2.yaml").read_text())
    horizontal = study["scene"]["excitation"]["horizontal"]
    assert horizontal["kind"] == "floor" and horizontal["building"] == BUILDING
    assert horizontal["ground"]["kind"] == "synthetic"
    assert horizontal["ground"]["pga"] == f"{LEVELS[2]!r} m/s^2"
    assert study["grid"]["excitation.horizontal.ground.seed"] == list(range(12, 18))


def test_record_stripes_go_under_the_floor(tmp_path, capsys):
    """Records as the stripes' motions: each stripe counts the floor scenes over each record
    scaled at the ground to the level."""
    records = ["elcentro1940_ns", "taft1952_ew_s69e"]
    path = _risk_file(tmp_path, {**BODY, "excitation": {"horizontal": FLOOR}},
                      stripes={"levels": ["1.5 m/s^2", "4 m/s^2"], "records": records},
                      replicates=20)
    assert main([str(path), "--json"]) == 0
    stripes = json.loads(capsys.readouterr().out)["bodies"][0]["fragility"]["stripes"]
    expected = [sum(bool(simulate(_floor_scene({"kind": "record", "name": name,
                                                "pga": level})).overturned)
                    for name in records) for level in ("1.5 m/s^2", "4 m/s^2")]
    assert stripes["records"] == records and stripes["overturned"] == expected
    study = yaml.safe_load((tmp_path / "results" / "t" / "t_stripe0.yaml").read_text())
    assert study["scene"]["excitation"]["horizontal"]["building"] == BUILDING
    assert study["grid"]["excitation.horizontal.ground.name"] == records


def _refused(tmp_path, capsys, scene, **sections):
    path = _risk_file(tmp_path, scene, **sections)
    with pytest.raises(SystemExit) as ended:
        main([str(path)])
    assert ended.value.code == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and not (tmp_path / "results").exists()
    return err.splitlines()


@pytest.mark.parametrize("excitation, line", [
    ({"vertical": {"kind": "sine", "amplitude": "0.1 g", "frequency": "2 Hz"}},
     "scene.excitation.vertical.kind: not supported in a risk file: the stripes give the "
     "ground motion, horizontal only (got: 'sine')"),
    ({"horizontal": {"kind": "sine", "amplitude": "0.1 g", "frequency": "2 Hz"}},
     "scene.excitation.horizontal.kind: not supported in a risk file: the stripes give the "
     "ground motion (a building's floor over it: kind floor) (got: 'sine')"),
    ({"horizontal": {"kind": "record", "name": "elcentro1940_ns"}},
     "scene.excitation.horizontal.kind: not supported in a risk file"),
    ({"horizontal": {**FLOOR, "ground": {"kind": "record", "name": "elcentro1940_ns"}}},
     "scene.excitation.horizontal.ground: leave it out: the stripes give the ground motion "
     "under the building"),
])
def test_a_motion_the_stripes_would_replace_is_refused(tmp_path, capsys, excitation, line):
    lines = _refused(tmp_path, capsys, {**BODY, "excitation": excitation},
                     stripes=_stripes())
    assert lines[0].endswith("1 problem(s):") and len(lines) == 2
    assert lines[1].strip().startswith(line)


def test_a_floor_takes_records_of_one_kind(tmp_path, capsys):
    lines = _refused(tmp_path, capsys, {**BODY, "excitation": {"horizontal": FLOOR}},
                     stripes={"levels": ["1 m/s^2", "2 m/s^2"],
                              "records": ["elcentro1940_ns", "rec.AT2"]})
    assert len(lines) == 2 and lines[1].strip().startswith(
        "stripes.records: under a building's floor, give bundled records or files, not both")


@pytest.mark.parametrize("sections", [
    {"fragility": {"median": "0.4 g", "beta": 0.3}},
    {"stripes": _stripes()},
])
def test_the_scene_is_checked_as_a_scene_with_or_without_stripes(tmp_path, capsys, sections):
    """``B: 0`` is refused at its dotted path, a known fragility or not; so is a floor
    without its building."""
    scene = {"body": {"B": 0, "H": "60 cm"}, "excitation": {"horizontal": {"kind": "floor"}}}
    lines = _refused(tmp_path, capsys, scene, **sections)
    assert [line.strip() for line in lines[1:]] == [
        "scene.body.B: must be greater than 0 (got: 0)",
        "scene.excitation.horizontal.building: required"]


SEED_DIM, PGA_DIM = "excitation_horizontal_ground_seed", "excitation_horizontal_ground_pga"


def _floor_dataset(ground_axis="excitation.horizontal.ground.pga", units="m s-2"):
    """A floor study's dataset as ``sweep.run`` names it: outcomes over the ground's PGA
    levels and seeds, the floor's PGA per cell (not proportional to the ground's)."""
    ground = np.array([1.0, 2.0, 3.0, 4.0, 6.0])
    over = np.array([[0, 0, 0, 0, 0, 0, 0, 0],   # 0 of 8
                     [0, 0, 1, 0, 0, 0, 1, 0],   # 2
                     [1, 0, 1, 0, 1, 1, 0, 1],   # 5
                     [1, 1, 1, 1, 0, 1, 1, 1],   # 7
                     [1, 1, 1, 1, 1, 1, 1, 1]])  # 8
    rng = np.random.default_rng(3)
    floor = ground[:, None] * rng.uniform(1.2, 2.8, over.shape)
    dims = (PGA_DIM, SEED_DIM)
    return xr.Dataset(
        {"outcome": (dims, np.where(over == 1, 2, 1).astype(np.int8)),
         "pga": (dims, floor, {"units": "m s-2"})},
        coords={PGA_DIM: (PGA_DIM, ground, {"units": units, "study_axis": ground_axis}),
                SEED_DIM: (SEED_DIM, np.arange(8.0), {"units": "1", "study_axis":
                                                      "excitation.horizontal.ground.seed"})})


def test_ground_pga_fits_the_levels_of_the_ground_and_pga_the_floor(tmp_path, capsys):
    """One body (the ground's PGA axis is the levels, not six bodies): θ, β against the
    ground's levels by ``--im ground_pga``, against each cell's floor PGA by ``--im pga``,
    both the maximum-likelihood lognormal computed here."""
    ds = _floor_dataset()
    path = tmp_path / "floor.nc"
    ds.to_netcdf(path)
    assert fragility_cli.main([str(path), "--over", SEED_DIM, "--im", "ground_pga",
                               "--replicates", "20", "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["levels"] == PGA_DIM and len(report["groups"]) == 1
    k = (ds.outcome == 2).sum(SEED_DIM).values
    theta, beta = _lognormal_mle(ds[PGA_DIM].values, k, np.full(k.shape, 8))
    fit = report["groups"][0]["fit"]
    assert fit["theta"] == pytest.approx(theta, rel=1e-5)
    assert fit["beta"] == pytest.approx(beta, rel=1e-5)

    frag = fragility(ds, [SEED_DIM], "pga", replicates=20)
    cells = (ds.outcome == 2).values.ravel()
    theta, beta = _lognormal_mle(ds.pga.values.ravel(), cells, np.ones(cells.size))
    assert float(frag.theta) == pytest.approx(theta, rel=1e-5)
    assert float(frag.beta) == pytest.approx(beta, rel=1e-5)


@pytest.mark.parametrize("axis, units, message", [
    ("excitation.horizontal.ground.scale", "1", "no axis excitation.horizontal.ground.pga "
                                                "scales a floor's ground"),
    ("excitation.horizontal.ground.pga", "1", "relative to the body"),
])
def test_ground_pga_without_the_ground_levels_is_refused(tmp_path, capsys, axis, units,
                                                         message):
    ds = _floor_dataset(axis, units)
    with pytest.raises(FragilityError, match=message):
        fragility(ds, [SEED_DIM], "ground_pga")
    path = tmp_path / "floor.nc"
    ds.to_netcdf(path)
    assert fragility_cli.main([str(path), "--over", SEED_DIM, "--im", "ground_pga"]) == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and message in err
