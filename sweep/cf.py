"""Every dataset the package writes: one metadata table, the Dataset builders, one encoding.

The datasets are those of docs/design.md section 6.

The table describes each variable once as a :class:`Variable` (dtype, CF ``units`` and
``long_name``, flags for integer codes from ``kernels.codes``, extra dimensions, comment), in
three parts, one per kind of dataset: ``VARIABLES``, the per-cell results of a study
(``runner.cells.run_chunk`` fills arrays of these dtypes, :func:`to_dataset` shapes them onto
the study's dimensions); ``REFINE_VARIABLES``, the boundaries of a refine study
(:func:`refine_dataset`, ``sweep.runner.refine``); ``HISTORY_VARIABLES``, the time history of
one scene (:func:`history_dataset`).  :func:`variable_attrs` turns an entry into CF attributes
and :func:`encoding` chooses how every dataset is stored (zlib level 1, no ``_FillValue`` on
integer flags and coordinates); ``netcdf.write_netcdf`` writes them.  xarray is imported
only when a Dataset is built.
"""
import datetime
import math
from collections import namedtuple

import numpy as np

from kernels import codes

from ._version import __version__
from .io import study_grid, vocabulary

CONVENTIONS = "CF-1.11"
PACKAGE = "rigid-block-sweeps"
COMPLEVEL = 1  # zlib level 1: most of the gain of compression at a fraction of its time

Variable = namedtuple("Variable", "dtype units long_name flags dims comment")
Variable.__new__.__defaults__ = (None, (), "")
Variable.__doc__ = """One result per cell: numpy ``dtype``, CF ``units`` and ``long_name``,
``flags`` = (values, meanings) for integer codes, extra trailing ``dims``, ``comment``."""

OUTCOME_FLAGS = ((codes.FAILED, codes.NO_ROCKING, codes.ROCKED, codes.OVERTURN),
                 codes.OUTCOME_NAMES)
STATUS_FLAGS = (tuple(range(len(codes.STATUS_NAMES))), codes.STATUS_NAMES)
OVERTURNED_FLAGS = ((-1, 0, 1), ("failed", "standing", "overturned"))
DIRECTION_FLAGS = ((-1, 0, 1), ("negative_theta", "none", "positive_theta"))
SLID_FLAGS = ((-1, 0, 1), ("failed", "no_slip", "slid"))
RESTRAINT_FLAGS = ((-1, 0, 1), ("none_or_failed", "held", "broke"))
SLID_THRESHOLD = 0.01  # m: a body whose base moved further than this along the floor slid
SLIP_COMMENT = ("how far the footprint of the base (where the middle of the base would be, set "
                "down flat about the corner it stands on) moved from where the body first "
                "stood, observed while it touches the floor with |theta| <= alpha: rocking "
                "about a corner does not move it, sliding and landing elsewhere after a jump "
                "do, a corner slipping as the body falls past alpha does not")
MOTION_COMMENT = ("the motion as applied (after scale, pga or pgv); PGV and PGD after a "
                  "zero-phase 0.1 Hz high-pass baseline correction (sweep.groundmotion."
                  "intensity); sines and sweeps: their steady amplitudes")

VARIABLES = {
    "outcome": Variable("int8", "1", "outcome of the cell", OUTCOME_FLAGS,
                        comment="failed: the scene ended with a failed status; rocked: "
                                "max_abs_theta > 0 without overturning"),
    "overturned": Variable("int8", "1", "body overturned", OVERTURNED_FLAGS),
    "status": Variable("int8", "1", "end status of the simulation", STATUS_FLAGS,
                       comment="; ".join(f"{n}: {m}" for n, m in
                                         zip(codes.STATUS_NAMES, codes.STATUS_MESSAGES))),
    "t_overturn": Variable("float64", "s", "time of overturning",
                           comment="NaN if the body did not overturn"),
    "overturn_direction": Variable("int8", "1", "sign of theta at overturning",
                                   DIRECTION_FLAGS,
                                   comment="theta > 0 is rotation about the left corner: "
                                           "positive_theta fell towards -x (to the left), "
                                           "negative_theta towards +x"),
    "max_abs_theta": Variable("float64", "rad", "largest absolute rotation angle"),
    "impact_count": Variable("int32", "1", "number of impacts"),
    "mode_time": Variable("float32", "s", "time spent in each motion type", dims=("mode",)),
    "max_slip": Variable("float32", "m", "largest slip of the base along the floor",
                         comment=SLIP_COMMENT),
    "max_travel": Variable("float32", "m", "largest horizontal travel of G relative to the "
                                           "floor",
                           comment="|x - x0| of the centre of mass, rotation included"),
    "max_lift": Variable("float32", "m", "largest gap under the lowest point of the body"),
    "t_rest": Variable("float64", "s", "time of coming to final rest",
                       comment="NaN if the body did not come to final rest"),
    "steps": Variable("int32", "1", "integration steps taken"),
    "energy_clamps": Variable("int32", "1", "impacts whose restitution was clamped to gain "
                                            "no energy",
                              comment="a plastic law replaced the impact law, which would "
                                      "have gained energy (docs/physics.md section 3); every "
                                      "impact clamped: check e_x, e_y"),
    "f_at_overturn": Variable("float64", "Hz", "floor frequency at overturning",
                              comment="instantaneous frequency of a sweep or sine; "
                                      "NaN if the body did not overturn"),
    "a_norm_at_overturn": Variable("float64", "1",
                                   "floor acceleration amplitude at overturning / (B/H) g",
                                   comment="the paper's normalized acceleration; NaN if the "
                                           "body did not overturn"),
    "v_norm_at_overturn": Variable("float64", "1",
                                   "floor velocity amplitude at overturning / v_H",
                                   comment="the paper's normalized velocity (v_H of Eq. 9); "
                                           "NaN if the body did not overturn"),
    "slid": Variable("int8", "1", "body slid", SLID_FLAGS,
                     comment=f"slid: max_slip > {SLID_THRESHOLD * 100:g} cm, the base moved "
                             "further along the floor; failed: the simulation failed"),
    "pga": Variable("float64", "m s-2", "peak ground acceleration of the horizontal motion",
                    comment=MOTION_COMMENT),
    "pgv": Variable("float64", "m s-1", "peak ground velocity of the horizontal motion",
                    comment=MOTION_COMMENT),
    "pgd": Variable("float64", "m", "peak ground displacement of the horizontal motion",
                    comment=MOTION_COMMENT + "; NaN for a pulse (the floor drifts after it)"),
    "significant_duration": Variable("float64", "s", "5-95 % Arias-intensity duration of the "
                                                     "horizontal motion",
                                     comment="records and synthetic motions; NaN otherwise"),
    "pga_norm": Variable("float64", "1", "PGA / (g tan alpha)",
                         comment="West's ratio: rocking starts above 1 without vertical motion"),
    "pgv_norm": Variable("float64", "1", "PGV p / (g tan alpha)",
                         comment="p = sqrt(g R / (i^2 + R^2)), sqrt(3 g / 4 R) for a uniform "
                                 "body; Dimitrakopoulos & DeJong (2012)"),
    "alpha_1": Variable("float64", "rad", "angle at G from the vertical to the left corner",
                        comment="atan(b1/y_G), b1 = B/2 + x_G; the body tips to the left "
                                "(overturn_direction +1) about this corner (docs/bodies.md)"),
    "alpha_2": Variable("float64", "rad", "angle at G from the vertical to the right corner",
                        comment="atan(b2/y_G), b2 = B/2 - x_G; the body tips to the right "
                                "(overturn_direction -1) about this corner (docs/bodies.md)"),
    "isolator_max_displacement": Variable(
        "float64", "m", "largest displacement of the isolator under the platform",
        comment="relative to the motion under it (docs/isolation.md); NaN without an "
                "isolator"),
    "restraint_broken": Variable("int8", "1", "restraint broken", RESTRAINT_FLAGS,
                                 comment="broke: the anchor's ties gave way, the body was "
                                         "then free (docs/anchors.md); none_or_failed: the "
                                         "scene has no restraint, or the simulation failed"),
}
MODE = ("mode", codes.MODE_NAMES, {"units": "1", "long_name": "motion type"})

# Results of a refine study, one per line (combination of the other axes).  ``units=None``: the
# refined axis's units; ``{axis}`` in a long name: the refined axis's long name; dims
# ``(REFINED,)``: along the refined axis's coarse values too.
REFINED = "refined"
# How a line's boundary was bracketed, by code (``sweep.runner.refine``: BRACKETED = 0, ...).
BRACKET_NAMES = ("bracketed", "never_overturned", "overturned_at_start", "simulation_failed")
BRACKET_FLAGS = (tuple(range(len(BRACKET_NAMES))), BRACKET_NAMES)
REFINE_VARIABLES = {
    "boundary": Variable("float64", None, "{axis}: overturning boundary",
                         comment="middle of [boundary_lower, boundary_upper]: the lowest value "
                                 "at which the body overturns, within half the bracket's "
                                 "width; NaN without a bracket"),
    "boundary_lower": Variable("float64", None,
                               "{axis}: highest value found at which the body stood",
                               comment="NaN when the body overturned at the lowest value"),
    "boundary_upper": Variable("float64", None,
                               "{axis}: lowest value found at which the body overturned",
                               comment="NaN when the body never overturned in the range, or a "
                                       "simulation failed first"),
    "bracket": Variable("int8", "1", "how the overturning boundary was bracketed",
                        BRACKET_FLAGS,
                        comment="never_overturned, overturned_at_start: no bracket in the "
                                "range of the coarse values; simulation_failed: bisection "
                                "stopped at a failed simulation, see the bracket so far"),
    "simulations": Variable("int32", "1", "simulations run (coarse values and midpoints)"),
    "coarse_transitions": Variable("int32", "1", "changes between standing and overturned "
                                                 "along the coarse values",
                                   comment="1: one boundary; more: the body overturns in bands "
                                           "and the lowest bracket is refined"),
    "coarse_overturned": Variable("int8", "1", "body overturned at the coarse values",
                                  OVERTURNED_FLAGS, dims=(REFINED,)),
}


# The time history of one scene, dimension ``time`` (``python -m sweep.scene --history``).
MODE_FLAGS = (tuple(range(len(codes.MODE_NAMES))), codes.MODE_NAMES)
HISTORY_VARIABLES = {
    "x": Variable("float64", "m", "horizontal position of the centroid relative to the floor"),
    "y": Variable("float64", "m", "height of the centroid above the floor"),
    "theta": Variable("float64", "rad", "rotation angle, positive about the left corner"),
    "u": Variable("float64", "m s-1", "horizontal velocity of the centroid relative to the "
                                      "floor"),
    "v": Variable("float64", "m s-1", "vertical velocity of the centroid"),
    "omega": Variable("float64", "rad s-1", "angular velocity"),
    "a_x": Variable("float64", "m s-2", "horizontal floor acceleration"),
    "a_y": Variable("float64", "m s-2", "vertical floor acceleration"),
    "mode": Variable("int8", "1", "motion type", MODE_FLAGS),
}
TIME = ("time", {"units": "s", "long_name": "time", "axis": "T"})


def empty(name, n):
    """An array for ``n`` cells of variable ``name``, filled with NaN or the failed code."""
    var = VARIABLES[name]
    extra = tuple(len(MODE[1]) for _ in var.dims)
    fill = np.nan if np.dtype(var.dtype).kind == "f" else (-1 if var.flags else 0)
    return np.full((n, *extra), fill, dtype=var.dtype)


def _flag_attrs(var):
    values, meanings = var.flags
    return {"flag_values": np.array(values, dtype=var.dtype),
            "flag_meanings": " ".join(meanings)}


def variable_attrs(name, table=None, axis=None):
    """CF attributes of a result variable of ``table`` (default ``VARIABLES``).

    ``axis``: the refined axis, for the units and long names of ``REFINE_VARIABLES``.
    """
    var = (VARIABLES if table is None else table)[name]
    attrs = {"units": axis.units if var.units is None else var.units,
             "long_name": var.long_name.format(axis=axis.long_name if axis else "")}
    if var.flags:
        attrs.update(_flag_attrs(var))
    if var.comment:
        attrs["comment"] = var.comment
    return attrs


def _sweep_rate(f0, f1, duration, law):
    """'down at 40 s per octave', 'up at 0.05 Hz/s', or '' when the numbers are not plain."""
    try:
        f0, f1, duration = float(f0), float(f1), float(duration)
    except (TypeError, ValueError):
        return ""
    direction = "down" if f1 < f0 else "up"
    if law == "log":
        octaves = abs(math.log2(f1 / f0))
        return f"{direction} at {duration / octaves:.4g} s per octave" if octaves else direction
    return f"{direction} at {abs(f1 - f0) / duration:.4g} Hz/s"


def describe_excitation(ground, varied=()):
    """One line naming the horizontal excitation of the base scene (the ``sweep_law``).

    A sweep is described by its law, phase, held amplitude, direction and rate; ``varied``
    names the study axes that change the horizontal excitation from cell to cell.
    """
    kind = ground.get("kind", "none")
    if kind == "sweep":
        law = ground.get("law", "log")
        phase = ("psi = 2 pi f0 (exp(k t) - 1)/k, k = ln(f1/f0)/T" if law == "log"
                 else "psi = 2 pi (f0 t + (f1 - f0) t^2/(2 T))")
        line = (f"{law} frequency sweep ({phase}) holding the "
                f"{ground.get('hold', 'acceleration')} amplitude, {ground.get('f_start')} to "
                f"{ground.get('f_stop')} Hz over {ground.get('duration')} s, "
                + _sweep_rate(ground.get("f_start"), ground.get("f_stop"),
                              ground.get("duration"), law))
    elif kind == "sine":
        line = "none (sine at a constant frequency)"
    elif kind == "record":
        line = f"none (record {ground.get('name') or ground.get('path')})"
    else:
        line = f"none ({kind})"
    if varied:
        line += f"; per cell, the study axes {', '.join(varied)} change it"
    return line


def _horizontal_axes(study):
    return tuple(axis.name for axis in study.axes
                 if any(path.startswith("excitation.horizontal.")
                        for path in vocabulary.targets(axis.name)))


def global_attrs(study, history=None):
    """Global attributes: conventions, title, the study's text, version, sweep law, times."""
    now = datetime.datetime.now(datetime.timezone.utc).replace(microsecond=0).isoformat()
    line = history or f"sweep.run_study({study.source or study.name!r})"
    return {
        "Conventions": CONVENTIONS,
        "title": study.title,
        "study_name": study.name,
        "study": study.text,
        "study_file": study.source or "",
        "source": f"{PACKAGE} {__version__}",
        "version": __version__,
        "sweep_law": describe_excitation(study.excitation, _horizontal_axes(study)),
        "history": f"{now} {line} - {PACKAGE} {__version__}",
        "date_created": now,
    }


def to_dataset(study, arrays, *, history=None):
    """The study's Dataset from per-cell arrays in cell order.

    Parameters
    ----------
    study : Study
    arrays : dict of str to ndarray, shape (n_cells, ...)
        Every variable of ``VARIABLES`` (see ``cells.run_chunk``).
    history : str, optional
        The command for the ``history`` attribute.

    Returns
    -------
    xarray.Dataset
        Dimensions = the study's dimensions (and ``mode``), coordinates = its axes.
    """
    import xarray as xr

    dims, _ = _dims(study)
    shape = study.shape
    coords = _coords(study)
    coords[MODE[0]] = (MODE[0], np.array(MODE[1]), MODE[2])
    data = {}
    for name, var in VARIABLES.items():
        if name in coords:  # e.g. a pga axis: its coordinate is the cells' PGA
            continue
        a = np.asarray(arrays[name], dtype=var.dtype)
        data[name] = (dims + var.dims, a.reshape(shape + a.shape[1:]), variable_attrs(name))
    return xr.Dataset(data, coords=coords, attrs=global_attrs(study, history))


def dataset_names(study):
    """{axis or zip-group name of the study: its name in the dataset}.

    A dotted scene path is named by its last key (``excitation.horizontal.magnitude`` ->
    ``magnitude``) when no other axis or group takes that name and it is not the name of an
    axis of ``io.vocabulary.AXES`` (``excitation.vertical.scale`` is not the ``scale``
    axis), else by the path with ``_`` for ``.`` (``excitation_vertical_scale``).  A name that is an
    attribute of ``xarray.Dataset`` or ``xarray.DataArray`` gets ``_factor`` (``size``) or
    ``_axis`` appended, so that ``ds.outcome.size_factor`` is the coordinate, not the element
    count.  Each coordinate keeps the study's name as its ``study_axis`` attribute.
    """
    import xarray as xr

    names = [axis.name for axis in study.axes]
    names += [dim.name for dim in study.dims if dim.name not in names]
    short = {n: n.rsplit(".", 1)[-1] for n in names}
    taken = list(short.values())
    out = {}
    for name in names:
        label = short[name]
        if label != name and (taken.count(label) > 1 or label in vocabulary.AXES):
            label = name.replace(".", "_")
        if (hasattr(xr.Dataset, label) or hasattr(xr.DataArray, label)
                or label in VARIABLES and label != name):
            label += "_factor" if label == "size" else "_axis"
        out[name] = label
    return out


def _dims(study):
    names = dataset_names(study)
    return tuple(names[dim.name] for dim in study.dims), names


def _coords(study):
    """Coordinates of every axis of a study, with their CF attributes."""
    dims, names = _dims(study)
    coords = {}
    for dim, dim_name in zip(study.dims, dims):
        for axis in dim.axes:
            coords[names[axis.name]] = (dim_name, axis.coords,
                                        {"units": axis.units, "long_name": axis.long_name,
                                         "study_axis": axis.name,
                                         **({"study_unit": axis.unit} if axis.unit else {})})
    return coords


def refine_attrs(study, rounds, simulations):
    """Global attributes of a refine study: its settings and what it cost."""
    _, axis = study_grid.refined_axis(study)
    return {
        "refine_axis": axis.name,
        "refine_dimension": dataset_names(study)[axis.name],
        "refine_tolerance": study.refine.tolerance,
        "refine_tolerance_units": axis.units,
        "refine_boundary": f"lowest {axis.name} at which the body overturns, by bisection "
                           "from the bracket between the first coarse value that overturned "
                           "and the one below it, to a bracket no wider than the tolerance",
        "refine_rounds": int(rounds),
        "refine_simulations": int(simulations),
        "refine_max_simulations": study_grid.max_simulations(study),
        "refine_dense_grid_simulations": study_grid.dense_simulations(study),
    }


def refine_dataset(study, arrays, *, rounds, history=None):
    """The Dataset of a refine study from per-line arrays (``refine.arrays``).

    Parameters
    ----------
    study : Study
        A study with ``refine``.
    arrays : dict of str to ndarray, shape (n_lines, ...)
        Every variable of ``REFINE_VARIABLES``, lines in C order of the other dimensions.
    rounds : int
        Rounds run, the coarse one included.
    history : str, optional
        The command for the ``history`` attribute.

    Returns
    -------
    xarray.Dataset
        Dimensions = the study's dimensions without the refined one (``coarse_overturned``
        has them all); coordinates = every axis, the refined one at its coarse values.
    """
    import xarray as xr

    k, axis = study_grid.refined_axis(study)
    dims, _ = _dims(study)
    line_dims, shape = dims[:k] + dims[k + 1:], study_grid.line_shape(study)
    data = {}
    for name, var in REFINE_VARIABLES.items():
        a = np.asarray(arrays[name], dtype=var.dtype)
        attrs = variable_attrs(name, REFINE_VARIABLES, axis)
        if var.dims:  # along the coarse values: the refined dimension back at its place
            data[name] = (dims, np.moveaxis(a.reshape(shape + a.shape[-1:]), -1, k), attrs)
        else:
            data[name] = (line_dims, a.reshape(shape), attrs)
    attrs = {**global_attrs(study, history),
             **refine_attrs(study, rounds, int(np.sum(arrays["simulations"])))}
    return xr.Dataset(data, coords=_coords(study), attrs=attrs)


def _nan_for_none(value):
    return np.nan if value is None else value


def history_dataset(history, scene, source=None, result=None):
    """The time history of one scene: a Dataset with dimension ``time``.

    Parameters
    ----------
    history : dict of str to ndarray, shape (n,)
        The kernel's history (``t`` and every name of ``HISTORY_VARIABLES``).
    scene : dict
        The resolved scene (its body's ``B``, ``H`` and G, ``x_G`` and ``y_G`` from the middle
        of the base, become attributes).
    source : str, optional
        The scene file, for the ``source`` attribute.
    result : SceneResult, optional
        The scene's result: its ``impact_count``, ``impact_log_truncated`` (1 when the
        result's impact log holds fewer impacts, else 0), ``energy_clamps`` and what the body
        did become attributes: ``status`` (its name), ``t_overturn`` and ``t_rest`` (NaN when
        none), ``overturn_direction`` (0 when none), ``max_abs_theta``, ``max_slip``,
        ``max_travel``, ``max_lift`` (units of ``VARIABLES``) and ``mode_time`` [s], one per motion type in the
        order of the ``flag_meanings`` of ``mode``.
    """
    import xarray as xr

    data = {name: ("time", np.asarray(history[name], dtype=var.dtype),
                   variable_attrs(name, HISTORY_VARIABLES))
            for name, var in HISTORY_VARIABLES.items()}
    body = scene["body"]
    x_G, y_G = (0.0, body["H"] / 2) if body.get("G") is None else body["G"]
    attrs = {"Conventions": CONVENTIONS, "title": "rigid block on a moving floor: history",
             "B": body["B"], "H": body["H"], "x_G": x_G, "y_G": y_G}
    if source is not None:
        attrs["source"] = source
    if result is not None:
        attrs.update(impact_count=result.impact_count,
                     impact_log_truncated=int(result.impact_log_truncated),
                     energy_clamps=result.energy_clamps, status=result.status,
                     t_overturn=_nan_for_none(result.t_overturn),
                     overturn_direction=result.overturn_direction or 0,
                     max_abs_theta=result.max_abs_theta, max_slip=result.max_slip,
                     max_travel=result.max_travel, max_lift=result.max_lift, t_rest=_nan_for_none(result.t_rest),
                     mode_time=np.array([result.mode_time[m] for m in codes.MODE_NAMES]))
    return xr.Dataset(data, coords={TIME[0]: (TIME[0], np.asarray(history["t"]), TIME[1])},
                      attrs=attrs)


def encoding(ds):
    """netCDF encoding: zlib level 1 on numbers; no ``_FillValue`` on integers and coordinates.

    Integer flags carry their ``flag_values`` (a fill value would be a code of its own), and
    coordinates are never missing.  Strings are stored uncompressed (netCDF-4 cannot filter
    variable-length data).
    """
    enc = {}
    for name, da in ds.variables.items():
        e = {}
        if da.dtype.kind in "iufb":
            e.update(zlib=True, complevel=COMPLEVEL)
        if da.dtype.kind in "iub" or name in ds.coords:
            e["_FillValue"] = None
        enc[name] = e
    return enc
