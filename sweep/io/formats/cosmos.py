"""COSMOS and CSMIP Volume 2 files: corrected accelerograms of one or several components.

COSMOS V2 (COSMOS Strong Motion Data Format, ver. 1.20, 2001; ``.V2``, ``.V2c``), per component:
text lines, the first giving their count (``Corrected acceleration (Format v01.20 with 13 text
lines)``); an integer and a real header, each announced by a line with its count and Fortran
format (``100 Real-header values follow on 20 lines, Format= (5F15.6)``); comment lines,
announced by their count; then data blocks, each announced by a line with its count, quantity,
units code and format (``42000 acceleration pts, approx 210 secs, units=cm/sec2(04),
Format=(1E15.6)``) and followed by an ``End-of-data`` line.  The sample step is real-header
value 62, in ms.

CSMIP Volume 2 (California Strong Motion Instrumentation Program, ``.V2``), per channel: 25 text
lines (the first ``Corrected accelerogram ... Chan  1: 360 Deg``), 100 integers on 7 lines and
100 reals on 13 lines, then the acceleration, velocity and displacement blocks, each announced
by a line with its count, step, units and format (``12000 points of accel data equally spaced
at .005 sec, in cm/sec2. (8f10.6)``), and an end line (``/& -- End of data for channel 1 --``).
Older files write ``3251 POINTS OF ACCEL DATA EQUALLY SPACED AT .020 SEC. (UNITS: CM/SEC/SEC)``
and no format: their values are in CSMIP's 8F10 layout.

Values are read in the fixed-width fields of the announced format.  Only the acceleration block
is used, as the network corrected it (instrument response, baseline, band-pass filter).
"""
import re
from collections import namedtuple

import numpy as np

from ... import bodies
from ..units import fixed_factor
from .base import (MAX_SAMPLES, Reading, RecordError, check_counts, check_finite, check_units,
                   fixed_width, line_error, make_record, parse_lines, read_lines)

EXTENSIONS = (".v2", ".v2c")
# COSMOS table 2, the acceleration units: code -> (name, factor to m/s^2)
COSMOS_UNITS = {2: ("g", bodies.G), 4: ("cm/s^2", 0.01), 7: ("in/s^2", 0.0254),
                10: ("gal", 0.01), 11: ("mg", bodies.G / 1000.0)}
_DT_MS = 62  # the real-header value that is the sample step [ms]
_CSMIP_HEADER_LINES = 25 + 7 + 13  # text, integer-header and real-header lines of a channel
_CSMIP_LAYOUT = (8, 10)  # values per line and field width where a CSMIP data line gives none

_FORMAT = r"\(\s*(?P<per_line>\d+)\s*[a-z]\s*(?P<width>\d+)(?:\.\d+)?\s*\)"
_COSMOS_FIRST = re.compile(r"\(format\s+v?\s*[\d.]+\s+with\s+(\d+)\s+text\s+lines\)", re.I)
_CSMIP_FIRST = re.compile(r"\s*corrected\s+accelerogram", re.I)
_HEADER_BLOCK = re.compile(r"\s*(?P<count>\d+)\s+(?:integer|real)-header\s+values\s+follow\b"
                           r".*?format\s*=\s*" + _FORMAT, re.I)
_COMMENTS = re.compile(r"\s*(\d+)\s+comment\s+line", re.I)
_END = re.compile(r"end[\s-]+of[\s-]+data", re.I)

_Dialect = namedtuple("_Dialect", "label header data example")
"""A file layout: its name, its channel-header reader, the pattern of a data block's first
line, and an example of the acceleration block's first line for messages."""
_Channel = namedtuple("_Channel", "name header dt block")
_Channel.__doc__ = """A component: its name, the header lines that describe it (the first, then
those naming the event and station), its sample step (None: on the data line) and its
acceleration block ``(match, index of the announcing line, values, line of each value)``."""


def read_cosmos(path, component=None, units=None):
    """Read the corrected acceleration of one component of a COSMOS or CSMIP Volume 2 file.

    Parameters
    ----------
    path : str or Path
    component : int or str, optional
        Which component, in a file that holds several: its place in the file (1, 2, ...) or its
        name, the orientation its header gives (``360 Deg``, ``Up``; case, spaces and a
        trailing ``deg`` ignored).
    units : str, optional
        Must be the unit the acceleration block's header gives, if given.

    Returns
    -------
    Record
        Acceleration in m/s^2, converted from the units the file gives.

    Raises
    ------
    RecordError
        A header or data line out of place or unreadable (the message names it), a unit that
        is not an acceleration, or several components and no ``component`` (the message lists
        them).
    """
    lines = read_lines(path)
    first = next((line for line in lines if line.strip()), "")
    dialect = _COSMOS if _COSMOS_FIRST.search(first) else _CSMIP
    channels = list(_channels(lines, dialect, path))
    if not channels:
        raise RecordError(f"{path}: empty file")
    k = _choose(channels, component, path)
    channel = channels[k]
    match, announced, values, line_of = channel.block
    stated, factor = _units(match, announced, path)
    check_units(units, stated, factor, path, announced + 1,
                said="the header gives the accelerations in")
    check_finite(values, line_of, path)
    dt = channel.dt if channel.dt is not None else _step(match["dt"], announced, path)
    description = "; ".join(channel.header[1:])
    provenance = (f"{path}: {dialect.label}, {description}, component {k + 1} of "
                  f"{len(channels)} ({channel.name}), acceleration block of line "
                  f"{announced + 1}: n = {len(values)}, dt = {dt:g} s, in {stated}; corrected "
                  f"by the network (Volume 2), used as given")
    reading = Reading("cosmos", dialect.label, "header",
                      f"line {announced + 1}: {lines[announced].strip()}",
                      (*channel.header, " ".join(lines[announced].split())),
                      f"{description}; component {k + 1} of {len(channels)} ({channel.name})")
    return make_record(path, dt, values * factor, provenance, stated, reading)


def _channels(lines, dialect, path):
    """Each channel's :class:`_Channel`, its acceleration block read, the others skipped."""
    start = 0
    while True:
        while start < len(lines) and not lines[start].strip():
            start += 1
        if start == len(lines):
            return
        name, header, dt, i = dialect.header(lines, start, path)
        acceleration = None
        while i < len(lines) and (match := dialect.data.match(lines[i])):
            if acceleration is None and match["quantity"].lower().startswith("accel"):
                values, line_of = _fixed_block(lines, i, int(match["count"]), _layout(match),
                                               path)
                acceleration = (match, i, values, line_of)
            i += 1 + _extent(lines, i, int(match["count"]), _layout(match), path)
            if i < len(lines) and _END.search(lines[i]):
                i += 1
        if acceleration is None:
            _expect(dialect.data, lines, i, path, dialect.example)
        yield _Channel(name, header, dt, acceleration)
        start = i


def _cosmos_header(lines, start, path):
    """``(name, header lines, dt, index of the first data block)`` of a COSMOS component."""
    first = _expect(_COSMOS_FIRST, lines, start, path,
                    "a COSMOS header, e.g. 'Corrected acceleration (Format v01.20 with 13 "
                    "text lines)'", search=True)
    data_type = lines[start][:first.start()].strip()
    if not re.match(r"corrected\s+acceleration", data_type, re.I):
        raise line_error(path, start + 1, f"{data_type!r}: only corrected acceleration "
                                          "(Volume 2) is read")
    text = lines[start:start + int(first[1])]
    i = start + len(text)
    integer = _expect(_HEADER_BLOCK, lines, i, path, "'100 Integer-header values follow on 10 "
                                                     "lines, Format= (10I8)'")
    i += 1 + _extent(lines, i, int(integer["count"]), _layout(integer), path)
    real = _expect(_HEADER_BLOCK, lines, i, path, "'100 Real-header values follow on 20 lines, "
                                                  "Format= (5F15.6)'")
    reals, line_of = _fixed_block(lines, i, int(real["count"]), _layout(real), path)
    if len(reals) < _DT_MS or not 0 < reals[_DT_MS - 1] < np.inf:
        raise line_error(path, line_of[-1] if len(reals) < _DT_MS else line_of[_DT_MS - 1],
                         f"real-header value {_DT_MS}, the sample step in ms, is missing or "
                         "not positive")
    i += 1 + _extent(lines, i, int(real["count"]), _layout(real), path)
    comments = _expect(_COMMENTS, lines, i, path, "'2 Comment line(s) follow, each starting "
                                                  "with a \"|\":'")
    i += 1 + int(comments[1])
    station = re.search(r"Sta\s+Chan\s+\S+\s*:\s*(.*?)\s*\(", text[8] if len(text) > 8 else "")
    name = station[1] if station and station[1] else "unnamed"
    header = tuple(" ".join(text[k].split()) for k in (0, 1, 4) if k < len(text))
    return name, header, reals[_DT_MS - 1] / 1000.0, i


def _csmip_header(lines, start, path):
    """``(name, header lines, None, index of the first data block)`` of a CSMIP channel: its
    sample step is on the data lines."""
    _expect(_CSMIP_FIRST, lines, start, path, "a COSMOS header ('Corrected acceleration "
            "(Format v01.20 with 13 text lines)') or a CSMIP Volume 2 channel ('Corrected "
            "accelerogram ... Chan  1: 360 Deg')")
    channel = re.search(r"Chan\s+\d+\s*:\s*(\S+(?: \S+)*)", lines[start], re.I)
    text = lines[start:start + _CSMIP_HEADER_LINES]
    header = tuple(" ".join(text[k].split()) for k in (0, 2, 5, 6) if k < len(text))
    name = channel[1] if channel else "unnamed"
    return name, header, None, start + _CSMIP_HEADER_LINES


_COSMOS = _Dialect(
    "COSMOS V2", _cosmos_header,
    re.compile(r"\s*(?P<count>\d+)\s+(?P<quantity>acceleration|velocity|displacement)\s+pts\b"
               r".*?units\s*=\s*(?P<units>[^(,]*?)\s*\(\s*(?P<code>\d+)\s*\)"
               r".*?format\s*=\s*" + _FORMAT, re.I),
    "'42000 acceleration pts, approx 210 secs, units=cm/sec2(04), Format=(1E15.6)'")
_CSMIP = _Dialect(
    "CSMIP Volume 2", _csmip_header,
    re.compile(r"\s*(?P<count>\d+)\s+points\s+of\s+(?P<quantity>accel|veloc|displ)\w*\s+data"
               r"\s+equally\s+spaced\s+at\s+(?P<dt>[0-9.]+)\s*sec[.,]\s*"
               r"(?:in\s+(?P<units>[^(]*?)|\(units:\s*(?P<old_units>[^)]*)\))\.?\s*"
               r"(?:" + _FORMAT + r")?\s*$", re.I),
    "'12000 points of accel data equally spaced at .005 sec, in cm/sec2. (8f10.6)'")


def _expect(pattern, lines, i, path, example, search=False):
    """The match of ``pattern`` on lines[i], or the error naming line i + 1."""
    line = lines[i] if i < len(lines) else None
    match = line is not None and (pattern.search(line) if search else pattern.match(line))
    if not match:
        got = "the end of the file" if line is None else repr(line.strip())
        raise line_error(path, i + 1, f"expected {example}, got {got}")
    return match


def _layout(match):
    """``(values per line, field width)`` of the block that ``match`` announces."""
    if match["per_line"] is None:
        return _CSMIP_LAYOUT
    return int(match["per_line"]), int(match["width"])


def _extent(lines, announced, count, layout, path):
    """Number of lines of the block of ``count`` values announced on lines[announced], written
    ``layout`` = (values per line, field width)."""
    per_line, width = layout
    if count > MAX_SAMPLES:
        raise line_error(path, announced + 1, f"{count} values, more than {MAX_SAMPLES}")
    if per_line < 1 or width < 1:
        raise line_error(path, announced + 1, f"a format of {per_line} values {width} "
                                              "characters wide cannot be read")
    n_lines = -(-count // per_line)
    if announced + 1 + n_lines > len(lines):
        raise line_error(path, len(lines), f"the file ends inside the block of {count} "
                                           f"values announced on line {announced + 1}")
    return n_lines


def _fixed_block(lines, announced, count, layout, path):
    """``(values, line of each value)`` of the block announced on lines[announced]."""
    n_lines = _extent(lines, announced, count, layout, path)
    per_line, width = layout
    numbers = np.arange(announced + 2, announced + 2 + n_lines)
    values, counts = parse_lines(lines[announced + 1:announced + 1 + n_lines], numbers, path,
                                 split=fixed_width(width))
    expected = np.full(n_lines, per_line)
    expected[-1:] = count - per_line * (n_lines - 1)
    check_counts(counts, expected, numbers, path,
                 f"expected {{expected}} values {width} characters wide "
                 f"(block of line {announced + 1}), found {{found}}")
    return values, np.repeat(numbers, counts)


def _units(match, announced, path):
    """``(name, factor to m/s^2)`` of the acceleration block announced by ``match``."""
    if "code" in match.groupdict():
        code = int(match["code"])
        if code not in COSMOS_UNITS:
            known = ", ".join(f"{c:02d} {name}" for c, (name, _) in COSMOS_UNITS.items())
            raise line_error(path, announced + 1, f"units code {code:02d} is not an "
                                                  f"acceleration unit ({known})")
        return COSMOS_UNITS[code]
    units = match["units"] or match["old_units"]
    try:
        return units, fixed_factor(units, "acceleration")
    except ValueError as err:
        raise line_error(path, announced + 1, f"units {units!r}: {err}") from None


def _step(text, announced, path):
    """The CSMIP sample step [s] written on a data block's first line."""
    try:
        dt = float(text)
    except ValueError:
        dt = 0.0
    if not 0 < dt < np.inf:
        raise line_error(path, announced + 1, f"the sample step {text!r} is not a positive "
                                              "number of seconds")
    return dt


def _key(name):
    """A component name without case, spaces and a trailing ``deg``."""
    return re.sub(r"deg$", "", "".join(str(name).lower().split()))


def _choose(channels, component, path):
    """Index of the channel that ``component`` (number from 1, or name) picks."""
    listing = ", ".join(f"{k} {c.name!r}" for k, c in enumerate(channels, 1))
    if component is None:
        if len(channels) == 1:
            return 0
        raise RecordError(f"{path}: holds {len(channels)} components ({listing}); give "
                          "component: its number or its name")
    if isinstance(component, int) and not isinstance(component, bool):
        if 1 <= component <= len(channels):
            return component - 1
    else:
        found = [k for k, c in enumerate(channels) if _key(c.name) == _key(component)]
        if len(found) == 1:
            return found[0]
    raise RecordError(f"{path}: component {component!r} does not pick one of the file's "
                      f"{len(channels)} components ({listing}); give its number where names "
                      "repeat")
