"""Text files of numbers in columns: time and acceleration (two columns), or accelerations alone
(one column, or any number of values per line read row by row) with the sample step given by
the user.  ``#`` starts a comment; blank lines are skipped.
"""
import numpy as np

from ..units import fixed_factor
from .base import (MAX_SAMPLES, RecordError, check_counts, check_finite, line_error,
                   make_record, parse_lines, read_lines)

# Times in text files carry a few decimals; a grid is uniform if every time is within this
# fraction of dt of t0 + k*dt (a wider jitter is a non-uniform file and is resampled).
_UNIFORM_TOL = 0.01
_DT_DIGITS = 12  # significant digits kept of dt fitted to printed times (0.02, not 0.0199...)


def read_two_column(path, units="m/s^2"):
    """Read a text file of two columns, time [s] and acceleration.

    Parameters
    ----------
    path : str or Path
    units : str
        Unit of the acceleration column: ``m/s^2`` (default), ``g``, ``gal`` or any fixed
        acceleration unit of :mod:`sweep.io.units`.

    Returns
    -------
    Record
        Times are taken relative to the first row.  Non-uniform times are resampled linearly
        onto a uniform grid whose step is the median step; the provenance says so.
    """
    factor = _factor(units, path)
    numbers, lines = _data_lines(path)
    values, counts = parse_lines(lines, numbers, path, bad="cannot read as a two-column text "
                                                          "file: {token!r} is not a number")
    check_counts(counts, 2, numbers, path,
                 "expected two columns (time, acceleration), found {found}")
    t, a = values[0::2], values[1::2]
    check_finite(t, numbers, path, "the time of data row")
    check_finite(a, numbers, path, "the acceleration of data row")
    dt, samples, note = _uniform(t, a * factor, numbers, path)
    provenance = f"{path}: two columns time/acceleration in {units}, n = {len(t)}{note}"
    return make_record(path, dt, samples, provenance)


def read_single_column(path, dt, units="m/s^2"):
    """Read a text file of accelerations alone, sampled every ``dt`` [s].

    Parameters
    ----------
    path : str or Path
        One value per line, or several read row by row.
    dt : float
        Sample step [s], from the scene: the file has no times.
    units : str
        Unit of the values, as for :func:`read_two_column`.
    """
    factor = _factor(units, path)
    numbers, lines = _data_lines(path)
    values, counts = parse_lines(lines, numbers, path)
    check_finite(values, np.repeat(numbers, counts), path)
    provenance = (f"{path}: one column of accelerations in {units}, n = {len(values)}, "
                  f"dt = {dt:g} s given in the scene")
    return make_record(path, dt, values * factor, provenance)


def _factor(units, path):
    try:
        return fixed_factor(units, "acceleration")
    except ValueError as err:
        raise RecordError(f"{path}: {err}") from None


def _data_lines(path):
    """``(numbers, lines)`` of the lines that hold data, comments cut off; numbers count from 1."""
    numbers, lines = [], []
    for number, line in enumerate(read_lines(path), 1):
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
