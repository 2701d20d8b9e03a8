"""Recorded floor accelerations: the bundled records, and a user's record files in any format.

A :class:`Record` holds uniformly sampled horizontal or vertical floor acceleration in m/s^2,
sample k at time k*dt after the record's start.  Bundled records live in ``sweep/data/records``
(provenance in its README.md); a user's file is read by :func:`read_record_file`, whichever of
:data:`FORMATS` it is in (``docs/record_formats.md``), by the readers of :mod:`sweep.io.formats`.
Arrays are read-only and cached, so that a study reading the same record per cell reads it once.
How each record was read (its :class:`~sweep.io.formats.base.Reading`) is what
:func:`floor_provenance` gives a scene's outputs.
"""
import functools
import importlib
import importlib.resources
import math
from pathlib import Path
from stat import S_ISREG

from .formats import columns
from .formats.at2 import read_at2
from .formats.base import MAX_SAMPLES, Reading, Record, RecordError
from .formats.columns import read_two_column

__all__ = ["ALIASES", "BUNDLED", "FORMATS", "MAX_SAMPLES", "NAMES", "Reading", "Record",
           "RecordError", "describe", "detect_format", "floor_provenance", "load_record",
           "provenance_line", "read_at2", "read_record_file", "read_two_column"]

BUNDLED = ("elcentro1940_ns", "elcentro1940_ew", "elcentro1940_ud", "taft1952_ew_s69e")
ALIASES = {"taft1952_ew": "taft1952_ew_s69e"}
NAMES = BUNDLED + tuple(ALIASES)
"""Names accepted by :func:`load_record`."""
FORMATS = ("at2", "knet", "cosmos", "columns", "column")
"""Record file formats: PEER ``.AT2``, K-NET/KiK-net ASCII, COSMOS or CSMIP Volume 2, two
columns (time, acceleration), one column (accelerations; ``dt`` given)."""

# Anchored at the sweep.data folder: files("sweep") fails while an editable install made before
# sweep/__init__.py existed presents sweep as a namespace package.
_DATA = importlib.resources.files("sweep.data") / "records"
# What each format gives itself, for refusing a dt given for it
_OWN = {"at2": "a PEER .AT2 file gives its DT",
        "knet": "a K-NET file gives its sampling rate",
        "cosmos": "a COSMOS or CSMIP file gives its sample step",
        "columns": "a two-column file gives its times (format: column reads accelerations "
                   "written two to a line)"}


def _reader(format):
    """The module of :mod:`sweep.io.formats` that reads ``format`` (``cosmos``, ``knet``),
    imported at its first use: a scene without a record file needs neither."""
    return importlib.import_module(f".formats.{format}", __package__)


@functools.cache
def _by_extension():
    """{lower-case file extension: the format it says}."""
    return {".at2": "at2", **dict.fromkeys(_reader("cosmos").EXTENSIONS, "cosmos"),
            **dict.fromkeys(_reader("knet").EXTENSIONS, "knet")}


@functools.lru_cache(maxsize=None)
def _load_bundled(name):
    resource = _DATA / f"{name}.txt"
    with importlib.resources.as_file(resource) as path:
        rec = read_two_column(path)
        lines = path.read_text().splitlines()
    header = [line[1:].strip() for line in lines if line.startswith("#")]
    provenance = "; ".join(header) + "; see sweep/data/records/README.md"
    converted = next((f"line {k}: {line.strip()}" for k, line in enumerate(lines, 1)
                      if line.startswith("#") and "m/s^2" in line), None)
    reading = Reading("columns", "bundled record (two columns)", "bundled",
                      converted, tuple(header), header[0] if header else "")
    return Record(name, rec.dt, rec.samples, provenance, reading=reading)


def load_record(name):
    """A bundled record by name (:data:`NAMES`), acceleration in m/s^2.

    Raises
    ------
    RecordError
        For an unknown name; the message lists the known ones.
    """
    canonical = ALIASES.get(name, name)
    if canonical not in BUNDLED:
        raise RecordError(f"unknown record '{name}'; bundled records: {', '.join(NAMES)}")
    return _load_bundled(canonical)


def detect_format(path):
    """The format of a record file (one of :data:`FORMATS`).

    By the extension where it tells (``.AT2``; ``.V2``, ``.V2c``; ``.NS``, ``.EW``, ``.UD`` and
    KiK-net's ``.NS1`` ... ``.UD2``), else by the first line that is not blank or a ``#``
    comment: ``Origin Time...`` is K-NET; ``COSMOS``, ``(Format v...`` or a line starting
    ``Corrected acceleration``/``accelerogram`` is COSMOS or CSMIP; two numbers are two columns
    (time, acceleration); one number, or three or more, are accelerations alone.
    """
    path = Path(path)
    by_extension = _by_extension().get(path.suffix.lower())
    if by_extension:
        return by_extension
    try:
        with open(path, errors="replace") as file:
            for number, line in enumerate(file, 1):
                data = line.split("#", 1)[0].split()
                if data:
                    return _format_of_line(line, data, number, path)
    except OSError as err:
        raise RecordError(f"{path}: cannot read: {err.strerror or err}") from None
    raise RecordError(f"{path}: no data rows")


def _format_of_line(line, data, number, path):
    """The format whose first line ``line`` (its fields before any ``#``: ``data``) is."""
    lower = line.lower()
    if line.startswith("Origin Time"):
        return "knet"
    if "cosmos" in lower or "(format v" in lower or \
            lower.lstrip().startswith(("corrected acceleration", "corrected accelerogram")):
        return "cosmos"
    try:
        for field in data:
            float(field)
    except ValueError:
        raise RecordError(
            f"{path}: line {number}: not the start of a record file this program reads (PEER "
            f".AT2, K-NET, COSMOS or CSMIP Volume 2, one or two columns of numbers): "
            f"{line.strip()[:80]!r}") from None
    return "columns" if len(data) == 2 else "column"


@functools.lru_cache(maxsize=32)
def _read_file_cached(path, format, units, dt, component, stamp):
    format = format or detect_format(path)
    if dt is not None and format != "column":
        raise RecordError(f"{path}: dt applies to one-column files only: {_OWN[format]}")
    if component is not None and format != "cosmos":
        raise RecordError(f"{path}: component applies to COSMOS and CSMIP files only, which "
                          "may hold several")
    if format == "at2":
        return read_at2(path, units)
    if format == "knet":
        return _reader(format).read_knet(path, units)
    if format == "cosmos":
        return _reader(format).read_cosmos(path, component, units)
    if format == "columns":
        return read_two_column(path, units)
    if dt is None:
        raise RecordError(f"{path}: a file of accelerations alone has no times: give dt (the "
                          "sample step, e.g. dt: 0.01 s)")
    return columns.read_single_column(path, dt, units)


def read_record_file(path, units=None, *, format=None, dt=None, component=None):
    """A user's record file in any of :data:`FORMATS`, acceleration in m/s^2.

    Parameters
    ----------
    path : str or Path
    units : str, optional
        Acceleration unit of the file's numbers.  Where the file states its unit (the header
        of AT2 (g), K-NET (gal), COSMOS and CSMIP files; a comment of a column file such as
        ``# acceleration [g]``) it is that one, and another is refused; a column file that
        states none is in m/s^2 by default.
    format : str, optional
        One of :data:`FORMATS`; default :func:`detect_format`.
    dt : float, optional
        Sample step [s] of a one-column file, which has no times; required there.
    component : int or str, optional
        Which component of a COSMOS or CSMIP file that holds several: its number (from 1)
        or name (:func:`sweep.io.formats.cosmos.read_cosmos`).

    Cached by path, options, modification time and size, so a study reads each file once.

    Raises
    ------
    RecordError
        A missing or unreadable file, not a regular file, a file the format's reader refuses
        (the message names the line), ``units`` other than the file's (the message names
        them and the line that states the file's), or an option that does not apply to the
        format.
    """
    path = Path(path)
    if format is not None and format not in FORMATS:
        raise RecordError(f"{path}: unknown format {format!r}; formats: {', '.join(FORMATS)}")
    if dt is not None and not 0 < dt < math.inf:
        raise RecordError(f"{path}: dt must be a positive number of seconds, got {dt}")
    try:
        stat = path.stat()
    except OSError as err:
        raise RecordError(f"{path}: cannot read: {err.strerror}") from None
    if not S_ISREG(stat.st_mode):  # a folder, or a device or pipe that may never end
        raise RecordError(f"{path}: not a regular file")
    return _read_file_cached(str(path), format, units, dt, component,
                             (stat.st_mtime_ns, stat.st_size))


# How each origin of a unit is said in one line (provenance_line)
_UNITS_SAID = {"header": "from the header", "comment": "from a # comment",
               "units:": "from the scene's units:", "default": "the default: no units: and no "
               "comment names one", "format": "the format's unit: the header names none",
               "bundled": "as converted for the bundled file"}


def describe(rec):
    """The provenance of a record read from a file or bundled, as a JSON-ready dict: ``source``
    (the file's path or the bundled name), ``format`` and ``reader`` (the format in words),
    ``units`` the numbers were read in, ``units_from`` (``header``, ``comment``, ``units:``,
    ``default``, ``format`` or ``bundled``) and ``units_line`` (the line that states it, or
    None), ``dt`` [s] and ``npts`` as read, ``title``, ``header`` (the header lines or the
    station and event text found), ``notes`` (what else was done to the numbers).  None for
    a record that no file gave (a synthetic motion)."""
    reading = rec.reading
    if reading is None:
        return None
    return {"source": rec.name, "format": reading.format, "reader": reading.reader,
            "units": rec.units, "units_from": reading.units_from,
            "units_line": reading.units_line, "dt": rec.dt, "npts": len(rec.samples),
            "title": reading.title, "header": list(reading.header), "notes": list(reading.notes)}


def floor_provenance(excitation):
    """``{component: describe(record)}`` of the components of a resolved ``excitation``
    (``scene_schema.resolve_scene``) that are records read from a file or bundled, or
    building's floors over such a record (said as the record on the ground is)."""
    found = {}
    for component, ground in excitation.items():
        ground = ground.get("ground", ground)  # a floor: the record under its building
        said = describe(ground["source"]) if ground["kind"] == "record" else None
        if said is not None:
            found[component] = said
    return found


def provenance_line(component, said):
    """One line of :func:`describe`'s dict ``said`` of the floor ``component``
    (``horizontal``): the record, its reader, unit and where it came from, dt, samples and
    the record's title."""
    where = _UNITS_SAID[said["units_from"]]
    if said["units_line"]:
        where += f", {said['units_line'].partition(':')[0]}"  # "line 3"
    line = (f"{component} record {said['source']}: read as {said['reader']}, in "
            f"{said['units']} ({where}), dt {said['dt']:g} s, {said['npts']} samples")
    return line + (f"; {said['title']}" if said["title"] else "")
