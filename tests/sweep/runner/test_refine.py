"""Boundary refinement (``refine:``): bisection against an oracle, closed-form thresholds found
within the tolerance (free rocking released at theta_0 >= alpha overturns; a constant floor
acceleration above West's (b/h) g overturns), the bracket holds the dense grid's transition,
one rank equals two, an interrupted run resumes, bad ``refine:`` keys are reported."""
import copy
import math
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from study_helpers import PY, cli, cli_env, without_run_attrs, write_study

import sweep
import sweep.runner.cells
from sweep import cf
from sweep.io import units
from sweep.runner.cell_checks import load_study
from sweep.io.problems import FileProblems
from sweep.run import main
from sweep.runner import grid, refine, store

BLOCK = {"body": {"B": 0.1, "H": 0.3}, "contact": {"mu": 0.8, "e_x": 0.0, "e_y": 0.0}}

# Free rocking from rest at theta_0: it overturns iff theta_0 > alpha = atan(b/h) (the
# unstable equilibrium).  b/h = 0.02 (alpha = 0.02) overturns at every coarse value, b/h = 1
# (alpha = 0.785) at none; t_end leaves > 3 s for a release 1e-6 rad above alpha to fall.
THETA = {"name": "theta", "scene": {**BLOCK, "solver": {"t_end": 5.0}},
         "grid": {"initial.theta": {"start": 0.06, "stop": 0.66, "num": 5},
                  "b_over_h": [0.02, 0.2, 0.333, 0.5, 1.0]},
         "refine": {"axis": "initial.theta", "tolerance": 0.005}, "output": "theta.nc"}
THETA_TOL, THETA_GAP = 0.005, 0.15


def _alpha(b_over_h):
    return np.arctan(np.asarray(b_over_h, dtype=float))


# --- the algorithm, against an oracle --------------------------------------------------------

def test_coarse_scan_by_hand():
    c = np.array([1.0, 2.0, 3.0, 4.0])
    b = refine.start(c, [[0, 0, 1, 1], [1, 1, 1, 1], [0, 0, 0, 0], [0, -1, 1, 1],
                         [0, 1, 0, 1], [0, 0, 1, 0]])
    np.testing.assert_array_equal(b.lower, [2, np.nan, 4, 1, 1, 2])
    np.testing.assert_array_equal(b.upper, [3, 1, np.nan, np.nan, 2, 3])
    assert [refine.BRACKET_NAMES[f] for f in b.flag] == [
        "bracketed", "overturned_at_start", "never_overturned", "simulation_failed",
        "bracketed", "bracketed"]
    assert b.transitions.tolist() == [1, 0, 0, 1, 3, 2]
    assert b.simulations.tolist() == [4] * 6


ORACLE = {"name": "oracle", "scene": {**BLOCK, "excitation": {"horizontal": {
    "kind": "sine", "amplitude": "1.5 west", "frequency": 4.0}}},
    "grid": {"amplitude": {"start": 1.0, "stop": 3.0, "num": 5, "unit": "west"},
             "b_over_h": [0.2, 0.25, 0.3, 0.35, 0.4]},
    "refine": {"axis": "amplitude", "tolerance": 0.01}}


def _overturns(a, b_over_h):
    """A made-up boundary per line: 1/-1/0 as the ``overturned`` variable."""
    if b_over_h == 0.2:
        return a >= 1.2345
    if b_over_h == 0.25:
        return True  # at the lowest value already
    if b_over_h == 0.3:
        return False  # never
    if b_over_h == 0.35:
        return -1 if 1.8 < a < 1.9 else a >= 1.85  # a failing simulation inside the bracket
    return 1.2 <= a < 1.6 or a >= 2.3  # bands: the lowest boundary is followed


def test_bisection_against_an_oracle():
    study = load_study(copy.deepcopy(ORACLE))
    seen = []

    def evaluate(index, round_study):
        out = []
        for cell in range(round_study.n_cells):
            coords = grid.cell_coords(round_study, cell)
            scene = grid.cell_scene(round_study, cell)  # what the cell simulates: its coordinates
            quantity = units.parse_quantity(scene["excitation"]["horizontal"]["amplitude"],
                                            "acceleration")
            assert (quantity.unit, quantity.value) == ("west", coords["amplitude"])
            assert scene["body"]["H"] == pytest.approx(0.1 / coords["b_over_h"])
            out.append(int(_overturns(coords["amplitude"], coords["b_over_h"])))
        seen.append((index, round_study.n_cells))
        return np.array(out, dtype=np.int8)

    b = refine.bisect(study, evaluate)
    rounds = math.ceil(math.log2(0.5 / 0.01))  # 0.5 west between coarse values: 6 halvings
    # lines 0, 3, 4 open; line 3 fails in round 2 and stops
    assert seen == [(0, 25), (1, 3), (2, 3)] + [(k, 2) for k in range(3, rounds + 1)]
    assert b.rounds == 1 + rounds
    names = [refine.BRACKET_NAMES[f] for f in b.flag]
    assert names == ["bracketed", "overturned_at_start", "never_overturned",
                     "simulation_failed", "bracketed"]
    for line, true in ((0, 1.2345), (4, 1.2)):
        assert b.lower[line] < true <= b.upper[line]
        assert b.upper[line] - b.lower[line] <= 0.01
        assert b.simulations[line] == 5 + rounds
    assert b.transitions.tolist() == [1, 0, 0, 1, 3]
    # the failing line: 1.75 stood, 1.875 failed; its bracket stays [1.75, 2]
    assert (b.lower[3], b.upper[3]) == (1.75, 2.0) and b.simulations[3] == 5 + 2
    assert np.isnan(b.lower[1]) and b.upper[1] == 1.0
    assert b.lower[2] == 3.0 and np.isnan(b.upper[2])
    # refine.max_simulations: coarse grid plus one midpoint per line and round
    assert refine.max_simulations(study) == 25 + 5 * rounds
    assert refine.dense_simulations(study) == 5 * (200 + 1)


# --- closed-form thresholds ------------------------------------------------------------------

@pytest.fixture(scope="module")
def theta_ds():
    return sweep.run_study(copy.deepcopy(THETA))


def test_initial_angle_threshold_is_alpha(theta_ds):
    ds = theta_ds
    alpha = _alpha(ds["b_over_h"].values)
    flags = [refine.BRACKET_NAMES[f] for f in ds["bracket"].values]
    assert flags == ["overturned_at_start", "bracketed", "bracketed", "bracketed",
                     "never_overturned"]
    lower, upper, boundary = (ds[v].values[1:4] for v in
                              ("boundary_lower", "boundary_upper", "boundary"))
    assert np.all(lower < alpha[1:4]) and np.all(alpha[1:4] < upper)
    assert np.all(upper - lower <= THETA_TOL)
    np.testing.assert_array_less(np.abs(boundary - alpha[1:4]), THETA_TOL / 2)
    rounds = math.ceil(math.log2(THETA_GAP / THETA_TOL))
    assert ds["simulations"].values.tolist() == [5, 5 + rounds, 5 + rounds, 5 + rounds, 5]
    theta = ds["theta"].values  # the dataset names a dotted axis by its last key
    expected = (theta[:, None] > alpha[None, :]).astype(np.int8)
    np.testing.assert_array_equal(ds["coarse_overturned"].values, expected)
    assert ds["coarse_overturned"].dims == ("theta", "b_over_h")
    assert ds["theta"].attrs["study_axis"] == "initial.theta"
    assert ds["coarse_transitions"].values.tolist() == [0, 1, 1, 1, 0]
    assert np.isnan(ds["boundary"].values[[0, 4]]).all()
    assert ds["boundary_upper"].values[0] == 0.06 and ds["boundary_lower"].values[4] == 0.66


def test_dataset_attributes(theta_ds):
    ds = theta_ds
    for name in list(ds.data_vars) + list(ds.coords):
        assert ds[name].attrs.get("units") and ds[name].attrs.get("long_name"), name
    for name in ("boundary", "boundary_lower", "boundary_upper"):
        assert ds[name].attrs["units"] == "rad" and ds[name].dims == ("b_over_h",)
    assert ds["bracket"].attrs["flag_meanings"].split() == list(refine.BRACKET_NAMES)
    assert ds["bracket"].attrs["flag_values"].tolist() == [0, 1, 2, 3]
    assert "refine:" in ds.attrs["study"] and ds.attrs["refine_axis"] == "initial.theta"
    assert ds.attrs["refine_tolerance"] == THETA_TOL
    assert ds.attrs["refine_tolerance_units"] == "rad"
    assert ds.attrs["refine_simulations"] == int(ds["simulations"].sum())


def test_bracket_holds_the_dense_grid_transition(theta_ds):
    """A dense grid at half the tolerance: its first overturning value and the one below it
    overlap the refined bracket, and both hold alpha."""
    raw = copy.deepcopy(THETA)
    del raw["refine"]
    raw["grid"] = {"initial.theta": {"start": 0.06, "stop": 0.66, "num": 241},
                   "b_over_h": [0.2, 0.5]}
    dense = sweep.run_study(raw)
    theta = dense["theta"].values
    for b_over_h in (0.2, 0.5):
        row = dense["overturned"].sel(b_over_h=b_over_h).values
        first = int(np.argmax(row == 1))
        assert np.all(row[:first] == 0) and np.all(row[first:] == 1)  # one transition
        below, above = theta[first - 1], theta[first]
        assert below < _alpha(b_over_h) < above
        line = theta_ds.sel(b_over_h=b_over_h)
        assert line["boundary_lower"] < above and below < line["boundary_upper"]


def test_constant_acceleration_threshold_in_west_units():
    """A floor acceleration held for the whole run overturns the block iff it exceeds West's
    (b/h) g, Eq. (1): the boundary is 1 west for every b/h (θ'' > 0 at every θ in (0, α))."""
    raw = {"name": "west", "scene": {**BLOCK, "excitation": {"horizontal": {
        "kind": "pulse", "shape": "rectangular", "amplitude": "1 west", "duration": 10.0}},
        "solver": {"t_end": 4.0}},
        "grid": {"amplitude": {"start": 0.53, "stop": 1.73, "num": 4, "unit": "west"},
                 "b_over_h": [0.2, 0.333]},
        "refine": {"axis": "amplitude", "tolerance": "0.01 west"}}
    ds = sweep.run_study(raw)
    assert ds["boundary"].attrs["units"] == "1" and "West" in ds["boundary"].attrs["long_name"]
    assert np.all(ds["bracket"].values == refine.BRACKETED)
    assert np.all(ds["boundary_lower"].values < 1.0) and np.all(1.0 < ds["boundary_upper"])
    assert np.all(ds["boundary_upper"] - ds["boundary_lower"] <= 0.01)
    assert np.all(ds["simulations"].values == 4 + math.ceil(math.log2(0.4 / 0.01)))


# --- files: validation, dry run, resume, ranks --------------------------------------------------

BAD = [  # (refine, path, word of the message)
    (3, "refine", "must be a mapping"),
    ({"axis": "initial.theta", "tolerance": 0.01, "tolerence": 1}, "refine.tolerence",
     "did you mean 'tolerance'"),
    ({"tolerance": 0.01}, "refine.axis", "required"),
    ({"axis": "amplitud", "tolerance": 0.01}, "refine.axis", "not an axis of grid"),
    ({"axis": "b_over_h", "tolerance": 0.0}, "refine.tolerance", "greater than 0"),
    ({"axis": "b_over_h", "tolerance": "0.01 west"}, "refine.tolerance", "dimensionless"),
    ({"axis": "initial.theta", "tolerance": "1 deg/s"}, "refine.tolerance", "expected an angle"),
    ({"axis": "initial.theta", "tolerance": "0.01 alpha"}, "refine.tolerance", "unit of grid"),
    ({"axis": "initial.theta", "tolerance": [1]}, "refine.tolerance", "positive number"),
    ({"axis": "e_y", "tolerance": 0.01}, "refine.axis", "increase"),
    ({"axis": "mu", "tolerance": 0.01}, "refine.axis", "at least two values"),
    ({"axis": "e_x", "tolerance": 0.01}, "refine.axis", "zip group"),
]


@pytest.mark.parametrize("spec, path, word", BAD)
def test_bad_refine_reported_with_dotted_path(spec, path, word):
    raw = copy.deepcopy(THETA)
    raw["grid"].update({"e_y": [0.2, 0.1], "mu": [0.8], "e_x": [0.0, -0.5],
                        "solver.rtol": [1e-8, 1e-9]})
    raw["zip"] = [["e_x", "solver.rtol"]]
    raw["refine"] = spec
    with pytest.raises(FileProblems) as info:
        load_study(raw)
    problems = {p.path: p for p in info.value.problems}
    assert list(problems) == [path], str(info.value)
    assert word in problems[path].message, problems[path]


def test_cli_bad_refine_exit_2_and_dry_run_counts(tmp_path):
    raw = copy.deepcopy(THETA)
    raw["refine"] = {"axis": "initial.theta", "tolerance": -1, "method": "x"}
    bad = write_study(tmp_path / "bad.yaml", raw)
    done = cli([bad], cwd=tmp_path, timeout=60)
    assert done.returncode == 2 and "Traceback" not in done.stderr
    assert "refine.tolerance: must be greater than 0 (got: -1)" in done.stderr
    assert "refine.method: unknown key" in done.stderr

    good = write_study(tmp_path / "good.yaml", THETA)
    done = cli([good, "--dry-run"], cwd=tmp_path, timeout=60)
    assert done.returncode == 0, done.stderr
    # 5 lines: 5 coarse values each, then ceil(log2(0.15/0.005)) = 5 midpoints at most
    assert "at most 50 simulations" in done.stdout
    assert "a grid of the same resolution: 605 cells" in done.stdout  # 5 x (0.6/0.005 + 1)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.yaml", "good.yaml"]


def test_interrupted_run_resumes_to_the_same_dataset(tmp_path, monkeypatch, capsys):
    study = write_study(tmp_path / "theta.yaml", THETA)
    monkeypatch.chdir(tmp_path)
    runner = sweep.runner.cells.ChunkRunner
    calls, original = [], runner.__call__

    def dies_in_round_2(self, study, cells):  # 25 coarse cells, 3 midpoints in round 1
        calls.append(len(cells))
        if len(calls) == 30:
            raise KeyboardInterrupt
        return original(self, study, cells)

    monkeypatch.setattr(runner, "__call__", dies_in_round_2)
    assert main([str(study), "--chunk-size", "1", "--quiet"]) == 130  # Ctrl-C
    assert "interrupted: the finished rounds and chunks are saved" in capsys.readouterr().err
    monkeypatch.setattr(runner, "__call__", original)
    parts = store.parts_dir(tmp_path / "theta.nc")
    assert [len(store.PartStore(store.round_dir(parts, k)).parts()) for k in range(3)] == \
        [25, 3, 1]
    assert not (tmp_path / "theta.nc").exists()
    capsys.readouterr()
    assert main([str(study), "--chunk-size", "2"]) == 0
    err = capsys.readouterr().err
    assert "resuming round 0: 25 of 25" in err and "resuming round 2: 1 of 3" in err
    assert not parts.exists()
    assert main([str(study), "-o", "ref.nc", "--quiet"]) == 0
    resumed, reference = xr.open_dataset("theta.nc"), xr.open_dataset("ref.nc")
    assert without_run_attrs(resumed).identical(without_run_attrs(reference))


MPIEXEC = shutil.which("mpiexec", path=str(Path(sys.executable).parent)) or \
    shutil.which("mpiexec")


@pytest.mark.mpi
@pytest.mark.skipif(MPIEXEC is None, reason="no mpiexec")
def test_two_ranks_equal_one_rank(tmp_path, theta_ds):
    study = write_study(tmp_path / "theta.yaml", THETA)
    one = cli([study, "-o", "one.nc", "--quiet"], cwd=tmp_path)
    assert one.returncode == 0, one.stderr
    two = subprocess.run([MPIEXEC, "-n", "2", PY, "-m", "sweep.run", str(study), "-o", "two.nc",
                          "--chunk-size", "1"], cwd=tmp_path, env=cli_env(),
                         capture_output=True, text=True, timeout=180)
    assert two.returncode == 0, two.stderr
    assert "rank 0:" in two.stdout and "rank 1:" in two.stdout  # both ranks computed
    a, b = xr.open_dataset(tmp_path / "one.nc"), xr.open_dataset(tmp_path / "two.nc")
    assert without_run_attrs(a).identical(without_run_attrs(b))
    # and the in-process run_study: the same numbers
    for name in cf.REFINE_VARIABLES:
        np.testing.assert_array_equal(a[name].values, theta_ds[name].values, err_msg=name)
    assert a["bracket"].dtype == np.int8 and a["coarse_overturned"].dtype == np.int8
