"""Inputs that cannot silently mean something else: warnings of implausible values, their path
and count; axes in degrees kept as written; a vertical record scaled with the horizontal one;
units of a record file checked against what the file states."""
import math
import subprocess
import warnings
from pathlib import Path

import numpy as np
import pytest

import sweep
from sweep.io import plausibility
from sweep.io.problems import FileProblems, InputWarning
from sweep.io.records import RecordError, read_record_file
from sweep.io.scene_schema import load_scene, resolve_scene
from sweep.runner.cell_checks import load_study
from sweep.runner import refine

from study_helpers import PY, cli_env

G = 9.80665
RECORDS = Path(__file__).resolve().parents[3] / "sweep" / "data" / "records"
BLOCK = {"B": 0.2, "H": 0.6}


def _doubts(raw, base_dir=None):
    """{path: message} of the implausible values of a scene."""
    scene = load_scene(raw, base_dir=base_dir)
    return {p.path: p.message for p in plausibility.scene_doubts(scene, resolve_scene(scene))}


def _sine(**extra):
    return {"body": dict(BLOCK), "excitation": {"horizontal": {
        "kind": "sine", "amplitude": "0.1 g", "frequency": 2.0, **extra}}}


def _record(**horizontal):
    return {"body": dict(BLOCK), "excitation": {"horizontal": {"kind": "record", **horizontal}}}


def _two_columns(folder, name, peak, comment=""):
    """A two-column file whose numbers peak at ``peak`` (at t = 0.02 s)."""
    path = folder / name
    path.write_text(f"{comment}0.00 0.0\n0.01 {peak / 2}\n0.02 {-peak}\n0.03 0.0\n")
    return path


# --- what is warned of, at which path -----------------------------------------------------

@pytest.mark.parametrize("body, doubted", [
    ({"B": 10, "H": 30}, {"body.H"}),                       # 10 m is the limit, not above it
    ({"B": 10.5, "H": 0.3, "i_g": 11}, {"body.B", "body.i_g"}),
    ({"B": "30 m", "H": "90 m"}, set()),                    # written with its unit: meant
    ({"B": "30 cm", "H": 0.9}, set()),
])
def test_bare_body_sizes(body, doubted):
    assert set(_doubts({"body": body})) == doubted


def test_bare_body_size_message():
    assert _doubts({"body": {"B": 30, "H": 0.9}}) == {
        "body.B": "30 (a bare number is in m): a body 30 m wide; did you mean 30 cm?"}


@pytest.mark.parametrize("scene, doubted", [
    (_sine(phase=90), {"excitation.horizontal.phase"}),
    (_sine(phase=6.28), set()),                             # below 2 pi
    (_sine(phase=-7), {"excitation.horizontal.phase"}),
    (_sine(phase="90 deg"), set()),
    ({"body": BLOCK, "initial": {"theta": 45}, "solver": {"theta_overturn": 90}},
     {"initial.theta", "solver.theta_overturn"}),
])
def test_bare_angles(scene, doubted):
    assert set(_doubts(scene)) == doubted


def test_bare_angle_message():
    assert _doubts(_sine(phase=90))["excitation.horizontal.phase"] == (
        f"90 (a bare number is in rad): {90 / (2 * math.pi):.3g} turns; did you mean 90 deg?")


def test_frequencies_and_friction():
    assert set(_doubts(_sine(frequency=150))) == {"excitation.horizontal.frequency"}
    assert _doubts(_sine(frequency=100)) == {}
    assert set(_doubts(_sine(frequency="150 Hz"))) == {
        "excitation.horizontal.frequency"}  # a unit written does not make 150 Hz plausible
    sweep_ = {"body": BLOCK, "excitation": {"horizontal": {
        "kind": "sweep", "amplitude": "1.0 m/s^2", "f_start": 1, "f_stop": 628, "duration": 5}}}
    assert set(_doubts(sweep_)) == {"excitation.horizontal.f_stop"}
    assert "write 99.95 Hz" in _doubts(sweep_)["excitation.horizontal.f_stop"]  # 628 / 2 pi
    friction = {"body": BLOCK, "contact": {"mu": 2.0, "mu_s": 40, "mu_k": 2.5, "mu_edge_s": 10,
                                           "mu_edge_k": 1000}}
    assert set(_doubts(friction)) == {"contact.mu_s", "contact.mu_k"}  # 10, 1000: no sliding


# El Centro NS peaks at 342.0 gal (sweep/data/records/README.md): 9 x 342.0 gal = 3.14 g
@pytest.mark.parametrize("scaling, doubted", [
    ({"scale": 8}, set()),                                  # 2.79 g
    ({"scale": -9}, {"excitation.horizontal.scale"}),       # 3.14 g, whatever the polarity
    ({"pga": "3.5 g"}, {"excitation.horizontal.pga"}),
    ({"pga": "3 g"}, set()),
    ({}, set()),
])
def test_scaled_record_pga(scaling, doubted):
    assert set(_doubts(_record(name="elcentro1940_ns", **scaling))) == doubted


def test_file_in_g_that_looks_like_m_per_s2(tmp_path):
    """Read in g, numbers above 5 are a PGA above 5 g: one warning at the unit, not two."""
    _two_columns(tmp_path, "ms2.txt", 9.81)
    _two_columns(tmp_path, "strong.txt", 4.0)
    _two_columns(tmp_path, "said_g.txt", 9.81, comment="# acceleration [g]\n")
    doubts = _doubts(_record(path="ms2.txt", units="g"), tmp_path)
    assert doubts == {"excitation.horizontal.units": "g: the file's numbers peak at 9.81, a PGA "
                                                     "of 9.81 g; are they in m/s^2 or gal?"}
    assert set(_doubts(_record(path="strong.txt", units="g"), tmp_path)) == {
        "excitation.horizontal.path"}                      # 4 g: the scaled PGA's warning
    assert _doubts(_record(path="ms2.txt"), tmp_path) == {}  # m/s^2 by default: 1 g
    assert set(_doubts(_record(path="said_g.txt"), tmp_path)) == {"excitation.horizontal.path"}


def test_plausible_scenes_warn_of_nothing():
    assert _doubts(_sine(phase="30 deg")) == {}
    assert _doubts(_record(name="elcentro1940_ns", pga="0.5 g")) == {}


def test_simulate_warns_once_per_value_and_the_category_filters(tmp_path):
    _two_columns(tmp_path, "ud.txt", 9.81, comment="# units: g\n")
    scene = {"body": {"B": 30, "H": 90}, "contact": {"mu": 5},
             "excitation": {"horizontal": {"kind": "sine", "amplitude": "0.1 g",
                                           "frequency": 150, "phase": 90},
                            "vertical": {"kind": "record", "path": str(tmp_path / "ud.txt")}},
             "solver": {"t_end": 0.05}}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        sweep.simulate(scene)
    said = [w.message for w in caught if w.category is InputWarning]
    assert [m.problem.path for m in said] == [
        "body.B", "body.H", "excitation.horizontal.phase", "excitation.horizontal.frequency",
        "contact.mu", "excitation.vertical.path"]
    assert str(said[0]) == "body.B: 30 (a bare number is in m): a body 30 m wide; did you " \
                           "mean 30 cm?"
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        warnings.simplefilter("ignore", InputWarning)
        sweep.simulate(scene)
    assert not [w for w in caught if w.category is InputWarning]


def test_commands_print_one_line_per_warning(tmp_path):
    (tmp_path / "scene.yaml").write_text(
        "body: {B: 30, H: 0.9}\nexcitation: {horizontal: {kind: sine, amplitude: 0.1 g, "
        "frequency: 2, phase: 90}}\nsolver: {t_end: 0.05}\n")
    (tmp_path / "study.yaml").write_text(
        "scene: {body: {B: 0.1, H: 0.3}, excitation: {horizontal: {kind: sine, amplitude: 1 "
        "west, frequency: 2, phase: 90}}, solver: {t_end: 0.05}}\n"
        "grid: {B: [0.1, 20, 30], frequency: [1, 2]}\n")
    runs = [subprocess.Popen([PY, "-m", module, name, option], cwd=tmp_path, env=cli_env(),
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            for module, name, option in (("sweep.scene", "scene.yaml", "--summary"),
                                         ("sweep.run", "study.yaml", "--dry-run"))]
    (_, scene_err), (_, study_err) = (run.communicate(timeout=120) for run in runs)
    assert [run.returncode for run in runs] == [0, 0], scene_err + study_err
    assert "InputWarning" not in scene_err + study_err  # not Python's file:line form
    scene_err, study_err = ("\n".join(line for line in err.splitlines() if "warning" in line)
                            for err in (scene_err, study_err))  # a cold kernel says so too
    assert scene_err.splitlines() == [
        "warning: body.B: 30 (a bare number is in m): a body 30 m wide; did you mean 30 cm?",
        "warning: excitation.horizontal.phase: 90 (a bare number is in rad): 14.3 turns; did "
        "you mean 90 deg?"]
    # 6 cells, one warning per axis and one for the base scene
    assert study_err.splitlines() == [
        "sweep.run: warning: scene.excitation.horizontal.phase: 90 (a bare number is in rad): "
        "14.3 turns; did you mean 90 deg?",
        "sweep.run: warning: grid.B[1]: 20 (a bare number is in m): a body 20 m wide; did you "
        "mean 20 cm? (and 1 more value of grid.B)"]


def test_study_warns_once_per_axis_not_per_cell():
    study = {"scene": {"body": {"B": 0.5, "H": 1.5}, "contact": {"mu": 0.8},
                       "excitation": {"horizontal": {"kind": "record",
                                                     "name": "elcentro1940_ns"}}},
             "grid": {"scale": [1, 9, 10, 12], "mu_s": [0.5, 3], "b_over_h": [0.04, 0.2]}}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        load_study(study)
    said = [w.message.problem for w in caught if w.category is InputWarning]
    # 16 cells; H = B / 0.04 = 12.5 m is computed in metres, not a bare number written
    assert sorted((p.path, p.value) for p in said) == [("grid.mu_s[1]", 3), ("grid.scale[1]", 9)]
    scale = next(p for p in said if p.path == "grid.scale[1]")
    assert scale.message.endswith("(and 2 more values of grid.scale)")  # 3.49 g and 4.18 g


# --- bare accelerations that read like g ---------------------------------------------------

def _g_message(value, written=None):
    """The message of a bare acceleration ``value`` read as m/s^2, from g = 9.80665 m/s^2."""
    return (f"{written or value} (a bare number is in m/s^2): {value / G:.3g} g; did you mean "
            f"{value} g ({value * G:.3g} m/s^2)? write '{value} g' or '{value} m/s^2' to "
            "silence this")


def test_bare_pga_below_2_reads_like_g():
    doubts = _doubts(_record(name="elcentro1940_ns", pga=0.4))
    assert doubts == {"excitation.horizontal.pga": _g_message(0.4)}
    # 0.4 m/s^2 is 0.0408 g; 0.4 g is 3.92 m/s^2
    assert "0.0408 g" in doubts["excitation.horizontal.pga"]
    assert "did you mean 0.4 g (3.92 m/s^2)?" in doubts["excitation.horizontal.pga"]


@pytest.mark.parametrize("pga", ["0.4 g", "0.4 m/s^2", "400 gal", "40 cm/s^2", 3.9, 2.0, 2])
def test_explicit_units_and_plausible_bare_pga_warn_of_nothing(pga):
    assert _doubts(_record(name="elcentro1940_ns", pga=pga)) == {}


@pytest.mark.parametrize("horizontal, doubted", [
    ({"kind": "record", "name": "elcentro1940_ns", "pga": 1.99}, True),
    ({"kind": "sine", "amplitude": 0.3, "frequency": 2.0}, True),             # an acceleration
    ({"kind": "sine", "amplitude": "0.3 m/s", "frequency": 2.0}, False),      # a velocity
    ({"kind": "sweep", "hold": "acceleration", "amplitude": 0.5, "f_start": 1, "f_stop": 2,
      "duration": 3}, True),
    ({"kind": "sweep", "hold": "velocity", "amplitude": 0.5, "f_start": 1, "f_stop": 2,
      "duration": 3}, False),                                                  # pgv-like: m/s
    ({"kind": "pulse", "shape": "rectangular", "amplitude": -0.5, "duration": 0.2}, True),
    ({"kind": "pulse", "shape": "rectangular", "amplitude": 0, "duration": 0.2}, False),
    ({"kind": "record", "name": "elcentro1940_ns", "pgv": 0.3}, False),       # velocity levels
])
def test_bare_accelerations_of_every_kind(horizontal, doubted):
    doubts = _doubts({"body": dict(BLOCK), "excitation": {"horizontal": horizontal}})
    key = "pga" if "pga" in horizontal else "amplitude"
    assert set(doubts) == ({f"excitation.horizontal.{key}"} if doubted else set())


def test_bare_pga_of_a_synthetic_motion_and_of_a_vertical_record():
    synthetic = {"kind": "synthetic", "magnitude": 6.5, "distance": "20 km", "vs30": "760 m/s",
                 "pga": 0.5}
    assert _doubts({"body": dict(BLOCK), "excitation": {"horizontal": synthetic}}) == {
        "excitation.horizontal.pga": _g_message(0.5)}
    pair = _pair({"pga": 0.2}, {"kind": "record", "name": "elcentro1940_ns", "pga": "0.5 g"})
    assert _doubts(pair) == {"excitation.vertical.pga": _g_message(0.2)}


def _pga_study(values):
    return {"scene": {"body": dict(BLOCK), "excitation": {"horizontal": {
        "kind": "record", "name": "elcentro1940_ns"}}, "solver": {"t_end": 0.1}},
        "grid": {"pga": values}}


@pytest.mark.parametrize("values, said", [
    ([0.1, 0.2, 0.4], [("grid.pga[0]", _g_message(0.1) + " (and 2 more values of grid.pga)")]),
    ({"start": 0.1, "stop": 0.5, "num": 2}, [("grid.pga[0]", _g_message(
        0.1, "0.1") + " (and 1 more value of grid.pga)")]),
    ([0.5, 1, 2, 4], []),                         # a bare 2 and 4: the axis is in m/s^2
    ({"values": [0.1, 0.2], "unit": "g"}, []),
    (["0.1 g", "3 m/s^2"], []),
])
def test_study_pga_axis_warned_of_once(values, said):
    assert _warned(load_study, _pga_study(values)) == said


def _warned(load, raw):
    """(path, message) of every InputWarning that loading ``raw`` gives."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        load(raw)
    return [(w.message.problem.path, w.message.problem.message) for w in caught
            if w.category is InputWarning]


def _survey(levels):
    return {"site": "yard", "bodies": [{"name": "s", "B": "20 cm", "H": "80 cm",
                                        "overturned": True}],
            "ensemble": {"motions": {"record": ["elcentro1940_ns"]}, "levels": {"pga": levels}}}


@pytest.mark.parametrize("levels, said", [
    ({"start": 0.1, "stop": 1.6, "num": 5},
     [("ensemble.levels.pga.start", _g_message(0.1) + " (and 1 more value of "
                                                      "ensemble.levels.pga)")]),
    ([0.1, 0.5], [("ensemble.levels.pga[0]", _g_message(0.1) + " (and 1 more value of "
                                                               "ensemble.levels.pga)")]),
    ({"values": [0.3, "5 m/s^2"]}, [("ensemble.levels.pga.values[0]", _g_message(0.3))]),
    ({"start": 0.5, "stop": 16, "num": 5}, []),   # a bare 16: the levels are in m/s^2
    ({"start": "0.1 g", "stop": "1.6 g", "num": 5}, []),
    ({"start": "1 m/s^2", "stop": "16 m/s^2", "num": 14}, []),
])
def test_bodies_file_levels_warned_of_once(levels, said):
    from sweep.io.bodies_schema import load_survey
    assert _warned(load_survey, _survey(levels)) == said


def test_scene_command_says_a_bare_pga_reads_like_g(tmp_path):
    (tmp_path / "statue.yaml").write_text(
        "body: {B: 20 cm, H: 80 cm}\nexcitation: {horizontal: {kind: record, name: "
        "elcentro1940_ns, pga: 0.4}}\nsolver: {t_end: 0.1}\n")
    done = subprocess.run([PY, "-m", "sweep.scene", "statue.yaml", "--summary"], cwd=tmp_path,
                          env=cli_env(), capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert [line for line in done.stderr.splitlines() if "warning" in line] == [
        "warning: excitation.horizontal.pga: " + _g_message(0.4)]
    assert "PGA 0.0408 g" in done.stdout  # what was run: 0.4 m/s^2, as written


# --- axes in degrees ------------------------------------------------------------------------

def _phase_axis(values):
    study = {"scene": {"body": dict(BLOCK), "excitation": {"horizontal": {
        "kind": "sine", "amplitude": "0.1 g", "frequency": 2.0}}}, "grid": {"phase": values}}
    return load_study(study).axes[0]


def test_axis_written_in_degrees_keeps_degrees():
    for values in (["0 deg", "90 deg", "180 deg"], {"values": [0, 90, 180], "unit": "deg"},
                   {"start": 0, "stop": 180, "num": 3, "unit": "deg"}):
        axis = _phase_axis(values)
        np.testing.assert_array_equal(axis.coords, [0.0, 90.0, 180.0])
        assert (axis.units, axis.unit) == ("degree", "deg")
    mixed = _phase_axis(["0 deg", "1 rad"])  # not one unit: radians, as every SI coordinate
    np.testing.assert_allclose(mixed.coords, [0.0, 1.0])
    assert mixed.units == "rad"


def test_degree_axis_in_the_dataset_refine_and_scenes():
    ds = sweep.run_study({"scene": {"body": dict(BLOCK), "contact": {"mu": 0.8},
                                    "excitation": {"horizontal": {
                                        "kind": "sine", "amplitude": "0.5 west",
                                        "frequency": 2.0}}, "solver": {"t_end": 0.2}},
                          "grid": {"phase": ["0 deg", "90 deg", "180 deg"]}})
    assert list(ds.phase.values) == [0.0, 90.0, 180.0]
    assert ds.phase.attrs["units"] == "degree" and ds.phase.attrs["study_unit"] == "deg"
    axis = _phase_axis(["0 deg", "90 deg"])
    assert axis.coordinate(load_scene(_sine(phase="0.5 rad")).excitation.horizontal.phase) == \
        pytest.approx(0.5 * 180 / math.pi, rel=1e-15)
    midpoint = refine.point_study(load_study({
        "scene": {"body": dict(BLOCK), "excitation": {"horizontal": {
            "kind": "sine", "amplitude": "0.1 g", "frequency": 2.0}}},
        "grid": {"phase": ["0 deg", "90 deg"]}, "refine": {"axis": "phase",
                                                           "tolerance": "1 deg"}}),
        [0], [45.0]).axes[0]
    assert midpoint.values == ("45.0 deg",)


def test_refine_tolerance_in_the_axis_unit():
    study = {"scene": {"body": dict(BLOCK), "excitation": {"horizontal": {
        "kind": "sine", "amplitude": "0.1 g", "frequency": 2.0}}},
        "grid": {"phase": {"values": [0, 90], "unit": "deg"}}}
    for tolerance, degrees in ((2, 2.0), ("0.5 deg", 0.5), ("0.01 rad", 0.01 * 180 / math.pi)):
        refined = load_study({**study, "refine": {"axis": "phase", "tolerance": tolerance}})
        assert refined.refine.tolerance == pytest.approx(degrees, rel=1e-15)


# --- the vertical record scaled with the horizontal -----------------------------------------

def _peak(name):
    return float(np.max(np.abs(np.loadtxt(RECORDS / f"{name}.txt")[:, 1])))


def _pair(vertical, horizontal=None):
    return {"body": dict(BLOCK), "excitation": {
        "horizontal": horizontal or {"kind": "record", "name": "elcentro1940_ns",
                                     "pga": "0.5 g"},
        "vertical": {"kind": "record", "name": "elcentro1940_ud", **vertical}}}


def test_vertical_scaled_with_the_horizontal():
    resolved = resolve_scene(_pair({"scale_with": "horizontal"}))
    vertical = resolved["excitation"]["vertical"]
    ud_peak = vertical["scale"] * float(np.max(np.abs(vertical["samples"])))
    assert ud_peak == pytest.approx(_peak("elcentro1940_ud") * 0.5 * G
                                    / _peak("elcentro1940_ns"), rel=1e-12)
    # the README's peaks, 206.0 and 342.0 gal: 206.0 x 490.3325 / 342.0 = 295.3 gal
    assert ud_peak == pytest.approx(2.9534, rel=2e-4)
    assert vertical["scale"] == resolved["excitation"]["horizontal"]["scale"]
    unscaled = resolve_scene(_pair({"scale_with": "horizontal"},
                                   {"kind": "record", "name": "elcentro1940_ns"}))
    assert unscaled["excitation"]["vertical"]["scale"] == 1.0


@pytest.mark.parametrize("scene, path, message", [
    (_pair({"scale_with": "horizontal", "pga": "0.2 g"}), "excitation.vertical.scale_with",
     "give no pga with it"),
    (_pair({"scale_with": "horizontal", "scale": 2}), "excitation.vertical.scale_with",
     "give no scale with it"),
    (_pair({"scale_with": "horizontal"}, {"kind": "sine", "amplitude": 1, "frequency": 2}),
     "excitation.vertical.scale_with", "of kind sine: only a record or a synthetic motion"),
    (_pair({}, {"kind": "record", "name": "elcentro1940_ns", "scale_with": "horizontal"}),
     "excitation.horizontal.scale_with", "only the vertical component"),
    (_pair({"scale_with": "vertical"}), "excitation.vertical.scale_with", "horizontal"),
])
def test_scale_with_refused(scene, path, message):
    with pytest.raises(FileProblems) as info:
        load_scene(scene)
    assert [p.path for p in info.value.problems] == [path]
    assert message in info.value.problems[0].message


# --- units of record files against what the files state --------------------------------------

def test_column_file_units_from_its_comment(tmp_path):
    path = _two_columns(tmp_path, "g.txt", 0.5, comment="# El Centro, NS\n# acceleration [g]\n")
    rec = read_record_file(path)
    assert rec.units == "g" and rec.pga == pytest.approx(0.5 * G, rel=1e-15)
    assert "in g (stated on line 2)" in rec.provenance
    assert read_record_file(path, "g").pga == rec.pga  # the same unit given: fine
    with pytest.raises(RecordError, match=r"g.txt: line 2: a comment gives the accelerations in "
                                          r"g, not m/s\^2 \(units: m/s\^2\)"):
        read_record_file(path, "m/s^2")
    plain = _two_columns(tmp_path, "plain.txt", 0.5, comment="# peak 0.35 g at 2.1 s\n")
    assert read_record_file(plain).units == "m/s^2"  # a value's unit states nothing
    assert "the default" in read_record_file(plain).provenance


def test_column_file_comments_that_disagree(tmp_path):
    path = _two_columns(tmp_path, "two.txt", 0.5, comment="# units: gal\n# acceleration [g]\n")
    with pytest.raises(RecordError, match=r"state different units \(line 1: gal, line 2: g\)"):
        read_record_file(path)
    assert read_record_file(path, "gal").pga == pytest.approx(0.005, rel=1e-15)


def test_one_column_file_units_from_its_comment(tmp_path):
    path = tmp_path / "acc.txt"
    path.write_text("# accelerations in gal, 100 samples/s\n1 -2 30\n4\n")
    rec = read_record_file(path, format="column", dt=0.01)
    np.testing.assert_allclose(rec.samples, [0.01, -0.02, 0.3, 0.04], rtol=1e-15)
    with pytest.raises(RecordError, match="line 1: a comment gives the accelerations in gal, "
                                          "not g"):
        read_record_file(path, "g", format="column", dt=0.01)


def test_header_units_in_a_scene(tmp_path):
    (tmp_path / "x.AT2").write_text("PEER NGA\nTEST\nACCELERATION TIME SERIES IN UNITS OF G\n"
                                    "NPTS=    4, DT=   .0100 SEC\n0.1 0.2 -0.3 0.0\n")
    with pytest.raises(FileProblems) as info:
        load_scene(_record(path="x.AT2", units="gal"), base_dir=tmp_path)
    assert "a PEER .AT2 file is in g, not gal (units: gal)" in str(info.value)
    assert resolve_scene(load_scene(_record(path="x.AT2", units="g"), base_dir=tmp_path))[
        "excitation"]["horizontal"]["source"].pga == pytest.approx(0.3 * G, rel=1e-15)


def test_bodies_files_warn_of_bare_sizes_at_their_place():
    """A bodies file's B: 30 is a 30 m body too: warned of at sites[i].bodies[j].B."""
    from sweep.io.bodies_schema import load_survey
    survey = {"sites": [{"name": "a", "bodies": [
        {"name": "s1", "B": "30 cm", "H": 0.9, "overturned": True},
        {"name": "s2", "B": 30, "H": "90 cm", "overturned": False}]}]}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        load_survey(survey)
    said = [w.message.problem for w in caught if w.category is InputWarning]
    assert [p.path for p in said] == ["sites[0].bodies[1].B"]
    assert "did you mean 30 cm" in said[0].message
