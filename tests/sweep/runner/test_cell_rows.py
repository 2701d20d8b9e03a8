"""The cells' kernel rows built as one array: the same bytes as the per-cell path, the closed
forms of the axis values, and the cells left to the per-cell path."""
import math
import warnings
from pathlib import Path

import numpy as np
import pytest

from sweep.bodies import G
from sweep.groundmotion import applied
from sweep.io.problems import FileProblems
from sweep.io.scene_schema import resolve_and_pack
from sweep.io.study_grid import cell_coords
from sweep.runner import cells
from sweep.runner.cell_checks import load_study
from sweep.runner.cell_rows import CellRows

STUDIES = sorted((Path(__file__).resolve().parents[3] / "studies").glob("*.yaml"))
SAMPLE = 40  # cells per bundled study, spread over the grid


def _study(grid, scene=None):
    scene = scene or {"body": {"B": 0.1, "H": 0.3},
                      "contact": {"mu": 0.8, "e_x": -0.8, "e_y": 0.2},
                      "excitation": {"horizontal": {"kind": "sine", "amplitude": "1.5 west",
                                                    "frequency": 4.0}}}
    return load_study({"name": "rows", "scene": scene, "grid": grid}, check_cells=False)


def _per_cell(rows_of, index):
    """Row, body and horizontal peaks of one cell through its checked scene."""
    resolved, row = resolve_and_pack(rows_of.scenes.scene(index), [])
    body = resolved["body"]
    i_g = np.nan if body["i_g"] is None else body["i_g"]
    G = (np.nan, np.nan) if body["G"] is None else body["G"]
    return row, np.array([body["B"], body["H"], i_g, *G]), \
        np.array(applied.peaks(resolved["excitation"]["horizontal"]))


def _bundled():
    """The bundled studies that load, with their CellRows."""
    out = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for path in STUDIES:
            try:
                study = load_study(path, check_cells=False)
            except FileProblems:  # a study of another command (risk, scene files)
                continue
            out.append((path.name, CellRows(study)))
    return out


def test_rows_equal_the_per_cell_rows_byte_for_byte_for_every_bundled_study():
    """Every bundled study whose cells are on the plain axes: a sample of its cells built
    together equals, byte for byte, each cell's checked scene resolved and packed alone (the
    rows, the bodies and the peaks of the horizontal motion)."""
    fast = 0
    for name, rows_of in _bundled():
        n = rows_of.study.n_cells
        sample = np.unique(np.linspace(0, n - 1, min(n, SAMPLE)).astype(np.int64))
        rows, bodies, motions, built = rows_of.build(sample)
        if rows_of.base is None:
            assert not built.any(), name
            continue
        fast += 1
        assert built.all(), name
        for k, index in enumerate(sample):
            row, body, peaks = _per_cell(rows_of, int(index))
            assert rows[k].tobytes() == row.tobytes(), (name, index)
            assert bodies[k].tobytes() == body.tobytes(), (name, index)
            assert motions[k].tobytes() == peaks.tobytes(), (name, index)
    assert fast >= 15  # smoke, fig05_landing_map and the fig08/09/10 families


def test_rows_are_the_closed_forms_of_the_axis_values():
    """Amplitude in West units x frequency x b/h x size: H = B/(b/h) scaled, A = a (B/H) g
    (Eq. (1)), i^2 = (b^2 + h^2)/3, G at H/2, t_end 5 s after a 2 s window and
    dt_out = min(0.02, 1/(20 f))."""
    scene = {"body": {"B": 0.1, "H": 0.3},
             "excitation": {"horizontal": {"kind": "sine", "amplitude": "1 west",
                                           "frequency": 1.0, "duration": 2.0, "start": 0.5}}}
    study = _study({"amplitude": {"values": [0.8, 2.0], "unit": "west"},
                    "frequency": [0.5, 4.0], "b_over_h": [0.5, 0.2], "size": [1.0, 3.0]},
                   scene)
    rows, bodies, motions, built = CellRows(study).build(np.arange(study.n_cells))
    assert built.all()
    for k in range(study.n_cells):
        v = cell_coords(study, k)
        B = 0.1 * v["size"]
        H = 0.1 / v["b_over_h"] * v["size"]
        body, floor, solver = rows[k]["body"], rows[k]["floor"]["x"], rows[k]["solver"]
        assert (body["B"], body["H"]) == pytest.approx((B, H), rel=1e-14)
        assert body["i2"] == pytest.approx(((B / 2) ** 2 + (H / 2) ** 2) / 3, rel=1e-14)
        assert (body["x_g"], body["y_g"]) == pytest.approx((0.0, H / 2), rel=1e-14)
        assert floor["amp"] == pytest.approx(v["amplitude"] * B / H * G, rel=1e-14)
        assert floor["freq"] == v["frequency"]
        assert solver["t_end"] == pytest.approx(0.5 + 2.0 + 5.0)
        assert solver["dt_out"] == pytest.approx(min(0.02, 1 / (20 * v["frequency"])))
        omega = 2 * math.pi * v["frequency"]
        A = v["amplitude"] * B / H * G
        assert motions[k][:3] == pytest.approx([A, A / omega, A / omega ** 2], rel=1e-14)
        assert bodies[k][:2] == pytest.approx([B, H], rel=1e-14)


def test_a_displacement_amplitude_and_a_sweep_rate_are_their_closed_forms():
    """A sine amplitude D given in m is D (2 pi f)^2; a log sweep's rate is
    ln(f_stop/f_start)/duration (kernels.codes), its PGV the largest A/omega of its ends."""
    sine = _study({"amplitude": ["1 mm", "3 cm"], "frequency": [2.0, 5.0]},
                  {"body": {"B": 0.1, "H": 0.3},
                   "excitation": {"horizontal": {"kind": "sine", "amplitude": "1 mm",
                                                 "frequency": 1.0}}})
    rows, _, _, built = CellRows(sine).build(np.arange(4))
    assert built.all()
    for k in range(4):
        v = cell_coords(sine, k)
        assert rows[k]["floor"]["x"]["amp"] == pytest.approx(
            v["amplitude"] * (2 * math.pi * v["frequency"]) ** 2, rel=1e-14)
    sweep = _study({"excitation.horizontal.f_stop": [4.0, 8.0],
                    "excitation.horizontal.duration": [10.0, 20.0]},
                   {"body": {"B": 0.1, "H": 0.3},
                    "excitation": {"horizontal": {"kind": "sweep", "amplitude": "0.5 g",
                                                  "f_start": 1.0, "f_stop": 2.0,
                                                  "duration": 5.0}}})
    rows, _, motions, built = CellRows(sweep).build(np.arange(4))
    assert built.all()
    for k in range(4):
        f1 = rows[k]["floor"]["x"]["f1"]
        T = rows[k]["floor"]["x"]["dur"]
        assert rows[k]["floor"]["x"]["freq"] == pytest.approx(math.log(f1 / 1.0) / T, rel=1e-14)
        assert rows[k]["solver"]["t_end"] == pytest.approx(T + 5.0)
        assert motions[k][1] == pytest.approx(0.5 * G / (2 * math.pi * 1.0), rel=1e-14)


def test_cells_that_do_not_check_or_leave_the_float_range_take_the_per_cell_path():
    """A negative friction coefficient and a displacement amplitude of 1e306 m at 10 Hz
    (1e306 (20 pi)^2 m/s^2 is beyond the float range) are not built together; build_rows
    reports each with its dotted path and value, and builds the other cells."""
    assert not math.isfinite(1e306 * (2 * math.pi * 10) ** 2)
    study = _study({"amplitude": ["1 m", "1e306 m"], "mu": [0.5, -0.2]},
                   {"body": {"B": 0.1, "H": 0.3},
                    "excitation": {"horizontal": {"kind": "sine", "amplitude": "1 m",
                                                  "frequency": 10.0}}})
    _, _, _, built = CellRows(study).build(np.arange(4))
    assert built.tolist() == [True, False, False, False]
    rows, _, _, _, problems = cells.build_rows(study, np.arange(4))
    assert sorted(problems) == [1, 2, 3]
    assert "contact.mu" in problems[1] and "-0.2" in problems[1]
    assert "excitation.horizontal.amplitude" in problems[2] and "in SI units" in problems[2]
    assert rows[0]["floor"]["x"]["amp"] == pytest.approx((2 * math.pi * 10) ** 2)


@pytest.mark.parametrize("scene", [
    {"body": {"B": 0.1, "H": 0.3, "G": [0.01, 0.1]}},             # G off the middle
    {"body": {"B": 0.1, "H": 0.3}, "initial": {"theta": "0.5 alpha"}},  # relative to the body
])
def test_a_body_axis_with_values_relative_to_the_body_elsewhere_is_built_cell_by_cell(scene):
    """With G given, or an initial angle in units of the body's alpha, a b/h axis changes
    more than the fields built together: every cell takes the per-cell path, and build_rows
    gives the per-cell rows."""
    scene = {**scene, "excitation": {"horizontal": {"kind": "sine", "amplitude": "1 west",
                                                    "frequency": 2.0}}}
    study = _study({"b_over_h": [0.25, 0.2]}, scene)
    rows_of = CellRows(study)
    assert rows_of.base is None and not rows_of.build(np.arange(2))[3].any()
    rows = cells.build_rows(study, np.arange(2))[0]
    for k in range(2):
        assert rows[k].tobytes() == _per_cell(rows_of, k)[0].tobytes()


@pytest.mark.parametrize("body", [
    {"B": 0.1, "H": 0.3, "G": [0.01, 0.1], "i_g": 0.05},            # G off the middle
    {"alpha_1": "10 deg", "alpha_2": "14 deg", "h": 0.5},             # the rock form
])
def test_an_amplitude_axis_on_a_body_given_with_g_is_built_together(body):
    """A fixed body with G off the middle: the West and v_H amplitudes take the smaller
    side's scale (sweep.bodies), G and i_g stay cell 0's; the same bytes as cell by cell."""
    study = _study({"amplitude": {"values": [0.5, 1.5], "unit": "west"},
                    "excitation.vertical.amplitude": ["0.2 v_H", "0.4 v_H"]},
                   {"body": body,
                    "excitation": {"horizontal": {"kind": "sine", "amplitude": "1 west",
                                                  "frequency": 2.0},
                                   "vertical": {"kind": "sine", "amplitude": "0.1 v_H",
                                                "frequency": 3.0}}})
    rows_of = CellRows(study)
    rows, bodies, motions, built = rows_of.build(np.arange(4))
    assert built.all()
    for k in range(4):
        row, body_k, peaks = _per_cell(rows_of, k)
        assert rows[k].tobytes() == row.tobytes()
        assert bodies[k].tobytes() == body_k.tobytes() and not np.isnan(body_k[3])
        assert motions[k].tobytes() == peaks.tobytes()
