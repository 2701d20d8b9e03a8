"""The cells' scenes of a study checked once per axis value, and each cell packed once."""
import math

import numpy as np
import pytest

from kernels import api
from sweep.bodies import G
from sweep.io import scene_schema, study_cells
from sweep.io.scene_schema import load_scene, resolve_and_pack, resolve_scene
from sweep.io.study_grid import cell_coords, cell_scene
from sweep.runner import cells
from sweep.runner.cell_checks import load_study

AMPLITUDES, FREQUENCIES, RATIOS, MUS = [0.8, 1.4, 2.0], [1.0, 4.0], [0.5, 0.2], [0.3, 0.9]


def _study(grid=None, scene=None):
    scene = scene or {"body": {"B": 0.1, "H": 0.3},
                      "contact": {"mu": 0.8, "e_x": -0.8, "e_y": 0.2},
                      "excitation": {"horizontal": {"kind": "sine", "amplitude": "1.5 west",
                                                    "frequency": 4.0}},
                      "solver": {"t_end": 0.2}}
    grid = grid or {"amplitude": {"values": AMPLITUDES, "unit": "west"},
                    "frequency": FREQUENCIES, "b_over_h": RATIOS, "mu": MUS}
    return load_study({"name": "plain", "scene": scene, "grid": grid}, check_cells=False)


def _count(monkeypatch, module, name):
    calls = []
    original = getattr(module, name)

    def counted(*args, **kwargs):
        calls.append(1)
        return original(*args, **kwargs)
    monkeypatch.setattr(module, name, counted)
    return calls


def test_rows_are_the_closed_forms_of_the_axis_values():
    """B kept, H = B/(b/h); a sine amplitude of a in West's units is a (B/H) g; mu sets the
    four friction coefficients; i^2 = (b^2 + h^2)/3 of a uniform block about its corner."""
    study = _study()
    rows, _, _, _, problems = cells.build_rows(study, np.arange(study.n_cells))
    assert not problems
    for index, row in enumerate(rows):
        v = cell_coords(study, index)
        B, H = 0.1, 0.1 / v["b_over_h"]
        assert row["body"]["B"] == B and row["body"]["H"] == pytest.approx(H, rel=1e-15)
        assert row["body"]["i2"] == pytest.approx(((B / 2) ** 2 + (H / 2) ** 2) / 3, rel=1e-14)
        assert row["floor"]["x"]["amp"] == pytest.approx(v["amplitude"] * B / H * G, rel=1e-14)
        assert row["floor"]["x"]["freq"] == v["frequency"]
        for key in ("mu_s", "mu_k", "mu_edge_s", "mu_edge_k"):
            assert row["contact"][key] == v["mu"]
        # default history step: 1/20 of the sine's period, at most 0.02 s
        assert row["solver"]["dt_out"] == pytest.approx(min(0.02, 1 / (20 * v["frequency"])))


def test_each_axis_value_is_validated_once_and_one_row_packed(monkeypatch):
    """3 x 2 x 2 x 2 = 24 cells: one scene checked for cell 0, one per value of each path
    (3 amplitudes, 2 frequencies, the breadth kept and 2 heights from b/h, both set in metres,
    2 values at each of the 4 friction paths the mu axis sets), and one kernel row packed for
    the whole study (cell 0's; the others set from the axes, runner/cell_rows.py)."""
    study = _study()
    loads = _count(monkeypatch, study_cells, "load_scene")
    packs = _count(monkeypatch, scene_schema, "scene_row")
    cells.build_rows(study, np.arange(study.n_cells))
    assert len(loads) == 1 + 3 + 2 + 1 + 2 + 4 * 2
    assert study.n_cells == 24 and len(packs) == 1


def test_scenes_equal_those_checked_cell_by_cell():
    """The scene put together from checked values is the one checked from the cell's raw
    scene, field for field, and resolves into the same SI values (a symmetry of two ways)."""
    study = _study()
    scenes = study_cells.CellScenes(study)
    for index in range(study.n_cells):
        fast = scenes.scene(index)
        slow = load_scene(cell_scene(study, index))
        assert repr(fast) == repr(slow)
        assert resolve_scene(fast)["excitation"] == resolve_scene(slow)["excitation"]


def test_a_value_that_does_not_check_is_reported_as_from_its_raw_scene():
    """A negative friction coefficient: the cell is reported with its dotted path and value,
    as checking its raw scene reports it; the other cells are built."""
    study = _study(grid={"mu": [0.5, -0.2]})
    rows, _, _, _, problems = cells.build_rows(study, np.arange(2))
    assert list(problems) == [1] and np.isnan(rows[1]["body"]["B"])
    with pytest.raises(Exception) as err:
        load_scene(cell_scene(study, 1))
    assert problems[1] == str(err.value)
    assert "contact.mu" in problems[1] and "-0.2" in problems[1]
    assert rows[0]["contact"]["mu_s"] == 0.5


def test_a_value_out_of_the_float_range_in_si_is_reported_once_packed():
    """A displacement amplitude of 1e306 m at 10 Hz is 1e306 (20 pi)^2 m/s^2: beyond the
    float range (inf), refused at its dotted path as resolve_scene refuses it."""
    assert not math.isfinite(1e306 * (2 * math.pi * 10) ** 2)
    study = _study(grid={"amplitude": ["1 m", "1e306 m"]},
                   scene={"body": {"B": 0.1, "H": 0.3},
                          "excitation": {"horizontal": {"kind": "sine", "amplitude": "1 m",
                                                        "frequency": 10.0}}})
    rows, _, _, _, problems = cells.build_rows(study, np.arange(2))
    assert list(problems) == [1]
    assert "excitation.horizontal.amplitude" in problems[1] and "in SI units" in problems[1]
    assert rows[0]["floor"]["x"]["amp"] == pytest.approx((2 * math.pi * 10) ** 2)


def test_resolve_and_pack_is_resolve_scene_and_scene_row():
    """One pass gives the resolved dict and the row that scene_row packs of it."""
    scene = load_scene(cells.WARM_UP_SCENE)
    resolved, row = resolve_and_pack(scene, [])
    assert resolved["body"] == resolve_scene(scene)["body"]
    assert row.tobytes() == api.scene_row(resolve_scene(scene), []).tobytes()


@pytest.mark.parametrize("scene, excluded", [
    ({"body": {"alpha_1": "10 deg", "alpha_2": "10 deg", "h": 0.5}}, {"body.B", "body.H"}),
    ({"body": {"B": 0.1, "H": 0.3},
      "excitation": {"horizontal": {"kind": "record", "name": "elcentro1940_ns"}}},
     {"excitation.horizontal.amplitude", "excitation.horizontal.frequency"}),
])
def test_fields_with_rules_across_fields_are_checked_per_cell(scene, excluded):
    """A rock-form body computes B and H from its angles, and a record has no amplitude or
    frequency: those paths are never set without checking the cell's scene."""
    paths = study_cells.alone(load_scene(scene))
    assert not paths & excluded
    assert "contact.mu" in paths
