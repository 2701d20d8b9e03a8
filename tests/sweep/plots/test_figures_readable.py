"""Figures a user can read as they are: nothing drawn off the figure, integer ticks on integer
axes, one unit per output (the site figure in the gal of the command's text), titles of at most
two lines, and legends that leave every datum visible.

Positions are read from the drawn figure (display coordinates after a draw) and compared with
the figure's own box or with the data handed to the drawing, never with the placement code."""
import re

import numpy as np
import pytest
import yaml
from matplotlib.collections import PathCollection
from study_helpers import SCENE
from test_fragility_cli import striped_study

import sweep
from sweep.estimate import estimate as deterministic
from sweep.io.bodies_schema import load_survey
from sweep.plots import fragility as fragility_plots
from sweep.plots.limits import figure_limits
from sweep.plots.map import figure_map
from sweep.plots.site import figure_site
from sweep.plots.spectra import figure_spectrum
from sweep.probability import site, site_report, site_studies
from sweep.probability.fragility import cells, fragility

LONG_TITLE = ("Overturning of a 20 x 80 cm marble statue on its plinth under synthetic motions "
              "of magnitudes 6 to 7.5 at 20 km on rock, scaled to twelve PGA levels, with a "
              "title as long as a user may well write")


def _renderer(fig):
    fig.canvas.draw()
    return fig.canvas.get_renderer()


def _within(box, outer, slack=1.0):
    return (box.x0 >= outer.x0 - slack and box.y0 >= outer.y0 - slack
            and box.x1 <= outer.x1 + slack and box.y1 <= outer.y1 + slack)


def assert_nothing_clipped(fig, renderer=None):
    """Every visible axes with its labels, ticks, titles and legends, the figure's title and
    its legends lie inside the figure (``renderer``: of a figure already drawn)."""
    renderer = renderer or _renderer(fig)
    boxes = [(f"axes {ax.get_ylabel()!r}", ax.get_tightbbox(renderer))
             for ax in fig.axes if ax.get_visible()]
    boxes += [("legend", legend.get_window_extent(renderer)) for legend in fig.legends]
    if fig._suptitle is not None:
        boxes.append(("title", fig._suptitle.get_window_extent(renderer)))
    for name, box in boxes:
        assert _within(box, fig.bbox), f"{name} {box.extents} leaves the figure {fig.bbox}"


def title_lines(text):
    return len(text.strip("\n").split("\n"))


def _data_points(ax, skip=()):
    """Display positions of what ``ax`` draws from data: markers, the vertices of lines
    (with ten points along each segment), of collections (but ``skip``) and scatter
    offsets."""
    points = []
    for line in ax.get_lines():
        xy = line.get_transform().transform(np.asarray(line.get_xydata(), float))
        if line.get_linestyle() not in ("None", "", " ") and len(xy) > 1:
            steps = np.linspace(0.0, 1.0, 10)[:, None, None]
            xy = (xy[:-1] + steps * (xy[1:] - xy[:-1])).reshape(-1, 2)
        points.append(xy)
    for collection in ax.collections:
        if collection in skip:
            continue
        if isinstance(collection, PathCollection):
            points.append(collection.get_offset_transform().transform(
                collection.get_offsets()))
        else:
            transform = collection.get_transform()
            points += [transform.transform(path.vertices) for path in collection.get_paths()
                       if len(path.vertices)]
    points = np.concatenate(points) if points else np.empty((0, 2))
    return points[np.all(np.isfinite(points), axis=1)]


def assert_legends_leave_data_visible(fig, background=(), renderer=None):
    """No legend inside an axes covers a datum of that axes (``background``: collections
    filling the whole axes, such as a shaded field, left out)."""
    renderer = renderer or _renderer(fig)
    for ax in fig.axes:
        legend = ax.get_legend()
        if legend is None:
            continue
        box = legend.get_window_extent(renderer)
        if not _within(box, ax.bbox):
            continue  # outside its axes: it hides nothing there
        points = _data_points(ax, skip=background)
        inside = ((points[:, 0] > box.x0) & (points[:, 0] < box.x1)
                  & (points[:, 1] > box.y0) & (points[:, 1] < box.y1))
        assert not inside.any(), f"the legend of {ax.get_title(loc='left')!r} hides data"


# --- integer axes -------------------------------------------------------------------------

@pytest.mark.parametrize("seeds", [3, 15])
def test_seed_axis_of_a_map_has_integer_ticks(seeds):
    ds = sweep.run_study({"name": "seeds", "scene": {**SCENE, "solver": {"t_end": 0.5}},
                          "grid": {"seed": list(range(seeds)),
                                   "amplitude": {"values": [0.5, 2.5], "unit": "west"}}})
    assert ds["seed"].dtype.kind == "i"
    for x, y in (("seed", "amplitude"), ("amplitude", "seed")):
        ax = figure_map(ds, x=x, y=y).axes[0]
        ax.figure.canvas.draw()
        axis, (low, high) = ((ax.xaxis, ax.get_xlim()) if x == "seed" else
                             (ax.yaxis, ax.get_ylim()))
        ticks = [t for t in axis.get_ticklocs() if min(low, high) <= t <= max(low, high)]
        assert len(ticks) >= 2 and all(float(t).is_integer() for t in ticks)
        labels = [t.get_text() for t in axis.get_ticklabels() if t.get_text()]
        assert labels and all(re.fullmatch(r"−?\d+", label) for label in labels)


# --- the fragility figures ------------------------------------------------------------------

@pytest.fixture(scope="module")
def striped_fragility():
    ds, _ = striped_study()
    ds.attrs["title"] = LONG_TITLE
    frag = fragility(ds, ["seed"], "pga", "pga", replicates=20)
    pga, pgv = (cells(ds, ["seed"], name, "pga").im for name in ("pga", "pgv"))
    return frag, pga, pgv, cells(ds, ["seed"], "pga", "pga").outcome


def test_fragility_map_keeps_its_labels_inside_and_its_title_short(striped_fragility):
    fig = fragility_plots.figure_map(*striped_fragility)
    renderer = _renderer(fig)
    first = fig.axes[0]
    assert first.get_ylabel() == "PGV [cm/s]"
    assert _within(first.yaxis.label.get_window_extent(renderer), fig.bbox)
    colorbar = fig.axes[-1]
    assert "P(overturning)" in colorbar.get_ylabel()
    assert _within(colorbar.yaxis.label.get_window_extent(renderer), fig.bbox)
    assert_nothing_clipped(fig, renderer)
    assert title_lines(fig._suptitle.get_text()) <= 2
    assert fig._suptitle.get_text().startswith("Overturning of a 20 x 80 cm marble statue")


def test_fragility_curves_title_and_legend_under_the_panels(striped_fragility):
    fig = fragility_plots.figure_curves(striped_fragility[0])
    renderer = _renderer(fig)
    assert_nothing_clipped(fig, renderer)
    assert title_lines(fig._suptitle.get_text()) <= 2
    panels = [ax for ax in fig.axes if ax.get_visible() and ax.get_label() != "<colorbar>"]
    assert all(ax.get_legend() is None for ax in panels)  # nothing inside a panel
    legend = fig.legends[0].get_window_extent(renderer)
    assert all(not legend.overlaps(ax.bbox) for ax in panels)
    for ax in panels:  # each fit's numbers in its panel's title, two lines at most
        assert title_lines(ax.get_title()) <= 2
        assert "θ = " in ax.get_title() or "no lognormal fit" in ax.get_title()


# --- the site figure: the text's units and numbers ------------------------------------------

@pytest.fixture(scope="module")
def graveyard(tmp_path_factory):
    folder = tmp_path_factory.mktemp("graveyard")
    path = folder / "graveyard.yaml"
    path.write_text(yaml.safe_dump({
        "sites": [{"name": "a graveyard with a rather long name, for a long heading",
                   "latitude": 35.0, "longitude": 139.5, "bodies": [
                       {"name": "slim", "B": "20 cm", "H": "80 cm", "overturned": True},
                       {"name": "stout", "B": "30 cm", "H": "60 cm", "overturned": False},
                       {"name": "slab", "B": "50 cm", "H": "55 cm", "overturned": True,
                        "mu": 0.5}]}],
        "ensemble": {"motions": {"record": ["elcentro1940_ns", "elcentro1940_ew",
                                            "taft1952_ew_s69e"]},
                     "levels": {"pga": {"start": "1 m/s^2", "stop": "12 m/s^2", "num": 6}},
                     "t_end": "8 s"}}, sort_keys=False))
    survey = load_survey(path)
    datasets = site_studies.ensemble_datasets(survey, site_studies.results_folder(path))
    yard = survey.sites[0]
    estimate = site.estimate_site(yard, survey.ensemble, datasets)
    limits = deterministic(yard.bodies)["lower_limits"]
    return estimate, limits, site_report.format_text(estimate, limits)


def test_site_figure_is_in_gal_with_the_numbers_of_the_text(graveyard):
    estimate, limits, text = graveyard
    row = re.search(r"^PGA \[gal\]\s+>= (\d+)\s+(\d+)\s+(\d+)\s+(\d+)$", text, re.M)
    assert row, text
    a_o, *quantiles = row.groups()
    pgv_row = re.search(r"^PGV \[cm/s\]\s+>= ([\d.]+)", text, re.M)
    fig = figure_site(estimate, limits)
    fallen, standing, density, consistency = fig.axes[:4]
    for ax in (density, consistency):
        assert ax.get_xlabel().endswith("[gal]")
    assert consistency.get_ylabel().endswith("[cm/s]")
    assert not [ax for ax in fig.axes if "[g]" in ax.get_xlabel() or "m/s" in ax.get_xlabel()]
    drawn = [t.get_text().split("\n")[1] for t in density.texts if "%\n" in t.get_text()]
    assert drawn == quantiles  # the posterior's quantiles, as the text prints them
    labels = [t.get_text() for t in density.get_legend().get_texts()]
    assert f"a_o = {a_o} gal (Eq. 14, slim)" in labels
    assert f"v_o = {pgv_row.group(1)} cm/s" in [t.get_text().strip()
                                                for t in consistency.texts]
    heading = fig._suptitle.get_text()
    assert f"{' / '.join(quantiles)} gal" in heading and "m/s" not in heading
    assert title_lines(heading) <= 2 and "kept out" in heading
    # the simulated motions where the estimate has them, in gal and cm/s
    offsets = np.concatenate([c.get_offsets() for c in consistency.collections
                              if isinstance(c, PathCollection)])
    np.testing.assert_allclose(np.sort(offsets[:, 0]),
                               np.sort(np.ravel(estimate.map.points_pga) * 100))
    np.testing.assert_allclose(np.sort(offsets[:, 1]),
                               np.sort(np.ravel(estimate.map.points_pgv) * 100))
    # the a_o line where the text puts it
    a_o_lines = [line for line in density.get_lines() if line.get_linestyle() == ":"]
    assert a_o_lines and float(a_o_lines[0].get_xdata()[0]) == pytest.approx(float(a_o),
                                                                           abs=0.5)
    renderer = _renderer(fig)
    assert_nothing_clipped(fig, renderer)
    shade = [c for c in consistency.collections if not isinstance(c, PathCollection)][:1]
    assert_legends_leave_data_visible(fig, background=shade, renderer=renderer)


# --- titles and legends of the other figures ------------------------------------------------

def test_long_study_titles_take_two_lines_at_most():
    ds = sweep.run_study({"name": "long", "title": LONG_TITLE + " " + LONG_TITLE,
                          "scene": {**SCENE, "solver": {"t_end": 0.5}},
                          "grid": {"amplitude": {"values": [0.5, 2.5], "unit": "west"},
                                   "frequency": [2.0, 4.0]}})
    fig = figure_map(ds)
    assert title_lines(fig._suptitle.get_text()) <= 2
    assert fig._suptitle.get_text().endswith("…")  # said to be cut, not silently
    assert_nothing_clipped(fig)


def test_spectrum_title_and_legend():
    ds = sweep.run_study({
        "name": "spectrum", "title": LONG_TITLE,
        "scene": {"body": {"B": 0.2, "H": 1.0}, "contact": {"mu": 1.0, "e_x": 0.0, "e_y": 0.0},
                  "excitation": {"horizontal": {"kind": "sine", "amplitude": "0.4 g",
                                                "frequency": 1.0, "duration": 1.0}},
                  "solver": {"t_end": 4.0}},
        "grid": {"B": [0.05, 0.2, 0.8, 3.2], "b_over_h": [0.15, 0.25]}})
    fig = figure_spectrum(ds)
    assert title_lines(fig._suptitle.get_text()) <= 2
    renderer = _renderer(fig)
    assert_nothing_clipped(fig, renderer)
    assert fig.axes[0].get_legend() is not None
    assert_legends_leave_data_visible(fig, renderer=renderer)


def test_fig17_legends_leave_every_curve_visible():
    fig = figure_limits()
    renderer = _renderer(fig)
    assert_nothing_clipped(fig, renderer)
    assert all(ax.get_legend() is not None for ax in fig.axes)
    assert_legends_leave_data_visible(fig, renderer=renderer)


def _contrast(a, b):
    """WCAG 2.1 contrast ratio of two sRGB colours."""
    def luminance(c):
        c = np.asarray(c, dtype=float)
        return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4) @ [
            0.2126, 0.7152, 0.0722]
    high, low = sorted((luminance(a), luminance(b)), reverse=True)
    return (high + 0.05) / (low + 0.05)


def test_risk_map_legend_names_the_contour_and_labels_stay_readable():
    """The target's contour and the bodies meeting it are in the legend; every cell's label
    lies inside its cell, above the contour, on the cell's colour with a WCAG contrast of at
    least 4.5."""
    from types import SimpleNamespace

    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.colors import to_rgb

    from sweep.plots.risk import figure_map
    from sweep.probability.hazard_curve import HazardCurve
    from sweep.probability.risk_report import RiskOutcome

    p = np.array([[0.084, 0.016, 0.010], [0.064, 0.017, 0.0048], [0.023, 0.011, 0.0031]])
    risks = np.empty(p.shape, dtype=object)
    for index in np.ndindex(*p.shape):
        risks[index] = SimpleNamespace(probability=p[index])
    xs, ys = np.array([0.1, 0.2, 0.4]), np.array([0.2, 0.3, 0.4])
    outcome = RiskOutcome(HazardCurve("pga", [1.0, 2.0], [1e-2, 1e-3]), 50.0,
                          0.02, 0.95, np.empty(p.shape, dtype=object), risks, ["B", "b_over_h"],
                          {"B": (xs, {"units": "m"}), "b_over_h": (ys, {})}, name="map")
    fig = figure_map(outcome)
    FigureCanvasAgg(fig)  # the figure is saved through savefig: no canvas of its own
    renderer = _renderer(fig)
    assert_nothing_clipped(fig, renderer)
    [legend] = fig.legends
    labels = [t.get_text() for t in legend.get_texts()]
    assert any(label.startswith("P = 0.02") for label in labels), labels
    assert any(label.startswith("P ≤ 0.02") for label in labels), labels
    ax = fig.axes[0]
    [mesh] = ax.collections[:1]
    contour = max(c.get_zorder() for c in ax.collections[1:])
    texts = [t for t in ax.texts if t.get_text().endswith("%")]
    assert len(texts) == p.size
    edges_x, edges_y = np.array([0.05, 0.15, 0.3, 0.5]), np.array([0.15, 0.25, 0.35, 0.45])
    for t in texts:
        i, j = (int(np.argmin(np.abs(v - c))) for v, c in zip((xs, ys), t.xy))
        assert t.get_text() == f"{100 * p[i, j]:.2g} %"
        assert t.get_zorder() > contour
        cell = ax.transData.transform([[edges_x[i], edges_y[j]], [edges_x[i + 1],
                                                                  edges_y[j + 1]]])
        box = t.get_bbox_patch().get_window_extent(renderer)
        assert cell[0, 0] <= box.x0 and box.x1 <= cell[1, 0]
        assert cell[0, 1] <= box.y0 and box.y1 <= cell[1, 1]
        background = np.array(t.get_bbox_patch().get_facecolor()[:3])
        assert np.allclose(background, mesh.cmap(mesh.norm(p[i, j]))[:3])
        assert _contrast(to_rgb(t.get_color()), background) >= 4.5  # WCAG 2.1 level AA
