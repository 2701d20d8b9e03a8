"""A study's dataset turned into probabilities over its ensemble and fitted fragility functions.

The cells of a study are split into *members* (the ensemble dimensions ``over``, e.g.
``seed`` or ``record``), *levels* (the dimension along which every member is scaled, e.g.
``pga``) and *groups* (every other dimension: one body each).  For each group and level:
the probabilities of overturning (outcome 2), of rocking (outcome >= 1) and of sliding
(``slid`` = 1) over the members with binomial intervals, and the median of the intensity
measure (IM); for each group: the lognormal fragility of overturning fitted to the cells
(``sweep.probability.fit``), and with ``pga`` and ``pgv`` in the dataset the two-parameter
surface.  The IM of a cell is that of the motion applied to the body (``pga``, ``pgv``: on a
building's floor, the floor's), or that of the ground under the building (``ground_pga``,
``ground_pgv``: the axis that scales a floor's ground, the IM a site's hazard is in).
Without a levels dimension (records at their own amplitudes) the fit is a "cloud" fit on the
IM of each cell, and the probabilities are given in bins of equal width in ln IM.
Failed cells (outcome −1) are left out of every count and fit, and counted.
"""
from collections import namedtuple
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from kernels import codes

from .. import cf
from .._version import __version__
from . import fit as fitting
from .intervals import METHODS, proportion_interval, validate_confidence

# intensity measures: units and long name when the dataset's variable lacks them
INTENSITY_MEASURES = {
    "pga": ("m s-2", "peak ground acceleration"),
    "pgv": ("m s-1", "peak ground velocity"),
    "pga_norm": ("1", "PGA / (g tan alpha)"),
    "pgv_norm": ("1", "PGV p / (g tan alpha)"),
    "ground_pga": ("m s-2", "peak ground acceleration under the building"),
    "ground_pgv": ("m s-1", "peak ground velocity under the building"),
}
GROUND = "excitation.horizontal.ground."  # the keys of a floor's ground (kind: floor)
GROUND_IMS = {"ground_pga": GROUND + "pga", "ground_pgv": GROUND + "pgv"}  # IM: its axis
LEVEL_NAMES = ("pga", "pgv", "scale", "amplitude")  # dimensions that scale the motions
AUTO = "auto"  # levels: the first of LEVEL_NAMES in the dataset (``default_levels``)
DEFAULT_BINS = 8  # bins in ln IM without a levels dimension
GRID_POINTS = 81  # IM values at which the fitted curve and its band are given
GRID_MARGIN = 1.5  # the grid runs from min IM / margin to max IM * margin
BIN, GRID, TERM = "im_bin", "im_grid", "term"
LEVEL = "level"  # in the table below: the levels dimension, or BIN
SURFACE_TERMS = ("intercept", "ln_pga", "ln_pgv")
EVENTS = ("overturned", "overturned_left", "overturned_right", "rocked", "slid")
SIDE_ANGLES = ("alpha_1", "alpha_2")  # each side's angle of a group's body

_IM = None  # units None and "{axis}" in the table: the IM's units and long name
FRAGILITY_VARIABLES = {
    "n_members": cf.Variable("int32", "1", "ensemble members counted",
                             dims=(LEVEL,), comment="failed cells left out"),
    "n_failed": cf.Variable("int32", "1", "failed cells left out", dims=(LEVEL,),
                            comment="cells whose simulation failed (outcome -1)"),
    "im_median": cf.Variable("float64", _IM, "{axis}: median over the members counted",
                             dims=(LEVEL,)),
    **{name: var for event, text in zip(EVENTS, (
        "overturned", "overturned to the left (-x, about corner 1: overturn_direction +1)",
        "overturned to the right (+x, about corner 2: overturn_direction -1)",
        "rocked (overturned or not)", "slid more than the threshold"))
       for name, var in (
           (f"k_{event}", cf.Variable("int32", "1", f"members that {text}", dims=(LEVEL,))),
           (f"p_{event}", cf.Variable("float64", "1", f"probability that the body {text}",
                                      dims=(LEVEL,), comment="k / n_members")),
           (f"p_{event}_lower", cf.Variable("float64", "1", f"lower confidence bound of "
                                            f"p_{event}", dims=(LEVEL,))),
           (f"p_{event}_upper", cf.Variable("float64", "1", f"upper confidence bound of "
                                            f"p_{event}", dims=(LEVEL,))))},
    "theta": cf.Variable("float64", _IM, "{axis}: median of the lognormal fragility "
                         "of overturning", comment="theta of P = Phi(ln(x/theta)/beta); NaN "
                                                   "when the fit is not identifiable"),
    "theta_lower": cf.Variable("float64", _IM, "{axis}: lower confidence bound of theta"),
    "theta_upper": cf.Variable("float64", _IM, "{axis}: upper confidence bound of theta"),
    "beta": cf.Variable("float64", "1", "dispersion of the lognormal fragility of "
                        "overturning", comment="beta of P = Phi(ln(x/theta)/beta), the "
                                               "standard deviation of ln x"),
    "beta_lower": cf.Variable("float64", "1", "lower confidence bound of beta"),
    "beta_upper": cf.Variable("float64", "1", "upper confidence bound of beta"),
    "fit_status": cf.Variable("int8", "1", "status of the lognormal fit",
                              (tuple(range(len(fitting.FIT_STATUS_NAMES))),
                               fitting.FIT_STATUS_NAMES),
                              comment="; ".join(f"{n}: {r}" for n, r in zip(
                                  fitting.FIT_STATUS_NAMES, fitting.FIT_REASONS))),
    "fit_points": cf.Variable("int32", "1", "cells in the lognormal fit",
                              comment="not failed, with a positive intensity measure"),
    "fit_levels": cf.Variable("int32", "1", "distinct intensity values in the lognormal fit"),
    "bootstrap_unfitted": cf.Variable("int32", "1", "bootstrap replicates that could not be "
                                                    "fitted",
                                      comment="no overturning, all overturned or one level; "
                                              "left out of the intervals"),
    "p_fit": cf.Variable("float64", "1", "fitted lognormal probability of overturning",
                         dims=(GRID,)),
    "p_fit_lower": cf.Variable("float64", "1", "lower pointwise confidence bound of p_fit",
                               dims=(GRID,)),
    "p_fit_upper": cf.Variable("float64", "1", "upper pointwise confidence bound of p_fit",
                               dims=(GRID,)),
    "surface_coefficient": cf.Variable(
        "float64", "1", "coefficients of the two-parameter fragility of overturning",
        dims=(TERM,), comment="P = Phi(b0 + b1 ln(PGA / 1 m s-2) + b2 ln(PGV / 1 m s-1)) "
                              "(Purvance et al. 2008); NaN when not identifiable"),
    "surface_status": cf.Variable("int8", "1", "status of the two-parameter fit",
                                  (tuple(range(len(fitting.FIT_STATUS_NAMES))),
                                   fitting.FIT_STATUS_NAMES)),
    "west_acceleration": cf.Variable(
        "float64", "m s-2", "West's acceleration (B/H) g of the group's body",
        comment="no rocking, hence no overturning, below it without vertical motion (Eq. 1); "
                "the surface is fitted above it when no cell below it overturned"),
    **{name: cf.Variable("float64", "rad", f"angle at G between the vertical and corner "
                                           f"{side} of the group's body",
                         comment=f"atan(b{side[0]}/y_G): it tips {towards} when "
                                 f"{sign}a_x > g tan {name}; alpha_1 = alpha_2: G in the middle")
       for name, side, towards, sign in zip(SIDE_ANGLES, ("1 (left, -x)", "2 (right, +x)"),
                                            ("to the left", "to the right"), ("", "-"))},
}


# Scene sections whose axes change the body or how it is simulated: each of their values is
# another body (a group of its own), never a member of an ensemble of motions
BODY_SECTIONS = ("body", "contact", "initial", "solver")


def _study_axes(ds, dim):
    """The study's axes along dimension ``dim``: each coordinate's ``study_axis`` (its name in
    a dataset without it), the dimension's own name if it has no coordinate."""
    return [c.attrs.get("study_axis", name) for name, c in ds.coords.items()
            if c.dims == (dim,)] or [dim]


def _sections(axis):
    """The scene sections an axis of a study sets (``grid.AXES`` or a dotted path); () for a
    name the project does not know."""
    from ..runner import grid

    if axis in grid.AXES or "." in axis:
        return {target.split(".")[0] for target in grid.targets(axis)}
    return set()


def body_dimension(ds, dim):
    """True when dimension ``dim`` of a study's dataset varies the body or its simulation
    (``B``, ``b_over_h``, ``size``, ``mu``, ``initial.theta``, ...): its cells are other
    bodies, never members of an ensemble."""
    return any(_sections(axis) & set(BODY_SECTIONS) for axis in _study_axes(ds, dim))


def level_dimension(ds, dim):
    """True when dimension ``dim`` of a study's dataset scales the motions: one of
    ``LEVEL_NAMES``, or the axis of a floor's ground that sets one of them
    (``excitation.horizontal.ground.pga``)."""
    return dim in LEVEL_NAMES or any(axis in {GROUND + name for name in LEVEL_NAMES}
                                     for axis in _study_axes(ds, dim))


def ensemble_dimensions(ds, levels=None):
    """The dimensions of a study's dataset whose cells can be the members of an ensemble:
    those of the motion (``record``, ``seed``, ``phase``, a scenario's ``magnitude``, ...),
    but for the levels (``levels`` and those of :func:`level_dimension`)."""
    dims = ds["outcome"].dims if "outcome" in ds.variables else ()
    return [d for d in dims if d != levels and not level_dimension(ds, d)
            and not body_dimension(ds, d)]


class FragilityError(ValueError):
    """A request the dataset cannot answer (an unknown dimension, a missing IM); one line."""


Cells = namedtuple("Cells", "dims outcome slid direction im group_coords level_coords")
Cells.__doc__ = """A study's cells as (groups, levels, members) arrays: ``dims`` = (group dims,
levels dim or None, ensemble dims); ``outcome`` int, ``slid`` and ``direction`` (the
overturning direction) int or None, ``im`` float;
``group_coords`` and ``level_coords`` the dataset's coordinates along them (the scalar ones
with the groups)."""


def default_levels(ds, over):
    """The dimension that scales the motions: the first of ``LEVEL_NAMES`` in the dataset's
    cells that is not an ensemble dimension, else the first that scales a floor's ground
    (:func:`level_dimension`), or None."""
    dims = [d for d in (ds["outcome"].dims if "outcome" in ds.variables else ())
            if d not in over]
    return next((name for name in LEVEL_NAMES if name in dims),
                next((d for d in dims if level_dimension(ds, d)), None))


def im_values(ds, im):
    """The intensity measure ``im`` of a study's cells: its variable or coordinate, or for
    ``ground_pga`` and ``ground_pgv`` the coordinate of the axis that scales a floor's ground
    to it; None when the dataset has none."""
    if im in GROUND_IMS:
        return next((c for c in ds.coords.values()
                     if c.attrs.get("study_axis") == GROUND_IMS[im]), None)
    return ds[im] if im in ds.variables else None


def validate_request(ds, over, im, levels):
    """Raise :class:`FragilityError` unless ``ds`` is a study dataset with the dimensions
    ``over`` and ``levels`` and the intensity measure ``im`` on its cells."""
    if "outcome" not in ds.variables:
        raise FragilityError("not a study dataset: it has no variable 'outcome' (a dataset "
                             "written by python -m sweep.run)")
    dims = ds["outcome"].dims
    listed = ", ".join(dims)
    for name in (*over, *([levels] if levels is not None else [])):
        if name not in dims:
            raise FragilityError(f"'{name}' is not a dimension of the dataset; its "
                                 f"dimensions are {listed}")
    if not over:
        raise FragilityError("give at least one ensemble dimension (--over)")
    for name in over:
        if body_dimension(ds, name):
            present = ensemble_dimensions(ds, levels)
            raise FragilityError(
                f"'{name}' is not an ensemble dimension: its cells are other bodies, each a "
                "group of its own; " + (f"the ensemble dimensions of this dataset: "
                                         f"{', '.join(present)}" if present else
                                         "this dataset has no ensemble dimension (record, "
                                         "seed or another axis of the motion)"))
    if len(set(over)) < len(over):
        raise FragilityError(f"an ensemble dimension is given twice: {', '.join(over)}")
    if levels in over:
        raise FragilityError(f"'{levels}' cannot be both the levels and an ensemble "
                             "dimension")
    if im not in INTENSITY_MEASURES:
        raise FragilityError(f"unknown intensity measure '{im}'; one of "
                             f"{', '.join(INTENSITY_MEASURES)}")
    values = im_values(ds, im)
    if values is None:
        present = [name for name in INTENSITY_MEASURES if im_values(ds, name) is not None]
        scaled = f" (no axis {GROUND_IMS[im]} scales a floor's ground)" if im in GROUND_IMS \
            else ""
        raise FragilityError(f"the dataset has no intensity measure '{im}'{scaled} (it has: "
                             f"{', '.join(present) or 'none'})")
    if not set(values.dims) <= set(dims):
        raise FragilityError(f"'{im}' has dimensions {', '.join(values.dims)} that the "
                             f"cells ({listed}) do not have")
    if im in GROUND_IMS and values.attrs.get("units") != INTENSITY_MEASURES[im][0]:
        raise FragilityError(f"'{im}': the axis {GROUND_IMS[im]} is in units "
                             f"{values.attrs.get('units')}, relative to the body; give the "
                             f"ground's levels in {INTENSITY_MEASURES[im][0]}, g, cm/s ...")


def cells(ds, over, im, levels):
    """The dataset's cells as :class:`Cells` (``validate_request`` first)."""
    import xarray as xr

    outcome = ds["outcome"]
    groups = tuple(d for d in outcome.dims if d not in over and d != levels)
    level_dims = (levels,) if levels is not None else ()
    order = groups + level_dims + tuple(over)
    shape = (int(np.prod([outcome.sizes[d] for d in groups])),
             outcome.sizes[levels] if levels is not None else 1, -1)

    def arranged(da):
        return xr.broadcast(da, outcome)[0].transpose(*order).values.reshape(shape)

    def along(dims, scalars):
        return {name: c for name, c in ds.coords.items()
                if (c.dims or scalars) and set(c.dims) <= set(dims)}

    return Cells(groups + (levels, tuple(over)), arranged(outcome).astype(np.int64),
                 arranged(ds["slid"]).astype(np.int64) if "slid" in ds.variables else None,
                 arranged(ds["overturn_direction"]).astype(np.int64)
                 if "overturn_direction" in ds.variables else None,
                 arranged(im_values(ds, im)).astype(float), along(groups, scalars=True),
                 along(level_dims, scalars=False))


def im_attrs(ds, im):
    """Units and long name of the intensity measure (the dataset's, else the defaults)."""
    units, long_name = INTENSITY_MEASURES[im]
    attrs = {} if im in GROUND_IMS else im_values(ds, im).attrs  # an axis: its path as name
    return SimpleNamespace(units=attrs.get("units", units),
                           long_name=attrs.get("long_name", long_name))


def fragility(ds, over, im, levels=AUTO, *, bins=DEFAULT_BINS, confidence=0.95,
              interval="wilson", fit_interval="bootstrap",
              replicates=fitting.DEFAULT_REPLICATES, seed=0, source=None, history=None):
    """The fragility dataset of a study: probabilities per group and level, and fits.

    Parameters
    ----------
    ds : xarray.Dataset
        A study's dataset (``outcome``, optionally ``slid``, and ``im`` on its cells).
    over : sequence of str
        Ensemble dimensions: their cells are the members.
    im : {"pga", "pgv", "pga_norm", "pgv_norm", "ground_pga", "ground_pgv"}
        Intensity measure, a variable or a coordinate of ``ds`` (:func:`im_values`).
    levels : str or None
        The dimension along which the members are scaled; ``AUTO``: the one
        :func:`default_levels` finds; None: each cell at its own IM, binned in ln IM.
    bins : int
        Bins of equal width in ln IM without ``levels``.
    confidence : float
        Coverage of every interval.
    interval : {"wilson", "exact"}
        Interval of the probabilities (``sweep.probability.intervals``).
    fit_interval : {"bootstrap", "delta"}
        Intervals of θ and β (``sweep.probability.fit``).
    replicates, seed : int
        Bootstrap replicates over the members and the seed of their draws.
    source, history : str, optional
        The input file and the command, for the global attributes.

    Returns
    -------
    xarray.Dataset
        The variables of ``FRAGILITY_VARIABLES`` (the ``slid`` ones only with ``slid`` in
        ``ds``, the ``surface`` ones only with ``pga`` and ``pgv``), dimensions the group
        dimensions plus ``levels`` (or ``im_bin``), ``im_grid`` and ``term``.
    """
    import xarray as xr

    if levels == AUTO:
        levels = default_levels(ds, over)
    validate_request(ds, over, im, levels)
    validate_confidence(confidence)
    if interval not in METHODS:
        raise FragilityError(f"unknown interval method '{interval}'; one of "
                             f"{', '.join(METHODS)}")
    if bins < 1:
        raise FragilityError(f"bins must be at least 1, got {bins}")
    data = cells(ds, over, im, levels)
    counted = data.outcome != codes.FAILED
    positive = counted & np.isfinite(data.im) & (data.im > 0)
    if levels is not None:
        level_index = np.broadcast_to(np.arange(data.outcome.shape[1])[None, :, None],
                                      data.outcome.shape)
        edges = None
    else:
        edges = _bin_edges(data.im[positive], bins)
        with np.errstate(invalid="ignore"):  # NaN IM: no bin, and not counted in one
            level_index = np.clip(np.searchsorted(edges, data.im, side="right") - 1, 0,
                                  bins - 1)
    overturned = data.outcome == codes.OVERTURN
    events = {"overturned": overturned}
    if data.direction is not None:       # each side apart: a body with G off the middle
        events.update(overturned_left=overturned & (data.direction == 1),
                      overturned_right=overturned & (data.direction == -1))
    events["rocked"] = data.outcome >= codes.ROCKED
    if data.slid is not None:
        events["slid"] = data.slid == 1
    arrays = _per_level(data, counted, positive, level_index,
                        data.outcome.shape[1] if edges is None else bins, events,
                        edges is not None, confidence, interval)
    grid = _grid(data.im[positive])
    arrays.update(_fits(data, counted, grid, confidence, fit_interval, replicates, seed))
    surface = "pga" in ds.variables and "pgv" in ds.variables
    if surface:
        pga, pgv = (cells(ds, over, name, levels).im for name in ("pga", "pgv"))
        west = (pga / cells(ds, over, "pga_norm", levels).im if "pga_norm" in ds.variables
                else np.full(pga.shape, np.nan))
        arrays.update(_surfaces(pga, pgv, west, data.outcome, counted))
    if "alpha_1" in ds.variables:  # each side's angle: G off the middle when they differ
        arrays.update({name: _group_median(cells(ds, over, name, levels).im)
                       for name in SIDE_ANGLES})
    axis = im_attrs(ds, im)
    group_dims = data.dims[:-2]
    group_shape = tuple(ds.sizes[d] for d in group_dims)
    dims = {LEVEL: levels if edges is None else BIN, GRID: GRID, TERM: TERM}
    variables = {}
    for name, values in arrays.items():
        var = FRAGILITY_VARIABLES[name]
        variables[name] = (group_dims + tuple(dims[d] for d in var.dims),
                           values.reshape(group_shape + values.shape[1:]).astype(var.dtype),
                           cf.variable_attrs(name, FRAGILITY_VARIABLES, axis))
    attrs = _global_attrs(ds, over, im, levels, bins, confidence, interval, fit_interval,
                          replicates, seed, int((~counted).sum()), data.outcome.size,
                          source, history)
    return xr.Dataset(variables, coords=_coords(data, axis, grid, edges, surface),
                      attrs=attrs)


def _coords(data, axis, grid, edges, surface):
    """Coordinates of a fragility dataset: the study's along the groups and levels, the
    curve's grid, the bins' edges (without levels) and the surface's terms."""
    coords = {**data.group_coords, **data.level_coords,
              GRID: (GRID, grid, {"units": axis.units,
                                  "long_name": f"{axis.long_name}: values of the fitted "
                                               "curve"})}
    if edges is not None:
        coords[BIN] = (BIN, np.arange(edges.size - 1), {"units": "1",
                                                        "long_name": "bin of ln IM"})
        for name, values, edge in (("im_lower", edges[:-1], "lower"),
                                   ("im_upper", edges[1:], "upper")):
            coords[name] = (BIN, values, {"units": axis.units, "long_name":
                                          f"{axis.long_name}: {edge} edge of the bin"})
    if surface:
        coords[TERM] = (TERM, np.array(SURFACE_TERMS),
                        {"units": "1", "long_name": "term of the two-parameter fit"})
    return coords


def _bin_edges(values, bins):
    """``bins`` + 1 edges of equal width in ln IM over ``values`` (one value: a factor 1.1
    either side)."""
    if values.size == 0:
        return np.full(bins + 1, np.nan)
    low, high = np.log(values.min()), np.log(values.max())
    if high == low:
        low, high = low - np.log(1.1), high + np.log(1.1)
    return np.exp(np.linspace(low, high, bins + 1))


def _grid(values):
    """Log-spaced IM values around ``values`` for the fitted curve."""
    if values.size == 0:
        return np.full(GRID_POINTS, np.nan)
    return np.geomspace(values.min() / GRID_MARGIN, values.max() * GRID_MARGIN, GRID_POINTS)


def _per_level(data, counted, positive, level_index, n_levels, events, binned, confidence,
               interval):
    """Counts, probabilities with intervals and IM medians per (group, level)."""
    import warnings

    n_groups = data.outcome.shape[0]
    # a cell counts in its level; binned cells need an IM to have a bin
    inside = positive if binned else counted
    flat = np.arange(n_groups)[:, None, None] * n_levels + level_index

    def count(mask):
        return np.bincount(flat[mask], minlength=n_groups * n_levels).reshape(n_groups,
                                                                              n_levels)

    members = count(inside)
    arrays = {"n_members": members, "n_failed": count(~counted)}
    for event, happened in events.items():
        k = count(inside & happened)
        lower, upper = proportion_interval(k, members, confidence, interval)
        with np.errstate(invalid="ignore", divide="ignore"):
            p = np.where(members > 0, k / members, np.nan)
        arrays.update({f"k_{event}": k, f"p_{event}": p, f"p_{event}_lower": lower,
                       f"p_{event}_upper": upper})
    median = np.full((n_groups, n_levels), np.nan)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # a level without cells: NaN
        for level in range(n_levels):
            values = np.where(positive & (level_index == level), data.im, np.nan)
            median[:, level] = np.nanmedian(values.reshape(n_groups, -1), axis=1)
    arrays["im_median"] = median
    return arrays


def _fits(data, counted, grid, confidence, fit_interval, replicates, seed):
    """The lognormal fit of overturning of each group and its curve on ``grid``."""
    n_groups, n_levels, n_members = data.outcome.shape
    members = np.broadcast_to(np.arange(n_members), (n_levels, n_members))
    names = ("theta", "theta_lower", "theta_upper", "beta", "beta_lower", "beta_upper",
             "fit_status", "fit_points", "fit_levels", "bootstrap_unfitted")
    out = {name: np.zeros(n_groups) for name in names}
    curves = {name: np.full((n_groups, grid.size), np.nan)
              for name in ("p_fit", "p_fit_lower", "p_fit_upper")}
    rng = np.random.default_rng(seed)
    for group in range(n_groups):
        overturned = data.outcome[group] == codes.OVERTURN
        result = fitting.fit_lognormal(
            data.im[group], overturned, counted[group], members, confidence=confidence,
            interval=fit_interval, replicates=replicates, seed=rng)
        values = (result.theta, *result.theta_interval, result.beta, *result.beta_interval,
                  result.status, result.points, result.levels, result.unfitted_replicates)
        for name, value in zip(names, values):
            out[name][group] = value
        curves["p_fit"][group] = result.probability(grid)
        curves["p_fit_lower"][group], curves["p_fit_upper"][group] = result.band(grid)
    return {**out, **curves}


def _group_median(values):
    """The median over each group's cells of ``values`` (groups, levels, members)."""
    return np.nanmedian(values.reshape(values.shape[0], -1), axis=1)


def _surfaces(pga, pgv, west, outcome, counted):
    """The two-parameter fit of each group: coefficients, status and West's acceleration.

    Below West's acceleration ``west`` a body does not rock without vertical motion: when no
    cell of the group below it overturned, the surface is fitted to the cells above it, so
    that the probit's tail does not spread overturning into the region where it cannot be.
    """
    coefficients = np.full((outcome.shape[0], len(SURFACE_TERMS)), np.nan)
    status = np.zeros(outcome.shape[0])
    a_west = np.full(outcome.shape[0], np.nan)
    for group in range(outcome.shape[0]):
        over = outcome[group] == codes.OVERTURN
        a_west[group] = np.nanmedian(west[group]) if np.isfinite(west[group]).any() else np.nan
        fitted = counted[group].astype(float)
        if np.isfinite(a_west[group]) and not np.any(over & (pga[group] < a_west[group])):
            fitted = fitted * (pga[group] >= a_west[group])
        result = fitting.fit_surface(pga[group], pgv[group], over, fitted)
        coefficients[group], status[group] = result.coefficients, result.status
    return {"surface_coefficient": coefficients, "surface_status": status,
            "west_acceleration": a_west}


def _global_attrs(ds, over, im, levels, bins, confidence, interval, fit_interval, replicates,
                  seed, failed, total, source, history):
    import datetime

    now = datetime.datetime.now(datetime.timezone.utc).replace(microsecond=0).isoformat()
    line = history or f"sweep.probability.fragility.fragility(over={list(over)}, im={im!r})"
    interval_text = {"wilson": "Wilson score interval (Wilson 1927)",
                     "exact": "exact Clopper-Pearson interval (Clopper & Pearson 1934)"}
    fit_text = {"bootstrap": f"bias-corrected and accelerated bootstrap over the ensemble "
                             f"members ({counted(replicates, 'replicate')}, seed {seed}), "
                             "each member resampled with all its levels",
                "delta": "delta method on ln theta and ln beta from the GLM covariance"}
    attrs = {
        "Conventions": cf.CONVENTIONS,
        "title": f"fragility of overturning: {ds.attrs.get('title', 'study')}",
        "source": f"{cf.PACKAGE} {__version__}",
        "history": f"{now} {line} - {cf.PACKAGE} {__version__}",
        "date_created": now,
        "input_file": str(source or ""),
        "input_title": ds.attrs.get("title", ""),
        "ensemble_dimensions": " ".join(over),
        "intensity_measure": im,
        "level_dimension": levels if levels is not None else "none",
        "confidence": confidence,
        "interval_method": interval_text[interval],
        "fit": "P = Phi(ln(x/theta)/beta) by maximum likelihood, a probit GLM on ln x "
               "(Baker 2015), over every counted cell with a positive IM",
        "fit_interval": fit_interval,
        "fit_interval_method": fit_text[fit_interval],
        "failed_cells": failed,
        "cells": total,
    }
    if levels is None:
        attrs["im_bins"] = f"{counted(bins, 'bin')} of equal width in ln {im}"
    return attrs


def counted(n, noun):
    """``1 motion``, ``3 motions``: a count and its noun, plural but for one."""
    return f"{n} {noun}{'s' * (n != 1)}"


def output_path(source, im):
    """The default path of the fragility dataset: ``<stem>_fragility_<im>.nc`` beside
    ``source``."""
    source = Path(source)
    return source.with_name(f"{source.stem}_fragility_{im}.nc")


COORDINATE_DIGITS = 6  # significant digits of a coordinate in a label: 0.7, not 0.7000000000000001


def describe_group(coords):
    """A readable name of a group from ``{name: (value, units)}``: "B 0.2 m × H 0.6 m
    (b/h 0.333)" for a body, else "name value units" joined by commas; coordinates to
    ``COORDINATE_DIGITS`` significant digits (float noise dropped, values kept apart)."""
    values = {name: value for name, (value, _) in coords.items()}
    parts, rest = [], dict(coords)
    digits = COORDINATE_DIGITS
    if "B" in values and ("H" in values or "b_over_h" in values):
        breadth = float(values["B"])
        height = float(values["H"]) if "H" in values else breadth / float(values["b_over_h"])
        parts.append(f"B {breadth:.{digits}g} m × H {height:.{digits}g} m "
                     f"(b/h {breadth / height:.3g})")
        for name in ("B", "H", "b_over_h"):
            rest.pop(name, None)
    for name, (value, units) in rest.items():
        text = f"{value:.{digits}g}" if isinstance(value, (float, np.floating)) else str(value)
        unit = "" if units in ("", "1", None) else f" {units}"
        parts.append(f"{name} {text}{unit}")
    return ", ".join(parts) or "all cells"


def group_coords(frag, index):
    """``{name: (value, units)}`` of the group at ``index`` (a dict of group dimension ->
    position) of a fragility dataset."""
    return {name: (c.isel({d: i for d, i in index.items() if d in c.dims}).item(),
                   c.attrs.get("units"))
            for name, c in frag.coords.items() if set(c.dims) <= set(index)}


def asymmetric(group):
    """True when the body of ``group`` (one group of a fragility dataset) has G off the middle
    of its base: its ``SIDE_ANGLES`` differ."""
    return all(name in group for name in SIDE_ANGLES) and \
        float(group["alpha_1"]) != float(group["alpha_2"])


def group_indices(frag):
    """Every group of a fragility dataset as ``{dim: position}``, in C order."""
    dims = frag["theta"].dims
    return [dict(zip(dims, position))
            for position in np.ndindex(*(frag.sizes[d] for d in dims))]
