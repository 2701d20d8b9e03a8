"""Hazard curves: the mean annual rate λ(x) at which a site's intensity measure exceeds x.

A :class:`HazardCurve` holds an intensity measure (``pga``, ``pgv`` or ``sa(T)``), its levels
in SI units (m/s² for accelerations, m/s for PGV) and their annual rates of exceedance.  It is
read from

* OpenQuake's ``hazard_curve-*.csv`` (:func:`read_openquake_csv`): a comment line with
  ``investigation_time`` and ``imt``, then ``lon,lat[,depth],poe-<level>...``; levels in g
  (cm/s for PGV), probabilities of exceedance P in the investigation time T;
* a USGS hazard curve export (:func:`read_usgs_json`, the JSON of the USGS hazard web
  service): ``response[].metadata.imt``, ``xvalues`` (g, cm/s for PGV) and ``data[].yvalues``,
  annual frequencies of exceedance (the ``Total`` component);
* two columns (:func:`read_columns`): ``im, annual_rate`` or ``im, poe`` with the investigation
  time, the units of ``im`` stated.

Probabilities of exceedance become rates by the Poisson model, λ = −ln(1 − P)/T
(:func:`rate_from_poe`; docs/probability.md §9).  Between levels the curve is a power law (straight
in log–log), λ(x) = λ_i (x/x_i)^(−k_i) (:meth:`HazardCurve.rate`).  Problems of a file raise
:class:`HazardFileError`, one line each, with the file and where in it.
"""
import csv
import json
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..bodies import G
from ..io.imt import SI_UNITS, im_dimension, normalize_im, openquake_imt  # noqa: F401

# units of the levels in the formats read: OpenQuake and USGS write g and cm/s
FORMAT_FACTOR = {"acceleration": G, "velocity": 0.01}


class HazardFileError(ValueError):
    """A hazard curve that cannot be used: ``str`` says where and why, on one line."""


def rate_from_poe(poe, investigation_time):
    """Annual rate λ = −ln(1 − P)/T of a probability of exceedance P in T years (Poisson)."""
    return -np.log1p(-np.asarray(poe, dtype=float)) / investigation_time


def poe_from_rate(rate, investigation_time):
    """Probability P = 1 − exp(−λ T) of at least one exceedance in T years (Poisson)."""
    return -np.expm1(-np.asarray(rate, dtype=float) * investigation_time)


@dataclass(frozen=True)
class HazardCurve:
    """λ(x) of one intensity measure at one site.

    Attributes
    ----------
    im : str
        ``pga``, ``pgv`` or ``sa(T)``.
    levels : ndarray, shape (n,)
        Increasing IM levels [m/s² or m/s].
    rates : ndarray, shape (n,)
        Annual rates of exceedance [1/yr], non-increasing, positive.
    source : str
        Where the curve came from (a file, or a source model).
    source_model : object, optional
        The ``source_hazard.SourceModel`` of a computed curve, which disaggregates it (None
        when read from a file).
    """

    im: str
    levels: np.ndarray
    rates: np.ndarray
    source: str = ""
    source_model: object = field(default=None, compare=False, repr=False)

    def __post_init__(self):
        levels = np.asarray(self.levels, dtype=float)
        rates = np.asarray(self.rates, dtype=float)
        object.__setattr__(self, "levels", levels)
        object.__setattr__(self, "rates", rates)
        problem = curve_problem(levels, rates)
        if problem:
            raise HazardFileError(f"{self.source or 'hazard curve'}: {problem}")

    @property
    def units(self):
        return SI_UNITS[im_dimension(self.im)]

    def slopes(self):
        """k_i = −Δ ln λ / Δ ln x of each segment between levels, shape (n − 1,)."""
        return -np.diff(np.log(self.rates)) / np.diff(np.log(self.levels))

    def rate(self, x):
        """λ(x) by log–log interpolation; NaN outside [levels[0], levels[-1]]."""
        x = np.asarray(x, dtype=float)
        with np.errstate(divide="ignore"):
            log_rate = np.interp(np.log(x), np.log(self.levels), np.log(self.rates),
                                 left=np.nan, right=np.nan)
        return np.exp(log_rate)

    def level_at_rate(self, rate):
        """The level x with λ(x) = ``rate`` (log–log interpolation); NaN outside the curve."""
        log_rate = np.log(np.asarray(rate, dtype=float))
        order = np.argsort(np.log(self.rates))  # np.interp wants increasing abscissae
        return np.exp(np.interp(log_rate, np.log(self.rates)[order], np.log(self.levels)[order],
                                left=np.nan, right=np.nan))


def curve_problem(levels, rates):
    """Why ``levels`` and ``rates`` are not a hazard curve, or None."""
    if levels.ndim != 1 or levels.shape != rates.shape:
        return "levels and rates must be two lists of equal length"
    if levels.size < 2:
        return "a hazard curve needs at least 2 levels"
    if not (np.all(np.isfinite(levels)) and np.all(np.isfinite(rates))):
        return "levels and rates must be finite numbers"
    if np.any(levels <= 0):
        return f"levels must be positive (got {levels[levels <= 0][0]:g})"
    if np.any(np.diff(levels) <= 0):
        return "levels must increase"
    if np.any(rates <= 0):
        return (f"rates of exceedance must be positive (got {rates[rates <= 0][0]:g} at level "
                f"{levels[rates <= 0][0]:g}); drop the levels never exceeded")
    rising = np.flatnonzero(np.diff(rates) > 0)
    if rising.size:
        i = rising[0]
        return (f"the rate of exceedance rises from {rates[i]:g} at {levels[i]:g} to "
                f"{rates[i + 1]:g} at {levels[i + 1]:g}: a hazard curve never increases")
    return None


def _float(text, where):
    try:
        return float(text)
    except (TypeError, ValueError):
        raise HazardFileError(f"{where}: not a number: {text!r}") from None


def read_openquake_csv(path, site=0):
    """The curve of row ``site`` of OpenQuake's ``hazard_curve-*.csv``.

    The first line is a comment (``#,,,,"..., investigation_time=50.0, imt='PGA'"``); the
    header names ``lon, lat`` (``depth`` in recent versions) and ``poe-<level>`` columns, the
    levels in g (cm/s for PGV).  Rates λ = −ln(1 − P)/T; levels whose P is 0 are dropped (no
    exceedance: the curve ends there).
    """
    path = Path(path)
    lines = path.read_text().splitlines()
    if not lines or not lines[0].startswith("#"):
        raise HazardFileError(f"{path}: line 1: not an OpenQuake hazard curve (no comment line "
                              "with investigation_time and imt)")
    meta = lines[0]
    found_time = re.search(r"investigation_time\s*=\s*([0-9.eE+-]+)", meta)
    found_imt = re.search(r"imt\s*=\s*'([^']+)'", meta)
    if not found_time or not found_imt:
        raise HazardFileError(f"{path}: line 1: investigation_time and imt not found")
    investigation_time = _float(found_time.group(1), f"{path}: line 1: investigation_time")
    try:
        im = normalize_im(found_imt.group(1))
    except ValueError as err:
        raise HazardFileError(f"{path}: line 1: {err}") from None
    rows = list(csv.reader(lines[1:]))
    header = [h.strip() for h in rows[0]] if rows else []
    poe_columns = [i for i, h in enumerate(header) if h.startswith("poe-")]
    if not poe_columns:
        raise HazardFileError(f"{path}: line 2: no poe-<level> columns")
    if not 0 <= site < len(rows) - 1:
        raise HazardFileError(f"{path}: site {site} not in the file ({len(rows) - 1} sites)")
    row = rows[1 + site]
    where = f"{path}: line {site + 3}"
    levels = np.array([_float(header[i][4:], f"{path}: line 2: {header[i]}")
                       for i in poe_columns])
    poes = np.array([_float(row[i], f"{where}: {header[i]}") for i in poe_columns])
    if np.any((poes < 0) | (poes > 1)):
        raise HazardFileError(f"{where}: probabilities of exceedance must lie in [0, 1]")
    keep = (poes > 0) & (poes < 1)  # P = 1: the rate is beyond what the file can say
    factor = FORMAT_FACTOR[im_dimension(im)]
    return _curve(im, levels[keep] * factor, rate_from_poe(poes[keep], investigation_time),
                  f"{path} (OpenQuake, T = {investigation_time:g} yr)")


def read_usgs_json(path, im=None, component="Total"):
    """The curve of ``im`` (the first in the file if None) of a USGS hazard web service
    response: ``response[i].metadata.imt.value`` (``PGA``, ``SA0P2``), ``metadata.xvalues``
    (g, cm/s for PGV) and ``data[j].yvalues`` (annual frequency of exceedance) of the
    ``component`` (``Total``)."""
    path = Path(path)
    try:
        document = json.loads(path.read_text())
        responses = document["response"]
        if isinstance(responses, dict):
            responses = [responses]
        found = []
        for response in responses:
            meta = response["metadata"]
            imt = meta["imt"]["value"] if isinstance(meta["imt"], dict) else meta["imt"]
            found.append((normalize_im(imt), meta, response["data"]))
    except (json.JSONDecodeError, KeyError, TypeError) as err:
        raise HazardFileError(f"{path}: not a USGS hazard curve response ({err})") from None
    except ValueError as err:
        raise HazardFileError(f"{path}: {err}") from None
    names = [f[0] for f in found]
    if not found or (im is not None and im not in names):
        raise HazardFileError(f"{path}: no curve of {im or 'any IM'} (found: "
                              f"{', '.join(names) or 'none'})")
    name, meta, data = found[names.index(im) if im is not None else 0]
    series = {d.get("component"): d["yvalues"] for d in data}
    if component not in series:
        raise HazardFileError(f"{path}: {name}: no component {component!r} (found: "
                              f"{', '.join(map(str, series))})")
    levels = np.asarray(meta["xvalues"], dtype=float) * FORMAT_FACTOR[im_dimension(name)]
    rates = np.asarray(series[component], dtype=float)
    keep = rates > 0
    return _curve(name, levels[keep], rates[keep], f"{path} (USGS, {component})")


def read_columns(path, im, units, kind="annual_rate", investigation_time=None):
    """Two columns ``im, annual_rate`` (or ``im, poe`` with ``investigation_time`` [yr]),
    comma or white-space separated, ``#`` comments and a header line of names allowed; ``im``
    in ``units`` (e.g. ``g``, ``m/s^2``, ``cm/s``)."""
    from ..io.units import fixed_factor

    path = Path(path)
    try:
        factor = fixed_factor(units, im_dimension(im))
    except ValueError as err:
        raise HazardFileError(f"{path}: units {units!r}: {err}") from None
    if kind == "poe" and investigation_time is None:
        raise HazardFileError(f"{path}: probabilities of exceedance need investigation_time")
    values = []
    for number, line in enumerate(path.read_text().splitlines(), 1):
        text = line.split("#", 1)[0].strip()
        if not text:
            continue
        cells = [c for c in re.split(r"[,\s;]+", text) if c]
        if len(cells) != 2:
            raise HazardFileError(f"{path}: line {number}: expected 2 columns, got {len(cells)}")
        try:
            values.append([float(c) for c in cells])
        except ValueError:
            if values:
                raise HazardFileError(f"{path}: line {number}: not numbers: {text!r}") from None
            continue  # a header line
    if not values:
        raise HazardFileError(f"{path}: no rows of numbers")
    levels, second = np.array(values).T
    if kind == "poe":
        if np.any((second < 0) | (second > 1)):
            raise HazardFileError(f"{path}: probabilities of exceedance must lie in [0, 1]")
        keep = (second > 0) & (second < 1)
        rates = rate_from_poe(second[keep], investigation_time)
        levels = levels[keep]
    else:
        rates = second
    return _curve(im, levels * factor, rates, f"{path}")


def _curve(im, levels, rates, source):
    return HazardCurve(im, levels, rates, source)


def write_columns(path, curve):
    """Write ``curve`` as two columns ``im, annual_rate`` in SI units (a header comment says
    which), atomically."""
    from ..io.files import replacing

    with replacing(path) as tmp:
        lines = [f"# {curve.im} [{curve.units}], annual rate of exceedance [1/yr]; "
                 f"from {curve.source}", f"{curve.im},annual_rate"]
        lines += [f"{x:.8g},{r:.8g}" for x, r in zip(curve.levels, curve.rates)]
        Path(tmp).write_text("\n".join(lines) + "\n")
    return Path(path)


def write_openquake_csv(path, curve, investigation_time=50.0, lon=0.0, lat=0.0):
    """Write ``curve`` as OpenQuake writes a hazard curve (probabilities of exceedance in
    ``investigation_time``, levels in g or cm/s), atomically: for a check of the reader and
    for OpenQuake's own tools."""
    from ..io.files import replacing

    factor = FORMAT_FACTOR[im_dimension(curve.im)]
    poes = poe_from_rate(curve.rates, investigation_time)
    header = ["lon", "lat", "depth"] + [f"poe-{x / factor:.8g}" for x in curve.levels]
    with replacing(path) as tmp:
        Path(tmp).write_text(
            f"#,,,,\"generated_by='sweep.risk', kind='mean', investigation_time="
            f"{investigation_time!r}, imt='{openquake_imt(curve.im)}'\"\n"
            + ",".join(header) + "\n"
            + ",".join([f"{lon:g}", f"{lat:g}", "0.0"] + [f"{p:.8e}" for p in poes]) + "\n")
    return Path(path)
