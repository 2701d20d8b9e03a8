"""K-NET and KiK-net ASCII files (NIED, Japan): one component per file, acceleration in gal.

NIED's format: 17 header lines, each a label in columns 1-18 and its value from column 19
(``Sampling Freq(Hz) 100Hz``, ``Scale Factor      7845(gal)/8223790``, ``Max. Acc. (gal)
48.060``), then the record as integer counts, 8 per line.  Acceleration [gal] = counts x the
scale factor, less the mean of the whole record: NIED's Max. Acc. is the peak after that
subtraction, and so is the record read here.  File names end in ``.NS``, ``.EW``, ``.UD``
(K-NET) or ``.NS1`` ... ``.UD2`` (KiK-net: 1 borehole, 2 surface).

Read here rather than with ObsPy (``obspy.read(path, format="KNET")``): its reader parses this
same fixed layout into counts and a calibration factor, but does not remove the mean, check
Max. Acc. or name the line of an error, and would make a large package a dependency for a
format this small.
"""
import re

import numpy as np

from .base import (Reading, RecordError, check_counts, check_finite, check_units, line_error,
                   make_record, parse_lines, read_lines)

EXTENSIONS = (".ns", ".ew", ".ud", ".ns1", ".ew1", ".ud1", ".ns2", ".ew2", ".ud2")
LABELS = ("Origin Time", "Lat.", "Long.", "Depth. (km)", "Mag.", "Station Code", "Station Lat.",
          "Station Long.", "Station Height(m)", "Record Time", "Sampling Freq(Hz)",
          "Duration Time(s)", "Dir.", "Scale Factor", "Max. Acc. (gal)", "Last Correction",
          "Memo.")
"""The header's labels, line by line (NIED also writes ``Lon.`` and ``Max Acc.``)."""
PER_LINE = 8
# The header's Max. Acc. is printed to 3 decimals; a wrong scale factor or a file cut short
# before its peak moves the data's peak much further than this fraction.
MAX_ACC_TOLERANCE = 0.01
GAL = 0.01  # m/s^2
_LABEL_WIDTH = 18
_FREQUENCY = re.compile(r"^\s*([0-9.]+)\s*Hz\s*$", re.IGNORECASE)
_SCALE = re.compile(r"^\s*([0-9.Ee+-]+)\s*\(gal\)\s*/\s*([0-9.Ee+-]+)\s*$", re.IGNORECASE)
_NUMBER = re.compile(r"^\s*(\S+)\s*$")


def read_knet(path, units=None):
    """Read a K-NET or KiK-net ASCII file into m/s^2, its mean removed; ``units``, if given,
    must be the header's (gal).

    Raises
    ------
    RecordError
        A header line out of place or unreadable, a data line that does not hold 8 integers
        (the last one: at most 8), or a Max. Acc. in the header more than
        :data:`MAX_ACC_TOLERANCE` away from the data's peak (a wrong scale factor or a
        truncated file).
    """
    lines = read_lines(path)
    while lines and not lines[-1].strip():
        lines.pop()
    if len(lines) <= len(LABELS):
        raise RecordError(f"{path}: not a K-NET file: {len(LABELS)} header lines and data "
                          f"expected, found {len(lines)} lines")
    header = {label: _value(lines, number, label, path)
              for number, label in enumerate(LABELS, 1)}
    frequency = _number(_FREQUENCY, header, "Sampling Freq(Hz)", "e.g. 100Hz", path)[0]
    numerator, denominator = _number(_SCALE, header, "Scale Factor", "e.g. 7845(gal)/8223790",
                                     path)
    check_units(units, "gal", GAL, path, LABELS.index("Scale Factor") + 1,
                said="the header's Scale Factor gives the accelerations in")
    max_acc = _number(_NUMBER, header, "Max. Acc. (gal)", "in gal", path)[0]
    numbers = np.arange(len(LABELS) + 1, len(lines) + 1)
    values, counts = parse_lines(lines[len(LABELS):], numbers, path, parse=_count,
                                 bad=f"expected {PER_LINE} integers, got {{token!r}}")
    expected = np.full(len(counts), PER_LINE)
    expected[-1] = min(counts[-1], PER_LINE)
    check_counts(counts, expected, numbers, path, "expected {expected} integers, found {found}")
    gal = values * (numerator / denominator)
    check_finite(gal, np.repeat(numbers, counts), path, "sample (after the scale factor)")
    mean = float(np.mean(gal))
    gal -= mean
    peak = float(np.max(np.abs(gal)))
    if abs(peak - max_acc) > MAX_ACC_TOLERANCE * max_acc:
        raise line_error(path, LABELS.index("Max. Acc. (gal)") + 1,
                         f"Max. Acc. = {max_acc:g} gal, but the data's peak (counts x "
                         f"{numerator:g}/{denominator:g}, mean removed) is {peak:.6g} gal, "
                         f"{100 * abs(peak / max_acc - 1):.3g} % "
                         "apart: a wrong scale factor or a truncated file")
    provenance = (f"{path}: K-NET/KiK-net ASCII, station {header['Station Code']}, "
                  f"Dir. {header['Dir.']}, event {header['Origin Time']} JST M{header['Mag.']}, "
                  f"record time {header['Record Time']} JST (15 s trigger delay included), "
                  f"scale factor {header['Scale Factor']}, mean of the whole record "
                  f"({mean:.6g} gal) removed, peak {peak:.6g} gal (header's Max. Acc. "
                  f"{max_acc:g}), n = {len(gal)}, dt = {1 / frequency:g} s")
    scale_line = LABELS.index("Scale Factor") + 1
    reading = Reading("knet", "K-NET/KiK-net ASCII", "header",
                      f"line {scale_line}: {lines[scale_line - 1].strip()}",
                      tuple(" ".join(line.split()) for line in lines[:len(LABELS)]),
                      f"station {header['Station Code']}, Dir. {header['Dir.']}, event "
                      f"{header['Origin Time']} JST M{header['Mag.']}",
                      (f"mean of the whole record ({mean:.6g} gal) removed",))
    return make_record(path, 1.0 / frequency, gal * GAL, provenance, "gal", reading)


def _count(token):
    """An integer count that a float holds exactly (NIED writes at most 7 digits)."""
    count = int(token)
    if abs(count) > 2 ** 53:
        raise ValueError(token)
    return count


def _key(label):
    """A label without case, spaces and dots, ``Long`` spelled ``Lon`` as NIED also does."""
    return re.sub(r"[^a-z]", "", label.lower()).replace("long", "lon")


def _value(lines, number, label, path):
    line = lines[number - 1]
    if _key(line[:_LABEL_WIDTH]) != _key(label):
        raise line_error(path, number, f"expected the K-NET header label {label!r}, "
                                       f"got {line.strip()!r}")
    return line[_LABEL_WIDTH:].strip()


def _number(pattern, header, label, example, path):
    """The positive finite numbers that ``pattern`` reads from the header value of ``label``."""
    match = pattern.match(header[label])
    try:
        numbers = [float(group) for group in match.groups()] if match else []
    except ValueError:
        numbers = []
    if not numbers or not all(0 < x < np.inf for x in numbers):
        raise line_error(path, LABELS.index(label) + 1,
                         f"{label} should be given by positive numbers ({example}), "
                         f"got {header[label]!r}")
    return numbers
