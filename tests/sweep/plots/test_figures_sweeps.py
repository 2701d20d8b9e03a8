"""Figs 8-16 from small sweep results; the classifier and the normalized plane checked against
independent values.

The classifier runs on constructed histories whose period ratio and phase are known by
construction; the normalized coordinates are checked against the closed forms of docs/physics.md
A11 (a_o = (B/H) g and v_H of a 10 x 30 cm block) and the sinusoid relations A = V w = D w^2.
"""
import math

import numpy as np
import pytest

from sweep import plot, run_study
from sweep.paper import classify, plane
from sweep.plots import histories as plot_histories
from sweep.plots import sweeps as plot_sweeps

G = 9.80665
ALPHA = math.atan(1 / 3)          # slenderness of a block with b/h = 1/3
A_O, V_H = 3.26888, 0.485554      # docs/physics.md A11: B x H = 0.1 x 0.3 m
DT = 0.002                        # s, sampling of the constructed histories
F_FLOOR = 2.0                     # Hz, floor frequency of the constructed histories

SCENE = {"body": {"B": 0.05, "H": 0.15}, "contact": {"mu": 0.8, "e_x": -0.8, "e_y": 0.2},
         "solver": {"max_events": 100000}}
TINY = {  # hold: (levels, f_start, f_stop) of 20 s sweeps, seconds to run
    "acceleration": (["1.2 west", "2.5 west"], 6.0, 1.0),
    "velocity": (["0.8 v_H", "2 v_H"], 0.5, 8.0),
    "displacement": (["15 mm", "40 mm"], 0.5, 6.0),
}


def _tiny_study(hold):
    levels, f_start, f_stop = TINY[hold]
    sweep = {"kind": "sweep", "hold": hold, "amplitude": levels[0], "f_start": f_start,
             "f_stop": f_stop, "duration": 20.0}
    return {"name": f"tiny_{hold}", "title": f"tiny {hold} sweeps",
            "scene": {**SCENE, "excitation": {"horizontal": sweep}},
            "grid": {"amplitude": levels}}


@pytest.fixture(scope="module")
def sweeps():
    """Datasets of three tiny sweep studies, one per kind of sweep."""
    return {hold: run_study(_tiny_study(hold)) for hold in TINY}


@pytest.fixture(scope="module")
def sweep_files(sweeps, tmp_path_factory):
    folder = tmp_path_factory.mktemp("sweeps")
    paths = {}
    for hold, ds in sweeps.items():
        paths[hold] = folder / f"{hold}.nc"
        ds.to_netcdf(paths[hold])
    return paths


# --- constructed histories --------------------------------------------------------------------

def _history(body_frequency, floor_phase, cycles=8, still=0.0):
    """θ rocks at 0.5 α and ``body_frequency`` for ``cycles`` body cycles (after ``still``
    seconds at rest), then rises from its last upward zero crossing through π/2 in a quarter
    floor period; a_x = sin(2 π F_FLOOR t + floor_phase).  Returns t, θ, a_x, t_overturn."""
    t_rock = cycles / body_frequency
    t_final = still + t_rock
    t_overturn = t_final + 0.25 / F_FLOOR
    t = np.arange(0.0, t_overturn + 5 * DT, DT)
    theta = np.where((t >= still) & (t < t_final),
                     0.5 * ALPHA * np.sin(2 * np.pi * body_frequency * (t - still)), 0.0)
    rising = t >= t_final
    theta[rising] = (0.5 * math.pi) * (t[rising] - t_final) / (t_overturn - t_final)
    return t, theta, np.sin(2 * np.pi * F_FLOOR * t + floor_phase), t_overturn


@pytest.mark.parametrize("floor_phase, kind, phase", [(0.0, "in_phase", 1.0),
                                                      (math.pi, "inverse_phase", -1.0)])
def test_one_body_cycle_per_floor_cycle_is_classified_by_its_phase(floor_phase, kind, phase):
    t, theta, a_x, t_over = _history(F_FLOOR, floor_phase)
    rocking = classify.classify_history(t, theta, a_x, ALPHA, t_over)
    assert rocking.kind == kind
    assert rocking.period_ratio == pytest.approx(1.0, abs=0.02)
    # the side is that of θ but while |θ| < ε α, where a_x is small too: c close to ±1
    assert rocking.phase == pytest.approx(phase, abs=0.02)
    assert rocking.half_cycles == classify.HALF_CYCLES
    assert rocking.t_final == pytest.approx(8 / F_FLOOR, abs=2 * DT)


def test_one_body_cycle_over_three_floor_cycles_is_subharmonic():
    t, theta, a_x, t_over = _history(F_FLOOR / 3, 0.0, cycles=6)
    rocking = classify.classify_history(t, theta, a_x, ALPHA, t_over)
    assert rocking.kind == "subharmonic"
    assert rocking.period_ratio == pytest.approx(3.0, abs=0.05)


def test_a_body_rocking_faster_than_the_floor_is_irregular():
    t, theta, a_x, t_over = _history(2 * F_FLOOR, 0.0, cycles=12)
    rocking = classify.classify_history(t, theta, a_x, ALPHA, t_over)
    assert rocking.kind == "irregular"
    assert rocking.period_ratio == pytest.approx(0.5, abs=0.02)


@pytest.mark.parametrize("floor_phase, kind", [(0.0, "in_phase"), (math.pi, "inverse_phase")])
def test_rocking_before_a_still_stretch_is_not_counted(floor_phase, kind):
    # two body cycles in the first second (a body released tilted), still until 21 s, then
    # pushed over in a quarter floor period; a_x = sin(2 pi 2 t + phase) rises through zero
    # at 21 s, so phase 0 pushes the body the way it falls
    t_over = 21.0 + 0.25 / F_FLOOR
    t = np.arange(0.0, t_over + 5 * DT, DT)
    theta = np.where(t < 1.0, 0.5 * ALPHA * np.sin(2 * np.pi * F_FLOOR * t), 0.0)
    theta = np.where(t >= 21.0, 0.5 * math.pi * (t - 21.0) / (t_over - 21.0), theta)
    a_x = np.sin(2 * np.pi * F_FLOOR * t + floor_phase)
    rocking = classify.classify_history(t, theta, a_x, ALPHA, t_over)
    assert rocking.kind == kind
    assert rocking.half_cycles == 0
    assert math.isnan(rocking.period_ratio)
    assert rocking.phase == pytest.approx(1.0 if kind == "in_phase" else -1.0, abs=1e-9)


def test_tilt_side_has_hysteresis():
    theta = ALPHA * np.array([0.0, 0.02, 0.06, 0.03, -0.04, -0.06, -0.01, 0.049, 0.051])
    assert classify.tilt_side(theta, ALPHA).tolist() == [0, 0, 1, 1, 1, -1, -1, -1, 1]


# --- the normalized plane ---------------------------------------------------------------------

BODY = {"B": 0.1, "H": 0.3, "i_g": None}


@pytest.mark.parametrize("hold, amplitude, f, a, v", [
    ("acceleration", 0.5 * G, 2.0, 0.5 * G / A_O, 0.5 * G / (4 * math.pi) / V_H),
    ("velocity", 0.2, 3.0, 6 * math.pi * 0.2 / A_O, 0.2 / V_H),
    ("displacement", 0.01, 3.0, (6 * math.pi) ** 2 * 0.01 / A_O, 6 * math.pi * 0.01 / V_H),
])
def test_plane_point_matches_closed_forms(hold, amplitude, f, a, v):
    ground = {"kind": "sweep", "hold": hold, "amplitude": amplitude}
    assert plane.plane_point(ground, BODY, f) == pytest.approx((v, a), rel=2e-6)


def test_dataset_coordinates_at_overturning_match_closed_forms(sweeps):
    # B x H = 5 x 15 cm: (B/H) g as 10 x 30 cm, v_H of Eq. (10) from r = sqrt(2.5^2 + 7.5^2) cm
    r, alpha = math.hypot(0.025, 0.075), math.atan(1 / 3)
    v_h = math.sqrt(8 * G * r / 3 * (1 - math.cos(alpha)) / math.cos(alpha) ** 2)
    a_o = G / 3
    acc, vel = sweeps["acceleration"], sweeps["velocity"]
    for level, f, a, v in zip((1.2, 2.5), acc.f_at_overturn.values,
                              acc.a_norm_at_overturn.values, acc.v_norm_at_overturn.values):
        assert a == pytest.approx(level, rel=1e-12)
        assert v == pytest.approx(level * a_o / (2 * math.pi * f) / v_h, rel=1e-9)
    for level, f, a, v in zip((0.8, 2.0), vel.f_at_overturn.values,
                              vel.a_norm_at_overturn.values, vel.v_norm_at_overturn.values):
        assert v == pytest.approx(level, rel=1e-12)
        assert a == pytest.approx(2 * math.pi * f * level * v_h / a_o, rel=1e-9)


def test_overturning_after_the_sweep_is_left_out(sweeps):
    ds = sweeps["velocity"].copy(deep=True)
    assert classify.overturned_cells(ds).tolist() == [0, 1]
    t = ds["t_overturn"].values
    t[1] = 20.0 + 1e-9  # the sweep lasts 20 s from t = 0
    assert classify.overturned_cells(ds).tolist() == [0]
    assert plane.sweep_cells(ds).late.tolist() == [False, True]


# --- figures ----------------------------------------------------------------------------------

def _points(ax, marker):
    """Finite (x, y) of the marker-only lines of ``marker`` on ``ax``."""
    found = [line.get_xydata() for line in ax.get_lines()
             if line.get_marker() == marker and line.get_linestyle() == "None"]
    xy = np.concatenate(found) if found else np.empty((0, 2))
    return xy[np.all(np.isfinite(xy), axis=1)]


def test_plane_figure_shows_every_overturning_and_point_p(sweeps):
    fig = plot_sweeps.figure_plane(list(sweeps.values()), label="Fig. 9")
    ax = fig.axes[0]
    assert ax.get_xscale() == ax.get_yscale() == "log"
    for hold, ds in sweeps.items():
        shown = _points(ax, plot_sweeps.HOLD_STYLE[hold]["marker"])
        over = ds["overturned"].values == 1
        expected = np.column_stack([ds.v_norm_at_overturn.values[over],
                                    ds.a_norm_at_overturn.values[over]])
        np.testing.assert_allclose(np.sort(shown, axis=0), np.sort(expected, axis=0))
    assert _points(ax, "*").tolist() == [[0.4, 1.0]]
    assert "B × H = 5 × 15 cm" in ax.get_title()


def test_lowest_points(sweeps):
    cells = plane.sweep_cells(sweeps["velocity"])
    lowest_v, lowest_a = plane.lowest_points(cells)
    ds = sweeps["velocity"]
    assert lowest_v[0] == pytest.approx(float(ds.v_norm_at_overturn.min()))
    assert lowest_a[1] == pytest.approx(float(ds.a_norm_at_overturn.min()))


def test_boundaries_classify_every_overturning(sweeps):
    rockings = [classify.classify_dataset(ds) for ds in sweeps.values()]
    fig = plot_sweeps.figure_boundaries(list(sweeps.values()), rockings, label="Fig. 11")
    labels = [text.get_text() for text in fig.legends[0].get_texts()]
    counts = [int(label.split("(n = ")[1].rstrip(")")) for label in labels if "(n = " in label]
    assert len(counts) == len(classify.KINDS)  # one legend entry per kind of rocking
    overturned = sum(int((ds["overturned"].values == 1).sum()) for ds in sweeps.values())
    assert sum(counts) == overturned
    assert any(label.startswith("West") for label in labels)


def test_history_figure_picks_the_in_phase_overturning_nearest_p(sweeps):
    panel = classify.FIGURE_PANELS["fig15"][1][0]
    found, _ = classify.find_overturning([sweeps["velocity"]], panel)
    ds = sweeps["velocity"]
    distance = np.hypot(np.log(ds.v_norm_at_overturn.values / 0.4),
                        np.log(ds.a_norm_at_overturn.values))
    # both velocity sweeps overturn pushed by the floor, within a few cycles (the paper)
    assert found.rocking.kind == "in_phase"
    assert found.index == int(np.nanargmin(distance))
    assert found.result.t_overturn == pytest.approx(float(ds.t_overturn[found.index]),
                                                    abs=1e-9)


@pytest.mark.parametrize("name", ["fig12", "fig13", "fig14", "fig15", "fig16"])
def test_history_figures_render(sweeps, name):
    found = classify.figure_overturnings(list(sweeps.values()), name)
    fig = plot_histories.figure_history(found, name)
    texts = " ".join(t.get_text() for ax in fig.axes for t in ax.texts)
    drawn = [ax for ax in fig.axes if ax.get_lines()]
    for panel in classify.FIGURE_PANELS[name][1]:  # drawn, or said to be missing
        missing = f"no overturning from {panel.kind.replace('_', ' ')} rocking" in texts
        assert missing or drawn
    assert fig._suptitle.get_text().startswith(f"Fig. {int(name[3:])}")


def test_cli_draws_from_several_datasets(sweep_files, tmp_path):
    out = tmp_path / "fig09.png"
    files = [str(sweep_files[h]) for h in TINY]
    assert plot.main([*files, "--figure", "fig09", "-o", str(out)]) == 0
    assert out.read_bytes().startswith(b"\x89PNG")
    with pytest.raises(SystemExit) as stop:  # a figure of one dataset refuses several
        plot.main([*files, "--figure", "map", "-o", str(tmp_path / "map.png")])
    assert stop.value.code == 2
