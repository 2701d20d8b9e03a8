"""Study files: every problem at once with dotted paths, exit status 2 and nothing written."""
import numpy as np
import pytest
from study_helpers import cli, make_study

from sweep.runner.cell_checks import load_study
from sweep.io.problems import FileProblems

BAD = """\
name: bad
scene:
  body: {B: 0.1, H: 0.3}
  contact: {mu: 0.8}
  excitation:
    horizontal: {kind: sine, amplitude: 1.5 west, frequency: 4.0}
grid:
  amplitude: {start: 1.0, stop: 3.0, num: 0, unit: west}
  frequency: [1.0, 2 Hz, 3 m]
  amplitud: [1, 2]
  e_y: [0.1, 1.5, 0.2]
  mu: {start: 0.1, stop: 0.5, num: 3, spacing: cubic}
  solver.rtol: [1.0e-6, -1.0]
  b_over_h: [0.2, 0]
  phase: {start: 0, stop: 1, num: 2, unit: parsec}
zip: [[e_y, frequency, nothing]]
outptu: x.nc
output: out/bad.nc
"""
EXPECTED = {  # dotted path -> a word of the message
    "outptu": "did you mean 'output'",
    "grid.amplitude.num": "integer >= 1",
    "grid.frequency[2]": "expected a frequency",
    "grid.amplitud": "did you mean 'amplitude'",
    "grid.mu.spacing": "linear, log",
    "grid.b_over_h": "positive",
    "grid.phase.unit": "unknown unit",
    "zip[0]": "not an axis of grid",
    "grid.solver.rtol[1]": "greater than 0",
    "grid.e_y[1]": "less than or equal to 1",
}


def test_every_problem_at_once(tmp_path):
    with pytest.raises(FileProblems) as info:
        load_study(_write(tmp_path, BAD))
    problems = {p.path: p for p in info.value.problems}
    for path, word in EXPECTED.items():
        assert path in problems, f"{path} not reported; got {sorted(problems)}"
        assert word in problems[path].message, problems[path]
    assert problems["grid.e_y[1]"].value == 1.5 and problems["grid.amplitude.num"].value == 0
    # 'frequency' is an axis (with its own problem), only 'nothing' is not
    assert [p.value for p in info.value.problems if p.path == "zip[0]"] == ["nothing"]


def _write(tmp_path, text, name="study.yaml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_cell_problems_once_per_axis_value(tmp_path):
    raw = make_study({"amplitude": {"start": 1, "stop": 2, "num": 5, "unit": "west"},
                      "e_y": [0.0, 2.0], "e_x": [-0.5, -3.0]})
    raw["scene"]["contact"]["e_x"] = 9  # overridden by the axis in every cell: not reported
    raw["scene"]["solver"]["t_end"] = -1  # the base scene's problem, reported once
    with pytest.raises(FileProblems) as info:
        load_study(raw)
    paths = [p.path for p in info.value.problems]
    assert sorted(paths) == ["grid.e_x[1]", "grid.e_y[1]", "scene.solver.t_end"]


@pytest.mark.parametrize("text, path", [
    ("scene: {body: {B: 0.1, H: 0.3}}\ngrid: {e_y: [0.1]}\ngrid: {e_y: [0.2]}\n", "grid"),
    ("grid: {e_y: [0.1]}\n", "scene"),
    ("scene: {body: {B: 0.1, H: 0.3}}\n", "grid"),
    ("scene: {body: {B: 0.1, H: 0.3}}\ngrid: {e_y: 0.1}\n", "grid.e_y"),
    ("scene: {body: {B: 0.1, H: 0.3}}\ngrid: {e_y: [0.1, 0.1]}\n", "grid.e_y"),
    ("scene: {body: {B: 0.1, H: 0.3}}\ngrid: {H: [0.3], b_over_h: [0.2]}\n", "grid.b_over_h"),
    ("scene: {body: {B: 0.1, H: 0.3}}\ngrid: {e_y: [0.1], e_x: [0.1, 0.2]}\nzip: [[e_y, e_x]]\n",
     "zip[0]"),
    ("scene: {body: {B: 0.1, H: 0.3}}\ngrid: {amplitude: [1 west, 2 gal]}\n", "grid.amplitude"),
    ("scene: {body: {B: 0.1, H: 0.3}, excitation: {horizontal: {kind: record}}}\n"
     "grid: {record: [elcentro1940_ns, nowhere]}\n", "grid.record[1]"),
    ("[1, 2]\n", "(file)"),
])
def test_single_problems(tmp_path, text, path):
    with pytest.raises(FileProblems) as info:
        load_study(_write(tmp_path, text))
    assert path in [p.path for p in info.value.problems], str(info.value)


def test_axes_coordinates_and_units(tmp_path):
    study = load_study(make_study({
        "amplitude": {"start": 100, "stop": 300, "num": 3, "unit": "gal"},
        "frequency": [2.0, 4.0], "b_over_h": [0.25, 0.5], "e_y": [0.0, 0.3]}))
    amp, freq, ratio, e_y = study.axes
    np.testing.assert_allclose(amp.coords, [1.0, 2.0, 3.0])  # SI
    assert (amp.units, freq.units, ratio.units, e_y.units) == ("m s-2", "Hz", "1", "1")
    west = load_study(make_study({"amplitude": {"values": [1.0, 1.5], "unit": "west"}})).axes[0]
    np.testing.assert_allclose(west.coords, [1.0, 1.5])  # the normalized level, per body
    assert west.units == "1" and "West" in west.long_name and west.unit == "west"
    assert study.output.as_posix() == "results/t.nc"


def test_cli_bad_file_exit_2_nothing_written(tmp_path):
    study = _write(tmp_path, BAD)
    done = cli([study], cwd=tmp_path, timeout=60)
    assert done.returncode == 2, done.stderr
    assert "Traceback" not in done.stderr
    for path, word in EXPECTED.items():
        assert f"{path}: " in done.stderr and word in done.stderr
    assert "(got: 1.5)" in done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["study.yaml"]  # no output, no parts


def test_cell_count_limit():
    study = make_study({"amplitude": {"start": 1, "stop": 2, "num": 1000},
                        "frequency": {"start": 1, "stop": 2, "num": 1000}})
    with pytest.raises(FileProblems) as info:
        load_study(study, max_cells=999_999)
    [problem] = info.value.problems
    assert problem.path == "grid" and problem.value == "amplitude 1000 x frequency 1000"
    assert "1000000 cells, more than the limit of 999999" in problem.message
    assert "--max-cells" in problem.message
    assert load_study(study, max_cells=0).n_cells == 1_000_000


def test_large_grids_checked_by_a_bounded_choice_of_cells():
    """Each value of every axis is checked; the cells are far fewer than the grid's."""
    from sweep.runner import cell_checks
    study = load_study(make_study({"amplitude": {"start": 1, "stop": 2, "num": 3000},
                                   "frequency": [1.0, 2.0, 3.0, -4.0]}), check_cells=False)
    checked = cell_checks.checked_cells(study)
    n_checked = cell_checks.CHECKED_PER_DIM + 4 + cell_checks.SAMPLED_CELLS
    assert study.n_cells > cell_checks.CHECK_ALL_CELLS and len(checked) <= n_checked
    assert [p.path for p in cell_checks.cell_problems(study)] == ["grid.frequency[3]"]


def test_axis_length_and_repeats():
    with pytest.raises(FileProblems) as info:
        load_study(make_study({"amplitude": {"start": 1, "stop": 2, "num": 10**7},
                               "mu": [0.5, 0.2] * 50_000}))
    assert {p.path: p.message for p in info.value.problems} == {
        "grid.amplitude.num": "must be an integer >= 1, at most 1000000",
        "grid.mu": "values repeat: 0.2"}


# --- axes that fit the scene: hints --------------------------------------------------------

RECORD_SCENE = {"body": {"B": 0.2, "H": 0.6},
                "excitation": {"horizontal": {"kind": "record", "name": "elcentro1940_ns"}}}
SINE_SCENE = {"body": {"B": 0.2, "H": 0.6},
              "excitation": {"horizontal": {"kind": "sine", "amplitude": "1 west",
                                            "frequency": 2.0}}}


def _problems(scene, grid):
    with pytest.raises(FileProblems) as info:
        load_study({"scene": scene, "grid": grid})
    return [(p.path, p.message) for p in info.value.problems]


def test_amplitude_axis_on_a_record_suggests_scale_pga_pgv_sa():
    """One problem at the axis, not one 'unknown key' per value."""
    [(path, message)] = _problems(RECORD_SCENE, {"amplitude": [1, 2, 3]})
    assert path == "grid.amplitude"
    assert message == ("sets excitation.horizontal.amplitude, which a record motion does not "
                       "have; scale it with an axis scale (a factor on its samples), pga, "
                       "pgv or sa (the peak it is scaled to)")


@pytest.mark.parametrize("scene, grid, path, words", [
    (SINE_SCENE, {"pga": [1, 2]}, "grid.pga", ["a sine motion does not have", "amplitude"]),
    (SINE_SCENE, {"scale": [1, 2]}, "grid.scale", ["amplitude"]),
    (SINE_SCENE, {"record": ["elcentro1940_ns"]}, "grid.record", ["of kind record"]),
    (RECORD_SCENE, {"seed": [1, 2]}, "grid.seed", ["an axis record"]),
    (RECORD_SCENE, {"frequency": [1, 2]}, "grid.frequency",
     ["a record motion does not have", "it takes start, duration, scale, pga, pgv"]),
    (RECORD_SCENE, {"excitation.horizontal.amplitude": [1]},
     "grid.excitation.horizontal.amplitude", ["scale", "pga", "pgv"]),
])
def test_axes_that_the_scenes_motion_lacks(scene, grid, path, words):
    [(found, message)] = _problems(scene, grid)
    assert found == path and all(word in message for word in words), message


@pytest.mark.parametrize("name, meant", [
    ("height", "H"), ("Height", "H"), ("hieght", "H"), ("width", "B"), ("h", "H"),
    ("PGA", "pga"), ("slenderness", "b_over_h"), ("theta", "initial.theta"),
    ("magnitude", "excitation.horizontal.magnitude"), ("amplitud", "amplitude"),
])
def test_unknown_axis_did_you_mean(name, meant):
    [(path, message)] = _problems(SINE_SCENE, {name: [0.5, 1.0]})
    assert path == f"grid.{name}" and f"unknown axis; did you mean '{meant}'?" in message


def test_H_with_b_over_h_says_to_vary_B_or_size():
    [(path, message)] = _problems(SINE_SCENE, {"H": [0.5, 1.0], "b_over_h": [0.2, 0.3]})
    assert path == "grid.b_over_h"
    assert message == ("b_over_h keeps B and sets H = B/(b/h), so an H axis conflicts with "
                       "it: vary B beside b_over_h, or size (a factor on B and H)")
    assert load_study({"scene": SINE_SCENE, "grid": {"B": [0.1, 0.2],
                                                     "b_over_h": [0.2, 0.3]}}).n_cells == 4
