"""Figs 8-11 of Ishiyama (1982): where frequency sweeps overturn, in the normalized plane.

Abscissa: the normalized velocity, velocity amplitude / v_H (the single-shock velocity of
Eq. 9); ordinate: the normalized acceleration, acceleration amplitude / ((B/H) g) (West,
Eq. 1), as the paper draws them, with West's line a = 1, the single-shock line v = 1 and the
paper's point P (v = 0.4, a = 1).  On these log axes a sweep runs along a straight line:
horizontal at constant acceleration, vertical at constant velocity, of slope 2 at constant
displacement.  A figure takes the datasets of one or several sweep studies
(``python -m sweep.plot A.nc V.nc D.nc --figure fig09 -o fig09.png``), read by
``sweep.paper.plane``; Fig. 11 also takes the classification of their overturnings
(``sweep.paper.classify.classify_dataset``).  An overturning after the excitation stopped is
not a result of the sweep: it is left out and counted.  Titles take two lines at most and
labels are wrapped to the axes (``style.fit_texts``); the legends lie under the plane.
"""
import textwrap

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.lines import Line2D

from ..paper.criteria import POINT_P
from ..paper.plane import lowest_points, sweep_cells
from .style import as_list, fit_texts, log_axes

HOLD_STYLE = {  # marker and colour of each kind of sweep, as the paper's three symbols
    "acceleration": {"marker": "o", "color": "tab:red"},
    "velocity": {"marker": "^", "color": "tab:blue"},
    "displacement": {"marker": "s", "color": "tab:green"},
}
CRITERIA_STYLE = {"west": {"color": "k", "ls": "--", "lw": 1.1},
                  "shock": {"color": "0.35", "ls": "-", "lw": 1.0}}
V_LIMITS, A_LIMITS = (0.1, 5.0), (0.15, 6.0)  # normalized velocity and acceleration shown
KIND_STYLE = {  # the paper's boundaries of Fig. 11 and the other kinds of the classifier
    "inverse_phase": {"marker": "o", "color": "tab:red", "ls": "-",
                      "label": "a: from inverse phase rocking"},
    "subharmonic": {"marker": "D", "color": "tab:purple", "ls": "--",
                    "label": "b: from subharmonic rocking"},
    "in_phase": {"marker": "^", "color": "tab:blue", "ls": "-.",
                 "label": "c: from in phase rocking"},
    "irregular": {"marker": "x", "color": "0.45", "ls": "none",
                  "label": "from irregular rocking"},
}
# kinds drawn as boundary lines, and the sweeps they come from (Fig. 11)
BOUNDARIES = {"inverse_phase": ("acceleration",), "subharmonic": tuple(HOLD_STYLE),
              "in_phase": ("velocity", "displacement")}

# --- drawing ----------------------------------------------------------------------------------

def draw_criteria(ax):
    """West's line a = 1 (Eq. 1), the single-shock line v = 1 (Eq. 9) and point P."""
    ax.axhline(1.0, **CRITERIA_STYLE["west"])
    ax.axvline(1.0, **CRITERIA_STYLE["shock"])
    ax.plot(*POINT_P, marker="*", ms=15, color="gold", mec="k", zorder=5, ls="none")
    ax.annotate("P", POINT_P, xytext=(-14, 6), textcoords="offset points", fontsize=12,
                fontweight="bold")
    return [Line2D([], [], **CRITERIA_STYLE["west"], label="West, Eq. (1): a = (B/H) g"),
            Line2D([], [], **CRITERIA_STYLE["shock"], label="single shock, Eq. (9): v = v_H"),
            Line2D([], [], marker="*", ms=12, color="gold", mec="k", ls="none",
                   label="P (v = 0.4 v_H, a = (B/H) g)")]


def plane_axes(ax):
    """Log axes of the normalized plane with plain tick labels."""
    log_axes(ax)
    ax.set_xlim(*V_LIMITS)
    ax.set_ylim(*A_LIMITS)
    ax.set_xlabel("normalized velocity: velocity amplitude / v_H")
    ax.set_ylabel("normalized acceleration: acceleration amplitude / ((B/H) g)")
    ax.grid(True, which="major", color="0.9", lw=0.6)


def _sweep_label(cells, mask):
    """'constant velocity, swept up: 16 of 21 overturned, ...; lowest v 0.533 (a = 1.12)'."""
    n = int(np.sum(mask))
    over = int(np.sum(mask & ~np.isnan(cells.point[:, 0])))
    text = (f"constant {cells.hold}, swept {'down' if cells.down else 'up'}: "
            f"{over} of {n} overturned")
    for count, what in ((np.sum(mask & cells.late), "after the sweep"),
                        (np.sum(mask & cells.failed), "failed")):
        if count:
            text += f", {int(count)} {what}"
    (v, a), _ = lowest_points(cells._replace(point=np.where(mask[:, None], cells.point, np.nan)))
    return text + (f"; lowest v {v:.3g} (a = {a:.3g})" if over else "")


def draw_sweeps(ax, cells):
    """Paths and overturning points of one study; one colour per series when it has several.

    Returns the legend handles.
    """
    style = HOLD_STYLE[cells.hold]
    handles = []
    several = len(cells.labels) > 1
    colours = plt.cm.tab20(np.arange(len(cells.labels)) % 20)
    for k, label in enumerate(cells.labels):
        mask = cells.series == k
        colour = colours[k] if several else style["color"]
        if not several:  # paths only for a single series: many would hide the points
            for (v0, a0), (v1, a1) in zip(cells.start[mask], cells.end[mask]):
                ax.plot([v0, v1], [a0, a1], color=colour, lw=0.7, alpha=0.35)
        ax.plot(*cells.point[mask].T, ls="none", marker=style["marker"], color=colour,
                mec="k", mew=0.5, ms=6)
        text = _sweep_label(cells, mask)
        handles.append(Line2D([], [], ls="none", marker=style["marker"], color=colour,
                              mec="k", mew=0.5,
                              label=f"{text}; {label}" if several else text))
    if not several:
        handles.append(Line2D([], [], color=style["color"], lw=0.7, alpha=0.5,
                              label=f"paths of the constant-{cells.hold} sweeps"))
    return handles


def _title(label, cells_list, what):
    bodies = {c.body for c in cells_list}
    body = bodies.pop() if len(bodies) == 1 else "several bodies"
    tilts = {c.tilt for c in cells_list}
    tilt = f", initial tilt {tilts.pop():.2g} α" if len(tilts) == 1 and 0 not in tilts else ""
    return f"{label + ': ' if label else ''}{what}, {body}{tilt}"


def figure_plane(data, label=None):
    """Figs 8-10: overturning points of sweep studies in the normalized plane.

    Parameters
    ----------
    data : xarray.Dataset or sequence of them
        Datasets of sweep studies (one per kind of sweep, or with other axes as series).
    label : str, optional
        The paper's figure, for the title ('Fig. 9').
    """
    datasets = as_list(data)
    cells_list = [sweep_cells(ds) for ds in datasets]
    fig, ax = plt.subplots(figsize=(8.4, 7.6), layout="constrained")
    plane_axes(ax)
    handles = []
    for cells in cells_list:
        handles += draw_sweeps(ax, cells)
    handles += draw_criteria(ax)
    fig.legend(handles=handles, loc="outside lower center", ncols=1, fontsize=8,
               frameon=False)
    title = _title(label, cells_list, "overturning in frequency sweeps")
    if len(datasets) == 1:  # one study: its own title says what varies
        title += f"\n{datasets[0].attrs.get('title', '')}"
    ax.set_title(title, fontsize=10)
    fit_texts(fig)
    return fig


def figure_boundaries(data, rockings, label=None):
    """Fig. 11: boundaries of overturning drawn through our overturning points by kind.

    ``rockings`` holds, per dataset, the classification of its overturned cells by the rocking
    before them ({cell id: Rocking}, ``sweep.paper.classify.classify_dataset``): curve a
    through the inverse-phase overturnings of the constant-acceleration sweeps, b through the
    subharmonic ones, c through the in-phase overturnings of the constant velocity and
    displacement sweeps; one line per study, dotted for a body released with an initial tilt
    (the paper's dotted curve).
    """
    fig, ax = plt.subplots(figsize=(8.4, 7.6), layout="constrained")
    plane_axes(ax)
    counts = dict.fromkeys(KIND_STYLE, 0)
    cells_list = []
    for ds, rocking in zip(as_list(data), rockings):
        cells = sweep_cells(ds)
        cells_list.append(cells)
        kinds = {i: r.kind for i, r in rocking.items()}
        for kind, style in KIND_STYLE.items():
            ids = np.array(sorted(i for i, k in kinds.items() if k == kind), dtype=int)
            counts[kind] += ids.size
            if ids.size == 0:
                continue
            pts = cells.point[ids]
            ax.plot(*pts.T, ls="none", marker=style["marker"], color=style["color"],
                    mec="k" if style["marker"] != "x" else None, mew=0.5, ms=5)
            if cells.hold in BOUNDARIES.get(kind, ()) and ids.size > 1:
                along = 1 if cells.hold == "acceleration" else 0  # the quantity swept over
                pts = pts[np.argsort(pts[:, along])]
                ax.plot(*pts.T, color=style["color"], lw=1.3,
                        ls=":" if cells.tilt else style["ls"])
    handles = [Line2D([], [], marker=s["marker"], color=s["color"],
                      ls=s["ls"] if k in BOUNDARIES else "none",
                      mec="k" if s["marker"] != "x" else None, mew=0.5,
                      label=f"{s['label']} (n = {counts[k]})")
               for k, s in KIND_STYLE.items()]
    if any(c.tilt for c in cells_list):
        handles.append(Line2D([], [], color="k", ls=":", lw=1.3,
                              label="dotted: body released with an initial tilt"))
    handles += draw_criteria(ax)
    sources = "; ".join(sorted({f"{c.body}{f', tilt {c.tilt:.2g} α' if c.tilt else ''}"
                                for c in cells_list}))
    handles.append(Line2D([], [], ls="none",
                          label=textwrap.fill(f"sweeps of: {sources}", 110)))
    fig.legend(handles=handles, loc="outside lower center", ncols=1, fontsize=8,
               frameon=False)
    ax.set_title(f"{label + ': ' if label else ''}boundaries of overturning, by the rocking "
                 "before it", fontsize=10)
    fit_texts(fig)
    return fig
