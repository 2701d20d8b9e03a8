"""Fragility figures from a fragility dataset (``sweep.probability.fragility``).

``figure_curves``: per group (body), the probability of overturning at each level (or bin)
with its confidence interval, and the fitted lognormal with its pointwise confidence band,
against the intensity measure on a log axis (PGA in m/s² with g on top, PGV in cm/s).
``figure_map``: per group, the two-parameter fragility Φ(b0 + b1 ln PGA + b2 ln PGV) as
filled contours over (PGA, PGV) with the 0.1, 0.5 and 0.9 lines labelled, and the cells as
markers, overturned or standing.  ``figure`` draws the one of a kind (``"curves"``,
``"map"``), as ``python -m sweep.fragility -o`` and ``python -m sweep.figures`` do.

Both are titled in two lines at most (the study and what is drawn; the ensemble and the
methods), their labels wrapped to their axes; their legends lie outside the panels, under
them, so that no point is hidden: a curve's θ and β are in its panel's title.
"""
import math

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.legend_handler import HandlerTuple
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from kernels import codes

from ..bodies import G
from ..probability.fragility import (asymmetric, cells, describe_group, group_coords,
                                     group_indices)
from .style import fit_suptitle, fit_texts, legend_columns, plain_log_axis

MAX_PANELS = 12  # more groups than this: this many, evenly spread over them
COLUMNS = 3
MIN_WIDTH = 8.0  # inches of a figure of one or two panels: room for its two-line title
CM = 100.0  # cm per m
# intensity measure -> (axis label, factor from SI to the plotted unit)
IM_AXES = {
    "pga": ("PGA [m/s²]", 1.0),
    "pgv": ("PGV [cm/s]", CM),
    "pga_norm": ("PGA / (g tan α)", 1.0),
    "pgv_norm": ("PGV p / (g tan α)", 1.0),
    "ground_pga": ("ground PGA under the building [m/s²]", 1.0),
    "ground_pgv": ("ground PGV under the building [cm/s]", CM),
}
IM_UNITS = {"pga": "m/s²", "pgv": "cm/s", "pga_norm": "", "pgv_norm": "", "ground_pga": "m/s²",
            "ground_pgv": "cm/s"}
PROBABILITY_LINES = (0.1, 0.5, 0.9)
OVERTURNED_STYLE = {"marker": "^", "s": 24, "facecolors": "black", "edgecolors": "white",
                    "linewidths": 0.5, "zorder": 3}
STANDING_STYLE = {"marker": "o", "s": 18, "facecolors": "white", "edgecolors": "#08306b",
                  "linewidths": 0.8, "zorder": 3}
FIT_COLOUR, DATA_COLOUR = "#cb181d", "#08306b"
DATA_STYLE = {"fmt": "o", "ms": 4, "color": DATA_COLOUR, "ecolor": DATA_COLOUR, "elinewidth": 1,
              "capsize": 2.5}
FIT_STYLE = {"color": FIT_COLOUR, "lw": 1.6}
BAND_STYLE = {"color": FIT_COLOUR, "alpha": 0.18, "lw": 0}
BAND_METHODS = {"bootstrap": "pointwise percentiles of the bootstrap fits over the members",
                "delta": "delta method"}
# a body with G off the middle: k/n of each side (overturn_direction +1 left, -1 right),
# drawn beside the level (a factor on the log axis) where any member overturned
SIDE_STYLES = {"left": {"marker": "<", "ms": 5, "color": "#6a51a3", "ls": "none"},
               "right": {"marker": ">", "ms": 5, "color": "#238b45", "ls": "none"}}
SIDE_SHIFT = {"left": 1 / 1.05, "right": 1.05}


def _shown_groups(frag):
    """The groups drawn (at most ``MAX_PANELS``, evenly spread) and a note when not all."""
    groups = group_indices(frag)
    if len(groups) <= MAX_PANELS:
        return list(range(len(groups))), groups, ""
    chosen = np.unique(np.linspace(0, len(groups) - 1, MAX_PANELS).round().astype(int))
    return list(chosen), groups, f" ({len(chosen)} of {len(groups)} groups shown)"


def _panels(count):
    """A figure of ``count`` panels sharing their axes, three to a row; its visible axes."""
    columns = min(COLUMNS, count)
    rows = math.ceil(count / columns)
    fig, axes = plt.subplots(rows, columns, figsize=(max(4.8 * columns, MIN_WIDTH),
                                                     3.9 * rows + 0.9),
                             layout="constrained", squeeze=False, sharex=True, sharey=True)
    for ax in axes.flat[count:]:
        ax.set_visible(False)
    return fig, list(axes.flat[:count])


def _interval_text(value, lower, upper, unit=""):
    """"6.57 m/s² [5.94, 7.28]"."""
    unit = f" {unit}" if unit else ""
    return f"{value:.3g}{unit} [{lower:.3g}, {upper:.3g}]"


def figure(kind, frag, ds, over, im, levels):
    """The fragility figure of ``kind`` of ``frag``: ``"curves"`` (:func:`figure_curves`) or
    ``"map"`` (:func:`figure_map`, the cells of the study dataset ``ds``, as
    ``sweep.probability.fragility.fragility(ds, over, im, levels)`` takes them)."""
    if kind == "map":
        pga, pgv = (cells(ds, over, name, levels).im for name in ("pga", "pgv"))
        return figure_map(frag, pga, pgv, cells(ds, over, im, levels).outcome)
    return figure_curves(frag)


def figure_curves(frag):
    """Fragility curves of every group (panels): p̂ with intervals, the fit with its band.

    Parameters
    ----------
    frag : xarray.Dataset
        A fragility dataset.

    Returns
    -------
    matplotlib.figure.Figure
    """
    im = frag.attrs["intensity_measure"]
    label, factor = IM_AXES[im]
    binned = frag.attrs["level_dimension"] == "none"
    interval = frag.attrs["interval_method"].split()[0]
    shown, groups, note = _shown_groups(frag)
    fig, axes = _panels(len(shown))
    confidence = f"{float(frag.attrs['confidence']):.0%}"
    for ax, which in zip(axes, shown):
        index = groups[which]
        group = frag.isel(index)
        p = group["p_overturned"].values
        x = group["im_median"].values * factor
        present = np.isfinite(p) & np.isfinite(x)
        ax.errorbar(x[present], p[present],
                    yerr=[p[present] - group["p_overturned_lower"].values[present],
                          group["p_overturned_upper"].values[present] - p[present]],
                    **DATA_STYLE)
        sides = asymmetric(group) and "p_overturned_left" in group
        if sides:
            _draw_sides(ax, group, x, present)
        grid = frag["im_grid"].values * factor
        if int(group["fit_status"]) == 0:
            ax.fill_between(grid, group["p_fit_lower"], group["p_fit_upper"], **BAND_STYLE)
            theta = [float(group[n]) * factor for n in ("theta", "theta_lower",
                                                        "theta_upper")]
            beta = [float(group[n]) for n in ("beta", "beta_lower", "beta_upper")]
            ax.plot(grid, group["p_fit"], **FIT_STYLE)
            fit = f"θ = {_interval_text(*theta, IM_UNITS[im])}, β = {_interval_text(*beta)}"
        else:
            reason = _flag_meaning(frag["fit_status"], int(group["fit_status"]))
            fit = f"no lognormal fit: {reason.replace('_', ' ')}"
        # the fit's numbers under the group's name: no legend inside the panel to hide data
        name = describe_group(group_coords(frag, index)) + (_angles_text(group) if sides else "")
        ax.set_title(f"{name}\n{fit}", fontsize=9)
        ax.grid(True, which="major", alpha=0.3)
    first = axes[0]
    first.set_xscale("log")
    plain_log_axis(first.xaxis)
    first.set_ylim(-0.03, 1.03)
    _label_outer(axes, label, "P(overturning)")
    members = int(frag["n_members"].max())
    entries = [(Line2D([], [], ls="", marker="o", ms=4, color=DATA_COLOUR),
                f"k/n at each {'bin' if binned else 'level'} (n ≤ {members}), "
                f"{interval} interval"),
               (Line2D([], [], **FIT_STYLE), "lognormal fit (θ, β: panel titles)"),
               (Patch(**BAND_STYLE), f"{confidence} pointwise band of the fit")]
    if any(asymmetric(frag.isel(groups[which])) for which in shown) and \
            "p_overturned_left" in frag:
        entries.append((tuple(Line2D([], [], **style) for style in SIDE_STYLES.values()),
                        "k/n that fell left (−x) / right (+x)"))
    handles, labels = zip(*entries)
    fig.legend(handles=handles, labels=labels, loc="outside lower center", fontsize=8,
               frameon=False, handler_map={tuple: HandlerTuple(ndivide=None)},
               ncols=legend_columns(fig, labels, 8))
    if im in ("pga", "ground_pga"):
        for ax in axes[:COLUMNS]:
            top = ax.secondary_xaxis("top", functions=(lambda a: a / G, lambda a: a * G))
            plain_log_axis(top.xaxis)
            top.set_xlabel(f"{label.split(' [')[0]} [g]", fontsize=8)
            top.tick_params(labelsize=8)
    band = BAND_METHODS[frag.attrs["fit_interval"]]
    _title(fig, frag, "fragility curves" + note, f"{confidence} intervals; band: {band}")
    fit_texts(fig)
    return fig


def _draw_sides(ax, group, x, present):
    """The probability of overturning to each side at each level where any member overturned,
    beside it (``gid`` "left", "right")."""
    shown = present & (group["k_overturned"].values > 0)
    for side, style in SIDE_STYLES.items():
        ax.plot(x[shown] * SIDE_SHIFT[side], group[f"p_overturned_{side}"].values[shown],
                **style, gid=side)


def _angles_text(group):
    """" (α_1 20°, α_2 12°)": each side's angle of a group's body."""
    return (f" (α_1 {math.degrees(float(group['alpha_1'])):.3g}°, "
            f"α_2 {math.degrees(float(group['alpha_2'])):.3g}°)")


def _label_outer(axes, xlabel, ylabel):
    """Axis labels on the panels at the bottom of each column and the left of each row;
    tick labels under every panel with none below it (shared axes hide them)."""
    for ax in axes:
        spec = ax.get_subplotspec()
        if spec.num1 + spec.get_gridspec().ncols >= len(axes):  # no panel below
            ax.set_xlabel(xlabel)
            ax.xaxis.set_tick_params(labelbottom=True)
        if spec.is_first_col():
            ax.set_ylabel(ylabel)


def _flag_meaning(da, code):
    meanings = da.attrs["flag_meanings"].split()
    return meanings[list(np.asarray(da.attrs["flag_values"])).index(code)]


def _title(fig, frag, what, details):
    """The figure's title, two lines at most (``style.fit_suptitle``): the study and what is
    drawn; the ensemble, ``details`` and the failed cells."""
    levels = frag.attrs["level_dimension"]
    along = f", levels {levels}" if levels != "none" else ", binned in ln IM"
    members = ", ".join(str(frag.attrs["ensemble_dimensions"]).split())
    failed = int(frag.attrs["failed_cells"])
    return fit_suptitle(fig, [f"{frag.attrs.get('input_title') or 'study'}: {what}",
                              f"members over {members}{along}; {details}; "
                              + (f"{failed} failed cells left out" if failed else
                                 "no failed cells")])


def figure_map(frag, pga, pgv, outcome):
    """Two-parameter fragility maps over (PGA, PGV), one panel per group.

    Parameters
    ----------
    frag : xarray.Dataset
        A fragility dataset with ``surface_coefficient``.
    pga, pgv : ndarray, shape (groups, levels, members)
        PGA [m/s²] and PGV [m/s] of the cells, groups in the order of ``frag``.
    outcome : ndarray of int, shape (groups, levels, members)
        Their outcome codes (failed cells are not drawn).

    Returns
    -------
    matplotlib.figure.Figure
    """
    shown, groups, note = _shown_groups(frag)
    fig, axes = _panels(len(shown))
    counted = outcome != codes.FAILED
    usable = counted & (pga > 0) & (pgv > 0)
    x_range = _log_range(pga[usable])
    y_range = _log_range(pgv[usable] * CM)
    grid_x, grid_y = np.meshgrid(np.geomspace(*x_range, 120), np.geomspace(*y_range, 120))
    filled = None
    for ax, which in zip(axes, shown):
        index = groups[which]
        group = frag.isel(index)
        b0, b1, b2 = group["surface_coefficient"].values
        west = float(group["west_acceleration"]) if "west_acceleration" in group else np.nan
        if int(group["surface_status"]) == 0:
            from scipy.special import ndtr
            surface = ndtr(b0 + b1 * np.log(grid_x) + b2 * np.log(grid_y / CM))
            if np.isfinite(west):  # no rocking below West's acceleration (Eq. 1)
                surface = np.where(grid_x < west, 0.0, surface)
            filled = ax.contourf(grid_x, grid_y, surface, levels=np.linspace(0, 1, 11),
                                 cmap="YlOrRd", alpha=0.85)
            # the lines end at West's acceleration, so that their labels sit on the fit
            lines = ax.contour(grid_x, grid_y, np.where(grid_x < west, np.nan, surface),
                               levels=PROBABILITY_LINES, colors="k",
                               linewidths=(0.8, 1.4, 0.8))
            ax.clabel(lines, fmt=lambda v: f"P = {v:g}", fontsize=7.5)
        else:
            reason = _flag_meaning(frag["surface_status"], int(group["surface_status"]))
            ax.text(0.03, 0.95, f"no surface fit: {reason.replace('_', ' ')}",
                    transform=ax.transAxes, fontsize=8, va="top")
        over = usable[which] & (outcome[which] == codes.OVERTURN)
        stand = usable[which] & (outcome[which] != codes.OVERTURN)
        ax.scatter(pga[which][stand], pgv[which][stand] * CM, **STANDING_STYLE)
        ax.scatter(pga[which][over], pgv[which][over] * CM, **OVERTURNED_STYLE)
        if np.isfinite(west):
            ax.axvline(west, color="k", ls="--", lw=1)
            ax.annotate("West: (B/H) g", (west, 1.0), xycoords=("data", "axes fraction"),
                        xytext=(3, -12), textcoords="offset points", fontsize=7.5)
        ax.set_title(describe_group(group_coords(frag, index)), fontsize=9)
    first = axes[0]
    first.set_xscale("log")
    first.set_yscale("log")
    plain_log_axis(first.xaxis)
    plain_log_axis(first.yaxis)
    first.set_xlim(*x_range)
    first.set_ylim(*y_range)
    _label_outer(axes, "PGA [m/s²]", "PGV [cm/s]")
    handles = [Line2D([], [], ls="", **_legend_marker(OVERTURNED_STYLE), label="overturned"),
               Line2D([], [], ls="", **_legend_marker(STANDING_STYLE), label="standing")]
    fig.legend(handles=handles, loc="outside lower center", ncol=2, fontsize=8,
               frameon=False)
    if filled is not None:
        fig.colorbar(filled, ax=list(axes), label="P(overturning) = "
                     "Φ(b0 + b1 ln PGA + b2 ln PGV)", shrink=0.9)
    _title(fig, frag, "two-parameter fragility over (PGA, PGV)" + note,
           "probit fit to every cell")
    fit_texts(fig)
    return fig


def _log_range(values):
    """(low, high) around positive ``values`` with a margin of 15 % in the log."""
    if values.size == 0:
        return 0.1, 10.0
    low, high = np.log(values.min()), np.log(values.max())
    margin = max(0.15 * (high - low), np.log(1.2))
    return math.exp(low - margin), math.exp(high + margin)


def _legend_marker(style):
    """Line2D keywords drawing a scatter ``style``'s marker."""
    face = style.get("facecolors", style.get("color"))
    edge = style.get("edgecolors", face)
    return {"marker": style["marker"], "markersize": math.sqrt(style["s"]),
            "markerfacecolor": face, "markeredgecolor": edge}
