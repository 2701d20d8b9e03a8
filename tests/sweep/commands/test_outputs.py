"""Outputs that put the answer first: ``--json`` (verdict first, one line per array),
``--summary``, the scene plot (the verdict as title, panels scaled to their data, quiet floor
components left out), a history that keeps the input's peaks, map panels titled with the body,
and ``sweep.plot`` on a refine study's result."""
import copy
import json
from pathlib import Path

import matplotlib
import numpy as np
import pytest
from matplotlib.collections import PathCollection
from study_helpers import cli, make_study

import sweep
from sweep import plot, scene
from sweep.io.scene_schema import MAX_HISTORY, resolve_scene
from sweep.plots.map import figure_map
from sweep.plots.scene import draw_scene
from sweep.runner.simulate import JSON_KEYS, simulate, to_json_dict
from sweep.netcdf import write_netcdf

matplotlib.use("Agg")

ROOT = Path(__file__).resolve().parents[3]
STEADY = ROOT / "studies" / "steady_rocking.yaml"  # 79 impacts in 10 s
VERDICT_KEYS = ("status", "overturned", "t_overturn", "overturn_direction", "overturn_towards",
                "message")
G = 9.80665  # standard gravity [m/s^2]
BLOCK = {"body": {"B": 0.1, "H": 0.3}, "contact": {"mu": 10, "e_x": 0.0, "e_y": 0.0}}
FALLING = {**BLOCK, "excitation": {"horizontal": {"kind": "sine", "amplitude": "2.5 west",
                                                  "frequency": 1.5}}}


def _no_constant(name):
    raise ValueError(f"not standard JSON: {name}")


def test_json_has_the_verdict_first_and_each_array_on_one_line():
    done = cli([STEADY, "--json"], cwd=ROOT, module="sweep.scene")
    assert done.returncode == 0, done.stderr
    data = json.loads(done.stdout, parse_constant=_no_constant)
    assert set(JSON_KEYS) <= set(data)
    assert tuple(data)[:len(VERDICT_KEYS)] == VERDICT_KEYS
    assert data["status"] == "ok" and data["impact_count"] == 79
    lines = done.stdout.splitlines()
    assert len(lines) < 40
    for key in ("impact_times", "omega_after", "impact_slipped"):
        (line,) = [line for line in lines if line.lstrip().startswith(f'"{key}"')]
        assert len(json.loads(line.split(":", 1)[1].rstrip(","))) == 79


@pytest.mark.parametrize("source, first, status", [
    (STEADY, "stood: max |θ|/α 0.38, no slip, 79 impacts, modes: rotation 10 s", "ok"),
    (FALLING, "overturned at t = 0.44 s: fell towards −x (left) with no impact", "overturned")])
def test_summary_is_what_the_body_did_then_the_status(tmp_path, capsys, source, first, status):
    if isinstance(source, dict):
        source = tmp_path / "falling.yaml"
        source.write_text(json.dumps(FALLING))  # JSON is YAML
    assert scene.main([str(source), "--summary"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert len(lines) == 2 and lines[0] == first
    assert lines[1].startswith(f"{status}: ")


@pytest.mark.parametrize("sign, towards", [(1.0, "-x"), (-1.0, "+x")])
def test_the_side_of_a_fall_is_where_the_body_lies(sign, towards):
    """A floor pushed right first tips the body over its left corner (theta > 0): it falls
    towards -x, where its centre of mass ends; the mirrored motion mirrors everything."""
    scene_ = copy.deepcopy(FALLING)
    scene_["excitation"]["horizontal"]["amplitude"] = f"{2.5 * sign} west"
    result = simulate(scene_, history=True)
    assert result.overturned and result.overturn_direction == sign
    assert result.overturn_towards == towards
    x_end = result.history["x"].values[-1]
    assert np.sign(x_end) == -sign and abs(x_end) > BLOCK["body"]["B"] / 2
    assert to_json_dict(result)["overturn_towards"] == towards


def test_history_of_a_record_keeps_its_peak():
    """Taft (dt = 0.01 s) scaled to 0.6 g: the history is sampled at the record's dt, so its
    largest |a_x| is the scaled peak itself; an explicit dt_out wins; a long scene's default
    stays within MAX_HISTORY samples."""
    taft = {"body": {"B": 0.4, "H": 0.8}, "contact": {"mu": 0.8},
            "excitation": {"horizontal": {"kind": "record", "name": "taft1952_ew_s69e",
                                          "pga": "0.6 g"}},
            "solver": {"t_end": 8.0}}
    result = simulate(taft, history=True)
    assert result.status == "ok"
    time = result.history["time"].values
    assert np.diff(time) == pytest.approx(0.01, rel=1e-12)
    assert np.max(np.abs(result.history["a_x"].values)) == pytest.approx(0.6 * G, rel=1e-9)
    given = copy.deepcopy(taft)
    given["solver"]["dt_out"] = 0.05
    assert resolve_scene(given)["solver"]["dt_out"] == 0.05
    sine = {**BLOCK, "excitation": {"horizontal": {"kind": "sine", "amplitude": "0.3 g",
                                                   "frequency": 4.0}}}
    assert resolve_scene(sine)["solver"]["dt_out"] == pytest.approx(1 / 80)
    long = {**sine, "solver": {"t_end": 1e6}}
    dt_out = resolve_scene(long)["solver"]["dt_out"]
    assert MAX_HISTORY - 2 < 1e6 / dt_out <= MAX_HISTORY


@pytest.fixture(scope="module")
def steady():
    return sweep.simulate(STEADY, history=True)


def test_plot_title_states_the_verdict(steady):
    fig = draw_scene(steady.history, "steady_rocking.yaml")
    assert fig.get_suptitle().startswith("stood: max |θ|/α 0.38, no slip, 79 impacts")
    assert fig.subfigs[0].get_suptitle() == "steady_rocking.yaml"
    falling = sweep.simulate(FALLING, history=True)
    assert draw_scene(falling.history).get_suptitle().startswith("overturned at t = 0.44 s")


def test_panels_are_scaled_to_their_data_and_quiet_floors_left_out(steady):
    """Positions, theta, horizontal floor, mode: four axes (no vertical motion); with a
    vertical component five; a free rocking on a still floor three, its theta/alpha of 0.06
    on an axis of its size, without the lines at ±1."""
    fig = draw_scene(steady.history)
    assert len(fig.axes) == 4
    assert any("no vertical floor motion" in ax.get_title(loc="right") for ax in fig.axes)
    shaken = {**BLOCK, "excitation": {
        "horizontal": {"kind": "sine", "amplitude": "0.5 west", "frequency": 4.0},
        "vertical": {"kind": "sine", "amplitude": "0.2 g", "frequency": 6.0}},
        "solver": {"t_end": 1.0}}
    assert len(draw_scene(sweep.simulate(shaken, history=True).history).axes) == 5
    free = {**BLOCK, "initial": {"theta": "0.06 alpha"}, "solver": {"t_end": 1.0}}
    axes = draw_scene(sweep.simulate(free, history=True).history).axes
    assert len(axes) == 3
    theta = axes[1]
    assert 0.06 < theta.get_ylim()[1] < 0.1
    assert "the floor does not move" in theta.get_title(loc="right")
    assert not [line for line in theta.get_lines() if set(line.get_ydata()) == {1}]


def test_map_panels_are_titled_with_the_body():
    study = make_study({"amplitude": {"values": [0.5, 2.5], "unit": "west"},
                        "frequency": [1.5, 8.0], "b_over_h": [0.333, 0.2], "mu": [0.8]})
    study["scene"]["solver"]["t_end"] = 1.0
    fig = figure_map(sweep.run_study(study))
    assert [ax.get_title() for ax in fig.axes if ax.get_visible()] == [
        "B 10 cm × H 30 cm (b/h 0.333); mu = 0.8", "B 10 cm × H 50 cm (b/h 0.2); mu = 0.8"]


def test_a_cross_in_any_panel_is_in_the_legend():
    """The legend sits beside the last panel; a cell that slid in the first panel only is
    still explained there."""
    study = make_study({"amplitude": {"values": [0.5, 2.5], "unit": "west"},
                        "frequency": [1.5, 8.0], "b_over_h": [0.333, 0.2]})
    study["scene"]["solver"]["t_end"] = 1.0
    ds = sweep.run_study(study).transpose("b_over_h", ...)
    assert not (ds["slid"] == 1).any()
    ds["slid"][0, 0, 0] = 1  # one cell of the first panel
    fig = figure_map(ds)
    first, last = [ax for ax in fig.axes if ax.get_visible()]
    assert first.get_legend() is None
    labels = [t.get_text() for t in last.get_legend().get_texts()]
    assert labels[-1] == "slid (base > 1 cm)"
    crosses = [[len(c.get_offsets()) for c in ax.collections if isinstance(c, PathCollection)]
               for ax in (first, last)]
    assert crosses == [[1], [0]]  # one cross, in the first panel


# free rocking from theta_0: overturns iff theta_0 > alpha (as in test_refine.py)
THETA = {"name": "theta", "scene": {**BLOCK, "solver": {"t_end": 3.0}},
         "grid": {"initial.theta": {"start": 0.06, "stop": 0.66, "num": 4},
                  "b_over_h": [0.02, 0.333, 1.0]},
         "refine": {"axis": "initial.theta", "tolerance": 0.02}}


@pytest.fixture(scope="module")
def theta_ds():
    return sweep.run_study(copy.deepcopy(THETA))


def test_plot_draws_a_refine_result_and_refuses_a_figure_that_does_not_fit(theta_ds,
                                                                          tmp_path, capsys):
    result = tmp_path / "theta.nc"
    write_netcdf(theta_ds, result)
    for figure in ("map", "boundary"):
        png = tmp_path / f"{figure}.png"
        assert plot.main([str(result), "--figure", figure, "-o", str(png)]) == 0
        assert png.stat().st_size > 0
    capsys.readouterr()
    for figure in ("fig18", "spectrum", "fig13"):
        assert plot.main([str(result), "--figure", figure, "-o", str(tmp_path / "x.png")]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "--figure map or boundary draws it" in err
    grid = tmp_path / "grid.nc"
    write_netcdf(sweep.run_study(make_study({"frequency": [2.0, 4.0]})), grid)
    assert plot.main([str(grid), "--figure", "boundary", "-o", str(tmp_path / "x.png")]) == 2
    assert capsys.readouterr().err.count("\n") == 1
    assert not (tmp_path / "x.png").exists()


def test_boundary_markers_say_where_no_bracket_was_found(theta_ds):
    """b/h = 0.02 overturns at the lowest theta_0, b/h = 1 never: a marker each."""
    ax = plot.draw("boundary", [theta_ds]).axes[0]
    labels = [text.get_text() for text in ax.get_legend().get_texts()]
    assert "stood up to the highest value" in labels
    assert "overturned at the lowest value" in labels
    assert ax.get_ylabel() == "overturning boundary: initial.theta [rad]"


def test_animation_in_real_time_on_a_floor_that_does_not_drift(tmp_path):
    """A sine started from rest integrates to a floor drifting at A/omega (2 m in 10 s);
    baseline-corrected it sways by a tenth of that, so the fixed view stays on the body.
    Frames come every 0.02 s of the history's 1/80 s samples."""
    from PIL import Image

    from sweep.plots.scene import animate_scene, floor_displacement
    amplitude, omega, dt = 4.9, 2 * np.pi * 4.0, 1 / 80
    time = np.arange(0.0, 10.0, dt)
    displacement = floor_displacement(amplitude * np.sin(omega * time), dt)
    assert np.max(np.abs(displacement)) < 0.1 * amplitude / omega * time[-1]
    short = {**BLOCK, "excitation": {"horizontal": {"kind": "sine", "amplitude": "1.5 west",
                                                    "frequency": 4.0}},
             "solver": {"t_end": 1.0}}
    animate_scene(sweep.simulate(short, history=True).history, tmp_path / "a.gif", quiet=True)
    with Image.open(tmp_path / "a.gif") as gif:
        assert gif.n_frames == 51 and gif.info["duration"] == 20
