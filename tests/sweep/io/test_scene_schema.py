"""Scene files: every problem at once with dotted paths, units, defaults, resolution to SI."""
import math

import numpy as np
import pytest

from kernels.api import DEFAULTS
from sweep.io.scene_schema import load_scene, resolve_scene
from sweep.io.study_grid import apply_overrides
from sweep.io.problems import FileProblems

G = 9.80665

DESIGN_EXAMPLE = """\
body: {B: 0.10, H: 0.30}            # full breadth and height [m]
contact:
  mu_s: 0.4
  mu_k: 0.3
  mu_edge_s: 0.4
  mu_edge_k: 0.3
  e_x: -0.8
  e_y: 0.2
excitation:
  horizontal: {kind: sine, amplitude: 1.5 west, frequency: 4.0, phase: 0.0}
  vertical:   {kind: none}
initial: {theta: 0.0, omega: 0.0, x_dot: 0.0, y_dot: 0.0, lift: 0.0}
solver: {method: adaptive, rtol: 1.0e-8, t_end: 10.0}
"""

BAD = """\
body: {B: 10 cm, H: -0.3, weight: 2}
contact: {mu: 0.4, e_x: -1.5, e_y: 0.2, e_y: 0.3}
excitation:
  horizontal: {kind: sine, amplitude: 1.5 wset, frequency: 4 s, amplitdue: 3}
  vertical: {kind: sweep, hold: velocity, amplitude: 1 g, f_start: 1, f_stop: 10}
initial: {theta: 0.1 west}
solver: {method: rk4, max_steps: 1.5}
"""


def _write(tmp_path, text, name="scene.yaml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def _resolve(raw):
    return resolve_scene(load_scene(raw))


def _scene(**excitation):
    return {"body": {"B": 0.1, "H": 0.3}, "excitation": excitation}


def test_design_example(tmp_path):
    r = resolve_scene(load_scene(_write(tmp_path, DESIGN_EXAMPLE)))
    assert r["body"] == {"B": 0.1, "H": 0.3, "i_g": None, "G": None}
    assert r["contact"] == {"mu_s": 0.4, "mu_k": 0.3, "mu_edge_s": 0.4, "mu_edge_k": 0.3,
                            "e_x": -0.8, "e_y": 0.2, "landing": "face_friction"}
    h = r["excitation"]["horizontal"]
    assert h["kind"] == "sine" and h["frequency"] == 4.0 and h["phase"] == 0.0
    assert h["amplitude"] == pytest.approx(1.5 * G / 3, rel=1e-12)
    assert r["excitation"]["vertical"] == {"kind": "none"}
    assert r["solver"]["t_end"] == 10.0 and r["solver"]["method"] == "adaptive"


def test_every_problem_at_once(tmp_path):
    with pytest.raises(FileProblems) as info:
        load_scene(_write(tmp_path, BAD))
    got = {p.path: p.value for p in info.value.problems}
    assert got == {
        "contact.e_y": "e_y",                              # duplicate key
        "body.H": -0.3,
        "body.weight": 2,
        "contact.e_x": -1.5,
        "excitation.horizontal.amplitude": "1.5 wset",
        "excitation.horizontal.frequency": "4 s",
        "excitation.horizontal.amplitdue": 3,
        "excitation.vertical.amplitude": "1 g",            # hold: velocity
        "excitation.vertical.duration": got["excitation.vertical.duration"],
        "initial.theta": "0.1 west",
        "solver.method": "rk4",
        "solver.max_steps": 1.5,
    }
    text = str(info.value)
    assert "body.H: must be greater than 0 (got: -0.3)" in text
    assert "excitation.horizontal.amplitdue: unknown key; did you mean 'amplitude'?" in text
    assert "excitation.vertical.duration: required" in text
    assert "'s' is a unit of time, expected a frequency" in text
    assert "expected a velocity (hold: velocity)" in text
    assert info.value.source.endswith("scene.yaml")


def test_duplicate_keys_reported_with_path(tmp_path):
    text = "body: {B: 0.1, H: 0.3}\nexcitation:\n  horizontal: {kind: none}\n" \
           "  horizontal: {kind: none}\n"
    with pytest.raises(FileProblems, match=r"excitation\.horizontal: duplicate key"):
        load_scene(_write(tmp_path, text))


@pytest.mark.parametrize("ground, path, message", [
    ({"kind": "wave"}, "excitation.horizontal.kind", "unknown kind"),
    ({"amplitude": 3}, "excitation.horizontal.kind", "required"),
    ({"kind": "record"}, "excitation.horizontal.name", "required"),
    ({"kind": "record", "name": "elcentro"}, "excitation.horizontal.name", "unknown record"),
    ({"kind": "record", "name": "elcentro1940_ns", "scale": 2, "pga": "0.5 g"},
     "excitation.horizontal.pga", "one of scale, pga, pgv and sa, not scale and pga"),
    ({"kind": "record", "name": "elcentro1940_ns", "units": "gal"},
     "excitation.horizontal.units", "path: file only"),
    ({"kind": "record", "path": "missing.AT2"}, "excitation.horizontal.path", "cannot read"),
    ({"kind": "pulse", "shape": "square", "amplitude": 1, "duration": 0.1},
     "excitation.horizontal.shape", "'rectangular' or 'triangular'"),
    ({"kind": "pulse", "shape": "rectangular", "amplitude": "1 cm", "duration": 0.1},
     "excitation.horizontal.amplitude", "expected an acceleration"),
    ({"kind": "sine", "amplitude": "1 deg", "frequency": 1},
     "excitation.horizontal.amplitude", "an acceleration, a velocity or a length"),
])
def test_ground_errors(ground, path, message):
    with pytest.raises(FileProblems) as info:
        load_scene(_scene(horizontal=ground))
    [problem] = info.value.problems
    assert problem.path == path and message in problem.message


def test_scene_must_be_a_mapping(tmp_path):
    with pytest.raises(FileProblems, match="must be a mapping"):
        load_scene(_write(tmp_path, "- 1\n"))
    with pytest.raises(FileProblems, match="empty"):
        load_scene(_write(tmp_path, ""))


def test_mu_shorthand_and_explicit_override():
    r = _resolve({"body": {"B": 0.1, "H": 0.3}, "contact": {"mu": 0.6}})
    assert [r["contact"][k] for k in ("mu_s", "mu_k", "mu_edge_s", "mu_edge_k")] == [0.6] * 4
    r = _resolve({"body": {"B": 0.1, "H": 0.3}, "contact": {"mu": 0.6, "mu_edge_k": 0.2}})
    assert [r["contact"][k] for k in ("mu_s", "mu_k", "mu_edge_s", "mu_edge_k")] == \
        [0.6, 0.6, 0.6, 0.2]


def test_defaults_and_contract_keys():
    r = _resolve({"body": {"B": 0.1, "H": 0.3}})
    assert r["contact"] == DEFAULTS["contact"]
    assert r["initial"] == DEFAULTS["initial"]
    assert r["solver"] == DEFAULTS["solver"]
    assert set(r) == {"body", "contact", "excitation", "initial", "solver"}
    assert r["excitation"] == {"horizontal": {"kind": "none"}, "vertical": {"kind": "none"}}


def test_units_resolved_with_the_scenes_body():
    r = _resolve({"body": {"B": "10 cm", "H": "300 mm"},
                  "excitation": {"horizontal": {"kind": "pulse", "shape": "triangular",
                                                "amplitude": "341.7 gal", "duration": "200 ms"},
                                 "vertical": {"kind": "sweep", "hold": "velocity",
                                              "amplitude": "1 v_H", "f_start": "1 Hz",
                                              "f_stop": 10, "duration": 60, "law": "linear"}},
                  "initial": {"theta": "0.1 alpha", "omega": "-5.7 deg/s", "x_dot": "100 cm/s",
                              "lift": "15 mm"},
                  "solver": {"theta_overturn": "90 deg", "dt": "1 ms"}})
    assert r["body"]["B"] == pytest.approx(0.1) and r["body"]["H"] == pytest.approx(0.3)
    h = r["excitation"]["horizontal"]
    assert h == pytest.approx({"kind": "pulse", "shape": "triangular", "amplitude": 3.417,
                               "duration": 0.2, "start": 0.0})
    v = r["excitation"]["vertical"]
    assert v["amplitude"] == pytest.approx(0.485554, abs=5e-7)
    assert (v["hold"], v["f_start"], v["f_stop"], v["duration"], v["law"], v["phase"]) == \
        ("velocity", 1.0, 10, 60, "linear", 0.0)
    assert r["initial"]["theta"] == pytest.approx(0.0321751, abs=5e-8)
    assert r["initial"]["omega"] == pytest.approx(-5.7 * math.pi / 180)
    assert r["initial"]["x_dot"] == pytest.approx(1.0)
    assert r["initial"]["lift"] == pytest.approx(0.015)
    assert r["solver"]["theta_overturn"] == pytest.approx(math.pi / 2)
    assert r["solver"]["dt"] == pytest.approx(1e-3)


def test_west_for_another_body():
    r = _resolve({"body": {"B": 0.25, "H": 1.0},
                  "excitation": {"horizontal": {"kind": "sine", "amplitude": "1 west",
                                                "frequency": 2}}})
    assert r["excitation"]["horizontal"]["amplitude"] == pytest.approx(2.45166, abs=5e-6)  # A11


@pytest.mark.parametrize("amplitude, frequency, expected", [
    ("341.7 gal", 2.0, 3.417),
    ("10 cm/s", 2.0, 0.1 * 2 * math.pi * 2.0),
    ("5 mm", 3.0, 0.005 * (2 * math.pi * 3.0) ** 2),
    ("0.4 v_H", 1 / 0.37332, 3.26888),  # point P of the 0.1 x 0.3 block (A11)
])
def test_sine_amplitude_converted_to_acceleration(amplitude, frequency, expected):
    r = _resolve(_scene(horizontal={"kind": "sine", "amplitude": amplitude,
                                    "frequency": frequency}))
    assert r["excitation"]["horizontal"]["amplitude"] == pytest.approx(expected, rel=2e-5)


def test_sweep_displacement_amplitude_kept_in_metres():
    r = _resolve(_scene(horizontal={"kind": "sweep", "hold": "displacement", "amplitude": "2 cm",
                                    "f_start": 0.5, "f_stop": 5, "duration": 30}))
    assert r["excitation"]["horizontal"]["amplitude"] == pytest.approx(0.02)
    assert r["excitation"]["horizontal"]["law"] == "log"


def test_record_bundled_with_pga():
    r = _resolve(_scene(horizontal={"kind": "record", "name": "elcentro1940_ns",
                                    "pga": "0.5 g", "start": 1.0},
                        vertical={"kind": "record", "name": "elcentro1940_ud", "scale": -1}))
    h, v = r["excitation"]["horizontal"], r["excitation"]["vertical"]
    assert h["dt"] == 0.02 and len(h["samples"]) == 2688
    assert h["scale"] * np.max(np.abs(h["samples"])) == pytest.approx(0.5 * G)
    assert h["scale"] == pytest.approx(0.5 * G / 3.41995, rel=1e-5)  # README peak 3.41995
    assert v["scale"] == -1 and v["start"] == 0.0 and v["duration"] is None
    # both components end: the later (NS from 1 s, 2688 samples of 0.02 s) + 5 s
    assert r["solver"]["t_end"] == pytest.approx(1.0 + 2688 * 0.02 + 5.0)


def test_record_path_relative_to_scene_file(tmp_path):
    (tmp_path / "motions").mkdir()
    (tmp_path / "motions" / "rec.txt").write_text("0 10\n0.01 -20\n0.02 5\n")
    text = ("body: {B: 0.1, H: 0.3}\nexcitation:\n"
            "  horizontal: {kind: record, path: motions/rec.txt, units: gal}\n")
    r = resolve_scene(load_scene(_write(tmp_path, text)))
    h = r["excitation"]["horizontal"]
    np.testing.assert_allclose(h["samples"], [0.1, -0.2, 0.05])
    assert h["dt"] == 0.01 and h["scale"] == 1.0


@pytest.mark.parametrize("horizontal, t_end", [
    ({"kind": "sine", "amplitude": 1, "frequency": 1, "start": 1, "duration": 2}, 8.0),
    ({"kind": "sine", "amplitude": 1, "frequency": 1}, 10.0),
    ({"kind": "pulse", "shape": "rectangular", "amplitude": 1, "duration": 0.5}, 5.5),
    ({"kind": "sweep", "amplitude": 1, "f_start": 1, "f_stop": 2, "duration": 60}, 65.0),
    ({"kind": "none"}, 10.0),
])
def test_t_end_from_excitation(horizontal, t_end):
    assert _resolve(_scene(horizontal=horizontal))["solver"]["t_end"] == pytest.approx(t_end)


def test_t_end_open_if_any_component_never_ends():
    r = _resolve(_scene(horizontal={"kind": "pulse", "shape": "rectangular", "amplitude": 1,
                                    "duration": 0.5},
                        vertical={"kind": "sine", "amplitude": 1, "frequency": 1}))
    assert r["solver"]["t_end"] == 10.0


def test_explicit_t_end_wins():
    raw = _scene(horizontal={"kind": "pulse", "shape": "rectangular", "amplitude": 1,
                             "duration": 0.5})
    raw["solver"] = {"t_end": "3 s"}
    assert _resolve(raw)["solver"]["t_end"] == 3.0


def test_vertical_none_shorthand(tmp_path):
    r = resolve_scene(load_scene(_write(tmp_path, "body: {B: 0.1, H: 0.3}\n"
                                                  "excitation: {vertical: none}\n")))
    assert r["excitation"]["vertical"] == {"kind": "none"}


def test_apply_overrides():
    raw = {"body": {"B": 0.1, "H": 0.3},
           "excitation": {"horizontal": {"kind": "sine", "amplitude": "1 west",
                                         "frequency": 2}}}
    new = apply_overrides(raw, {"excitation.horizontal.amplitude": "1.5 west",
                                "body.H": 0.6, "contact.mu": 0.8})
    assert raw["body"]["H"] == 0.3 and "contact" not in raw  # input untouched
    r = _resolve(new)
    assert r["excitation"]["horizontal"]["amplitude"] == pytest.approx(1.5 * G / 6)
    assert r["contact"]["mu_edge_k"] == 0.8
    with pytest.raises(FileProblems, match="body.B: cannot set 'body.B.x'"):
        apply_overrides(raw, {"body.B.x": 1})


def test_overridden_values_are_checked():
    raw = apply_overrides({"body": {"B": 0.1, "H": 0.3}}, {"body.H": "3 west"})
    with pytest.raises(FileProblems, match="body.H: 'west' is a unit of acceleration"):
        load_scene(raw)


def test_empty_sections(tmp_path):
    text = "body: {B: 0.1, H: 0.3}\ncontact:\ninitial:\n"
    r = resolve_scene(load_scene(_write(tmp_path, text)))
    assert r["contact"] == DEFAULTS["contact"]
    with pytest.raises(FileProblems) as info:
        load_scene({"body": None})
    assert [p.path for p in info.value.problems] == ["body.B", "body.H"]
    assert apply_overrides({"contact": None}, {"contact.mu": 0.5}) == {"contact": {"mu": 0.5}}


# --- bodies with G off the middle (docs/bodies.md) --------------------------------------------

def test_rock_form_becomes_B_and_G_and_is_echoed_back():
    """alpha_1, alpha_2, R_1, R_2 -> b_i = R_i sin alpha_i, h = R_i cos alpha_i, B = b1 + b2,
    G = [(b1 - b2)/2, h], H = 2h; ``sweep.bodies.describe`` gives the four back."""
    from sweep.bodies import describe
    a1, a2, R1 = math.radians(20), math.radians(12), 1.2
    R2 = R1 * math.cos(a1) / math.cos(a2)
    body = _resolve({"body": {"alpha_1": "20 deg", "alpha_2": "12 deg", "R_1": R1,
                              "R_2": R2}})["body"]
    b1, b2, h = R1 * math.sin(a1), R2 * math.sin(a2), R1 * math.cos(a1)
    assert body["B"] == pytest.approx(b1 + b2, rel=1e-15) and body["H"] == pytest.approx(2 * h)
    np.testing.assert_allclose(body["G"], [(b1 - b2) / 2, h], rtol=1e-15)
    echo = describe(body["B"], body["H"], body["G"], body["i_g"])
    np.testing.assert_allclose([echo[k] for k in ("alpha_1", "alpha_2", "R_1", "R_2")],
                               [a1, a2, R1, R2], rtol=1e-14)
    assert echo["i_g_default"] and echo["i_g"] == pytest.approx(
        math.sqrt((body["B"] ** 2 + body["H"] ** 2) / 12))


@pytest.mark.parametrize("body, path", [
    ({"B": 0.2, "H": 0.6, "G": [0.1, 0.3]}, "body.G"),             # on the right edge
    ({"B": 0.2, "H": 0.6, "G": [0.0, 0.7]}, "body.G"),             # above the top
    ({"alpha_1": 0.3, "alpha_2": 0.2, "R_1": 1.0, "R_2": 1.0}, "body.R_2"),   # heights differ
    ({"alpha_1": 0.3, "R_1": 1.0}, "body.alpha_2"),
    ({"B": 0.2, "H": 0.6, "alpha_1": 0.3, "alpha_2": 0.2, "R_1": 1.0, "R_2": 1.0}, "body.B"),
])
def test_bad_bodies_are_one_problem_each(body, path):
    with pytest.raises(FileProblems) as info:
        _resolve({"body": body})
    assert [p.path for p in info.value.problems] == [path]


def test_body_units_take_the_smaller_side():
    """1 west = g min(b1, b2)/y_G; 1 alpha = min(alpha_1, alpha_2)."""
    r = _resolve({"body": {"B": 0.2, "H": 0.6, "G": [0.03, 0.25]},
                  "excitation": {"horizontal": {"kind": "sine", "amplitude": "1 west",
                                                "frequency": 1}},
                  "initial": {"theta": "1 alpha"}})
    assert r["excitation"]["horizontal"]["amplitude"] == pytest.approx(G * 0.07 / 0.25,
                                                                       rel=1e-15)
    assert r["initial"]["theta"] == pytest.approx(math.atan2(0.07, 0.25), rel=1e-15)
