"""What a record reader returns, and the checks every reader shares.

A reader turns one file into a :class:`Record`: uniformly sampled acceleration in m/s^2.  A file
it cannot take raises :class:`RecordError` with a message that starts with the file's path and,
where one line is at fault, names it (``line 23: expected 8 integers, got 'abc'``).  A unit the
user gives (``units:``) that is not the one the file states is refused (:func:`check_units`).
Each reader says how it read the file (:class:`Reading`: the format, where the unit came from,
the header lines it found), which the scene's outputs show.  :class:`Record` itself is a motion as
numbers, defined in ``sweep.groundmotion.record`` and imported here for the readers.
"""
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...groundmotion.record import Record
from ..units import fixed_factor

# Most samples a record may have once on its uniform grid: 80 MB of float64, 28 hours at
# dt = 0.01 s.  A file of a few rows whose median step is tiny would otherwise be resampled
# into terabytes.
MAX_SAMPLES = 10_000_000
# Sample steps a record may have [s]: 100 kHz to 1 Hz.  Accelerographs sample at 50-1000 Hz; a
# step outside these bounds is a misread header, and the baseline correction would pad it
# with PAD_S / dt zeros.
MIN_DT, MAX_DT = 1e-5, 1.0
_MAX_VALUES = 2 * MAX_SAMPLES  # numbers a file may hold: two columns of MAX_SAMPLES rows


class RecordError(ValueError):
    """A record name is unknown or a record file cannot be read."""


UNITS_FROM = ("header", "comment", "units:", "default", "format", "bundled")
"""Where the unit of a file's numbers came from: a header line, a ``#`` comment, the scene's
``units:`` key, the default of column files (m/s^2), the format itself (a PEER ``.AT2`` file is
in g), or the bundled record's conversion (``sweep/data/records/README.md``)."""


@dataclass(frozen=True)
class Reading:
    """How a reader read a record file: what ``--summary``, ``--json`` and plot captions show.

    Attributes
    ----------
    format : str
        The reader's key (``sweep.io.records.FORMATS``): ``at2``, ``knet``, ``cosmos``,
        ``columns`` or ``column``.
    reader : str
        The format in words: ``PEER NGA AT2``, ``K-NET/KiK-net ASCII``, ``COSMOS V2``, ...
    units_from : str
        Where the unit of the numbers came from, one of :data:`UNITS_FROM`.
    units_line : str or None
        The line that states the unit, ``line <n>: <text>``; None where no line does.
    header : tuple of str
        The header lines, or the station and event text, that the reader found.
    title : str
        One line that names the record (event, station, component) where the file says it.
    notes : tuple of str
        What was done to the numbers besides the unit (a mean removed, a resampling).
    """

    format: str
    reader: str
    units_from: str
    units_line: str = None
    header: tuple = ()
    title: str = ""
    notes: tuple = ()


def line_error(path, number, message):
    """The :class:`RecordError` of line ``number`` (counted from 1) of ``path``."""
    return RecordError(f"{path}: line {number}: {message}")


def read_lines(path):
    """The lines of a text file up to a DOS end-of-file mark (Ctrl-Z, in files of the 1980s);
    bytes that are not UTF-8 become U+FFFD and fail as numbers."""
    try:
        text = Path(path).read_text(errors="replace")
    except OSError as err:
        raise RecordError(f"{path}: cannot read: {err.strerror or err}") from None
    return text.split("\x1a", 1)[0].splitlines()


def parse_lines(lines, numbers, path, *, split=str.split, parse=float,
                bad="{token!r} is not a number"):
    """The numbers written on ``lines``, line by line.

    Parameters
    ----------
    lines : sequence of str
    numbers : sequence of int
        The file's line number of each of ``lines``, for messages.
    path : str or Path
    split : callable
        Line to its fields (default: at white space; :func:`fixed_width` for Fortran fields).
    parse : callable
        Field to number: ``float`` or ``int``.
    bad : str
        Message for a field that ``parse`` refuses, formatted with ``token``.

    Returns
    -------
    values : ndarray, shape (n,)
        float64, in the order written.
    counts : ndarray of int, shape (len(lines),)
        How many values each line holds.
    """
    values, counts = [], []
    for number, line in zip(numbers, lines):
        tokens = split(line)
        try:
            values.extend(map(parse, tokens))
        except ValueError:
            token = next(t for t in tokens if not _parses(parse, t))
            raise line_error(path, number, bad.format(token=token.strip())) from None
        counts.append(len(tokens))
        if len(values) > _MAX_VALUES:
            raise line_error(path, number, f"more than {_MAX_VALUES} values")
    return np.array(values, dtype=np.float64), np.array(counts, dtype=np.int64)


def _parses(parse, token):
    try:
        parse(token)
    except ValueError:
        return False
    return True


def fixed_width(width):
    """Splitter of a line into consecutive fields ``width`` characters wide (Fortran ``F10.6``)."""
    def split(line):
        line = line.rstrip()
        return [line[k:k + width] for k in range(0, len(line), width)]
    return split


def check_counts(counts, expected, numbers, path, message):
    """Refuse the first line whose count of values is not ``expected`` (an int, or one per line);
    ``message`` is formatted with ``expected`` and ``found``."""
    expected = np.broadcast_to(expected, counts.shape)
    bad = np.flatnonzero(counts != expected)
    if bad.size:
        k = bad[0]
        raise line_error(path, numbers[k], message.format(expected=expected[k], found=counts[k]))


def check_finite(values, line_of, path, what="value"):
    """Refuse NaN and infinite values (written as nan, inf or beyond the float range), naming
    the line (``line_of[k]`` holds value k) and the value's place: ``what`` k."""
    bad = np.flatnonzero(~np.isfinite(values))
    if bad.size:
        k = bad[0]
        raise line_error(path, line_of[k], f"{what} {k + 1} is not a finite number: {values[k]}")


def check_units(given, stated, factor, path, line=None,
                said="the file gives its accelerations in"):
    """Refuse a ``given`` acceleration unit (the scene's ``units:``, None: none given) that is
    not the unit ``stated`` by the file (``factor`` to m/s^2), on ``line`` if one line says it.

    Raises
    ------
    RecordError
        Naming the file's unit and the line that states it.
    """
    if given is None or math.isclose(fixed_factor(given, "acceleration"), factor,
                                     rel_tol=1e-12):
        return
    at = f"line {line}: " if line else ""
    raise RecordError(f"{path}: {at}{said} {stated}, not {given} (units: {given}): leave "
                      "units: out")


def make_record(path, dt, samples, provenance, units="m/s^2", reading=None):
    """The :class:`Record` of a file: ``samples`` [m/s^2] every ``dt`` [s], checked and frozen;
    ``units``: the unit the file's numbers were read in; ``reading``: how (:class:`Reading`).

    Raises
    ------
    RecordError
        Fewer than two samples or more than :data:`MAX_SAMPLES`, a step outside
        [:data:`MIN_DT`, :data:`MAX_DT`], or a sample that left the float range in the
        conversion to m/s^2.
    """
    if len(samples) < 2:
        raise RecordError(f"{path}: needs at least two samples")
    if len(samples) > MAX_SAMPLES:
        raise RecordError(f"{path}: {len(samples)} samples, more than {MAX_SAMPLES}")
    if not MIN_DT <= dt <= MAX_DT:
        raise RecordError(f"{path}: the sample step must be between {MIN_DT:g} and "
                          f"{MAX_DT:g} s (a sampling rate of 1 Hz to 100 kHz), got {dt:g} s")
    samples = np.ascontiguousarray(samples, dtype=np.float64)
    bad = np.flatnonzero(~np.isfinite(samples))
    if bad.size:
        raise RecordError(f"{path}: sample {bad[0] + 1} leaves the float range in m/s^2")
    samples.flags.writeable = False
    return Record(str(path), float(dt), samples, provenance, units, reading)
