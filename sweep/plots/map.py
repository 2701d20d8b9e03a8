"""Outcome maps of a study, and the boundaries of a refine study.

One panel per value of the other axes, cells coloured by outcome.

Reads only the Dataset of ``sweep.run`` (``outcome`` with its ``flag_values`` and
``flag_meanings``, coordinates with ``units``, ``long_name`` and ``study_axis``).  By default
frequency runs along x (log scale when the values are log-spaced) and amplitude along y; an
amplitude in West's units gets the line amplitude = 1, West's criterion for the start of
rocking (Eq. 1).  Cells whose body slid (``slid``: its base moved more than 1 cm along the
floor) carry a cross, so that a squat body that slid far is not read as "no rocking" alone.  A panel whose axes leave the body fixed is
titled with the body ("B 10 cm × H 30 cm (b/h 0.333)", from the study's base scene and the
panel's values of ``B``, ``H``, ``b_over_h`` and ``size``), the other axes' values follow
with their units.

An axis of strings (``record``: bundled names, paths, the files of a ``{glob: ...}``; or any
other) is categorical: one row or column of cells per value, named by its tick label (a file
by its name, without its folder).  Unless ``x`` or ``y`` is given, such an axis runs along y,
one row per record from the top, and the numeric axis beside it (``pga``, ``scale``) along x:
the record x PGA map reads as one strip of outcomes per record against the intensity, with
the names written level whatever their length (``--x record`` gives one column per record,
names slanted).  An axis of integers (``seed``) has integer ticks, and an axis of a few values
a tick on each.  Levels are drawn in the unit the study wrote them in (``study_unit``: a
``pga`` axis written in g is drawn in g, though stored in m/s^2).  Titles take at most two lines and axis labels are wrapped to their axes
(``style.fit_texts``).

A refine study's dataset (``cf.REFINE_VARIABLES``) is drawn by :func:`figure_boundary`: the
boundary along the refined axis against another axis, with its bracket, over the coarse
values seen standing and overturned.
"""
import itertools
from pathlib import PurePath

import matplotlib.pyplot as plt
import numpy as np
import yaml
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.ticker import LogLocator, MaxNLocator, NullFormatter, ScalarFormatter

from ..cf import SLID_THRESHOLD
from ..io import units
from ..runner.verdict import length_text
from .style import (OUTCOME_COLOURS, POINTS_PER_INCH, RELATIVE_LABELS, axis_label, cell_edges,
                    fit_suptitle, fit_texts, outcome_colours, study_axis, text_width)

MAX_PANELS = 6  # more combinations of the other axes than this: the first ones are drawn
FEW_VALUES = 8  # a linear axis of at most this many values gets a tick on each
CATEGORY_INCHES = 0.22  # room of one row or column of a string axis (8-point names)
CATEGORY_FONT_SIZE = 8
BODY_AXES = ("B", "H", "b_over_h", "size", "body.B", "body.H")  # study axes that change the body


def _value_text(coord, value):
    """'mu = 0.4', 'frequency = 4 Hz', 'amplitude = 1.5 west', 'record = elcentro1940_ns'."""
    if coord.dtype.kind not in "fi":
        return f"{coord.name} = {value}"
    unit = coord.attrs.get("study_unit")
    if unit not in RELATIVE_LABELS:  # the coordinate is in its units (SI, or degree)
        unit = coord.attrs.get("units", "")
    return f"{coord.name} = {value:.4g}" + ("" if unit in ("", "1") else f" {unit}")


def in_study_units(ds):
    """``ds`` with every numeric dimension coordinate in the fixed unit its study was written
    in (a ``pga`` axis of 0.1 g steps is drawn as 0.1, 0.2 ... g, not 0.9807, 1.961 ... m s-2);
    coordinates in SI, degrees or body-relative units as stored are kept."""
    shown = {}
    for name in ds.dims:
        coord = ds.coords.get(name)
        unit = None if coord is None else coord.attrs.get("study_unit")
        if (unit is None or unit in RELATIVE_LABELS or coord.dtype.kind != "f"
                or coord.attrs.get("units") == "degree"):
            continue
        for dimension in units.DIMENSIONS:
            try:
                factor = units.fixed_factor(unit, dimension)
            except ValueError:
                continue
            if factor != 1.0:
                shown[name] = (coord / factor).assign_attrs({**coord.attrs, "units": unit})
            break
    return ds.assign_coords(shown)


def _base_body(ds):
    """B and H [m] of the study's base scene (its ``study`` attribute), or None."""
    scene = (yaml.safe_load(ds.attrs.get("study", "")) or {}).get("scene") or {}
    body = scene.get("body") or {}
    try:
        return tuple(units.parse_quantity(body[key], "length").to_si() for key in "BH")
    except (KeyError, ValueError):
        return None


def _body_text(ds, values):
    """'B 10 cm × H 30 cm (b/h 0.333)': the base body with the body axes among ``values``
    ({study axis: coordinate}) applied as a study's cells apply them, or None."""
    body = _base_body(ds)
    if body is None:
        return None
    B, H = body
    B = values.get("B", values.get("body.B", B))
    H = values.get("H", values.get("body.H", H))
    if "b_over_h" in values:
        H = B / values["b_over_h"]
    if "size" in values:
        B, H = B * values["size"], H * values["size"]
    return f"B {length_text(B)} × H {length_text(H)} (b/h {B / H:.3g})"


def panel_title(ds, sel, x, y):
    """Title of the panel ``sel`` ({dimension: index}) of a map along ``x`` and ``y``: the
    body when the panel's axes leave it fixed, then every other value with its unit."""
    along = [ds[c] for c in ds.coords if set(ds[c].dims) & {x, y}]
    coords = [(ds[c], int(sel[ds[c].dims[0]])) for c in ds.coords
              if len(ds[c].dims) == 1 and ds[c].dims[0] in sel]
    texts = [_value_text(c, c.values[i]) for c, i in coords if study_axis(c) not in BODY_AXES]
    if not any(study_axis(c) in BODY_AXES for c in along):
        body = _body_text(ds, {study_axis(c): float(c.values[i]) for c, i in coords
                               if study_axis(c) in BODY_AXES})
        if body is not None:
            return "; ".join([body, *texts])
    return ", ".join(_value_text(c, c.values[i]) for c, i in coords)


def categorical(coord):
    """Whether a coordinate's values are names (strings), drawn one row or column each."""
    return coord.dtype.kind not in "biuf"


def category_labels(values):
    """Tick labels of a string axis: each value, a path by its file name (the whole value
    where two files share a name)."""
    names = [PurePath(str(v)).name or str(v) for v in values]
    return names if len(set(names)) == len(names) else [str(v) for v in values]


def cells_along(coord):
    """Where a map puts the cells of ``coord``: (centres, edges, scale), scale 'category'
    (centres 0, 1, ...: one per name), 'log' (log-spaced values) or 'linear'."""
    if categorical(coord):
        return np.arange(coord.size, dtype=float), np.arange(coord.size + 1) - 0.5, "category"
    values = np.asarray(coord.values, dtype=float)
    log = _log_spaced(values)
    return values, cell_edges(values, log), "log" if log else "linear"


def _label(coord):
    """Axis label of a map: the names of a string axis say what they are, so its own name
    ('record'); otherwise ``style.axis_label``."""
    return coord.name if categorical(coord) else axis_label(coord)


def _ticks(ax, which, coord, centres, scale):
    """Ticks of the ``which`` ('x' or 'y') axis of a map along ``coord``: names on a string
    axis (first at the top along y, slanted along x), plain numbers at 1, 2, 5 x 10^k on a
    log axis, integers on an integer axis, and a tick on each of a few values."""
    axis = ax.xaxis if which == "x" else ax.yaxis
    if scale == "category":
        axis.set_ticks(centres, labels=category_labels(coord.values),
                       fontsize=CATEGORY_FONT_SIZE)
        axis.set_tick_params(which="minor", length=0)
        if which == "y":
            ax.invert_yaxis()
        else:
            plt.setp(axis.get_ticklabels(), rotation=30, ha="right", rotation_mode="anchor")
        return
    if scale == "log":
        (ax.set_xscale if which == "x" else ax.set_yscale)("log")
        axis.set_major_formatter(ScalarFormatter())
        axis.set_minor_formatter(NullFormatter())
        axis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
        return
    integer = coord.dtype.kind in "iu"
    if centres.size <= FEW_VALUES:
        axis.set_ticks(centres, labels=[f"{int(v)}" if integer else f"{v:.4g}"
                                        for v in centres])
    elif integer:
        axis.set_major_locator(MaxNLocator(integer=True))


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
        chosen = x is None and y is None
        y = y or rest.pop(0)
        x = x or rest.pop(0)
        if chosen and categorical(ds[x]) and not categorical(ds[y]):
            x, y = y, x  # names along y, written level; the numbers along x
    for name in (x, y):
        if name not in dims:
            raise ValueError(f"{name!r} is not a dimension of the dataset: {dims}")
    return x, y


def _mark_slid(ax, slid, x, y, xs, ys):
    """A small cross on every cell whose body slid (``slid`` == 1), the cells centred at
    ``xs`` and ``ys``; True if any."""
    slid = slid.transpose(y, x)
    X, Y = np.meshgrid(xs, ys)
    hit = slid.values == 1
    ax.scatter(X[hit], Y[hit], marker="x", s=10, c="k", linewidths=0.7)
    return bool(hit.any())


def draw_outcome_map(ax, da, x, y, legend=True, slid=None, slid_elsewhere=False):
    """Draw one 2-D outcome slice ``da`` (dims x and y) on ``ax``; cells of ``slid`` == 1
    (the same slice of the dataset's ``slid``) get a cross, which the legend explains when
    this slice or, with ``slid_elsewhere``, another panel of the figure has one."""
    da = da.transpose(y, x)
    (xs, x_edges, x_scale), (ys, y_edges, y_scale) = cells_along(da[x]), cells_along(da[y])
    cmap, norm = outcome_colours()
    ax.pcolormesh(x_edges, y_edges, da.values, cmap=cmap, norm=norm, edgecolors="white",
                  linewidth=0.3)
    _ticks(ax, "x", da[x], xs, x_scale)
    _ticks(ax, "y", da[y], ys, y_scale)
    ax.set_xlabel(_label(da[x]))
    ax.set_ylabel(_label(da[y]))
    if da[y].attrs.get("study_unit") == "west":
        ax.axhline(1.0, color="k", ls="--", lw=1)
        ax.annotate("West: a = (B/H) g", (xs.max(), 1.0), xytext=(-2, 3), ha="right",
                    textcoords="offset points", fontsize=8)
    any_slid = slid is not None and _mark_slid(ax, slid, x, y, xs, ys)
    if legend:
        meanings = da.attrs.get("flag_meanings", "failed no_rocking rocked overturned").split()
        values = list(np.atleast_1d(da.attrs.get("flag_values", sorted(OUTCOME_COLOURS))))
        present = set(np.unique(da.values).tolist())
        handles = [Patch(color=OUTCOME_COLOURS[int(v)], label=m.replace("_", " "))
                   for v, m in zip(values, meanings) if int(v) in present or int(v) >= 0]
        if any_slid or slid_elsewhere:
            handles.append(Line2D([], [], marker="x", color="k", ls="", markersize=5,
                                  label=f"slid (base > {length_text(SLID_THRESHOLD)})"))
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0),
                  fontsize=8, frameon=False)


def figure_map(ds, x=None, y=None):
    """Outcome map(s) of a study Dataset, or the boundaries of a refine study's
    (:func:`figure_boundary`): a matplotlib Figure.

    Parameters
    ----------
    ds : xarray.Dataset
        A dataset of ``sweep.run`` (``outcome``, or ``boundary`` from a refine study).
    x, y : str, optional
        Dimensions along x and y; default frequency and amplitude, else the first two.
    """
    if "boundary" in ds:
        return figure_boundary(ds, x, y)
    ds = in_study_units(ds)
    x, y = _axes_of(ds, x, y)
    outcome = ds["outcome"]
    others = [d for d in outcome.dims if d not in (x, y)]
    combos = list(itertools.product(*(range(ds.sizes[d]) for d in others)))[:MAX_PANELS]
    n = len(combos)
    cols = min(n, 3)
    rows = int(np.ceil(n / cols))
    width, height = 4.6, 3.8  # of a panel [in]; more for many names along an axis
    if categorical(ds[x]):
        width = max(width, CATEGORY_INCHES * ds.sizes[x] + 1.6)
    if categorical(ds[y]):  # the names written level beside the panel
        height = max(height, CATEGORY_INCHES * ds.sizes[y] + 1.4)
        width += max(text_width(name, CATEGORY_FONT_SIZE)
                     for name in category_labels(ds[y].values)) / POINTS_PER_INCH
    fig, axes = plt.subplots(rows, cols, figsize=(width * cols + 1.4, height * rows),
                             squeeze=False, layout="constrained")
    slid = [ds["slid"].isel(dict(zip(others, combo))) if "slid" in ds else None
            for combo in combos]
    slid_shown = any(s is not None and bool((s == 1).any()) for s in slid)
    for k, combo in enumerate(combos):
        ax = axes.flat[k]
        sel = dict(zip(others, combo))
        draw_outcome_map(ax, outcome.isel(sel), x, y, legend=(k == cols - 1 or n == 1),
                         slid=slid[k], slid_elsewhere=slid_shown)
        ax.set_title(panel_title(ds, sel, x, y), fontsize=10)
    for ax in axes.flat[n:]:
        ax.set_visible(False)
    fit_suptitle(fig, ds.attrs.get("title", "outcome map"), fontsize=11)
    fit_texts(fig)
    return fig


# refine studies: the boundary found by bisection -------------------------------------------

# coarse_overturned code -> colour of the coarse cells behind a boundary: failed, stood, fell
COARSE_COLOURS = {-1: OUTCOME_COLOURS[-1], 0: OUTCOME_COLOURS[0], 1: "#fcbba1"}
# lines without a bracket: bracket flag -> (marker, where it is drawn, legend text)
UNBRACKETED = {"never_overturned": ("^", "boundary_lower", "stood up to the highest value"),
               "overturned_at_start": ("v", "boundary_upper", "overturned at the lowest value"),
               "simulation_failed": ("X", "boundary_lower", "a simulation failed")}


def refined_dimension(ds):
    """The dimension a refine dataset was bisected along (``coarse_overturned`` has it,
    ``boundary`` not)."""
    return next(d for d in ds["coarse_overturned"].dims if d not in ds["boundary"].dims)


def _bracket_codes(ds):
    """{bracket name: code} from the ``flag_meanings`` of ``bracket``."""
    attrs = ds["bracket"].attrs
    return dict(zip(attrs["flag_meanings"].split(), np.atleast_1d(attrs["flag_values"])))


def draw_boundary(ax, ds, x):
    """One line of boundaries of a refine dataset ``ds`` (every dimension but ``x`` and the
    refined one already selected): the coarse cells, standing and overturned, behind the
    boundary with its bracket as error bars and markers for lines without a bracket.
    Returns the legend's handles."""
    y = refined_dimension(ds)
    coarse = ds["coarse_overturned"].transpose(y, x)
    (xs, x_edges, x_scale), (_, y_edges, _) = cells_along(ds[x]), cells_along(ds[y])
    codes = sorted(COARSE_COLOURS)
    cmap = plt.matplotlib.colors.ListedColormap([COARSE_COLOURS[c] for c in codes])
    norm = plt.matplotlib.colors.BoundaryNorm(np.arange(codes[0] - 0.5, codes[-1] + 1.0), cmap.N)
    ax.pcolormesh(x_edges, y_edges, coarse.values, cmap=cmap, norm=norm, edgecolors="white",
                  linewidth=0.3)
    _ticks(ax, "x", ds[x], xs, x_scale)
    boundary, lower, upper = (ds[name].values for name in
                              ("boundary", "boundary_lower", "boundary_upper"))
    ax.errorbar(xs, boundary, yerr=[boundary - lower, upper - boundary], color="k", lw=1.2,
                marker="o", markersize=3, capsize=3, zorder=3)
    handles = [Line2D([], [], color="k", marker="o", markersize=3,
                      label="boundary (bars: highest\nstanding, lowest overturned)"),
               Patch(color=COARSE_COLOURS[0], label="coarse value: stood"),
               Patch(color=COARSE_COLOURS[1], label="coarse value: overturned")]
    flags = ds["bracket"].values
    for name, code in _bracket_codes(ds).items():
        if name in UNBRACKETED and np.any(flags == code):
            marker, where, text = UNBRACKETED[name]
            ax.plot(xs[flags == code], ds[where].values[flags == code], ls="", marker=marker,
                    color="k", markersize=7, zorder=3)
            handles.append(Line2D([], [], ls="", marker=marker, color="k", label=text))
    ax.set_xlabel(_label(ds[x]))
    ax.set_ylabel(f"overturning boundary: {axis_label(ds[y])}")
    if ds[y].attrs.get("study_unit") == "west":
        ax.axhline(1.0, color="k", ls="--", lw=1)
        ax.annotate("West: a = (B/H) g", (xs.min(), 1.0), xytext=(2, -11),
                    textcoords="offset points", fontsize=8)
    return handles


def figure_boundary(ds, x=None, y=None):
    """The boundaries of a refine study's Dataset (``cf.refine_dataset``): a matplotlib
    Figure, one panel per value of the dimensions other than ``x`` and the refined one.

    Parameters
    ----------
    ds : xarray.Dataset
        Needs ``boundary``, ``boundary_lower``, ``boundary_upper``, ``bracket`` and
        ``coarse_overturned``.
    x : str, optional
        Dimension along x: default the first dimension of ``boundary``.
    y : str, optional
        The refined dimension, always along y (any other is refused).
    """
    refined = refined_dimension(ds)
    if y not in (None, refined):
        raise ValueError(f"a boundary is drawn with its refined dimension {refined!r} along y, "
                         f"not {y!r}")
    lines = list(ds["boundary"].dims)
    if not lines:
        raise ValueError("the refine study has no other axis to draw its boundary against")
    x = x or lines[0]
    if x not in lines:
        raise ValueError(f"{x!r} is not a dimension of the boundaries: {lines}")
    others = [d for d in lines if d != x]
    combos = list(itertools.product(*(range(ds.sizes[d]) for d in others)))[:MAX_PANELS]
    cols = min(len(combos), 3)
    rows = int(np.ceil(len(combos) / cols))
    fig, axes = plt.subplots(rows, cols, figsize=(4.8 * cols + 2.2, 3.9 * rows),
                             squeeze=False, layout="constrained")
    for ax, combo in zip(axes.flat, combos):
        sel = dict(zip(others, combo))
        handles = draw_boundary(ax, ds.isel(sel), x)
        ax.set_title(panel_title(ds, sel, x, refined), fontsize=10)
    axes.flat[min(len(combos), cols) - 1].legend(handles=handles, loc="upper left",
                                                 bbox_to_anchor=(1.01, 1.0), fontsize=8,
                                                 frameon=False)
    for ax in axes.flat[len(combos):]:
        ax.set_visible(False)
    fit_suptitle(fig, [ds.attrs.get("title", "overturning boundary"),
                       f"bisection to {ds.attrs.get('refine_tolerance', np.nan):g} "
                       f"{_tolerance_unit(ds[refined])}: "
                       f"{ds.attrs.get('refine_simulations', '?')} simulations (a grid of the "
                       f"same resolution: {ds.attrs.get('refine_dense_grid_simulations', '?')})"])
    fit_texts(fig)
    return fig


def _tolerance_unit(coord):
    unit = coord.attrs.get("study_unit") or coord.attrs.get("units", "")
    return "" if unit == "1" else unit
