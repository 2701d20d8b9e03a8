"""PEER NGA ``.AT2`` files: acceleration in g (a ``units:`` other than g is refused).

The format: four header lines, the fourth giving NPTS and DT (``NPTS= 5372, DT= .0100 SEC`` or
the older ``5372 .0100 NPTS, DT``), then NPTS values in any number of columns.  The second line
names the event, date, station and component, the third the quantity and its unit
(``ACCELERATION TIME SERIES IN UNITS OF G``): a unit other than g named there is refused.
"""
import math
import re

import numpy as np

from ... import bodies
from ..units import fixed_factor
from .base import (MAX_SAMPLES, Reading, RecordError, check_finite, check_units, line_error,
                   make_record, parse_lines, read_lines)

_HEADER_LINES = 4
_UNITS = re.compile(r"\bUNITS?\s+OF\s+(\S+)", re.IGNORECASE)


def read_at2(path, units=None):
    """Read a PEER NGA ``.AT2`` file (acceleration in g) into m/s^2; ``units``, if given,
    must be g."""
    check_units(units, "g", bodies.G, path, said="a PEER .AT2 file is in")
    lines = read_lines(path)
    if len(lines) <= _HEADER_LINES:
        raise RecordError(f"{path}: not a PEER .AT2 file (fewer than 5 lines)")
    kind = lines[2].upper()
    if "VELOCITY" in kind or "DISPLACEMENT" in kind:
        raise RecordError(f"{path}: line 3 says this is not an acceleration record: {lines[2]}")
    units_from, units_line = _stated_units(lines[2], path)
    npts, dt = _npts_dt(lines[3], path)
    numbers = range(_HEADER_LINES + 1, len(lines) + 1)
    values, counts = parse_lines(lines[_HEADER_LINES:], numbers, path)
    if len(values) != npts:
        raise RecordError(f"{path}: header says NPTS = {npts}, found {len(values)} values")
    check_finite(values, np.repeat(numbers, counts), path)
    provenance = f"{path}: PEER NGA AT2, {lines[1].strip()}, NPTS = {npts}, DT = {dt:g} s, g"
    reading = Reading("at2", "PEER NGA AT2", units_from, units_line,
                      tuple(line.strip() for line in lines[:_HEADER_LINES]), lines[1].strip())
    return make_record(path, dt, values * bodies.G, provenance, "g", reading)


def _stated_units(line, path):
    """``(units_from, units_line)`` of the third header line: ``header`` where it names g,
    ``format`` where it names no unit (the format's g is taken)."""
    match = _UNITS.search(line)
    if match is None:
        return "format", None
    named = match[1].rstrip(".,;")
    try:
        factor = fixed_factor(named, "acceleration")
    except ValueError:
        return "format", None
    if not math.isclose(factor, bodies.G, rel_tol=1e-12):
        raise line_error(path, 3, f"names the unit {named}; a PEER .AT2 file is read in g")
    return "header", f"line 3: {line.strip()}"


def _npts_dt(line, path):
    npts = re.search(r"NPTS\s*=\s*(\d+)", line, re.IGNORECASE)
    dt = re.search(r"DT\s*=\s*([0-9.Ee+-]+)", line, re.IGNORECASE)
    try:
        if npts and dt:
            n, step = int(npts.group(1)), float(dt.group(1))
        else:  # old format: "NPTS DT" as the first two numbers of the line
            first, second = line.split()[:2]
            n, step = int(first), float(second)
    except ValueError:
        n, step = 0, 0.0
    if n < 2 or not 0 < step < math.inf:
        raise RecordError(f"{path}: line 4 should give NPTS and DT, got: {line.strip()}")
    if n > MAX_SAMPLES:
        raise line_error(path, 4, f"NPTS = {n} is more than {MAX_SAMPLES}")
    return n, step
