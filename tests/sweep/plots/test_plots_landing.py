"""The landing figure: the class of every cell of a small landing study (``sweep.paper.landing``;
Fig. 5's body with the face_friction landing, docs/landing.md), the same when the body moves
left (mirror, docs/physics.md A1), the figure (``sweep.plots.landing``) with our panels marked, and
the panels it marks agreeing with the scene files."""
from pathlib import Path

import matplotlib
import numpy as np
import pytest
import yaml

import sweep
from sweep.paper.landing import (OVERTURNS_BACK, OVERTURNS_FORWARD, SLIDES, TILTS_BACK,
                                 TILTS_FORWARD, landing_classes)
from sweep.plots.landing import PAPER_PANELS, figure_landing

matplotlib.use("Agg")
STUDIES = Path(__file__).resolve().parents[3] / "studies"
E_X = [-1.0, -0.99, -0.9, 0.0]
E_Y = [0.2, 0.5, 0.8]
# class at (e_x, e_y) of studies/fig05_landing_map.yaml (docs/landing.md 5)
CLASSES = [[SLIDES, SLIDES, SLIDES],
           [OVERTURNS_FORWARD, TILTS_BACK, OVERTURNS_BACK],
           [TILTS_FORWARD, OVERTURNS_FORWARD, OVERTURNS_BACK],
           [OVERTURNS_FORWARD, OVERTURNS_FORWARD, OVERTURNS_FORWARD]]


@pytest.fixture(scope="module")
def landings():
    """Fig. 5's landing over e_x, e_y, moving left and right: 24 cells."""
    return sweep.run_study({
        "name": "landing_test", "title": "Fig. 5 landings",
        "scene": {"body": {"B": "10 cm", "H": "30 cm"},
                  "contact": {"mu_s": 0.4, "mu_edge_s": 0.4, "mu_k": 0.3, "mu_edge_k": 0.3,
                              "landing": "face_friction"},
                  "initial": {"lift": "15 cm"}, "solver": {"t_end": 3.0}},
        "grid": {"initial.x_dot": [-1.0, 1.0], "e_x": E_X, "e_y": E_Y}})


def test_classes_both_ways(landings):
    """Every class but failed, and forward and back relative to the velocity: a body moving
    left is the mirror image of one moving right."""
    classes = landing_classes(landings).transpose("x_dot", "e_x", "e_y").values
    np.testing.assert_array_equal(classes[0], CLASSES)
    np.testing.assert_array_equal(classes[1], CLASSES)
    assert landings["overturn_direction"].sel(x_dot=1.0, e_x=0.0).values.tolist() == [-1] * 3


def test_figure_marks_our_panels(landings):
    """One panel per direction of the velocity, our four Fig. 5 panels named on each."""
    fig = figure_landing(landings, x="e_x", y="e_y")
    axes = [ax for ax in fig.axes if ax.get_visible()]
    assert len(axes) == 2
    for ax in axes:
        assert sorted(t.get_text() for t in ax.texts) == sorted(PAPER_PANELS)
    assert "x_dot = -1" in axes[0].get_title()


def test_panels_are_those_of_the_scene_files():
    for name, pair in PAPER_PANELS.items():
        contact = yaml.safe_load((STUDIES / f"fig0{name}_after_jump.yaml").read_text())["contact"]
        assert (contact["e_x"], contact["e_y"]) == pair and contact["landing"] == "face_friction"
