"""Rocking spectra: peak |theta|/alpha of blocks under one motion against their p.

After Makris & Konstantinidis (2003, EESD 32): rectangular blocks under one floor motion
against their frequency parameter p, one line per slenderness.

A study of bodies of several sizes under one motion (axes ``B`` or ``size`` with ``b_over_h``,
e.g. ``studies/rocking_spectrum_elcentro.yaml``) is read like a response spectrum: p along x
(p^2 = g r/(i^2 + r^2), for a uniform block sqrt(3g/4R) with R the half-diagonal), the peak
rotation over the slenderness angle along y, and the overturned blocks as marks in a band above
|theta|/alpha = 1, one row per line.  Each cell's body and motion come from the study kept in
the dataset's attributes (``sweep.paper.classify.study_of``), so any axes that set the body
work.  SI units throughout; docs/physics.md 1.1 for the symbols.  The title takes two lines at most
(the study; its motion, peaks and contact) and the legend a corner free of lines and marks,
else the outside of the axes (``style.place_legend``).
"""
import itertools
import math

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from ..bodies import G
from ..paper import classify, criteria
from .style import fit_suptitle, fit_texts, place_legend, plain_log_axis

MAX_LINES = 10  # more combinations of the other axes than this: the first ones are drawn
BAND_TOP = {"log": 2.6, "linear": 1.45}  # top of the y axis, above the overturned band at 1
MARKER_SIZE = 3.5


# --- what the dataset holds -------------------------------------------------------------------

def cell_blocks(ds):
    """The body of every cell of a study's dataset.

    Parameters
    ----------
    ds : xarray.Dataset
        A dataset of ``sweep.run`` (its ``study`` attribute holds the study's text).

    Returns
    -------
    xarray.Dataset
        On the dimensions of ``outcome``: ``breadth`` B and ``height`` H [m], ``R``
        half-diagonal [m], ``alpha`` [rad], ``p`` frequency parameter [rad/s] and ``uniform``
        (no ``i_g`` given).

    References
    ----------
    docs/physics.md 1.1: p^2 = g r/(i^2 + r^2), uniform rectangle i^2 = r^2/3.
    """
    study = classify.study_of(ds)
    columns = np.empty((study.n_cells, 3))
    for index in range(study.n_cells):
        body = classify.resolved_cell(study, index)["body"]
        columns[index] = body["B"], body["H"], np.nan if body["i_g"] is None else body["i_g"]
    B, H, i_g = (c.reshape(study.shape) for c in columns.T)
    uniform = np.isnan(i_g)
    body = criteria.body_constants(B, H, np.where(uniform, np.hypot(B, H) / math.sqrt(12.0), i_g))
    dims = ds["outcome"].dims
    values = {"breadth": (B, "m", "full breadth B"), "height": (H, "m", "full height H"),
              "R": (body.r, "m", "half-diagonal"), "alpha": (body.alpha, "rad", "slenderness"),
              "p": (body.p, "rad s-1", "frequency parameter"),
              "uniform": (uniform, "1", "uniform body")}
    return xr.Dataset({name: (dims, v, {"units": u, "long_name": n})
                       for name, (v, u, n) in values.items()}, coords=ds["outcome"].coords)


def size_dim(blocks):
    """The dimension along which only the size of the body changes (alpha constant, p not)."""
    for dim in blocks["alpha"].dims:
        alpha = blocks["alpha"].transpose(dim, ...).values
        p = blocks["p"].transpose(dim, ...).values
        if np.allclose(alpha, alpha[:1], rtol=1e-12, atol=0) and np.ptp(p, axis=0).min() > 0:
            return dim
    raise ValueError("a rocking spectrum needs a dimension along which only the size of the "
                     "body changes (size, or B with b_over_h); the dataset has "
                     f"{list(blocks['alpha'].dims)}")


def standing_limit(p, outcome):
    """Largest p [rad/s] up to which every block of a line stands (outcome 0 or 1): inf if
    none fell, -inf if the one of the smallest p fell."""
    order = np.argsort(p)
    fallen = np.flatnonzero(~np.isin(outcome[order], (0, 1)))
    if fallen.size == 0:
        return math.inf
    return -math.inf if fallen[0] == 0 else float(p[order][fallen[0] - 1])


# --- the figure -------------------------------------------------------------------------------

def _uniform_radius(p):
    """Half-diagonal R = 3g/(4p^2) [m] of a uniform block of frequency parameter p [rad/s]."""
    with np.errstate(divide="ignore"):
        return 0.75 * G / np.square(p)


def _uniform_p(R):
    """Frequency parameter p = sqrt(3g/4R) [rad/s] of a uniform block of half-diagonal R [m]."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.sqrt(0.75 * G / np.asarray(R))


def _angle_text(alpha):
    """0.15 for 0.15000047, 0.0333 for 0.033333."""
    return f"{alpha:.2f}" if abs(alpha - round(alpha, 2)) < 5e-5 else f"{alpha:.3g}"


def _value_text(ds, dim, index):
    value = ds[dim].values[index]
    return f"{dim} = {value:.4g}" if ds[dim].dtype.kind == "f" else f"{dim} = {value}"


def _lines(ds, blocks, x):
    """(label, selection) of every line: one per combination of the dimensions other than x."""
    others = [d for d in blocks["alpha"].dims if d != x]
    setting_alpha = {d for d in others
                     if np.ptp(blocks["alpha"].transpose(d, ...).values, axis=0).max() > 0}
    lines = []
    for combo in itertools.product(*(range(ds.sizes[d]) for d in others)):
        sel = dict(zip(others, combo))
        alpha = float(blocks["alpha"].isel(sel).values.flat[0])
        label = ", ".join([f"α = {_angle_text(alpha)} rad (b/h = {math.tan(alpha):.3f})"]
                          + [_value_text(ds, d, i) for d, i in sel.items()
                             if d not in setting_alpha])
        lines.append((alpha, label, sel))
    lines.sort(key=lambda line: line[0])
    return [(label, sel) for _, label, sel in lines[:MAX_LINES]]


def _limit_text(limit, uniform):
    if limit == math.inf:
        return "stands at every p"
    if limit == -math.inf:
        return "falls at the lowest p"
    size = f", R ≥ {_uniform_radius(limit):.2g} m" if uniform else ""
    return f"stands for all p ≤ {limit:.3g} rad/s{size}"


def _peak_acceleration(ground):
    """Peak |a_x| [m/s^2] of a resolved floor component (``io.scene_schema.resolve_scene``),
    for datasets written without a ``pga`` variable; NaN for a sweep not holding acceleration."""
    if ground["kind"] == "none":
        return 0.0
    if ground["kind"] == "record":
        return abs(ground["scale"]) * float(np.max(np.abs(ground["samples"])))
    if ground["kind"] == "sweep" and ground["hold"] != "acceleration":
        return math.nan
    return abs(ground["amplitude"])


def _peaks_text(ds, ground):
    """'PGA 0.349 g, PGV 34.4 cm/s' from the dataset's per-cell peaks, else the
    peak acceleration of ``ground``; a range where the cells differ."""
    pga = ds["pga"].values if "pga" in ds else np.array([_peak_acceleration(ground)])
    parts = []
    for name, values, scale, unit in (("PGA", pga, 1.0 / G, "g"),
                                      ("PGV", ds["pgv"].values if "pgv" in ds else [], 100.0,
                                       "cm/s")):
        values = np.asarray(values, dtype=float)
        values = values[np.isfinite(values)]
        if values.size == 0:
            continue
        low, high = scale * values.min(), scale * values.max()
        text = f"{high:.3g}" if np.isclose(low, high, rtol=1e-9) else f"{low:.3g} to {high:.3g}"
        parts.append(f"{name} {text} {unit}")
    return ", ".join(parts)


def _title(ds, study):
    """The study's title; its motion with peaks; friction and restitution of its first cell."""
    scene = classify.resolved_cell(study, 0)
    ground = scene["excitation"]["horizontal"]
    kind = ground["kind"]
    if kind == "record":
        motion = f"record {study.excitation.get('name') or study.excitation.get('path')}"
    elif kind == "sine":
        cycles = ground["frequency"] * (ground["duration"] or math.inf)
        motion = ("one-sine pulse" if math.isclose(cycles, 1.0) else "sine") + (
            f" of period {1.0 / ground['frequency']:.3g} s")
    elif kind == "pulse":
        motion = f"{ground['shape']} pulse of {ground['duration']:.3g} s"
    else:
        motion = "no floor motion" if kind == "none" else kind
    contact = scene["contact"]
    mu_keys = ("mu_s", "mu_k", "mu_edge_s", "mu_edge_k")
    mus = {contact[k] for k in mu_keys}
    friction = (f"μ = {mus.pop():g}" if len(mus) == 1 else
                ", ".join(f"{k} = {contact[k]:g}" for k in mu_keys))
    return [ds.attrs.get("title") or "Rocking spectrum",
            f"{motion}: {_peaks_text(ds, ground)}; {friction}, e_x = {contact['e_x']:g}, "
            f"e_y = {contact['e_y']:g}"]


def figure_spectrum(ds, yscale="log"):
    """Rocking spectrum of a study Dataset: peak |theta|/alpha against p, one line per alpha.

    Parameters
    ----------
    ds : xarray.Dataset
        A dataset of ``sweep.run`` with a dimension that changes only the size of the body
        (``size``, or ``B`` with ``b_over_h``); every other dimension gives lines.
    yscale : {"log", "linear"}
        Scale of the y axis.

    Returns
    -------
    matplotlib.figure.Figure
        Lines through the blocks that stood (marks: no rocking and failed cells at the
        bottom edge), overturned blocks as crosses in the band above 1, one row per line; a
        top axis in R for uniform blocks.
    """
    if yscale not in BAND_TOP:
        raise ValueError(f"`yscale` must be one of {sorted(BAND_TOP)}, got {yscale!r}")
    blocks = cell_blocks(ds)
    x = size_dim(blocks)
    lines = _lines(ds, blocks, x)
    ratio = (ds["max_abs_theta"] / blocks["alpha"]).values
    outcome = ds["outcome"].values
    uniform = bool(blocks["uniform"].all())
    fig, ax = plt.subplots(figsize=(9.0, 5.8), layout="constrained")
    top = BAND_TOP[yscale]
    rows = (np.geomspace(1.12, 0.86 * top, len(lines)) if yscale == "log"
            else np.linspace(1.06, top - 0.06, len(lines)))
    if yscale == "linear":
        bottom = 0.0
    else:  # the decade below the smallest peak of a block that rocked and stood
        rocked = ratio[(outcome == 1) & (ratio > 0)]
        bottom = 10.0 ** math.floor(math.log10(rocked.min())) if rocked.size else 0.01
    colours = plt.get_cmap("viridis")(np.linspace(0.0, 0.85, len(lines)))
    edge = {"no rocking": [], "failed": []}
    for (label, sel), colour, row in zip(lines, colours, rows):
        index = tuple(sel.get(d, slice(None)) for d in blocks["p"].dims)
        p, y, out = blocks["p"].values[index], ratio[index], outcome[index]
        order = np.argsort(p)
        p, y, out = p[order], y[order], out[order]
        text = _limit_text(standing_limit(p, out), uniform)
        shown = np.where((out == 1) | ((out == 0) & (yscale == "linear")), y, np.nan)
        ax.plot(p, shown, "-o", color=colour, ms=MARKER_SIZE, lw=1.6, label=f"{label}: {text}")
        fallen = out == 2
        ax.plot(p[fallen], np.full(fallen.sum(), row), "x", color=colour, ms=6, mew=1.6)
        if yscale == "log":
            edge["no rocking"].append((p[out == 0], colour))
        edge["failed"].append((p[out == -1], "0.45"))
    for name, marker in (("no rocking", "v"), ("failed", "s")):
        label = f"{name} (on the bottom edge)"
        for p_edge, colour in edge[name]:
            if p_edge.size:
                ax.plot(p_edge, np.full(p_edge.size, bottom), marker, color=colour, ms=6,
                        clip_on=False, label=label)
                label = None  # one legend entry for every line
    band = ax.axhspan(1.0, top, color="0.92", zorder=0)
    ax.axhline(1.0, color="k", lw=0.8)
    ax.text(0.01, rows[-1], "overturned (×), one row per line",
            transform=ax.get_yaxis_transform(), va="center", fontsize=8.5)
    ax.set_xscale("log")
    plain_log_axis(ax.xaxis)
    ax.set_yscale(yscale)
    if yscale == "log":
        plain_log_axis(ax.yaxis)
    ax.set_ylim(bottom, top)
    ax.set_xlabel("frequency parameter p [rad/s]   (larger blocks to the left)")
    ax.set_ylabel("peak |θ| / α")
    ax.grid(True, which="major", color="0.85", lw=0.6)
    if uniform:
        secondary = ax.secondary_xaxis("top", functions=(_uniform_radius, _uniform_p))
        plain_log_axis(secondary.xaxis)
        secondary.set_xlabel("half-diagonal R = 3g/(4p²) [m]")
    fit_suptitle(fig, _title(ds, classify.study_of(ds)))
    fit_texts(fig)
    place_legend(ax, background=[band], fontsize=8, framealpha=0.9)
    return fig
