"""Hazard curve files: OpenQuake CSV, USGS JSON and two columns, read and written.

Read into a :class:`~sweep.probability.hazard_curve.HazardCurve`, and written:

* OpenQuake's ``hazard_curve-*.csv`` (:func:`read_openquake_csv`): a comment line with
  ``investigation_time`` and ``imt`` (in each form OpenQuake has written), then
  ``lon,lat[,depth],poe-<level>...`` (or ``<IMT>-<level>`` columns); levels in g (cm/s for
  PGV), probabilities of exceedance P in the investigation time T;
* a USGS hazard curve export (:func:`read_usgs_json`, the JSON of the USGS hazard web
  service): ``response[].metadata.imt``, ``xvalues`` (g, cm/s for PGV) and ``data[].yvalues``,
  annual frequencies of exceedance (the ``Total`` component);
* two columns (:func:`read_columns`): ``im, annual_rate`` or ``im, poe``; the IM, the units of
  its levels, the kind of the second column and the investigation time of probabilities are
  read from the file (a ``# units: g`` comment, a header such as ``pga_g,poe_50yr``) or given,
  and a given one that contradicts the file is refused.

Problems of a file raise ``HazardFileError``, one line each, with the file and where in it;
levels implausible for the IM in the units read (a unit mistaken) are warned
(:data:`PLAUSIBLE_LEVELS`).  docs/risk.md, "Formats in and out".
"""
import csv
import json
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..bodies import G
from ..io.imt import display_scale, im_dimension, normalize_im, openquake_imt
from ..io.problems import Problem, warn
from ..io.units import fixed_factor, parse_quantity
from .hazard_curve import HazardCurve, HazardFileError, poe_from_rate, rate_from_poe

# units of the levels in the formats read: OpenQuake and USGS write g and cm/s
FORMAT_FACTOR = {"acceleration": G, "velocity": 0.01}
FORMAT_UNITS = {"acceleration": "g", "velocity": "cm/s"}
# (lowest, highest) plausible level [SI]: a curve above the highest, or wholly below the
# lowest, is likely read in the wrong units.  10 g is over twice the largest PGA recorded
# (about 4 g); hazard curves start at a few thousandths of a g.  For PGV the same factors
# on the largest PGV recorded (about 3 m/s) and on PGV ≈ 1 m/s per g: 10 m/s and 0.1 cm/s.
PLAUSIBLE_LEVELS = {"acceleration": (1e-3 * G, 10.0 * G), "velocity": (1e-3, 10.0)}
SI_NAMES = {"acceleration": "m/s^2", "velocity": "m/s"}  # as a file writes them
MAX_BYTES = 100_000_000  # a larger file is not a hazard curve (and /dev/zero ends)


def _float(text, where):
    try:
        return float(text)
    except (TypeError, ValueError):
        raise HazardFileError(f"{where}: not a number: {text!r}") from None


def read_text(path):
    """The text of a curve file (UTF-8, a byte-order mark allowed).

    Raises
    ------
    HazardFileError
        A file that is binary (a NUL byte), not UTF-8, or larger than :data:`MAX_BYTES`.
    OSError
        A file that cannot be opened.
    """
    with open(path, "rb") as stream:
        data = stream.read(MAX_BYTES + 1)
    if len(data) > MAX_BYTES:
        raise HazardFileError(f"{path}: larger than {MAX_BYTES // 10**6} MB: not a hazard "
                              "curve")
    nul = data.find(b"\0")
    if nul >= 0:
        raise HazardFileError(f"{path}: not a text file (a NUL byte at byte {nul})")
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as err:
        raise HazardFileError(f"{path}: not a text file in UTF-8 (byte {err.start} is "
                              f"{data[err.start]:#04x})") from None


def _positive_time(text, where):
    """An investigation time [yr] read at ``where``: a positive, finite number."""
    value = _float(text, where)
    if not (np.isfinite(value) and value > 0):
        raise HazardFileError(f"{where}: must be a positive number of years: {text!r}")
    return value


def _openquake_comment(line):
    """``{"investigation_time": text, "imt": text}`` (those found) of the comment line of an
    OpenQuake CSV, in each form OpenQuake has written: ``# investigation_time=1.0,imt="PGA"``,
    ``# mean, investigation_time=50.0, imt="PGA", checksum=...``, ``# max,
    investigation_time=50.0,imt=SA(0.1)``, ``#,,,,"generated_by='OpenQuake engine 3.7',
    ..., investigation_time=50.0, imt='PGA'"`` (recent versions), and the quotes doubled as
    a CSV cell writes them (``imt=""PGA""``).  OpenQuake reads the same ``key=value`` pairs
    (``parse_comment`` of openquake.baselib.writers, later hdf5)."""
    text = line.lstrip("#").lstrip(", \t").strip()
    if len(text) >= 2 and text[0] == text[-1] == '"':
        text = text[1:-1]
    text = text.replace('""', '"')
    found = {}
    for key in ("investigation_time", "imt"):
        match = re.search(rf"\b{key}\s*=\s*(?:'([^']*)'|\"([^\"]*)\"|([^,\s'\"]+))", text)
        if match:
            found[key] = next(g for g in match.groups() if g is not None).strip()
    return found


# a level column of OpenQuake: poe-0.1 (the comment's imt) or PGA-0.1, SA(0.2)-0.1:float32
_LEVEL_COLUMN = re.compile(r"(?P<imt>.+?)-(?P<level>\d[\d.]*(?:[eE][+-]?\d+)?)(?::\w+)?")


def _openquake_columns(header, imt, im, where):
    """(im, [(column index, level text)]) of the curve chosen in an OpenQuake header: the
    ``poe-<level>`` columns of the comment's ``imt``, or the ``<IMT>-<level>`` columns of the
    comment's imt, of ``im``, or of the only IMT of the file."""
    columns = {}
    for i, name in enumerate(header):
        match = _LEVEL_COLUMN.fullmatch(name.strip())
        if match:
            columns.setdefault(match["imt"], []).append((i, match["level"]))
    if "poe" in columns:
        if imt is None:
            raise HazardFileError(f"{where[0]}: imt not found (the poe-<level> columns need "
                                  "it)")
        return _openquake_im(imt, where[0]), columns["poe"]
    named = {}
    for name, found in columns.items():
        try:
            named[normalize_im(name)] = found
        except ValueError:
            continue  # an IMT this package does not use (IA, ...), chosen by no one
    if not named:
        raise HazardFileError(f"{where[1]}: no poe-<level> (or <IMT>-<level>) columns")
    wanted = _openquake_im(imt, where[0]) if imt is not None else im
    if wanted is None and len(named) > 1:
        raise HazardFileError(f"{where[1]}: curves of {', '.join(named)}: say which",
                              key="im")
    wanted = wanted or next(iter(named))
    if wanted not in named:
        raise HazardFileError(f"{where[1]}: no curve of {wanted} (found: "
                              f"{', '.join(named)})", key="im" if imt is None else None)
    return wanted, named[wanted]


def _openquake_im(imt, where):
    try:
        return normalize_im(imt)
    except ValueError as err:
        raise HazardFileError(f"{where}: {err}") from None


def _openquake_meta(path, lines):
    """(number of comment lines, where they are, investigation time [yr], imt text or None)
    of the comment lines that open an OpenQuake CSV."""
    count = 0
    while count < len(lines) and lines[count].lstrip().startswith("#"):
        count += 1
    if not count:
        raise HazardFileError(f"{path}: line 1: not an OpenQuake hazard curve (no comment line "
                              "with investigation_time and imt)")
    meta = {}
    for line in lines[:count]:
        meta = {**_openquake_comment(line), **meta}
    where = f"{path}: line{'s 1-' if count > 1 else ' '}{count}"
    if "investigation_time" not in meta:
        raise HazardFileError(f"{where}: investigation_time not found")
    return (count, where, _positive_time(meta["investigation_time"],
                                         f"{where}: investigation_time"), meta.get("imt"))


def read_openquake_csv(path, site=0, im=None):
    """The curve of row ``site`` of OpenQuake's ``hazard_curve-*.csv``.

    The first line (or lines) is a comment with ``investigation_time`` and ``imt`` (each form
    OpenQuake has written: :func:`_openquake_comment`); the header names ``lon, lat``
    (``depth`` in recent versions) and ``poe-<level>`` columns, or ``<IMT>-<level>`` columns
    of one or more IMTs (older versions; ``im`` chooses among several), the levels in g (cm/s
    for PGV).  Rates λ = −ln(1 − P)/T; levels whose P is 0 are dropped (no exceedance: the
    curve ends there), and those whose P is 1 (a rate beyond what the file can say).
    """
    path = Path(path)
    lines = read_text(path).splitlines()
    count, said, investigation_time, imt = _openquake_meta(path, lines)
    numbered = [(n, row) for n, row in enumerate(csv.reader(lines[count:]), count + 1) if row]
    if not numbered:
        raise HazardFileError(f"{path}: no header line after the comment")
    header_line, header = numbered[0]
    im, columns = _openquake_columns(header, imt, im, (said, f"{path}: line {header_line}"))
    sites = numbered[1:]
    if not 0 <= site < len(sites):
        raise HazardFileError(f"{path}: site {site} not in the file ({len(sites)} sites)",
                              key="site" if sites else None)
    number, row = sites[site]
    where = f"{path}: line {number}"
    if len(row) != len(header):
        raise HazardFileError(f"{where}: {len(row)} cells, the header has {len(header)}")
    levels = np.array([_float(level, f"{path}: line {header_line}: {header[i]}")
                       for i, level in columns])
    poes = np.array([_float(row[i], f"{where}: {header[i]}") for i, _ in columns])
    if not np.all((poes >= 0) & (poes <= 1)):
        raise HazardFileError(f"{where}: probabilities of exceedance must lie in [0, 1]")
    keep = (poes > 0) & (poes < 1)
    dimension = im_dimension(im)
    return _checked_curve(im, levels[keep] * FORMAT_FACTOR[dimension],
                          rate_from_poe(poes[keep], investigation_time),
                          f"{path} (OpenQuake, T = {investigation_time:g} yr)", path,
                          FORMAT_UNITS[dimension])


def read_usgs_json(path, im=None, component="Total"):
    """The curve of ``im`` (the first in the file if None) of a USGS hazard web service
    response: ``response[i].metadata.imt.value`` (``PGA``, ``SA0P2``), ``metadata.xvalues``
    (g, cm/s for PGV) and ``data[j].yvalues`` (annual frequency of exceedance) of the
    ``component`` (``Total``)."""
    path = Path(path)
    try:
        document = json.loads(read_text(path))
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
                              f"{', '.join(names) or 'none'})", key="im" if found else None)
    name, meta, data = found[names.index(im) if im is not None else 0]
    try:
        series = {d.get("component"): np.asarray(d["yvalues"], dtype=float) for d in data}
        levels = np.asarray(meta["xvalues"], dtype=float) * FORMAT_FACTOR[im_dimension(name)]
    except (AttributeError, KeyError, TypeError, ValueError) as err:
        raise HazardFileError(f"{path}: {name}: not a USGS hazard curve ({err})") from None
    if component not in series:
        raise HazardFileError(f"{path}: {name}: no component {component!r} (found: "
                              f"{', '.join(map(str, series))})")
    rates = series[component]
    if rates.shape != levels.shape:
        raise HazardFileError(f"{path}: {name}: {levels.size} xvalues, {rates.size} yvalues")
    keep = rates != 0  # never exceeded: the curve ends there
    return _checked_curve(name, levels[keep], rates[keep], f"{path} (USGS, {component})", path,
                          FORMAT_UNITS[im_dimension(name)])


# --- two columns ---------------------------------------------------------------------------

_RATE_NAMES = {"rate", "annual_rate", "rate_of_exceedance", "annual_rate_of_exceedance",
               "exceedance_rate", "annual_exceedance_rate", "frequency", "annual_frequency",
               "annual_frequency_of_exceedance", "afe", "mafe", "lambda"}
_POE_NAME = re.compile(r"(?:poe|pe|prob|probability|probability_of_exceedance)"
                       r"(?:_(?:in_)?(?P<years>\d+(?:\.\d*)?)_?(?:y|yr|yrs|year|years)?)?")
_COMMENT = re.compile(r"\s*(?P<key>units?|investigation[_ ]time)\s*[:=]\s*(?P<value>.*?)\s*",
                      re.IGNORECASE)
_YEARS = re.compile(r"(?P<number>\S+?)\s*(?:y|yr|yrs|year|years)?", re.IGNORECASE)


@dataclass
class _Stated:
    """What a two-column file states: ``values[key] = (value, where)``, ``key`` one of
    ``im``, ``units``, ``kind``, ``investigation_time``."""

    path: Path
    values: dict = field(default_factory=dict)

    def say(self, key, value, where, same=lambda a, b: a == b):
        """Record ``key`` = ``value`` stated at ``where``; a file that says two things is
        refused."""
        if key in self.values and not same(self.values[key][0], value):
            first, at = self.values[key]
            raise HazardFileError(f"{self.path}: {key} {first} ({at}) and {value} ({where}) "
                                  "disagree")
        self.values.setdefault(key, (value, where))


def _unit_si(unit):
    """(dimension, SI factor) of a unit of IM levels; ValueError if not one."""
    quantity = parse_quantity(f"1 {unit}", ("acceleration", "velocity"))
    if quantity.body_relative:
        raise ValueError(f"'{unit}' is relative to the body; use a fixed unit")
    return quantity.dimension, quantity.to_si()


def _same_unit(a, b):
    return _unit_si(a) == _unit_si(b)


def _header_cells(text):
    """The cells of a header line: split at commas, semicolons or tabs, else at spaces
    keeping a bracketed unit with its name (``pga [g] poe``)."""
    if re.search(r"[,;\t]", text):
        return [c.strip() for c in re.split(r"[,;\t]", text)]
    return re.findall(r"[^\s\[(]+(?:\([\d.]+\)[^\s\[(]*)?(?:\s*[\[(][^\])]*[\])])?", text)


def _level_name(cell):
    """(im or None, unit text or None) that the name of the level column states:
    ``pga_g``, ``pga [g]``, ``pga(g)``, ``PGA (cm/s^2)``, ``sa(0.2)_g``, ``im``."""
    name, unit = cell.strip(), None
    bracket = re.fullmatch(r"(.*?)\s*[\[(]([^\[\]()]*)[\])]", name)
    if bracket and not re.fullmatch(r"\s*[\d.]+\s*", bracket[2]):
        name, unit = bracket[1], bracket[2].strip()
    elif "_" in name:
        head, suffix = name.rsplit("_", 1)
        try:
            _unit_si(suffix)
            name, unit = head, suffix
        except ValueError:
            pass  # pga_rotd50: a name, no unit
    try:
        im = normalize_im(name)
    except ValueError:
        im = None
    return im, unit


def _second_name(cell):
    """(kind or None, investigation time text or None) that the name of the second column
    states: ``annual_rate``, ``rate [1/yr]``, ``poe``, ``probability``, ``poe_50yr``."""
    text = re.sub(r"[\[(]\s*1?\s*/\s*(?:y|yr|year)\s*[\])]$", "", cell.strip().lower())
    text = re.sub(r"[\s\-\[\]()]+", "_", text).strip("_")
    if text in _RATE_NAMES:
        return "annual_rate", None
    match = _POE_NAME.fullmatch(text)
    return ("poe", match["years"]) if match else (None, None)


def _header(stated, cells, number):
    """Record what a header line of two names states."""
    where = f"line {number}, {','.join(cells)!r}"
    im, unit = _level_name(cells[0])
    if im is not None:
        stated.say("im", im, where)
    if unit is not None:
        _file_unit(stated, unit, where)
    kind, years = _second_name(cells[1])
    if kind is not None:
        stated.say("kind", kind, where)
    if years is not None:
        stated.say("investigation_time",
                   _positive_time(years, f"{stated.path}: {where}"), where)


def _file_unit(stated, unit, where):
    try:
        _unit_si(unit)
    except ValueError as err:
        raise HazardFileError(f"{stated.path}: {where}: {err}") from None
    stated.say("units", unit, where, _same_unit)


def _comment(stated, text, number):
    """Record a ``# units: g`` or ``# investigation_time: 50`` comment."""
    match = _COMMENT.fullmatch(text)
    if not match:
        return
    where = f"line {number}, '#{text.rstrip()}'"
    if match["key"].lower().startswith("unit"):
        _file_unit(stated, match["value"], where)
    else:
        years = _YEARS.fullmatch(match["value"])
        stated.say("investigation_time", _positive_time(
            years["number"] if years else match["value"], f"{stated.path}: {where}"), where)


def _column_file(path):
    """(levels, second column, :class:`_Stated`) of a two-column file."""
    stated, values = _Stated(path), []
    for number, line in enumerate(read_text(path).splitlines(), 1):
        text, _, comment = line.partition("#")
        if comment:
            _comment(stated, comment, number)
        text = text.strip()
        if not text:
            continue
        cells = [c for c in re.split(r"[,\s;]+", text) if c]
        try:
            numbers = [float(c) for c in cells]
        except ValueError:
            numbers = None
        if numbers is not None and len(numbers) == 2:
            values.append(numbers)
            continue
        if values and numbers is None:
            raise HazardFileError(f"{path}: line {number}: not numbers: {text!r}")
        header = _header_cells(text) if numbers is None else cells
        if len(header) != 2:
            raise HazardFileError(f"{path}: line {number}: expected 2 columns, got "
                                  f"{len(header)}")
        _header(stated, header, number)
    if not values:
        raise HazardFileError(f"{path}: no rows of numbers")
    levels, second = np.array(values).T
    return levels, second, stated


def _settled(stated, key, given, same=lambda a, b: a == b):
    """The value of ``key``: the one given, else the file's; a given one that contradicts
    the file's is refused (HazardFileError with ``key``)."""
    if key not in stated.values:
        return given
    value, where = stated.values[key]
    if given is not None and not same(given, value):
        raise HazardFileError(f"{stated.path}: contradicts the file, which says {value} "
                              f"({where})", key=key)
    return value


def _required(path, key, what):
    return HazardFileError(f"{path}: required: the file does not state {what}", key=key)


def read_columns(path, im=None, units=None, kind=None, investigation_time=None):
    """Two columns ``im, annual_rate`` (or ``im, poe`` with ``investigation_time`` [yr]),
    comma or white-space separated, ``#`` comments and a header line of names allowed.

    What the file states is read, and what is given must agree with it (else
    :class:`HazardFileError` whose ``key`` names the setting: ``im``, ``units``, ``kind``,
    ``investigation_time``): the IM and the units of its levels from the first column's name
    (``pga_g``, ``pga [g]``, ``pga(g)``, ``PGA (cm/s^2)``, ``sa(0.2)_g``) or a ``# units: g``
    comment; the kind of the second column from its name (``annual_rate``, ``rate``, ``afe``;
    ``poe``, ``probability``, ``prob``) and the investigation time from it (``poe_50yr``) or
    a ``# investigation_time: 50`` comment.  Neither given nor stated: the IM and the units
    are required, the kind is annual rates.  ``investigation_time`` given without ``kind``
    means ``kind="poe"``.
    """
    path = Path(path)
    levels, second, stated = _column_file(path)
    im = _settled(stated, "im", im)
    if im is None:
        raise _required(path, "im", "its intensity measure (a header such as pga_g,poe)")
    if units is not None:
        try:
            _unit_si(units)
        except ValueError as err:
            raise HazardFileError(f"{path}: units {units!r}: {err}", key="units") from None
    units = _settled(stated, "units", units, _same_unit)
    if units is None:
        raise _required(path, "units", "the units of its levels (a '# units: g' comment or "
                                       "a header such as pga_g)")
    try:
        factor = fixed_factor(units, im_dimension(im))
    except ValueError as err:
        where = stated.values.get("units", (None, None))[1]
        raise HazardFileError(f"{path}: units {units!r}{f' ({where})' if where else ''}: "
                              f"{err}", key=None if where else "units") from None
    if kind is None and investigation_time is not None:
        kind = "poe"
    kind = _settled(stated, "kind", kind) or "annual_rate"
    if kind == "annual_rate" and investigation_time is not None:
        raise HazardFileError(f"{path}: an investigation time is for probabilities of "
                              "exceedance, the second column is annual rates",
                              key="investigation_time")
    if kind == "poe":
        levels, second = _from_poe(stated, levels, second, investigation_time)
    return _checked_curve(im, levels * factor, second, f"{path}", path, units)


def _from_poe(stated, levels, poes, investigation_time):
    """(levels, annual rates) of probabilities of exceedance in the investigation time given
    or stated; levels of P = 0 or 1 dropped."""
    years = _settled(stated, "investigation_time", investigation_time, _same_time)
    if years is None:
        raise _required(stated.path, "investigation_time", "the investigation time of its "
                        "probabilities of exceedance (a header such as poe_50yr or a "
                        "'# investigation_time: 50' comment)")
    if not np.all((poes >= 0) & (poes <= 1)):
        raise HazardFileError(f"{stated.path}: probabilities of exceedance must lie in [0, 1]")
    keep = (poes > 0) & (poes < 1)
    return levels[keep], rate_from_poe(poes[keep], years)


def _same_time(a, b):
    return bool(np.isclose(a, b, rtol=1e-9, atol=0.0))


def check_given_units(curve, units, path):
    """Refuse ``units`` given for an OpenQuake or USGS file's ``curve`` unless they are the
    format's, g (cm/s for PGV): HazardFileError with ``key="units"``."""
    if units is None:
        return
    dimension = im_dimension(curve.im)
    try:
        agree = _unit_si(units) == (dimension, FORMAT_FACTOR[dimension])
    except ValueError as err:
        raise HazardFileError(f"{path}: units {units!r}: {err}", key="units") from None
    if not agree:
        raise HazardFileError(f"{path}: contradicts the file, whose levels are in "
                              f"{FORMAT_UNITS[dimension]}", key="units")


def _checked_curve(im, levels, rates, source, path, unit):
    """The :class:`HazardCurve`, its levels warned when implausible for the IM in ``unit``."""
    curve = HazardCurve(im, levels, rates, source)
    message = implausible_levels(curve, unit)
    if message:
        warn([Problem(str(path), unit, message)])
    return curve


def implausible_levels(curve, unit):
    """Why the curve's levels, read in ``unit``, are unlikely to be in that unit, or None:
    above the highest of :data:`PLAUSIBLE_LEVELS`, or all below the lowest."""
    lowest, highest = PLAUSIBLE_LEVELS[im_dimension(curve.im)]
    factor, label = display_scale(curve.units)
    top = curve.levels[-1]
    if top > highest:
        return (f"the levels reach {top / factor:.3g} {label} (read in {unit}), above "
                f"{highest / factor:g} {label}: implausible for {curve.im}; check the units")
    if top < lowest:
        return (f"every level is below {lowest / factor:g} {label} (the largest "
                f"{top / factor:.3g} {label}, read in {unit}): implausible for {curve.im}; "
                "check the units")
    return None


def write_columns(path, curve):
    """Write ``curve`` as two columns ``im, annual_rate`` in SI units (a ``# units:``
    comment says which), atomically."""
    from ..io.files import replacing

    with replacing(path) as tmp:
        lines = [f"# {curve.im}, annual rate of exceedance [1/yr]; from {curve.source}",
                 f"# units: {SI_NAMES[im_dimension(curve.im)]}", f"{curve.im},annual_rate"]
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
