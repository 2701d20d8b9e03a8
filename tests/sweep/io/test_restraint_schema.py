"""The scene files' ``restraint`` and ``body.mass`` (docs/anchors.md): their units against
the exact factors, bad input as dotted-path problems with exit status 2, the JSON and text of
``python -m sweep.scene``, studies over ``restraint.strength`` and ``body.mass`` against
single-scene runs and the closed-form threshold g b/h + 2 T b/(m h), the dataset's flags,
and the page's example."""
import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
import yaml

from kernels.api import scene_row
from sweep import cf
from sweep.bodies import G
from sweep.io.problems import FileProblems
from sweep.io.scene_schema import load_scene, resolve_scene
from sweep.runner.cell_checks import load_study
from sweep.runner.cells import run_chunk
from sweep.runner.simulate import simulate

DOCS = Path(__file__).resolve().parents[3] / "docs"
B, H, F = 0.4, 1.2, 0.2                  # m, m, Hz
AMPLITUDE = 0.55 * G                     # m/s^2, one cycle of a slow sine


def _scene(strength="800 N", mass="100 kg", **extra):
    scene = {"body": {"B": f"{B} m", "H": f"{H} m", "mass": mass},
             "contact": {"mu": 0.8},
             "excitation": {"horizontal": {"kind": "sine", "amplitude": AMPLITUDE,
                                           "frequency": F, "duration": 1 / F}},
             "restraint": {"kind": "anchor", "strength": strength}, **extra}
    if strength is None:
        del scene["restraint"]
    return scene


def _threshold(strength, mass):
    """(1) of docs/anchors.md for the symmetric body: g b/h + 2 T b/(m h)."""
    b, h = B / 2, H / 2
    return G * b / h + 2 * strength * b / (mass * h)


@pytest.mark.parametrize("strength, mass, newtons, kilograms", [
    ("800 N", "100 kg", 800.0, 100.0),
    ("0.8 kN", "0.1 t", 800.0, 100.0),
    ("1 kgf", "1 lb", 9.80665, 0.45359237),
    ("1 lbf", 0.45359237, 0.45359237 * 9.80665, 0.45359237),
])
def test_units_of_strength_and_mass(strength, mass, newtons, kilograms):
    """N, kN, kgf (9.80665 N), lbf (0.45359237 kg x 9.80665 m/s^2); kg, t, lb (0.45359237 kg):
    resolved in SI, and the kernel's tie strength per unit mass is their ratio."""
    resolved = resolve_scene(_scene(strength, mass))
    assert resolved["restraint"] == {"kind": "anchor",
                                     "strength": pytest.approx(newtons, rel=1e-15)}
    assert resolved["body"]["mass"] == pytest.approx(kilograms, rel=1e-15)
    row = scene_row(resolved)
    assert row["restraint"]["tie"] == pytest.approx(newtons / kilograms, rel=1e-14)


def test_no_restraint_is_none():
    """Without a restraint the resolved scene has neither restraint nor mass."""
    resolved = resolve_scene(_scene(None, None))
    assert "restraint" not in resolved and "mass" not in resolved["body"]
    assert scene_row(resolved)["restraint"]["kind"] == 0.0


@pytest.mark.parametrize("change, expected", [
    ({"mass": None}, {"body.mass"}),
    ({"strength": "-800 N"}, {"restraint.strength"}),
    ({"mass": "0 kg"}, {"body.mass"}),
    ({"mass": -3}, {"body.mass"}),
    ({"strength": "8 m"}, {"restraint.strength"}),
    ({"kind": "bolt"}, {"restraint.kind"}),
    ({"initial": {"theta": "1 deg", "x_dot": "1 cm/s", "omega": 0}},
     {"initial.theta", "initial.x_dot"}),
])
def test_bad_input_is_one_line_per_problem_and_status_2(tmp_path, capsys, change, expected):
    """Each problem at its dotted path, with the value given; exit status 2, no traceback."""
    from sweep.scene import main

    scene = _scene()
    if "mass" in change:
        scene["body"]["mass"] = change["mass"]
        if change["mass"] is None:
            del scene["body"]["mass"]
    scene["restraint"].update({k: v for k, v in change.items() if k in ("strength", "kind")})
    scene.update({k: v for k, v in change.items() if k == "initial"})
    path = tmp_path / "anchored.yaml"
    path.write_text(yaml.safe_dump(scene))
    with pytest.raises(FileProblems) as err:
        load_scene(str(path))
    assert {p.path for p in err.value.problems} == expected
    with pytest.raises(SystemExit) as ended:
        main([str(path)])
    said = capsys.readouterr().err
    assert ended.value.code == 2 and "Traceback" not in said
    assert {line.split(":")[0].strip() for line in said.splitlines()
            if line.startswith("  ")} == expected


@pytest.mark.parametrize("factor, broken", [(0.98, False), (1.02, True)])
def test_json_and_text_say_whether_the_anchor_held(tmp_path, capsys, factor, broken):
    """``restraint: {kind, strength, broken, t_broken}`` in the JSON; t_broken where the sine
    reaches (1), asin(threshold/A)/(2 pi f); the text's third line says the same."""
    from sweep.scene import main

    threshold = _threshold(800.0, 100.0)
    scene = _scene()
    scene["excitation"]["horizontal"]["amplitude"] = factor * threshold
    path = tmp_path / "anchored.yaml"
    path.write_text(yaml.safe_dump(scene))
    main([str(path), "--json"])
    restraint = json.loads(capsys.readouterr().out)["restraint"]
    assert set(restraint) == {"kind", "strength", "broken", "t_broken"}
    assert restraint["kind"] == "anchor" and restraint["strength"] == 800.0
    assert restraint["broken"] is broken
    if broken:
        t = math.asin(1 / factor) / (2 * math.pi * F)
        assert restraint["t_broken"] == pytest.approx(t, abs=1e-6)
    else:
        assert restraint["t_broken"] is None
    main([str(path), "--summary"])
    line = capsys.readouterr().out.splitlines()[2]
    if broken:
        said = re.fullmatch(r"anchor of strength 800 N: broke at t = (\S+) s", line)
        assert float(said.group(1)) == pytest.approx(t, abs=1e-5)
    else:
        assert line == "anchor of strength 800 N: held throughout"


def test_json_has_no_restraint_without_one(tmp_path, capsys):
    from sweep.scene import main

    path = tmp_path / "free.yaml"
    path.write_text(yaml.safe_dump(_scene(None, None)))
    main([str(path), "--json"])
    assert "restraint" not in json.loads(capsys.readouterr().out)
    main([str(path), "--summary"])
    assert len(capsys.readouterr().out.splitlines()) == 2


@pytest.mark.parametrize("axis, values, unit, strengths, masses", [
    ("restraint.strength", [200, 400, 800], "N", [200.0, 400.0, 800.0], [100.0] * 3),
    ("body.mass", [0.05, 0.4], "t", [800.0] * 2, [50.0, 400.0]),
])
def test_study_axis_cells_agree_with_the_threshold_and_single_scenes(axis, values, unit,
                                                                     strengths, masses):
    """A grid over the strength or the mass: each cell at rest where the sine stays below
    (1), broken where it exceeds it, and as the same scene run alone."""
    raw = {"name": "anchored", "scene": _scene(),
           "grid": {axis: {"values": values, "unit": unit}}}
    study = load_study(raw, check_cells=False)
    out = run_chunk(study, np.arange(len(values)))
    dataset = cf.to_dataset(study, out)
    coordinate = dataset[axis.split(".")[-1]]
    assert coordinate.attrs["units"] == {"N": "N", "t": "kg"}[unit]
    np.testing.assert_allclose(coordinate.values, strengths if unit == "N" else masses)
    for k, (strength, mass) in enumerate(zip(strengths, masses)):
        broke = AMPLITUDE > _threshold(strength, mass)
        assert out["restraint_broken"][k] == int(broke)
        assert (out["max_abs_theta"][k] > 0) == broke and (out["max_slip"][k] > 0) == broke
        alone = simulate(_scene(f"{strength} N", f"{mass} kg"))
        assert alone.restraint["broken"] == broke
        assert out["outcome"][k] == (2 if alone.overturned else int(alone.max_abs_theta > 0))
        assert out["max_abs_theta"][k] == alone.max_abs_theta
    assert set(out["restraint_broken"].tolist()) == {0, 1}       # both sides of (1) seen


def test_dataset_flags_none_held_broke():
    """CF flags of ``restraint_broken``: -1 for a cell without a restraint or that failed
    (a negative strength cannot be built), 0 held, 1 broke."""
    attrs = cf.variable_attrs("restraint_broken")
    assert attrs["flag_values"].tolist() == [-1, 0, 1]
    assert attrs["flag_meanings"] == "none_or_failed held broke"
    raw = {"name": "anchored", "scene": _scene(),
           "grid": {"restraint.strength": {"values": [-1, 200, 2000], "unit": "N"}}}
    with pytest.warns(RuntimeWarning, match="cell 0"):
        out = run_chunk(load_study(raw, check_cells=False), np.arange(3))
    assert out["restraint_broken"].tolist() == [-1, 1, 0] and out["outcome"][0] == -1
    free = {"name": "free", "scene": _scene(None, None), "grid": {"mu": [0.8]}}
    assert run_chunk(load_study(free, check_cells=False), [0])["restraint_broken"][0] == -1


def test_the_pages_example_loads_and_holds_below_its_threshold():
    """The scene of docs/anchors.md: 250 kg, 1.5 kN; El Centro at 0.5 g is below (1)
    (0.74 g), so the anchor holds and the statue stands still."""
    text = (DOCS / "anchors.md").read_text(encoding="utf-8")
    scene = yaml.safe_load(re.search(r"```yaml\n(.*?)```", text, re.S).group(1))
    assert _threshold(1500.0, 250.0) / G == pytest.approx(0.74, abs=0.005)
    result = simulate(scene)
    assert result.pga == pytest.approx(0.5 * G, rel=1e-6) and result.pga < _threshold(1500, 250)
    assert result.restraint == {"kind": "anchor", "strength": 1500.0, "broken": False,
                                "t_broken": None}
    assert result.max_abs_theta == 0.0 and result.max_slip == 0.0
