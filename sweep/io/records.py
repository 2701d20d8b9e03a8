"""Recorded floor accelerations: the bundled records and readers for a user's files.

A :class:`Record` holds uniformly sampled horizontal or vertical floor acceleration in m/s^2,
sample k at time k*dt after the record's start.  Bundled records live in ``sweep/data/records``
(provenance in its README.md); user files are PEER NGA ``.AT2`` files or two-column text files.
Arrays are read-only and cached, so that a study reading the same record per cell reads it once.
"""
import functools
import importlib.resources
import math
import re
import warnings
from dataclasses import dataclass
from pathlib import Path
from stat import S_ISREG

import numpy as np

from ..paper import criteria
from .units import fixed_factor

BUNDLED = ("elcentro1940_ns", "elcentro1940_ew", "elcentro1940_ud", "taft1952_ew_s69e")
ALIASES = {"taft1952_ew": "taft1952_ew_s69e"}
NAMES = BUNDLED + tuple(ALIASES)
"""Names accepted by :func:`load_record`."""

# Times in text files carry a few decimals; a grid is uniform if every time is within this
# fraction of dt of t0 + k*dt (a wider jitter is a non-uniform file and is resampled).
_UNIFORM_TOL = 0.01
# Anchored at the sweep.data folder: files("sweep") fails while an editable install made before
# sweep/__init__.py existed presents sweep as a namespace package.
_DATA = importlib.resources.files("sweep.data") / "records"
_DT_DIGITS = 12  # significant digits kept of dt fitted to printed times (0.02, not 0.0199...)
# Most samples a record may have once on its uniform grid: 80 MB of float64, 28 hours at
# dt = 0.01 s.  A file of a few rows whose median step is tiny would otherwise be resampled
# into terabytes.
MAX_SAMPLES = 10_000_000


class RecordError(ValueError):
    """A record name is unknown or a record file cannot be read."""


@dataclass(frozen=True, eq=False)
class Record:
    """A uniformly sampled acceleration record.

    Attributes
    ----------
    name : str
        Bundled name, or the file's path.
    dt : float
        Sample step [s].
    samples : ndarray, shape (n,)
        Acceleration [m/s^2], read-only.
    provenance : str
        Where the data come from and what was done to them.
    """

    name: str
    dt: float
    samples: np.ndarray
    provenance: str

    @property
    def pga(self):
        """Peak absolute acceleration [m/s^2]."""
        return float(np.max(np.abs(self.samples)))

    @functools.cached_property
    def intensity(self):
        """:class:`~sweep.groundmotion.intensity.Intensity` of the samples (scale 1)."""
        from ..groundmotion.intensity import measures
        return measures(self.samples, self.dt)

    @property
    def duration(self):
        """Time from the first to the last sample [s]."""
        return self.dt * (len(self.samples) - 1)


def _frozen(a):
    """C-contiguous float64 read-only copy-or-view, safe to share from the cache."""
    a = np.ascontiguousarray(a, dtype=np.float64)
    a.flags.writeable = False
    return a


def _round(dt):
    """``dt`` to ``_DT_DIGITS`` significant digits."""
    return float(f"{dt:.{_DT_DIGITS}g}")


def _uniform(t, a, source):
    """``(dt, samples, note)`` on a uniform grid from times ``t``, resampling if needed."""
    if len(t) < 2:
        raise RecordError(f"{source}: needs at least two samples")
    steps = np.diff(t)
    if not np.all(steps > 0):
        row = int(np.argmin(steps > 0)) + 2
        raise RecordError(f"{source}: times must increase (data row {row})")
    if not np.isfinite(t[-1] - t[0]):
        raise RecordError(f"{source}: the times span more than the float range")
    dt = _round(float((t[-1] - t[0]) / (len(t) - 1)))
    if np.max(np.abs(t - t[0] - dt * np.arange(len(t)))) <= _UNIFORM_TOL * dt:
        return dt, a, ""
    dt = _round(float(np.median(steps)))
    # 1e-9 keeps the last time when (t[-1] - t[0])/dt is an integer up to rounding
    count = np.floor((t[-1] - t[0]) / dt + 1e-9) + 1
    if not count <= MAX_SAMPLES:
        raise RecordError(f"{source}: non-uniform times resampled onto their median step dt = "
                          f"{dt:g} s would make {count:g} samples, more than {MAX_SAMPLES}")
    grid = t[0] + dt * np.arange(int(count))
    note = (f"; non-uniform times resampled linearly onto dt = {dt:g} s "
            f"(the median step), {len(grid)} samples")
    return dt, np.interp(grid, t, a), note


def _finite(values, path, what):
    """Refuse NaN and infinite values (written as nan, inf or beyond the float range)."""
    bad = np.flatnonzero(~np.isfinite(values))
    if bad.size:
        raise RecordError(f"{path}: {what} {bad[0] + 1} is not a finite number: "
                          f"{values.flat[bad[0]]}")


def _read_columns(path):
    try:
        with warnings.catch_warnings():  # an empty file is reported below, not warned about
            warnings.simplefilter("ignore", UserWarning)
            data = np.loadtxt(path, comments="#", ndmin=2)
    except (OSError, ValueError) as err:
        raise RecordError(f"{path}: cannot read as a two-column text file: {err}") from None
    if data.size == 0:
        raise RecordError(f"{path}: no data rows")
    if data.shape[1] != 2:
        raise RecordError(f"{path}: expected two columns (time, acceleration), "
                          f"found {data.shape[1]}")
    _finite(data[:, 0], path, "the time of data row")
    _finite(data[:, 1], path, "the acceleration of data row")
    return data[:, 0], data[:, 1]


@functools.lru_cache(maxsize=None)
def _load_bundled(name):
    resource = _DATA / f"{name}.txt"
    with importlib.resources.as_file(resource) as path:
        t, a = _read_columns(path)
        header = [line[1:].strip() for line in path.read_text().splitlines()
                  if line.startswith("#")]
    dt, samples, _ = _uniform(t, a, name)
    provenance = "; ".join(header) + "; see sweep/data/records/README.md"
    return Record(name, dt, _frozen(samples), provenance)


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


def read_two_column(path, units="m/s^2"):
    """Read a text file of two columns, time [s] and acceleration, ``#`` lines skipped.

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
    try:
        factor = fixed_factor(units, "acceleration")
    except ValueError as err:
        raise RecordError(f"{path}: {err}") from None
    t, a = _read_columns(path)
    dt, samples, note = _uniform(t, a * factor, path)
    provenance = f"{path}: two columns time/acceleration in {units}, n = {len(t)}{note}"
    return Record(str(path), dt, _frozen(samples), provenance)


def read_at2(path):
    """Read a PEER NGA ``.AT2`` file (acceleration in g) into m/s^2.

    The format: four header lines, the fourth giving NPTS and DT (``NPTS= 5372, DT= .0100 SEC``
    or the older ``5372 .0100 NPTS, DT``), then NPTS values in any number of columns.
    """
    try:
        lines = Path(path).read_text(errors="replace").splitlines()
    except OSError as err:
        raise RecordError(f"{path}: cannot read: {err}") from None
    if len(lines) < 5:
        raise RecordError(f"{path}: not a PEER .AT2 file (fewer than 5 lines)")
    kind = lines[2].upper()
    if "VELOCITY" in kind or "DISPLACEMENT" in kind:
        raise RecordError(f"{path}: line 3 says this is not an acceleration record: {lines[2]}")
    npts, dt = _at2_npts_dt(lines[3], path)
    try:
        values = np.array(" ".join(lines[4:]).split(), dtype=np.float64)
    except ValueError as err:
        raise RecordError(f"{path}: a value after the header is not a number: {err}") from None
    if len(values) != npts:
        raise RecordError(f"{path}: header says NPTS = {npts}, found {len(values)} values")
    _finite(values, path, "value")
    provenance = f"{path}: PEER NGA AT2, {lines[1].strip()}, NPTS = {npts}, DT = {dt:g} s, g"
    return Record(str(path), dt, _frozen(values * criteria.G), provenance)


def _at2_npts_dt(line, path):
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
    return n, step


@functools.lru_cache(maxsize=32)
def _read_file_cached(path, units, stamp):
    if Path(path).suffix.lower() == ".at2":
        return read_at2(path)
    return read_two_column(path, units)


def read_record_file(path, units=None):
    """A user's record file: ``.AT2`` (in g) or two columns (``units``, default m/s^2).

    Cached by path, units and modification time, so a study reads each file once.

    Raises
    ------
    RecordError
        Missing or unreadable file, not a regular file, or ``units`` given for an ``.AT2``
        file.
    """
    path = Path(path)
    if path.suffix.lower() == ".at2" and units is not None:
        raise RecordError(f"{path}: units apply to two-column files only (.AT2 files are in g)")
    try:
        stat = path.stat()
    except OSError as err:
        raise RecordError(f"{path}: cannot read: {err.strerror}") from None
    if not S_ISREG(stat.st_mode):  # a folder, or a device or pipe that may never end
        raise RecordError(f"{path}: not a regular file")
    return _read_file_cached(str(path), units or "m/s^2", (stat.st_mtime_ns, stat.st_size))
