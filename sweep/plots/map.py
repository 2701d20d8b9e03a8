"""Outcome maps of a study: one panel per value of the other axes, cells coloured by outcome.

Reads only the Dataset of ``sweep.run`` (``outcome`` with its ``flag_values`` and
``flag_meanings``, coordinates with ``units`` and ``long_name``).  By default frequency runs
along x (log scale when the values are log-spaced) and amplitude along y; an amplitude in
West's units gets the line amplitude = 1, West's criterion for the start of rocking (Eq. 1).  Cells whose body slid (``slid``) carry a
cross, so that a squat body that slid far is not read as "no rocking" alone.
"""
import itertools

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.ticker import LogLocator, NullFormatter, ScalarFormatter

from .style import OUTCOME_COLOURS, cell_edges, outcome_colours

MAX_PANELS = 6  # more combinations of the other axes than this: the first ones are drawn


# short labels of axes in the paper's body-relative units
RELATIVE_LABELS = {"west": "{} / (B/H) g", "v_H": "{} / v_H", "alpha": "{} / α"}


def _label(da):
    """Axis label ``long name [units]`` (no brackets for a dimensionless ratio)."""
    unit = da.attrs.get("study_unit")
    if unit in RELATIVE_LABELS:
        return RELATIVE_LABELS[unit].format(da.name)
    name = da.attrs.get("long_name", da.name)
    units = da.attrs.get("units", "")
    return name if units in ("", "1") else f"{name} [{units}]"


def _log_spaced(values):
    v = np.asarray(values, dtype=float)
    if v.size < 3 or np.any(v <= 0):
        return False
    ratios = v[1:] / v[:-1]
    return np.allclose(ratios, ratios[0], rtol=1e-6) and not np.allclose(ratios, 1.0)


def _axes_of(ds, x, y):
    dims = [d for d in ds["outcome"].dims]
    if x is None and y is None and "frequency" in dims and "amplitude" in dims:
        return "frequency", "amplitude"
    if x is None or y is None:
        rest = [d for d in dims if d not in (x, y)]
        if len(rest) < (x is None) + (y is None):
            raise ValueError(f"an outcome map needs two dimensions; the dataset has {dims}")
        y = y or rest.pop(0)
        x = x or rest.pop(0)
    for name in (x, y):
        if name not in dims:
            raise ValueError(f"{name!r} is not a dimension of the dataset: {dims}")
    return x, y


def _mark_slid(ax, slid, x, y):
    """A small cross on every cell whose body slid (``slid`` == 1); True if any."""
    slid = slid.transpose(y, x)
    X, Y = np.meshgrid(slid[x].values, slid[y].values)
    hit = slid.values == 1
    ax.scatter(X[hit], Y[hit], marker="x", s=10, c="k", linewidths=0.7)
    return bool(hit.any())


def draw_outcome_map(ax, da, x, y, legend=True, slid=None):
    """Draw one 2-D outcome slice ``da`` (dims x and y) on ``ax``; cells of ``slid`` == 1
    (the same slice of the dataset's ``slid``) get a cross."""
    da = da.transpose(y, x)
    xs, ys = da[x].values, da[y].values
    logx, logy = _log_spaced(xs), _log_spaced(ys)
    cmap, norm = outcome_colours()
    ax.pcolormesh(cell_edges(xs, logx), cell_edges(ys, logy), da.values, cmap=cmap, norm=norm,
                  edgecolors="white", linewidth=0.3)
    for log, axis, scale in ((logx, ax.xaxis, ax.set_xscale), (logy, ax.yaxis, ax.set_yscale)):
        if log:
            scale("log")
            axis.set_major_formatter(ScalarFormatter())
            axis.set_minor_formatter(NullFormatter())
            axis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
    ax.set_xlabel(_label(da[x]))
    ax.set_ylabel(_label(da[y]))
    if da[y].attrs.get("study_unit") == "west":
        ax.axhline(1.0, color="k", ls="--", lw=1)
        ax.annotate("West: a = (B/H) g", (xs.min(), 1.0), xytext=(2, 3),
                    textcoords="offset points", fontsize=8)
    any_slid = slid is not None and _mark_slid(ax, slid, x, y)
    if legend:
        meanings = da.attrs.get("flag_meanings", "failed no_rocking rocked overturned").split()
        values = list(np.atleast_1d(da.attrs.get("flag_values", sorted(OUTCOME_COLOURS))))
        present = set(np.unique(da.values).tolist())
        handles = [Patch(color=OUTCOME_COLOURS[int(v)], label=m.replace("_", " "))
                   for v, m in zip(values, meanings) if int(v) in present or int(v) >= 0]
        if any_slid:
            handles.append(Line2D([], [], marker="x", color="k", ls="", markersize=5,
                                  label="slid"))
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0),
                  fontsize=8, frameon=False)


def figure_map(ds, x=None, y=None):
    """Outcome map(s) of a study Dataset: a matplotlib Figure.

    Parameters
    ----------
    ds : xarray.Dataset
        A dataset of ``sweep.run`` (needs ``outcome``).
    x, y : str, optional
        Dimensions along x and y; default frequency and amplitude, else the first two.
    """
    x, y = _axes_of(ds, x, y)
    outcome = ds["outcome"]
    others = [d for d in outcome.dims if d not in (x, y)]
    combos = list(itertools.product(*(range(ds.sizes[d]) for d in others)))[:MAX_PANELS]
    n = len(combos)
    cols = min(n, 3)
    rows = int(np.ceil(n / cols))
    fig, axes = plt.subplots(rows, cols, figsize=(4.6 * cols + 1.4, 3.8 * rows),
                             squeeze=False, layout="constrained")
    for k, combo in enumerate(combos):
        ax = axes.flat[k]
        sel = dict(zip(others, combo))
        draw_outcome_map(ax, outcome.isel(sel), x, y, legend=(k == cols - 1 or n == 1),
                         slid=ds["slid"].isel(sel) if "slid" in ds else None)
        title = ", ".join(f"{d} = {ds[d].values[i]:.4g}" if ds[d].dtype.kind == "f"
                          else f"{d} = {ds[d].values[i]}" for d, i in sel.items())
        ax.set_title(title, fontsize=10)
    for ax in axes.flat[n:]:
        ax.set_visible(False)
    fig.suptitle(ds.attrs.get("title", "outcome map"), fontsize=11)
    return fig
