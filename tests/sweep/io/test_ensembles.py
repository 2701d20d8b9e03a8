"""Ensembles as study axes: record names, paths and globs, seeds, PGA and PGV targets, and the
per-cell intensity measures, normalized measures and the slid flag."""
import math

import numpy as np
import pytest
import yaml

import sweep
from sweep.io.problems import FileProblems
from sweep.io.records import load_record
from sweep.runner.cell_checks import load_study
from sweep.paper import criteria

G = 9.80665
BODY = {"B": 0.2, "H": 0.6}


def _two_column(path, scale):
    """A short record file: El Centro NS's first 3 s times ``scale``, in m/s^2."""
    rec = load_record("elcentro1940_ns")
    n = int(3.0 / rec.dt)
    t = np.arange(n) * rec.dt
    np.savetxt(path, np.column_stack([t, scale * rec.samples[:n]]))


def _study(tmp_path, grid, excitation=None, **scene):
    raw = {"scene": {"body": BODY, "contact": {"mu": 1.0},
                     "excitation": {"horizontal": excitation or
                                    {"kind": "record", "name": "elcentro1940_ns"}},
                     "solver": {"t_end": 3.0}, **scene},
           "grid": grid}
    path = tmp_path / "study.yaml"
    path.write_text(yaml.safe_dump(raw))
    return load_study(path)


def test_record_axis_takes_names_paths_and_globs(tmp_path):
    (tmp_path / "motions").mkdir()
    for k, scale in enumerate((0.5, 1.0, 2.0)):
        _two_column(tmp_path / "motions" / f"m{k}.txt", scale)
    study = _study(tmp_path, {"record": {"glob": "motions/*.txt"}})
    assert study.axes[0].values == ("motions/m0.txt", "motions/m1.txt", "motions/m2.txt")
    ds = sweep.run_study(study)
    # the files' own peaks, in the order of the sorted glob
    np.testing.assert_allclose(ds.pga.values, [0.5 * 3.4199455, 3.4199455, 2 * 3.4199455],
                               rtol=1e-6)
    mixed = _study(tmp_path, {"record": ["elcentro1940_ew", "motions/m1.txt"]})
    ds = sweep.run_study(mixed)
    assert ds.pga.values[0] == pytest.approx(np.max(np.abs(load_record("elcentro1940_ew")
                                                           .samples)))


def test_a_glob_that_matches_nothing_is_a_problem(tmp_path):
    with pytest.raises(FileProblems) as err:
        _study(tmp_path, {"record": {"glob": "none/*.AT2"}})
    assert err.value.problems[0].path == "grid.record.glob"


@pytest.mark.parametrize("key, unit, measure", [("pga", "g", "pga"), ("pgv", "cm/s", "pgv")])
def test_motions_scaled_to_a_target(tmp_path, key, unit, measure):
    """Every record of the ensemble scaled so that its PGA (or PGV) is the axis value: the
    stored measure is the target, whatever the record's own peak."""
    study = _study(tmp_path, {"record": ["elcentro1940_ns", "elcentro1940_ew",
                                         "taft1952_ew_s69e"],
                              key: {"values": [0.1, 0.3] if unit == "g" else [10, 30],
                                    "unit": unit}})
    ds = sweep.run_study(study)
    target = ds[key]  # the coordinate
    other = "pgv" if key == "pga" else "pga"
    assert other in ds.data_vars
    # the measure of each cell, computed from its scaled record, is the target
    for record in ds.record.values:
        rec = load_record(str(record))
        peak = getattr(rec.intensity, measure)
        for level in target.values:
            cell = ds.sel(record=record, **{key: level})
            ratio = cell[other].item() / getattr(rec.intensity, other)
            assert ratio == pytest.approx(level / peak, rel=1e-9)


def test_seed_axis_gives_a_sine_random_phases(tmp_path):
    study = _study(tmp_path, {"seed": {"start": 0, "stop": 3, "num": 4}},
                   excitation={"kind": "sine", "amplitude": "1.2 west", "frequency": 2.0,
                               "duration": 0.5})
    assert study.axes[0].coords.dtype == np.int64
    ds = sweep.run_study(study)
    np.testing.assert_array_equal(ds.seed.values, [0, 1, 2, 3])
    theta = ds.max_abs_theta.values
    assert len(np.unique(theta)) == 4  # one half-second burst: the phase decides the rocking
    again = sweep.run_study(study)
    np.testing.assert_array_equal(again.max_abs_theta.values, theta)  # reproducible


def test_normalized_measures_against_the_body(tmp_path):
    """pga_norm = PGA/(g tan alpha), pgv_norm = PGV p/(g tan alpha), p = sqrt(3g/4R)."""
    study = _study(tmp_path, {"b_over_h": [0.2, 0.4], "size": [1.0, 4.0]},
                   excitation={"kind": "sine", "amplitude": "300 gal", "frequency": 2.0})
    ds = sweep.run_study(study)
    for bh in (0.2, 0.4):
        for size in (1.0, 4.0):
            cell = ds.sel(b_over_h=bh, size_factor=size)
            B, H = 0.2 * size, 0.2 * size / bh
            R = 0.5 * math.hypot(B, H)
            p = math.sqrt(3 * G / (4 * R))
            assert cell.pga.item() == pytest.approx(3.0)
            assert cell.pgv.item() == pytest.approx(3.0 / (4 * np.pi))
            assert cell.pga_norm.item() == pytest.approx(3.0 / (G * bh))
            assert cell.pgv_norm.item() == pytest.approx(3.0 / (4 * np.pi) * p / (G * bh))
            assert p == pytest.approx(float(criteria.body_constants(B, H).p))


def test_a_squat_body_that_slides_is_flagged(tmp_path):
    """B/H = 2 with mu 0.2 under 0.5 g: it cannot rock (West: 2 g) but slides; a slender
    body with high friction rocks without sliding."""
    squat = _study(tmp_path, {"frequency": [2.0]},
                   excitation={"kind": "sine", "amplitude": "0.5 g", "frequency": 2.0},
                   body={"B": 0.6, "H": 0.3}, contact={"mu": 0.2})
    ds = sweep.run_study(squat)
    assert ds.outcome.item() == 0 and ds.slid.item() == 1 and ds.max_slip.item() > 0.05
    slender = _study(tmp_path, {"frequency": [2.0]},
                     excitation={"kind": "sine", "amplitude": "1.2 west", "frequency": 2.0},
                     contact={"mu": 1.0})
    ds = sweep.run_study(slender)
    assert ds.outcome.item() >= 1 and ds.slid.item() == 0
    # G moves with the rotation by centimetres; the base, by what bouncing impacts slip
    assert ds.max_slip.item() < 0.01 < ds.max_travel.item()
    assert ds.max_slip.attrs["units"] == ds.max_travel.attrs["units"] == "m"


def test_bodies_that_rock_over_are_not_flagged_slid(tmp_path):
    """Slender bodies (mu = 1 > b/h) knocked over by El Centro at 1-3 g rock about their
    corners until they fall: none is flagged, though G's travel exceeds what rotation explains
    by more than the threshold in some (the floor moves under a falling body)."""
    study = _study(tmp_path, {"pga": {"values": [1.0, 2.0, 3.0], "unit": "g"},
                              "H": [0.6, 1.0]})
    ds = sweep.run_study(study).transpose("pga", "H", ...)
    fell = ds.outcome.values == 2
    assert fell.sum() >= 3
    assert np.all(ds.slid.values[fell] == 0) and np.all(ds.max_slip.values[fell] < 0.01)
    theta = np.minimum(ds.max_abs_theta.values, np.pi / 2)
    b, h = BODY["B"] / 2, ds.H.values[None, :] / 2
    beyond = ds.max_travel.values - b * (1 - np.cos(theta)) - h * np.sin(theta)
    assert np.any(beyond[fell] > 0.01)


def test_synthetic_motions_as_an_ensemble(tmp_path):
    """A seed axis over a synthetic scenario: one motion per seed, reproducible, each scaled
    to the PGA level; the scene's JSON reports the applied motion's peaks."""
    synthetic = {"kind": "synthetic", "model": "boore2003", "magnitude": 6.5,
                 "distance": "20 km", "vs30": "760 m/s", "seed": 0}
    study = _study(tmp_path, {"seed": [0, 1, 2], "pga": {"values": [2.0, 4.0],
                                                         "unit": "m/s^2"}},
                   excitation=synthetic, solver={"t_end": 30.0})
    ds = sweep.run_study(study)
    assert "pga" not in ds.data_vars  # the coordinate holds it
    pgv = ds.pgv.transpose("seed", "pga").values
    assert len(np.unique(pgv[:, 0])) == 3  # three seeds, three motions
    np.testing.assert_allclose(pgv[:, 1], 2 * pgv[:, 0], rtol=1e-9)  # scaled together
    result = sweep.simulate({"body": BODY, "excitation": {"horizontal": {**synthetic,
                                                                         "pga": "0.2 g"}}})
    assert result.pga == pytest.approx(0.2 * G, rel=1e-12)
    assert 0.0 < result.pgv < result.pga  # a PGV/PGA ratio of an earthquake, ~0.1 s


def test_synthetic_scenario_errors_have_their_path(tmp_path):
    scene = {"body": BODY, "excitation": {"horizontal": {
        "kind": "synthetic", "model": "nosuch", "magnitude": 9.5, "distance": "20 km",
        "vs30": "760 m/s"}}}
    with pytest.raises(FileProblems) as err:
        sweep.simulate(scene)
    paths = {p.path for p in err.value.problems}
    assert {"excitation.horizontal.model", "excitation.horizontal.magnitude"} <= paths


def test_nothing_rocks_below_wests_level_for_any_seed(tmp_path):
    """Without vertical motion a body on a rigid floor does not even rock while the floor's
    acceleration stays below (B/H) g (West, Eq. 1): no seed of the ensemble overturns it."""
    synthetic = {"kind": "synthetic", "model": "boore2003", "magnitude": 7.0,
                 "distance": "10 km", "vs30": "760 m/s"}
    west = G * BODY["B"] / BODY["H"]
    study = _study(tmp_path, {"seed": list(range(12)),
                              "pga": {"values": [0.5 * west, 0.9 * west, 0.999 * west,
                                                 1.5 * west, 3.0 * west]}},
                   excitation=synthetic, solver={"t_end": 25.0})
    ds = sweep.run_study(study)
    below = ds.pga_norm < 1.0
    assert int(below.sum()) == 12 * 3
    assert (ds.outcome.where(below) == 0).sum() == 36  # neither rocked nor overturned
    assert (ds.outcome.where(~below) >= 1).sum() == 24  # above it, every one rocks
