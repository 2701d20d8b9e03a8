"""Text files of numbers in columns: time and acceleration, or accelerations alone.

Two columns (time and acceleration), or accelerations alone (one column, or any number of
values per line read row by row) with the sample step given by the user.  ``#`` starts a
comment; blank lines are skipped.

A comment may state the acceleration unit: ``# acceleration [g]``, ``# units: gal``, ``# m/s^2``
(:func:`stated_units`).  The numbers are read in that unit unless the user gives another, which
is refused; without either they are in m/s^2.
"""
import re

import numpy as np

from ..units import fixed_factor
from .base import (MAX_SAMPLES, Reading, RecordError, check_counts, check_finite, check_units,
                   line_error, make_record, parse_lines, read_lines)

# Times in text files carry a few decimals; a grid is uniform if every time is within this
# fraction of dt of t0 + k*dt (a wider jitter is a non-uniform file and is resampled).
_UNIFORM_TOL = 0.01
_DT_DIGITS = 12  # significant digits kept of dt fitted to printed times (0.02, not 0.0199...)
DEFAULT_UNITS = "m/s^2"
HEADER_COMMENTS = 20  # comments of a file shown as its header (a file may comment every row)
_WORD = re.compile(r"[A-Za-z][A-Za-z0-9/^*]*")  # a unit's spelling: m/s^2, cm/sec2, gal, g
_AFTER_NUMBER = re.compile(r"\d\s*$")  # "0.35 g", "342 gal": a value, not the column's unit
_INTRODUCED = re.compile(r"(?:\b(?:in|units?|of)\s*[:=]?|[\[(])\s*$", re.IGNORECASE)


def read_two_column(path, units=None):
    """Read a text file of two columns, time [s] and acceleration.

    Parameters
    ----------
    path : str or Path
    units : str, optional
        Unit of the acceleration column: ``m/s^2``, ``g``, ``gal`` or any fixed acceleration
        unit of :mod:`sweep.io.units`; default the unit a comment states, else m/s^2.

    Returns
    -------
    Record
        Times are taken relative to the first row.  Non-uniform times are resampled linearly
        onto a uniform grid whose step is the median step; the provenance says so.
    """
    text = read_lines(path)
    units, factor, said, units_from = _units(units, text, path)
    numbers, lines = _data_lines(text, path)
    values, counts = parse_lines(lines, numbers, path, bad="cannot read as a two-column text "
                                                          "file: {token!r} is not a number")
    check_counts(counts, 2, numbers, path,
                 "expected two columns (time, acceleration), found {found}")
    t, a = values[0::2], values[1::2]
    check_finite(t, numbers, path, "the time of data row")
    check_finite(a, numbers, path, "the acceleration of data row")
    dt, samples, note = _uniform(t, a * factor, numbers, path)
    provenance = f"{path}: two columns time/acceleration in {said}, n = {len(t)}{note}"
    reading = _reading("columns", "two columns (time, acceleration)", units_from, text,
                       (note[2:],) if note else ())
    return make_record(path, dt, samples, provenance, units, reading)


def read_single_column(path, dt, units=None):
    """Read a text file of accelerations alone, sampled every ``dt`` [s].

    Parameters
    ----------
    path : str or Path
        One value per line, or several read row by row.
    dt : float
        Sample step [s], from the scene: the file has no times.
    units : str, optional
        Unit of the values, as for :func:`read_two_column`.
    """
    text = read_lines(path)
    units, factor, said, units_from = _units(units, text, path)
    numbers, lines = _data_lines(text, path)
    values, counts = parse_lines(lines, numbers, path)
    check_finite(values, np.repeat(numbers, counts), path)
    provenance = (f"{path}: one column of accelerations in {said}, n = {len(values)}, "
                  f"dt = {dt:g} s given in the scene")
    reading = _reading("column", "one column (accelerations, dt given)", units_from, text)
    return make_record(path, dt, values * factor, provenance, units, reading)


def _comments(text):
    """The ``#`` comments of a file's lines, ``(line number, text)``, in order."""
    return [(number, line.partition("#")[2].strip()) for number, line in enumerate(text, 1)
            if "#" in line and line.partition("#")[2].strip()]


def _reading(format, reader, units_from, text, notes=()):
    """The :class:`Reading` of a column file: its comments are its header (the first
    ``HEADER_COMMENTS``), the first one its title; ``units_from`` = ``(where, line number or
    None)`` from :func:`_units`."""
    found = _comments(text)
    where, line = units_from
    return Reading(format, reader, where, None if line is None else
                   f"line {line}: {text[line - 1].strip()}",
                   tuple(comment for _, comment in found[:HEADER_COMMENTS]),
                   found[0][1] if found else "",
                   notes)


def stated_units(text):
    """The acceleration units the comments of a file state: ``[(unit, factor to m/s^2, line
    number)]``, one for each comment line that names one unit.

    A unit is named where it is compound (``m/s^2``), in brackets (``[g]``, ``(gal)``), after
    ``in``, ``unit(s)`` or ``of`` (``units: g``), or alone in its comment (``# gal``).  A unit
    right after a number (``peak 0.35 g``) is a value's, and a line that names several
    (``converted from g to m/s^2``) states none.
    """
    found = []
    for number, line in enumerate(text, 1):
        comment = line.partition("#")[2]
        named = {}
        for match in _WORD.finditer(comment):
            before = comment[:match.start()]
            if _AFTER_NUMBER.search(before) or not (
                    "/" in match[0] or comment.strip() == match[0] or _INTRODUCED.search(before)):
                continue
            try:
                named.setdefault(fixed_factor(match[0], "acceleration"), match[0])
            except ValueError:
                continue  # not an acceleration unit
        if len(named) == 1:
            (factor, unit), = named.items()
            found.append((unit, factor, number))
    return found


def _units(given, text, path):
    """``(unit, factor to m/s^2, how the provenance says it, (where from, line))`` of a file's
    numbers: the unit its comments state (:func:`stated_units`; from ``comment``, its line),
    which ``given`` (``units:``) must equal, else ``given`` (``units:``), else m/s^2
    (``default``).  Comments that state different units need ``given``."""
    stated = {}  # factor -> (unit, line) of the first line that states it
    for unit, factor, line in stated_units(text):
        stated.setdefault(factor, (unit, line))
    if len(stated) > 1:
        lines = ", ".join(f"line {line}: {unit}" for unit, line in stated.values())
        if given is None:
            raise RecordError(f"{path}: the comments state different units ({lines}): give "
                              "units:")
        return (given, _factor(given, path), f"{given} (units:; the comments state {lines})",
                ("units:", None))
    if stated:
        (factor, (unit, line)), = stated.items()
        check_units(given, unit, factor, path, line, said="a comment gives the accelerations "
                                                           "in")
        return unit, factor, f"{unit} (stated on line {line})", ("comment", line)
    if given is not None:
        return given, _factor(given, path), f"{given} (units:)", ("units:", None)
    return (DEFAULT_UNITS, 1.0, f"{DEFAULT_UNITS} (the default: no units: nor a comment)",
            ("default", None))


def _factor(units, path):
    try:
        return fixed_factor(units, "acceleration")
    except ValueError as err:
        raise RecordError(f"{path}: {err}") from None


def _data_lines(text, path):
    """``(numbers, lines)`` of the lines of ``text`` that hold data, comments cut off; numbers
    count from 1."""
    numbers, lines = [], []
    for number, line in enumerate(text, 1):
        data = line.split("#", 1)[0]
        if data.strip():
            numbers.append(number)
            lines.append(data)
    if not lines:
        raise RecordError(f"{path}: no data rows")
    return np.array(numbers), lines


def _round(dt):
    """``dt`` to ``_DT_DIGITS`` significant digits."""
    return float(f"{dt:.{_DT_DIGITS}g}")


def _uniform(t, a, numbers, path):
    """``(dt, samples, note)`` on a uniform grid from times ``t`` (row k on line numbers[k]),
    resampling if needed."""
    if len(t) < 2:
        raise RecordError(f"{path}: needs at least two samples")
    steps = np.diff(t)
    if not np.all(steps > 0):
        row = int(np.argmin(steps > 0)) + 1
        raise line_error(path, numbers[row], f"times must increase (data row {row + 1})")
    if not np.isfinite(t[-1] - t[0]):
        raise RecordError(f"{path}: the times span more than the float range")
    dt = _round(float((t[-1] - t[0]) / (len(t) - 1)))
    if np.max(np.abs(t - t[0] - dt * np.arange(len(t)))) <= _UNIFORM_TOL * dt:
        return dt, a, ""
    dt = _round(float(np.median(steps)))
    # 1e-9 keeps the last time when (t[-1] - t[0])/dt is an integer up to rounding
    count = np.floor((t[-1] - t[0]) / dt + 1e-9) + 1
    if not count <= MAX_SAMPLES:
        raise RecordError(f"{path}: non-uniform times resampled onto their median step dt = "
                          f"{dt:g} s would make {count:g} samples, more than {MAX_SAMPLES}")
    grid = t[0] + dt * np.arange(int(count))
    note = (f"; non-uniform times resampled linearly onto dt = {dt:g} s "
            f"(the median step), {len(grid)} samples")
    return dt, np.interp(grid, t, a), note
