"""The paper's normalized plane for frequency sweeps (Ishiyama 1982, Figs 8-11).

Abscissa: the normalized velocity, velocity amplitude / v_H (the single-shock velocity of
Eq. 9); ordinate: the normalized acceleration, acceleration amplitude / ((B/H) g) (West,
Eq. 1).  On these log axes a sweep runs along a straight line: horizontal at constant
acceleration, vertical at constant velocity, of slope 2 at constant displacement.
``sweep_cells`` reads a sweep study's dataset into where each cell's sweep starts, ends and
overturns; an overturning after the excitation stopped is not a result of the sweep and is
marked ``late``.
"""
import itertools
from collections import namedtuple

import numpy as np

from ..io import units
from ..io.scene_models import HOLD_DIMENSIONS
from . import classify, criteria

SweepCells = namedtuple("SweepCells", "hold down start end point late failed series labels "
                                      "body tilt")
SweepCells.__doc__ = """The cells of one sweep study in the normalized plane.

hold : 'acceleration', 'velocity' or 'displacement'; down : True when swept down in frequency;
start, end : ndarray, shape (n, 2), (v, a) where each cell's sweep starts and where it ends
(at the overturning, or at the end of the sweep; NaN for a failed cell); point : ndarray,
shape (n, 2), (v, a) at overturning during the sweep, NaN otherwise; late : bool array,
overturned after the excitation stopped; failed : bool array; series : int array, the
combination of the study's other axes (not ``amplitude``) of each cell; labels : one text per
series; body : text naming the body (or bodies); tilt : initial tilt / alpha of the cells."""


def plane_point(ground, body, f):
    """(v, a): the sweep ``ground`` (resolved, SI) at frequency ``f`` in the normalized plane."""
    held = units.Quantity(ground["amplitude"], "", HOLD_DIMENSIONS[ground["hold"]])
    a, v = criteria.normalized_plane(units.acceleration_amplitude(held, f), f, body["B"],
                                     body["H"], body["i_g"])
    return float(v), float(a)


def value_text(name, value):
    """'amplitude = 1.1 west', 'vertical_amplitude = 0.3 g': an axis value as written."""
    try:
        value = units.parse_quantity(value, units.DIMENSIONS)
    except ValueError:
        pass  # a name
    return f"{name} = {value}"


def _series(study):
    """Index of the combination of the study's dimensions other than ``amplitude`` of each
    cell (in cell order), and one label per combination."""
    others = [k for k, dim in enumerate(study.dims)
              if all(axis.name != "amplitude" for axis in dim.axes)]
    positions = np.indices(study.shape).reshape(len(study.dims), -1)[others]
    sizes = [study.dims[k].size for k in others]
    series = (np.ravel_multi_index(positions, sizes) if others
              else np.zeros(positions.shape[1], dtype=int))
    labels = [", ".join(value_text(axis.name, axis.values[i])
                        for k, i in zip(others, combo) for axis in study.dims[k].axes)
              for combo in itertools.product(*(range(n) for n in sizes))]
    return series, labels


def _body_text(bodies):
    """'B x H = 5 x 15 cm (b/h = 1/3)' or 'several bodies'."""
    if len(bodies) > 1:
        return "several bodies"
    B, H = next(iter(bodies))
    return f"B × H = {100 * B:.3g} × {100 * H:.3g} cm (b/h = 1/{H / B:.3g})"


def _amplitudes(ds, study, group, scenes):
    """The held amplitude [SI unit of the hold] of every cell: from the dataset's ``amplitude``
    coordinate (body-relative levels times the cell's body), else from the cell's scene."""
    k = classify.amplitude_dim(study)
    if k is None:  # every cell is a group of its own: its scene has its amplitude
        return np.array([scene["excitation"]["horizontal"]["amplitude"] for scene in scenes])
    coord = ds["amplitude"]
    position = np.indices(study.shape).reshape(len(study.dims), -1)[k]
    unit = coord.attrs.get("study_unit", "")
    out = np.empty(study.n_cells)
    for i, (g, p) in enumerate(zip(group, position)):
        value = float(coord.values[p])
        scene = scenes[g]
        hold = scene["excitation"]["horizontal"]["hold"]
        quantity = units.parse_quantity(f"{value!r} {unit}".strip(), HOLD_DIMENSIONS[hold])
        out[i] = quantity.to_si(scene["body"]) if quantity.body_relative else value
    return out


def sweep_cells(ds):
    """The cells of a sweep study's dataset in the normalized plane (a ``SweepCells``).

    The overturning points are the dataset's ``v_norm_at_overturn`` and
    ``a_norm_at_overturn``; where each sweep starts and ends follows from its amplitude (the
    ``amplitude`` coordinate) and the scene of its group (``classify.scene_groups``: one
    resolved scene per combination of the other axes).
    """
    study = classify.study_of(ds)
    group, scenes = classify.scene_groups(study)
    for scene in scenes:
        if scene["excitation"]["horizontal"]["kind"] != "sweep":
            raise ValueError(f"the horizontal excitation of {study.name} is not a sweep")
    amplitude = _amplitudes(ds, study, group, scenes)
    n = int(ds["outcome"].size)
    f_over = ds["f_at_overturn"].values.ravel()
    v_over, a_over = (ds[f"{q}_norm_at_overturn"].values.ravel() for q in "va")
    overturned = ds["overturned"].values.ravel() == 1
    failed = ds["outcome"].values.ravel() == -1
    t_overturn = ds["t_overturn"].values.ravel()
    end_of = np.array([classify.excitation_end(scene) for scene in scenes])[group]
    late = overturned & (t_overturn > end_of)
    start, end = np.full((n, 2), np.nan), np.full((n, 2), np.nan)
    for i in range(n):
        scene = scenes[group[i]]
        ground = {**scene["excitation"]["horizontal"], "amplitude": amplitude[i]}
        body = scene["body"]
        start[i] = plane_point(ground, body, ground["f_start"])
        if not failed[i]:
            on_time = overturned[i] and not late[i]
            end[i] = plane_point(ground, body, f_over[i] if on_time else ground["f_stop"])
    ground = scenes[-1]["excitation"]["horizontal"]
    during = overturned & ~late
    point = np.where(during[:, None], np.column_stack([v_over, a_over]), np.nan)
    series, labels = _series(study)
    bodies = {(s["body"]["B"], s["body"]["H"]) for s in scenes}
    tilts = {s["initial"]["theta"] / criteria.body_constants(s["body"]["B"],
                                                               s["body"]["H"]).alpha
             for s in scenes}
    return SweepCells(ground["hold"], ground["f_stop"] < ground["f_start"], start, end, point,
                      late, failed, series, labels, _body_text(bodies),
                      float(max(tilts, key=abs)))


def lowest_points(cells):
    """(v, a) of the overturning with the lowest normalized velocity and of the one with the
    lowest normalized acceleration (NaN without overturning)."""
    ok = ~np.isnan(cells.point[:, 0])
    if not np.any(ok):
        return (np.nan, np.nan), (np.nan, np.nan)
    pts = cells.point[ok]
    return tuple(pts[np.argmin(pts[:, 0])]), tuple(pts[np.argmin(pts[:, 1])])
