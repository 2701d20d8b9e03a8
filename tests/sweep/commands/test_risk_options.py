"""A risk map's grid takes a study's scene paths as its axes (the options): each option's
probability equals that of a risk file run on its own with the value fixed in its scene (the
same stripes); the text, the JSON and the CSV list every option, and whether it meets the
target agrees with P ≤ target; an axis that is no axis, or that sets the motion the stripes
give, is refused with its dotted path and exit status 2."""
import csv
import json

import numpy as np
import pytest
import yaml

from sweep.risk import main

G = 9.80665
K0, K = 2e-3, 2.5  # λ(x) = K0 x^-K, x in m/s²
CURVE_G = np.geomspace(0.01, 5.0, 30)  # levels of the curve file [g]
AXIS = "excitation.horizontal.building.height_ratio"
RATIOS = [0.3, 1.0]  # a low floor and the roof: the roof's P is above the target
TARGET = 0.02


def _scene(height_ratio=0.667):
    building = {"period": "0.6 s", "damping": "5 %", "height_ratio": height_ratio}
    return {"body": {"B": "15 cm", "H": "60 cm"}, "contact": {"mu": 0.8},
            "solver": {"max_events": 100000},
            "excitation": {"horizontal": {"kind": "floor", "building": building}}}


def _risk_file(folder, name, scene, grid=None):
    folder.mkdir(exist_ok=True)
    (folder / "curve.txt").write_text("pga_g,annual_rate\n" + "".join(
        f"{x!r},{K0 * (x * G) ** -K!r}\n" for x in CURVE_G.tolist()))
    path = folder / f"{name}.yaml"
    path.write_text(yaml.safe_dump({
        "name": name, "hazard": {"file": {"path": "curve.txt", "format": "columns",
                                          "im": "pga", "units": "g"}},
        "scene": scene, "target": TARGET, "replicates": 50,
        "stripes": {"levels": ["1 m/s^2", "1.8 m/s^2", "3.2 m/s^2", "5.6 m/s^2"],
                    "motions": 6, "seed": 0, "vs30": "760 m/s",
                    "scenario": {"magnitude": 6.5, "distance": "20 km"}},
        **({"grid": grid} if grid else {})}))
    return path


def _json(path, capsys, *args):
    assert main([str(path), "--json", *args]) == 0
    return json.loads(capsys.readouterr().out)


@pytest.fixture(scope="module")
def options(tmp_path_factory):
    folder = tmp_path_factory.mktemp("options")
    return folder, _risk_file(folder, "map", _scene(), {AXIS: RATIOS})


def test_each_option_is_the_risk_of_its_scene_run_alone(options, capsys):
    folder, path = options
    bodies = _json(path, capsys)["bodies"]
    assert [b[AXIS] for b in bodies] == RATIOS
    for body, ratio in zip(bodies, RATIOS):
        alone = _json(_risk_file(folder, f"alone{ratio:g}", _scene(ratio)), capsys)["bodies"]
        assert body["probability"] == pytest.approx(alone[0]["probability"], rel=1e-12)
        assert body["interval"]["probability"] == pytest.approx(
            alone[0]["interval"]["probability"], rel=1e-12)


def test_every_option_listed_and_judged_against_the_target(options, capsys, tmp_path):
    folder, path = options
    document = _json(path, capsys)
    assert document["grid"] == [{"axis": AXIS, "units": "1"}]
    p = [b["probability"] for b in document["bodies"]]
    upper = [b["interval"]["probability"][1] for b in document["bodies"]]
    assert [b["meets_target"] for b in document["bodies"]] == [x <= TARGET for x in p]
    assert [b["meets_target_upper"] for b in document["bodies"]] == \
        [x <= TARGET for x in upper]
    assert p[0] <= TARGET < p[1]  # the roof misses the target, the low floor meets it

    table = tmp_path / "options.csv"
    figure = tmp_path / "options.png"
    assert main([str(path), "--csv", str(table), "--options", str(figure)]) == 0
    text = capsys.readouterr().out
    rows = text[text.index("options (2; target 2 %):"):].splitlines()[2:4]
    for row, ratio, x, hi in zip(rows, RATIOS, p, upper):
        assert row.split()[:2] == [f"{ratio:.4g}", f"{100 * x:.3g}"]
        assert row.split()[-2:] == ["yes" if x <= TARGET else "no",
                                    "yes" if hi <= TARGET else "no"]
    with open(table, newline="") as f:
        written = list(csv.DictReader(f))
    assert [float(r[AXIS]) for r in written] == RATIOS
    assert [float(r["probability"]) for r in written] == pytest.approx(p, rel=1e-5)
    assert figure.stat().st_size > 0


def _refused(path):
    with pytest.raises(SystemExit) as exited:
        main([str(path)])
    assert exited.value.code == 2


@pytest.mark.parametrize("axis, says", [
    ("bogus", "unknown axis"),
    ("excitation.horizontal.ground.seed", "the stripes give the ground motion"),
    ("seed", "sets excitation.horizontal.seed"),
])
def test_refused_axes_exit_2_with_their_path(tmp_path, capsys, axis, says):
    path = _risk_file(tmp_path, "bad", _scene(), {AXIS: RATIOS, axis: [1, 2]})
    _refused(path)
    err = capsys.readouterr().err
    line = next(line for line in err.splitlines() if f"grid.{axis}:" in line)
    assert says in line and "Traceback" not in err
    assert f"grid.{AXIS}" not in err  # the valid floor axis is not blamed


def test_a_motion_axis_is_refused_without_a_floor(tmp_path, capsys):
    scene = {k: v for k, v in _scene().items() if k != "excitation"}
    path = _risk_file(tmp_path, "bad", scene, {"contact.mu": [0.3, 0.8], AXIS: RATIOS})
    _refused(path)
    err = capsys.readouterr().err
    assert f"grid.{AXIS}: sets {AXIS}: the stripes give the ground motion" in err
    assert "grid.contact.mu" not in err
