"""Figs. 18-21 of Ishiyama (1982): bodies under recorded earthquakes, H against H/B.

Each cell of a study is one homogeneous rectangular body shaken by a whole record; the figures
colour it by outcome: A no rocking, B rocking without overturning, C overturning (the paper's
regions of Fig. 21).  The criteria of Eq. (14), a_o = (B/H) g <= PGA, and Eq. (16),
v_o <= PGV, are drawn at the peaks of the horizontal record: for a bundled record those of the
paper's Table 5, times the study's ``scale``; for a record given by ``path:`` the peak of its
samples and the peak of their running integral (meaningful for baseline-corrected files such as
PEER's).  Fig. 21 puts every cell of every record of a study on the plane
(PGA/a_o, PGV/v_o), where the criteria are the lines x = 1 and y = 1.

Datasets need the dimensions ``B`` and ``b_over_h`` (or ``B`` and ``H``); any other dimension
(e.g. ``excitation.vertical.scale``, 0 without and 1 with the vertical record) gives panels,
and ``record`` gives the records of Fig. 21.  Titles take two lines at most and labels are
wrapped to their axes (``style.fit_suptitle``, ``style.fit_texts``).
"""
import itertools
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import yaml
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from ..io import records, units
from ..paper import criteria
from .style import (OUTCOME_COLOURS, cell_edges, fit_suptitle, fit_texts, log_axes,
                    outcome_colours)

# Table 5 of the paper: record -> peak acceleration [m/s^2], velocity [m/s], displacement [m]
TABLE5 = {
    "elcentro1940_ns": (3.417, 0.3232, 0.1086),
    "elcentro1940_ew": (2.101, 0.3647, 0.1978),
    "elcentro1940_ud": (2.063, 0.1021, 0.0555),
    "taft1952_ew_s69e": (1.759, 0.1771, 0.0915),
}
# outcome code -> region of the paper's Fig. 21
REGIONS = {-1: "failed", 0: "A: no rocking", 1: "B: rocking, no overturning",
           2: "C: overturning"}
NOT_BUNDLED = ("Taft 1952 NS and UD and the Miyagi-ken-oki 1978 records are not bundled; "
               "run them from your own .AT2 files with `path:`.")
H_WINDOW_CM = (10.0, 400.0)  # heights shown [cm]: the sizes of furniture and monuments
CRITERIA_STYLE = {"acceleration": {"color": "k", "ls": "--", "lw": 1.4},
                  "velocity": {"color": "k", "ls": "-.", "lw": 1.4}}
MAX_PANELS = 4


# --- what the dataset holds -------------------------------------------------------------------

def _scene(ds):
    """The study's base scene (raw dict) from the dataset's ``study`` attribute."""
    study = yaml.safe_load(ds.attrs.get("study", "")) or {}
    return study.get("scene") or {}


def record_peaks(horizontal, name=None, base_dir="."):
    """Peak acceleration [m/s^2] and velocity [m/s] of a study's horizontal record.

    Parameters
    ----------
    horizontal : dict
        The raw ``excitation.horizontal`` of the study's scene (``kind: record``).
    name : str, optional
        The record of this cell when a ``record`` axis overrides the scene's ``name``.

    Returns
    -------
    pga, pgv : float
    source : str
        Where the peaks come from, for the legend.
    """
    name = name or horizontal.get("name")
    if name is not None:
        record = records.load_record(name)
        table = TABLE5.get(records.ALIASES.get(name, name))
    else:
        record = records.read_record_file(Path(base_dir) / horizontal["path"],
                                          horizontal.get("units"))
        table = None
    scale = float(horizontal.get("scale", 1.0))
    if horizontal.get("pga") is not None:
        scale = units.parse_quantity(horizontal["pga"], "acceleration").to_si() / record.pga
    if table is not None:
        return scale * table[0], scale * table[1], "Table 5" + (
            f" x {scale:.3g}" if scale != 1.0 else "")
    velocity = np.cumsum(0.5 * (record.samples[1:] + record.samples[:-1])) * record.dt
    return abs(scale) * record.pga, abs(scale) * float(np.max(np.abs(velocity))), "record"


def _record_names(ds, scene):
    if "record" in ds.dims:
        return [str(v) for v in ds["record"].values]
    horizontal = (scene.get("excitation") or {}).get("horizontal") or {}
    if horizontal.get("kind") != "record":
        raise ValueError("the study's horizontal excitation is not a record")
    return [horizontal.get("name") or Path(horizontal["path"]).stem]


def _peaks_of(ds, scene, name):
    horizontal = (scene.get("excitation") or {}).get("horizontal") or {}
    base_dir = Path(ds.attrs.get("study_file") or ".").parent
    return record_peaks(horizontal, name if "record" in ds.dims else None, base_dir)


def _size_dims(da):
    """The two dimensions giving the body's size: (B, b_over_h) or (B, H)."""
    for names in (("B", "b_over_h"), ("B", "H")):
        if all(d in da.dims for d in names):
            return names
    raise ValueError(f"a figure of bodies under records needs the dimensions B and b_over_h "
                     f"(or B and H); the dataset has {list(da.dims)}")


def _height_and_slenderness(B, b_over_h=None, H=None):
    """H [m] and H/B from B and b/h, or from B and H."""
    if b_over_h is not None:
        return B / b_over_h, 1.0 / b_over_h
    return H, H / B


def body_coords(da):
    """Heights H [m] and slenderness H/B of the cells of ``da``: arrays of its shape."""
    import xarray as xr

    _, *coords = xr.broadcast(da, *(da[d] for d in _size_dims(da)))
    return _height_and_slenderness(**{c.name: c.transpose(*da.dims).values for c in coords})


def _panel_dims(ds):
    return [d for d in ds["outcome"].dims if d not in ("B", "H", "b_over_h", "record")]


def _panel_title(ds, scene, sel):
    parts = []
    for dim, i in sel.items():
        value = ds[dim].values[i]
        if ds[dim].attrs.get("study_axis") == "excitation.vertical.scale":
            vertical = (scene.get("excitation") or {}).get("vertical") or {}
            parts.append("horizontal only" if value == 0 else
                         f"with vertical {vertical.get('name') or vertical.get('path')}"
                         + (f" x {value:g}" if value != 1 else ""))
        else:
            parts.append(f"{dim} = {value:.4g}" if ds[dim].dtype.kind == "f"
                         else f"{dim} = {value}")
    return ", ".join(parts)


# --- Figs. 18-20 ------------------------------------------------------------------------------

def criteria_ratios(B, H, pga, pgv):
    """x = PGA/a_o (Eq. 14) and y = PGV/v_o (Eq. 16) of bodies B x H [m]: the criteria hold
    where both are >= 1."""
    return pga / criteria.ishiyama_acceleration(B, H), pgv / criteria.ishiyama_velocity(B, H)


def region_of(x, y):
    """Region of the paper's Fig. 21 by the criteria: A (x < 1), B (x >= 1, y < 1), C."""
    return np.where(x < 1.0, "A", np.where(y < 1.0, "B", "C"))


def draw_criteria(ax, pga, pgv, source, H_range_cm, HB_range):
    """Lines a_o = PGA (Eq. 14) and v_o = PGV (Eq. 16) and the letters A, B, C of Fig. 21."""
    H_cm, HB = np.meshgrid(np.geomspace(*H_range_cm, 300), np.geomspace(*HB_range, 300))
    x, y = criteria_ratios(H_cm / 100.0 / HB, H_cm / 100.0, pga, pgv)
    for key, ratio in (("acceleration", x), ("velocity", y)):
        style = CRITERIA_STYLE[key]
        ax.contour(H_cm, HB, ratio, levels=[1.0], colors=style["color"],
                   linestyles=style["ls"], linewidths=style["lw"])
    region = region_of(x, y)
    for letter in "ABC":
        inside = region == letter
        if inside.sum() > 0.02 * region.size:  # label only regions large enough to show
            ax.text(np.exp(np.median(np.log(H_cm[inside]))),
                    np.exp(np.median(np.log(HB[inside]))), letter, fontsize=16,
                    fontweight="bold", ha="center", va="center", color="k", alpha=0.75)
    return [Line2D([], [], label=f"Eq. (14): (B/H) g = {100 * pga:.1f} gal ({source})",
                   **CRITERIA_STYLE["acceleration"]),
            Line2D([], [], label=f"Eq. (16): v_o = {100 * pgv:.2f} cm/s ({source})",
                   **CRITERIA_STYLE["velocity"])]


def _outcome_legend(outcome):
    """Patches of the outcomes; 'failed' only when some cell of ``outcome`` failed."""
    failed = bool(np.any(np.asarray(outcome) == -1))
    return [Patch(color=OUTCOME_COLOURS[code], label=label) for code, label in REGIONS.items()
            if code >= 0 or failed]


def draw_bodies(ax, da):
    """Cells of a 2-D outcome slice (dims B and b_over_h, or B and H) on H [cm] vs H/B."""
    names = _size_dims(da)
    if da.ndim != 2:
        raise ValueError(f"expected a 2-D slice over {names}; got {da.dims}")
    # cell edges in log space; cells are parallelograms on log axes, drawn exactly
    edges = np.meshgrid(*(cell_edges(da[d].values, log=True) for d in names), indexing="ij")
    H_edges, HB_edges = _height_and_slenderness(**dict(zip(names, edges)))
    cmap, norm = outcome_colours()
    ax.pcolormesh(100 * H_edges, HB_edges, da.transpose(*names).values, cmap=cmap, norm=norm,
                  edgecolors="face", linewidth=0.0)
    log_axes(ax)
    ax.set_xlabel("height of the body H [cm]")
    ax.set_ylabel("height / breadth H/B")


def _in_window(H):
    return (100 * H >= H_WINDOW_CM[0]) & (100 * H <= H_WINDOW_CM[1])


def tally(da, pga, pgv):
    """Counts of cells per region of the criteria (A, B, C) and outcome, inside the window.

    Returns
    -------
    dict of str to dict of str to int
        ``{"A": {"no_rocking": n, "rocked": n, "overturned": n, "failed": n}, "B": ...}``.
    """
    H, HB = body_coords(da)
    region = region_of(*criteria_ratios(H / HB, H, pga, pgv))
    shown, outcome = _in_window(H), da.values
    names = {-1: "failed", 0: "no_rocking", 1: "rocked", 2: "overturned"}
    return {r: {name: int(np.sum(shown & (region == r) & (outcome == code)))
                for code, name in names.items()} for r in "ABC"}


def _tally_text(counts):
    fallen = sum(c["overturned"] for c in counts.values())
    inside = counts["C"]["overturned"]
    c_total = sum(counts["C"].values())
    return (f"overturned: {fallen}, of which {inside} in C; "
            f"C: {inside}/{c_total} overturned; A: {counts['A']['rocked']} rocked")


def figure_record_map(ds):
    """Figs. 18-20: outcomes on H [cm] vs H/B with the criteria at the record's peaks."""
    scene = _scene(ds)
    names = _record_names(ds, scene)
    if len(names) != 1:
        raise ValueError("the dataset has several records: draw it with --figure fig21")
    pga, pgv, source = _peaks_of(ds, scene, names[0])
    outcome = ds["outcome"]
    others = _panel_dims(ds)
    combos = list(itertools.product(*(range(ds.sizes[d]) for d in others)))[:MAX_PANELS]
    fig, axes = plt.subplots(1, len(combos), figsize=(max(9.0, 6.0 * len(combos)), 6.4),
                             squeeze=False, layout="constrained")
    for ax, combo in zip(axes.flat, combos):
        sel = dict(zip(others, combo))
        da = outcome.isel(sel)
        draw_bodies(ax, da)
        HB = body_coords(da)[1]
        HB_range = (float(HB.min()), float(HB.max()))
        lines = draw_criteria(ax, pga, pgv, source, H_WINDOW_CM, HB_range)
        ax.set_xlim(*H_WINDOW_CM)
        ax.set_ylim(*HB_range)
        title = _panel_title(ds, scene, sel)
        ax.set_title((title + "\n" if title else "") + _tally_text(tally(da, pga, pgv)),
                     fontsize=9)
    _legend_below(fig, _outcome_legend(outcome) + lines)
    fit_suptitle(fig, [ds.attrs.get("title", "bodies under a record"),
                       f"record {names[0]}: PGA {100 * pga:.1f} gal, PGV {100 * pgv:.2f} cm/s "
                       f"({source}); letters A, B, C: regions of the criteria"])
    fit_texts(fig)
    return fig


def _legend_below(fig, handles):
    """The legend under the panels, with the note on records that are not bundled."""
    fig.legend(handles=handles, fontsize=8, ncol=3, loc="outside lower center", frameon=False,
               title=NOT_BUNDLED, title_fontsize=7)


# --- Fig. 21 ----------------------------------------------------------------------------------

def normalized_cells(ds, name, pga, pgv):
    """Every cell of record ``name``: PGA/a_o, PGV/v_o and outcome (flat arrays), in window."""
    da = ds["outcome"].sel(record=name) if "record" in ds.dims else ds["outcome"]
    H, HB = body_coords(da)
    x, y = criteria_ratios(H / HB, H, pga, pgv)
    shown = _in_window(H)
    return x[shown], y[shown], da.values[shown]


def figure_summary(ds):
    """Fig. 21: every body of every record on (PGA/a_o, PGV/v_o), and outcomes per region."""
    scene = _scene(ds)
    names = _record_names(ds, scene)
    fig, (ax, bar) = plt.subplots(1, 2, figsize=(13.0, 6.0), layout="constrained",
                                  gridspec_kw={"width_ratios": [1.2, 1.0]})
    markers = itertools.cycle("osD^v")
    rows = []
    for name in names:
        pga, pgv, source = _peaks_of(ds, scene, name)
        x, y, outcome = normalized_cells(ds, name, pga, pgv)
        marker = next(markers)
        for code in sorted(OUTCOME_COLOURS):
            pick = outcome == code
            if np.any(pick):
                ax.scatter(x[pick], y[pick], s=9, marker=marker, color=OUTCOME_COLOURS[code],
                           edgecolors="0.3", linewidths=0.2)
        region = region_of(x, y)
        for r in "ABC":
            inside = region == r
            rows.append((f"{name} {r}", [np.sum(inside & (outcome == c)) for c in (0, 1, 2, -1)]))
        ax.scatter([], [], marker=marker, color="0.6", label=f"{name} ({source})")
    ax.axvline(1.0, **CRITERIA_STYLE["acceleration"])
    ax.axhline(1.0, **CRITERIA_STYLE["velocity"])
    log_axes(ax)
    ax.set_xlabel("PGA / a_o   (a_o = (B/H) g, Eq. 14)")
    ax.set_ylabel("PGV / v_o   (v_o = 0.4 v_H, Eq. 16)")
    for letter, (xt, yt) in {"A": (0.15, 0.5), "B": (0.62, 0.06), "C": (0.62, 0.93)}.items():
        ax.text(xt, yt, letter, transform=ax.transAxes, fontsize=18, fontweight="bold",
                alpha=0.75)
    _legend_below(fig, _outcome_legend(ds["outcome"]) + ax.get_legend_handles_labels()[0])
    ax.set_title("each body under each record; criteria: x = 1 (Eq. 14), y = 1 (Eq. 16)",
                 fontsize=9)
    _draw_region_bars(bar, rows)
    fit_suptitle(fig, [ds.attrs.get("title", "bodies under records"),
                       f"bodies with H from {H_WINDOW_CM[0]:g} to {H_WINDOW_CM[1]:g} cm"])
    fit_texts(fig)
    return fig


def _draw_region_bars(ax, rows):
    """Stacked bars: share of each outcome among the cells of each record and region."""
    labels = [label for label, _ in rows]
    counts = np.array([c for _, c in rows], dtype=float)
    totals = counts.sum(axis=1)
    shares = np.divide(counts, totals[:, None], out=np.zeros_like(counts),
                       where=totals[:, None] > 0)
    y = np.arange(len(rows))[::-1]
    left = np.zeros(len(rows))
    for k, code in enumerate((0, 1, 2, -1)):
        ax.barh(y, shares[:, k], left=left, color=OUTCOME_COLOURS[code], edgecolor="white")
        left += shares[:, k]
    for yi, total in zip(y, totals):
        ax.text(1.01, yi, f"{int(total)} bodies", va="center", fontsize=8)
    ax.set_yticks(y, labels, fontsize=8)
    ax.set_xlim(0, 1.25)
    ax.set_xticks([0, 0.25, 0.5, 0.75, 1.0])
    ax.set_xlabel("share of the bodies in the region")
    ax.set_title("outcomes in the regions A (x < 1), B (x >= 1, y < 1), C (x, y >= 1)",
                 fontsize=9)
