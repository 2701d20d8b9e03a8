"""Bodies with G off the middle (docs/bodies.md) in what the commands say and draw: the
{alpha_1, alpha_2, h} form, the R_2 that would agree, each side's overturnings in the
fragility and risk outputs, the body drawn from its own corners and G, the tipping lines at
each side's angle."""
import json
import math
from types import SimpleNamespace

import matplotlib
import matplotlib.pyplot as plt
import numpy as np
import pytest
import xarray as xr
import yaml

import sweep
from sweep.bodies import G
from sweep.io.problems import FileProblems
from sweep.io.scene_schema import resolve_scene
from sweep.runner.simulate import simulate

matplotlib.use("Agg")

A1, A2, H_G = 14.0, 22.0, 1.2  # deg, deg, m: the rock tipping at 14 deg and 22 deg
SINE = {"horizontal": {"kind": "sine", "amplitude": "0.4 g", "frequency": "1 Hz",
                       "duration": "3 s"}}


def _h_form(a1=A1, a2=A2, h=H_G):
    return {"alpha_1": f"{a1} deg", "alpha_2": f"{a2} deg", "h": f"{h} m"}


def _r_form(a1=A1, a2=A2, h=H_G):
    return {"alpha_1": f"{a1} deg", "alpha_2": f"{a2} deg",
            "R_1": h / math.cos(math.radians(a1)), "R_2": h / math.cos(math.radians(a2))}


def _corners(a1=A1, a2=A2, h=H_G):
    """b1, b2 of the closed form b_i = h tan alpha_i."""
    return h * math.tan(math.radians(a1)), h * math.tan(math.radians(a2))


def _lines(ax, gid):
    """The lines of ``ax`` drawn with ``gid``."""
    return [line for line in ax.lines if line.get_gid() == gid]


# --- the {alpha_1, alpha_2, h} form and the R_2 message ---------------------------------------

def test_h_form_gives_b_from_tan_alpha_and_the_r_form_scene():
    """b_i = h tan alpha_i, B = b1 + b2, G = [(b1 - b2)/2, h], H = 2h; the R form with
    R_i = h / cos alpha_i gives the same body, JSON and outcome."""
    b1, b2 = _corners()
    body = resolve_scene({"body": _h_form()})["body"]
    assert body["B"] == pytest.approx(b1 + b2, rel=1e-15)
    assert body["H"] == pytest.approx(2 * H_G, rel=1e-15)
    np.testing.assert_allclose(body["G"], [(b1 - b2) / 2, H_G], rtol=1e-15)
    by_h, by_r = (simulate({"body": form, "contact": {"mu": 0.8}, "excitation": SINE})
                  for form in (_h_form(), _r_form()))
    for key in ("B", "H", "R_1", "R_2", "alpha_1", "alpha_2"):
        assert by_h.body[key] == pytest.approx(by_r.body[key], rel=1e-14)
    np.testing.assert_allclose(by_h.body["G"], by_r.body["G"], rtol=1e-14)
    assert by_h.body["alpha_1"] == pytest.approx(math.radians(A1), rel=1e-14)
    assert (by_h.status, by_h.overturn_direction, by_h.impact_count) == \
        (by_r.status, by_r.overturn_direction, by_r.impact_count)
    assert by_h.t_overturn == pytest.approx(by_r.t_overturn, rel=1e-9)


@pytest.mark.parametrize("unit, factor", [("m", 1.0), ("cm", 100.0)])
def test_a_disagreeing_r2_is_told_the_value_that_agrees(unit, factor):
    """R_2 = R_1 cos alpha_1 / cos alpha_2, in R_2's own unit, to 12 digits."""
    R1, a1, a2 = 1.2, math.radians(20), math.radians(12)
    agreeing = R1 * math.cos(a1) / math.cos(a2) * factor
    body = {"alpha_1": "20 deg", "alpha_2": "12 deg", "R_1": f"{R1} m",
            "R_2": f"{1.2 * factor:g} {unit}"}
    with pytest.raises(FileProblems) as info:
        resolve_scene({"body": body})
    (problem,) = info.value.problems
    assert problem.path == "body.R_2"
    assert f"= {agreeing:.6g} {unit}: give R_2: {agreeing:.12g} {unit}" in problem.message
    assert "{alpha_1, alpha_2, h}" in problem.message
    body["R_2"] = f"{agreeing!r} {unit}"  # the value given back is accepted
    assert resolve_scene({"body": body})["body"]["G"][1] == pytest.approx(R1 * math.cos(a1))


def test_a_disagreeing_r2_is_one_line_and_status_2(tmp_path, capsys):
    from sweep.scene import main

    path = tmp_path / "rock.yaml"
    path.write_text(yaml.safe_dump({"body": {"alpha_1": "20 deg", "alpha_2": "12 deg",
                                             "R_1": "1.2 m", "R_2": "1.2 m"}}))
    with pytest.raises(SystemExit) as ended:
        main([str(path)])
    err = capsys.readouterr().err
    assert ended.value.code == 2 and "Traceback" not in err
    assert [line for line in err.splitlines() if line.startswith("  body.R_2: R_2 = 1.2 m")]


@pytest.mark.parametrize("body, path", [
    ({**_h_form(), "R_1": "1 m"}, "body.h"),             # R and h
    ({"alpha_1": "14 deg", "alpha_2": "22 deg", "R_1": "1 m"}, "body.R_2"),
    ({"alpha_1": "14 deg", "h": "1 m"}, "body.alpha_2"),
    ({"alpha_1": "94 deg", "alpha_2": "22 deg", "h": "1 m"}, "body.alpha_1"),
])
def test_incomplete_rock_forms_are_one_problem_each(body, path):
    with pytest.raises(FileProblems) as info:
        resolve_scene({"body": body})
    assert [p.path for p in info.value.problems] == [path]


def test_a_bare_h_of_a_hundred_metres_is_doubted():
    """``h: 120`` is 120 m (a bare number is SI): a warning at body.h says so."""
    from sweep.io.problems import InputWarning

    with pytest.warns(InputWarning, match=r"body\.h: 120 \(a bare number is in m\)"):
        simulate({"body": {"alpha_1": "14 deg", "alpha_2": "22 deg", "h": 120},
                  "contact": {"mu": 0.8}, "solver": {"t_end": 0.1}})


# --- each side in the fragility outputs -------------------------------------------------------

ROCK = {"alpha_1": "14 deg", "alpha_2": "17 deg", "h": "60 cm"}  # tips both ways
SYNTHETIC = {"horizontal": {"kind": "synthetic", "model": "boore2003", "magnitude": 7.0,
                            "distance": "10 km", "vs30": "760 m/s"}}


@pytest.fixture(scope="module")
def rock_study(tmp_path_factory):
    """8 synthetic motions at 3 PGA levels on a rock of alpha 14 and 17 deg: its dataset
    and the file it is written to."""
    from sweep.netcdf import write_netcdf

    study = {"name": "rock", "scene": {"body": ROCK, "contact": {"mu": 0.8},
                                       "excitation": SYNTHETIC},
             "grid": {"seed": list(range(8)), "pga": {"values": [5.0, 8.0, 12.0]}}}
    ds = sweep.run_study(study)
    path = tmp_path_factory.mktemp("rock") / "rock.nc"
    write_netcdf(ds, path)
    return ds, path


def _sides_by_level(ds):
    """Overturned to the left (+1) and right (-1) at each PGA level, counted over the seeds
    from the study's own outcome and overturn_direction."""
    over = (ds["outcome"] == 2).transpose("pga", "seed").values
    direction = ds["overturn_direction"].transpose("pga", "seed").values
    return ((over & (direction == 1)).sum(axis=1), (over & (direction == -1)).sum(axis=1),
            over.sum(axis=1))


def test_fragility_json_and_dataset_count_each_side(rock_study, tmp_path, capsys):
    from sweep.fragility import main

    ds, path = rock_study
    left, right, total = _sides_by_level(ds)
    assert left.sum() > 0 and right.sum() > 0  # the study tips both ways
    assert main([str(path), "--over", "seed", "--im", "pga", "--replicates", "50", "--json",
                 "--dataset", str(tmp_path / "frag.nc")]) == 0
    (group,) = json.loads(capsys.readouterr().out)["groups"]
    assert group["overturned_left"]["k"] == left.tolist()
    assert group["overturned_right"]["k"] == right.tolist()
    assert (np.add(group["overturned_left"]["k"], group["overturned_right"]["k"])
            == group["overturned"]["k"]).all() and group["overturned"]["k"] == total.tolist()
    assert group["alpha_1"] == pytest.approx(math.radians(14), rel=1e-12)
    assert group["alpha_2"] == pytest.approx(math.radians(17), rel=1e-12)
    frag = xr.open_dataset(tmp_path / "frag.nc")
    np.testing.assert_array_equal(frag["k_overturned_left"].values, left)
    np.testing.assert_array_equal(frag["k_overturned_right"].values, right)


def test_fragility_table_and_figure_give_each_side(rock_study, capsys):
    from sweep.fragility import format_table
    from sweep.plots.fragility import figure_curves
    from sweep.probability.fragility import fragility

    ds, _ = rock_study
    left, right, total = _sides_by_level(ds)
    frag = fragility(ds, ["seed"], "pga", replicates=50)
    last = format_table(frag).splitlines()[-1]
    assert "alpha_1 14 deg, alpha_2 17 deg" in last
    expected = [f"{level:.4g}: {lo}/{hi}" for level, lo, hi, k in
                zip(ds["pga"].values, left, right, total) if k > 0]
    assert last.endswith(", ".join(expected))
    fig = figure_curves(frag)
    drawn = {side: _lines(fig.axes[0], side)[0].get_ydata() for side in ("left", "right")}
    shown = total > 0
    np.testing.assert_allclose(drawn["left"], (left / 8)[shown])
    np.testing.assert_allclose(drawn["right"], (right / 8)[shown])
    plt.close("all")


def test_a_symmetric_body_gets_no_side_line(rock_study):
    """alpha_1 = alpha_2 (G in the middle): no line of sides in the table."""
    from sweep.fragility import format_table
    from sweep.probability.fragility import fragility

    ds, _ = rock_study
    frag = fragility(ds.assign(alpha_2=ds["alpha_1"]), ["seed"], "pga", replicates=20)
    assert "G off the middle" not in format_table(frag)


# --- each side in the risk outputs ------------------------------------------------------------

def test_stripe_sides_count_each_stripe_and_need_the_variables(rock_study):
    """Each PGA level of the study as a stripe: the counts of ``_sides_by_level``; a dataset
    without alpha_1 (an older version's) gives no sides."""
    from sweep.probability.stripe_results import stripe_sides

    ds, _ = rock_study
    stripes = [ds.isel(pga=j, drop=True) for j in range(ds.sizes["pga"])]
    left, right, _ = _sides_by_level(ds)
    sides = stripe_sides(stripes)
    assert sides.left.tolist() == left.tolist() and sides.right.tolist() == right.tolist()
    assert (sides.alpha_1, sides.alpha_2) == pytest.approx(
        (math.radians(14), math.radians(17)), rel=1e-12)
    assert stripe_sides([s.drop_vars("alpha_1") for s in stripes]) is None


def test_risk_json_dataset_and_text_count_each_side_per_stripe(tmp_path, capsys):
    from sweep.risk import main

    source = {"model": "BSSA14", "im": "pga", "vs30": "760 m/s",
              "levels": {"start": "0.02 g", "stop": "2.5 g", "num": 25},
              "sources": [{"kind": "point", "distance": "10 km", "depth": "8 km",
                           "recurrence": {"rate": 0.02, "m_min": 5.5, "m_max": 7.5}}]}
    levels = [4.0, 8.0, 14.0]
    path = tmp_path / "risk.yaml"
    path.write_text(yaml.safe_dump({
        "name": "t", "hazard": {"source": source},
        "scene": {"body": ROCK, "contact": {"mu": 0.8}},
        "stripes": {"levels": [f"{x} m/s^2" for x in levels], "motions": 10, "seed": 0},
        "replicates": 50}))
    assert main([str(path), "--json"]) == 0
    body = json.loads(capsys.readouterr().out)["bodies"][0]
    folder = tmp_path / "results" / "t"
    left, right, total = [], [], []
    for j in range(len(levels)):
        stripe = xr.load_dataset(folder / f"t_stripe{j}.nc")
        over = stripe["overturned"].values == 1
        direction = stripe["overturn_direction"].values
        left.append(int((over & (direction == 1)).sum()))
        right.append(int((over & (direction == -1)).sum()))
        total.append(int(over.sum()))
    assert sum(left) > 0 and sum(right) > 0  # the stripes tip it both ways
    counts = body["fragility"]["stripes"]
    assert counts["overturned_left"] == left and counts["overturned_right"] == right
    assert np.add(left, right).tolist() == counts["overturned"] == total
    assert (body["alpha_1"], body["alpha_2"]) == pytest.approx(
        (math.radians(14), math.radians(17)), rel=1e-12)
    risk = xr.load_dataset(folder / "risk.nc")
    assert risk["stripe_overturned_left"].values.tolist() == left
    assert risk["stripe_overturned_right"].values.tolist() == right
    assert main([str(path)]) == 0
    pairs = ", ".join(f"{x / G:.3g}: {lo}/{hi}" for x, lo, hi in zip(levels, left, right))
    assert f"at each stripe [g]: {pairs}" in capsys.readouterr().out
    _risk_figure_draws_each_side(path, levels, left, right)


def _risk_figure_draws_each_side(path, levels, left, right):
    """The risk figure's fragility panel: each side's k/n (counted from the stripes' datasets
    above) at the stripes where any overturned."""
    from sweep.io.risk_schema import load_risk
    from sweep.plots.risk import figure_body
    from sweep.probability.risk_inputs import checked_hazard
    from sweep.probability.risk_report import compute

    spec = load_risk(path, hazard=checked_hazard)
    outcome = compute(spec, path.parent / "results" / "t")
    fig = figure_body(outcome)
    shown = np.add(left, right) > 0
    for side, counts in (("left", left), ("right", right)):
        (line,) = [a for ax in fig.axes for a in ax.get_lines() if a.get_gid() == side]
        assert line.get_ydata() == pytest.approx((np.array(counts) / 10)[shown])
        assert line.get_xdata() == pytest.approx(
            np.array(levels)[shown] / G * (1.05 if side == "right" else 1 / 1.05))


# --- the body drawn as it is ------------------------------------------------------------------

@pytest.fixture(scope="module")
def rock_history():
    return simulate({"body": _h_form(), "contact": {"mu": 0.8}, "excitation": SINE},
                    history=True).history


def test_scene_plot_draws_the_rocks_base_corners_and_g(rock_history):
    """The first outline (at rest) from G: base corners (-b1, -h) and (b2, -h), the apex at
    H - h = h above G, a triangle; the history says the body is a rock."""
    from sweep.plots.scene import draw_scene

    assert rock_history.attrs["body_form"] == "rock"
    fig = draw_scene(rock_history)
    positions = fig.axes[0]
    first = _lines(positions, "outline")[0]
    (centre,) = _lines(positions, "G")
    x, y = np.asarray(first.get_xdata()), np.asarray(first.get_ydata())
    gx, gy = centre.get_xdata()[0], centre.get_ydata()[0]
    b1, b2 = _corners()
    np.testing.assert_allclose(np.c_[x - gx, y - gy] / 100,
                               [[-b1, -H_G], [b2, -H_G], [0, H_G], [-b1, -H_G]], atol=1e-12)


def test_a_rectangle_with_g_off_the_middle_is_its_b_by_h_box():
    from sweep.plots.scene import draw_scene

    history = simulate({"body": {"B": 0.2, "H": 0.6, "G": [0.03, 0.25]},
                        "contact": {"mu": 0.8}, "excitation": SINE}, history=True).history
    assert history.attrs["body_form"] == "rectangle"
    positions = draw_scene(history).axes[0]
    first = _lines(positions, "outline")[0]
    (centre,) = _lines(positions, "G")
    offsets = np.c_[np.asarray(first.get_xdata()) - centre.get_xdata()[0],
                    np.asarray(first.get_ydata()) - centre.get_ydata()[0]] / 100
    b1, b2, h, top = 0.1 + 0.03, 0.1 - 0.03, 0.25, 0.6 - 0.25
    np.testing.assert_allclose(offsets, [[-b1, -h], [b2, -h], [b2, top], [-b1, top],
                                         [-b1, -h]], atol=1e-12)


def test_animation_draws_the_same_corners(rock_history, monkeypatch):
    """The first frame's body from its G: the rock's base corners and apex."""
    from sweep.plots import scene as scene_plots

    seen = {}

    def first_frame(path, frames, fps):
        next(iter(frames))
        ax = plt.gcf().axes[0]
        seen["body"] = _lines(ax, "outline")[0].get_xydata()
        seen["G"] = _lines(ax, "G")[0].get_xydata()[0]

    monkeypatch.setattr(scene_plots, "save_gif", first_frame)
    scene_plots.animate_scene(rock_history, "unused.gif", quiet=True, fps=10)
    b1, b2 = _corners()
    np.testing.assert_allclose((seen["body"] - seen["G"]) / 100,
                               [[-b1, -H_G], [b2, -H_G], [0, H_G], [-b1, -H_G]], atol=1e-9)


def test_tipping_lines_at_each_sides_alpha(rock_history):
    """θ/α with α = min(α_1, α_2) = 14 deg: the lines at α_1/α = 1 and −α_2/α = −22/14, in
    the scene plot and in the paper's histories."""
    from sweep.plots.histories import _draw_history
    from sweep.plots.scene import draw_scene

    expected = sorted([1.0, -A2 / A1])
    ax_theta = draw_scene(rock_history).axes[1]
    levels = sorted(line.get_ydata()[0] for line in _lines(ax_theta, "alpha"))
    np.testing.assert_allclose(levels, expected, rtol=1e-12)
    t = rock_history["time"].values
    found = SimpleNamespace(result=SimpleNamespace(history=rock_history, t_overturn=t[-1]),
                            rocking=SimpleNamespace(t_start=t[0], t_final=t[-1]))
    _, (ax_t, ax_f) = plt.subplots(2)
    _draw_history(ax_t, ax_f, found, (t[0], t[-1]))
    levels = sorted(line.get_ydata()[0] for line in _lines(ax_t, "alpha"))
    np.testing.assert_allclose(levels, expected, rtol=1e-12)
    plt.close("all")
