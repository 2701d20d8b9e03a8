"""Overturning boundaries by bisection along one axis of a study (docs/design.md section 7).

A study with ``refine: {axis, tolerance}`` seeks, on every *line* (one combination of the other
axes' values), the lowest value of the refined axis at which the body overturns.  Round 0 is
the study's own grid: the coarse values.  Scanning a line's coarse values upward, the first
one that overturned and the one below it bracket the boundary.  Each further round simulates
the midpoints of all brackets still wider than the tolerance as one batch of cells (a *point
study*: one dimension along which every axis takes its points' values), run, stored and
resumed like any grid, and keeps the half whose ends differ.

Only that first transition is followed.  On a line whose coarse values overturn, stand and
overturn again (``coarse_transitions`` > 1) the bracket is the lowest one the coarse values
show; a band of overturning between two standing coarse values is not seen.  A line whose
scan meets a failed simulation before any overturning, or whose midpoint fails, stops there
(``simulation_failed``) and keeps its bracket so far.

The lines and what a refine study may cost (``refined_axis``, ``line_shape``, ``wide``,
``max_simulations``, ...) are counted in ``sweep.io.study_grid``, the names of the bracket
codes (``BRACKET_NAMES``) are the dataset's (``sweep.cf``); both are imported here under the
same names.
"""
import dataclasses
from collections import namedtuple

import numpy as np

from ..cf import BRACKET_NAMES
from ..io import units
from ..io.study_axes import Dim
from ..io.study_grid import (SLACK, dense_simulations, line_shape, max_rounds,  # noqa: F401
                             max_simulations, refined_axis, rounds_needed, wide)

BRACKETED, NEVER_OVERTURNED, OVERTURNED_AT_START, FAILED = 0, 1, 2, 3  # of BRACKET_NAMES
OVERTURNED, STANDING = 1, 0  # values of the ``overturned`` variable (-1: failed)
POINT = "point"  # the one dimension of a point study

Brackets = namedtuple("Brackets", "lower upper flag simulations transitions coarse rounds")
Brackets.__doc__ = """State of the bisection, one entry per line (lines in C order of the other
dimensions): ``lower`` highest value found standing, ``upper`` lowest value found overturned
(NaN: none), ``flag`` a code of ``BRACKET_NAMES``, ``simulations`` run on the line,
``transitions`` changes between standing and overturned along the coarse values, ``coarse``
the coarse values' ``overturned`` codes, shape (n_lines, n_coarse), ``rounds`` done so far."""


def coarse_cells(study):
    """Cell ids of the study's grid by line and coarse value, int64 of shape (n_lines, n)."""
    k, axis = refined_axis(study)
    ids = np.arange(study.n_cells, dtype=np.int64).reshape(study.shape)
    return np.moveaxis(ids, k, -1).reshape(-1, axis.coords.size)


def start(coords, coarse):
    """Brackets from the coarse values of every line.

    Parameters
    ----------
    coords : ndarray, shape (n,)
        The refined axis's coordinates, increasing.
    coarse : ndarray of int8, shape (n_lines, n)
        ``overturned`` of each line at each coarse value: 1, 0, or -1 (failed).

    Returns
    -------
    Brackets
        Per line: the first coarse value that did not stand and the one below it.
    """
    coarse = np.asarray(coarse, dtype=np.int8)
    n_lines = coarse.shape[0]
    lower, upper = np.full(n_lines, np.nan), np.full(n_lines, np.nan)
    flag = np.full(n_lines, BRACKETED, dtype=np.int8)
    transitions = np.zeros(n_lines, dtype=np.int32)
    for line, row in enumerate(coarse):
        known = row[row >= 0]
        transitions[line] = np.count_nonzero(np.diff(known))
        stops = np.flatnonzero(row != STANDING)
        if stops.size == 0:
            flag[line], lower[line] = NEVER_OVERTURNED, coords[-1]
            continue
        j = stops[0]
        if j > 0:
            lower[line] = coords[j - 1]
        if row[j] == OVERTURNED:
            upper[line] = coords[j]
            flag[line] = BRACKETED if j > 0 else OVERTURNED_AT_START
        else:
            flag[line] = FAILED
    simulations = np.full(n_lines, coarse.shape[1], dtype=np.int32)
    return Brackets(lower, upper, flag, simulations, transitions, coarse, 1)


def open_lines(brackets, tolerance):
    """Lines whose bracket is still wider than ``tolerance``, and their midpoints."""
    width = brackets.upper - brackets.lower
    lines = np.flatnonzero((brackets.flag == BRACKETED) & wide(width, tolerance))
    return lines, 0.5 * (brackets.lower[lines] + brackets.upper[lines])


def narrow(brackets, lines, midpoints, overturned):
    """Brackets after simulating ``lines`` at their ``midpoints`` (``overturned`` codes)."""
    overturned = np.asarray(overturned)
    lower, upper = brackets.lower.copy(), brackets.upper.copy()
    flag, simulations = brackets.flag.copy(), brackets.simulations.copy()
    upper[lines[overturned == OVERTURNED]] = midpoints[overturned == OVERTURNED]
    lower[lines[overturned == STANDING]] = midpoints[overturned == STANDING]
    flag[lines[overturned < 0]] = FAILED
    simulations[lines] += 1
    return brackets._replace(lower=lower, upper=upper, flag=flag, simulations=simulations,
                             rounds=brackets.rounds + 1)


def _raw(axis, value):
    """A coordinate of ``axis`` as a scene value: ``"1.25 west"``, ``"45.0 deg"``,
    ``"0.3 m/s"``, ``0.25``."""
    value = float(value)
    if axis.written_coords:
        return f"{value!r} {axis.unit}"
    # coordinates are SI: written with the SI unit, as a bare number may mean another unit
    si = units.units_of(axis.dimension) if axis.dimension in units.DIMENSIONS else ()
    return f"{value!r} {si[0]}" if si else value


def point_study(study, lines, values):
    """The cells of one round: line ``lines[i]`` at ``values[i]`` of the refined axis.

    A study with one dimension, ``point``, that holds every axis of ``study``; its cells run,
    are stored and resume like those of any grid.
    """
    k, _ = refined_axis(study)
    lines = np.asarray(lines, dtype=np.int64)
    positions = iter(np.unravel_index(lines, line_shape(study)) if len(study.dims) > 1 else ())
    axes = []
    for i, dim in enumerate(study.dims):
        if i == k:
            axis = dim.axes[0]
            axes.append(dataclasses.replace(axis, values=tuple(_raw(axis, v) for v in values),
                                            coords=np.asarray(values, dtype=np.float64)))
            continue
        where = next(positions)
        axes += [dataclasses.replace(axis, values=tuple(axis.values[p] for p in where),
                                     coords=axis.coords[where]) for axis in dim.axes]
    return dataclasses.replace(study, dims=(Dim(POINT, tuple(axes)),), refine=None)


def bisect(study, evaluate):
    """Every round of a refine study; the final brackets.

    Parameters
    ----------
    study : Study
        A study with ``refine``.
    evaluate : callable
        ``evaluate(round, round_study)`` runs the cells of a round (round 0: ``study`` itself,
        then point studies) wherever they run and returns their ``overturned`` codes in cell
        order.

    Returns
    -------
    Brackets
    """
    _, axis = refined_axis(study)
    coarse = np.asarray(evaluate(0, study))[coarse_cells(study)]
    brackets = start(axis.coords, coarse)
    while True:
        lines, midpoints = open_lines(brackets, study.refine.tolerance)
        if lines.size == 0:
            return brackets
        overturned = evaluate(brackets.rounds, point_study(study, lines, midpoints))
        brackets = narrow(brackets, lines, midpoints, overturned)


def arrays(brackets):
    """The per-line arrays of ``cf.REFINE_VARIABLES``; ``boundary`` is the bracket's middle."""
    return {"boundary": 0.5 * (brackets.lower + brackets.upper),
            "boundary_lower": brackets.lower, "boundary_upper": brackets.upper,
            "bracket": brackets.flag, "simulations": brackets.simulations,
            "coarse_transitions": brackets.transitions,
            "coarse_overturned": brackets.coarse}
