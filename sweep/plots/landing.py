"""The landing figure (Ishiyama 1982, Fig. 5): the class of every cell of a landing study.

The classes of ``sweep.paper.landing`` (slides, tilts forward or back and stands, overturns
forward or back) drawn as a map, with our Fig. 5 panels or Fig. 5's landing velocity marked
(docs/landing.md).
"""
import itertools
import math
import textwrap

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import BoundaryNorm, ListedColormap
from matplotlib.patches import Patch

from ..paper import classify
from ..paper.criteria import G
from ..paper.landing import (FAILED, OVERTURNS_BACK, OVERTURNS_FORWARD, SLIDES, TILTS_BACK,
                             TILTS_FORWARD, landing_classes)
from .map import panel_title
from .style import axis_label, study_axis

LEGEND = {  # class code (sweep.paper.landing) -> (legend text, colour)
    FAILED: ("failed", "#9e9e9e"),
    SLIDES: (f"slides (|θ| < {classify.EPSILON:g} α)", "#f0f0f0"),
    TILTS_FORWARD: ("tilts forward, stands", "#fdae6b"),
    TILTS_BACK: ("tilts back, stands", "#9ecae1"),
    OVERTURNS_FORWARD: ("overturns forward", "#d94801"),
    OVERTURNS_BACK: ("overturns back", "#08519c"),
}
# (e_x, e_y) of our panels, as in studies/fig05[a-d]_after_jump.yaml
PAPER_PANELS = {"5a": (-1.0, 0.2), "5b": (-0.9, 0.2), "5c": (0.0, 0.0), "5d": (-0.9, 0.8)}
# (u-, v-) [m/s] of Fig. 5's landing: released 15 cm above the floor at 1 m/s
PAPER_LANDING = (1.0, -math.sqrt(2.0 * G * 0.15))
MAX_PANELS = 9  # more combinations of the other axes than this: the first ones are drawn
# An e_x axis is drawn as log(1 + e_x + E_X_OFFSET): stretched near -1, where the friction
# impulse, proportional to 1 + e_x (docs/landing.md (L2)), is small and the outcomes change.
E_X_OFFSET = 0.05
E_X_TICKS = (-1.0, -0.95, -0.9, -0.8, -0.5, 0.0, 0.5, 1.0)


def _stretch_e_x(ax, ds, x, y):
    """Draw an e_x axis of ``ax`` on the scale log(1 + e_x + ``E_X_OFFSET``)."""
    scale = (lambda e: np.log(np.maximum(1.0 + e + E_X_OFFSET, 1e-300)),
             lambda s: np.exp(s) - 1.0 - E_X_OFFSET)
    for dim, set_scale, set_ticks in ((x, ax.set_xscale, ax.set_xticks),
                                      (y, ax.set_yscale, ax.set_yticks)):
        if study_axis(ds[dim]) == "e_x":
            set_scale("function", functions=scale)
            set_ticks(E_X_TICKS, [f"{t:g}" for t in E_X_TICKS])


def _panel_name(ds, sel):
    """'5b' when the panel's e_x and e_y are those of one of our Fig. 5 panels, else ''."""
    values = {study_axis(ds[d]): float(ds[d].values[i]) for d, i in sel.items()}
    e = (values.get("e_x"), values.get("e_y"))
    return next((name for name, pair in PAPER_PANELS.items()
                 if None not in e and np.allclose(e, pair)), "")


def _mark_paper(ax, ds, x, y):
    """Our Fig. 5 panels on an (e_x, e_y) map; Fig. 5's landing on an (x_dot, y_dot) map."""
    axes = (study_axis(ds[x]), study_axis(ds[y]))
    if axes == ("e_x", "e_y"):
        points = PAPER_PANELS
    elif axes == ("initial.x_dot", "initial.y_dot"):
        points = {"Fig. 5": PAPER_LANDING}
    else:
        return
    for name, (px, py) in points.items():
        ax.plot(px, py, "o", ms=6, mfc="white", mec="k", mew=1.2, clip_on=False, zorder=3)
        ax.annotate(name, (px, py), xytext=(5, 4), textcoords="offset points", fontsize=9,
                    fontweight="bold", zorder=3,
                    bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none",
                          "alpha": 0.8})


def figure_landing(ds, x=None, y=None):
    """Map of what the body did after landing, one panel per combination of the other axes.

    Parameters
    ----------
    ds : xarray.Dataset
        A landing study's dataset (``studies/fig05_landing_map.yaml``,
        ``fig05_landing_speeds.yaml``).
    x, y : str, optional
        Dimensions along x and y; default the last two of the grid.

    Returns
    -------
    matplotlib.figure.Figure
        Classes of ``sweep.paper.landing.landing_classes`` as colours; our Fig. 5 panels
        marked on an (e_x, e_y) map, Fig. 5's landing velocity on an (x_dot, y_dot) map.
    """
    dims = list(ds["outcome"].dims)
    if x is None or y is None:
        rest = [d for d in dims if d not in (x, y)]
        if len(rest) < (x is None) + (y is None):
            raise ValueError(f"a landing map needs two dimensions; the dataset has {dims}")
        y = y or rest.pop()
        x = x or rest.pop()
    for name in (x, y):
        if name not in dims:
            raise ValueError(f"{name!r} is not a dimension of the dataset: {dims}")
    classes = landing_classes(ds)
    others = [d for d in dims if d not in (x, y)]
    combos = list(itertools.product(*(range(ds.sizes[d]) for d in others)))[:MAX_PANELS]
    cols = min(len(combos), 3)
    rows = math.ceil(len(combos) / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(4.4 * cols + 1.0, 3.6 * rows + 0.8),
                             squeeze=False, layout="constrained")
    codes = sorted(LEGEND)
    cmap = ListedColormap([LEGEND[c][1] for c in codes])
    norm = BoundaryNorm(np.arange(codes[0] - 0.5, codes[-1] + 1.0), cmap.N)
    for ax, combo in zip(axes.flat, combos):
        sel = dict(zip(others, combo))
        panel = classes.isel(sel).transpose(y, x)
        ax.pcolormesh(ds[x].values, ds[y].values, panel.values, cmap=cmap, norm=norm,
                      shading="nearest")
        _stretch_e_x(ax, ds, x, y)
        _mark_paper(ax, ds, x, y)
        ax.set_xlabel(axis_label(ds[x]))
        ax.set_ylabel(axis_label(ds[y]))
        name = _panel_name(ds, sel)
        title = panel_title(ds, sel, x, y) if sel else ""
        ax.set_title(f"{title} (our {name})" if name else title, fontsize=9)
    for ax in axes.flat[len(combos):]:
        ax.set_visible(False)
    present = set(np.unique(classes.values).tolist())
    handles = [Patch(facecolor=LEGEND[c][1], edgecolor="0.6", label=LEGEND[c][0])
               for c in codes if c in present or c != FAILED]
    fig.legend(handles=handles, loc="outside lower center", ncols=3, fontsize=8,
               frameon=False)
    title = ds.attrs.get("title", "landing after a translation jump")
    fig.suptitle(textwrap.fill(title, 22 * cols + 30), fontsize=11)
    return fig
