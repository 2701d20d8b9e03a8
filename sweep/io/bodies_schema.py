"""Bodies files of ``python -m sweep.estimate``: bodies seen at sites, and an ensemble.

Bodies seen overturned and standing at sites, and optionally the ensemble of motions the sites
may have felt.

A bodies file, with several sites::

    sites:
      - name: graveyard A
        latitude: 35.2                     # optional, degrees north
        longitude: 139.1                   # optional, degrees east
        bodies:
          - {name: stone 1, B: 30 cm, H: 90 cm, overturned: true, direction: N}
          - {name: stone 2, B: 40 cm, H: 80 cm, overturned: false, mu: 0.6}
    ensemble:                              # optional: the probabilistic estimate
      motions: {record: [elcentro1940_ns, elcentro1940_ew, taft1952_ew_s69e]}
      levels: {pga: {start: 1 m/s^2, stop: 16 m/s^2, num: 14}}
      contact: {mu: 0.6, e_x: -0.8, e_y: 0.2}
      probabilities: [0.05, 0.5, 0.95]

or, for one site, ``site: <name>`` and ``bodies: [...]`` at the top (the first format of the
command, still read).  ``B``, ``H`` (and the optional radius of gyration ``i_g``) are lengths
with units (``sweep.io.units``); ``mu`` is the friction coefficient, if known; ``direction`` any
label of the direction of fall.

``ensemble`` (every key but ``motions`` and ``levels`` optional):

``motions``
    ``{record: [names or paths]}`` (bundled records by name, files as PEER ``.AT2`` or two
    columns, relative to the bodies file's folder), ``{record: {glob: 'motions/*.AT2'}}`` (the
    extension in any case; the other files of its folder are warned of), or
    ``{synthetic: {model: boore2003, magnitude, distance, vs30, dt}, seeds: N}`` (the motions
    of seeds 0 .. N-1 of ``sweep.groundmotion.stochastic``).  Each is one member.
``levels``
    ``{pga: {start, stop, num, spacing: log|linear}}`` (default log) or ``{pga: [values]}``:
    the PGA every member is scaled to, increasing, at least 2 levels.
``contact``
    ``mu`` for the bodies that give none (default :data:`DEFAULT_MU`), ``e_x``, ``e_y`` for
    all (default those of ``kernels.api.DEFAULTS``).
``t_end``
    Simulated time; by default from the motions (``sweep.probability.site_studies``).
``probabilities``
    The probability levels of the bounds, each in (0, 1); default :data:`DEFAULT_PROBABILITIES`.

``load_survey`` checks a file with the pydantic models below and reports every problem at
once with its dotted path (``sites[0].bodies[2].B``, ``ensemble.levels.pga.num``), as scene
and study files do; ``load_bodies`` reads a one-site file.
"""
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any, Literal, Optional, Union

import numpy as np
from pydantic import (Field, PrivateAttr, StrictBool, StrictFloat, StrictInt, StrictStr,
                      ValidationInfo, field_validator, model_validator)

from . import records
from .files import find_files, named
from .plausibility import body_doubts, glob_notes, levels_doubt
from .loader import load_file
from .problems import MISSING, FieldError, Problem, fields_checked, warn
from .fields import (Acceleration, Coefficient, Duration, Length, Real, StrictModel,
                           quantity)

DEFAULT_MU = 0.6  # friction of a body that gives none: stone on stone or concrete
DEFAULT_PROBABILITIES = (0.05, 0.5, 0.95)
MAX_LEVELS = 1000  # levels of an ensemble: far finer than any bound needs
MAX_MEMBERS = 100_000  # motions of an ensemble
MAX_PROBABILITIES = 20


@dataclass(frozen=True)
class Body:
    """One body of a bodies file, in SI units."""

    name: str
    B: float
    H: float
    overturned: bool
    i_g: float = None
    mu: float = None
    direction: str = None


@dataclass(frozen=True)
class Site:
    """A site: its name, optional coordinates [degrees] and bodies."""

    name: str
    bodies: tuple
    latitude: float = None
    longitude: float = None


@dataclass(frozen=True)
class Ensemble:
    """The motions a site may have felt, in SI units.

    Attributes
    ----------
    records : tuple of str
        Bundled record names and absolute paths of record files (``record`` motions), or ().
    synthetic : dict or None
        ``model``, ``magnitude``, ``distance`` [m], ``vs30`` [m/s], ``dt`` [s] or None.
    seeds : int
        Synthetic members: seeds 0 .. seeds - 1 (0 for records).
    levels : tuple of float
        PGA [m/s^2] each member is scaled to, increasing.
    mu : float
        Friction coefficient of the bodies that give none.
    e_x, e_y : float or None
        Restitution coefficients (None: the kernel's defaults).
    t_end : float or None
        Simulated time [s] (None: from the motions).
    probabilities : tuple of float
        Probability levels of the bounds, increasing.
    """

    records: tuple
    synthetic: dict
    seeds: int
    levels: tuple
    mu: float
    e_x: float
    e_y: float
    t_end: float
    probabilities: tuple

    @property
    def members(self):
        """Number of motions of the ensemble."""
        return len(self.records) or self.seeds


@dataclass(frozen=True)
class Survey:
    """A checked bodies file: its ``sites``, ``ensemble`` (or None), its path (None for a
    dict) and whether it is written in the one-site format (``site`` + ``bodies``)."""

    sites: tuple
    ensemble: Ensemble
    source: Path = None
    one_site_format: bool = False


# --- bodies and sites -------------------------------------------------------------------------

Name = Union[StrictStr, StrictInt, StrictFloat]


class BodyEntry(StrictModel):
    """An entry of ``bodies``: size, state and what else is known of the body."""

    name: Optional[Name] = None
    B: Length
    H: Length
    i_g: Optional[Length] = None
    overturned: StrictBool
    mu: Optional[Coefficient] = None
    direction: Optional[StrictStr] = None


BodyList = Annotated[list[BodyEntry], Field(min_length=1)]


class SiteEntry(StrictModel):
    """An entry of ``sites``: a name, optional coordinates and the bodies seen there."""

    name: Name
    latitude: Optional[Annotated[Real, Field(ge=-90.0, le=90.0)]] = None
    longitude: Optional[Annotated[Real, Field(ge=-180.0, le=180.0)]] = None
    bodies: BodyList


# --- the ensemble -----------------------------------------------------------------------------

def _absolute(q):
    """An acceleration that does not depend on the body (levels are shared by all bodies)."""
    if q.body_relative:
        raise ValueError("must be an acceleration in m/s^2, gal or g: the levels are shared "
                         "by every body, 'west' is not")
    if not q.value > 0:
        raise ValueError("must be greater than 0")
    return q


class LevelRange(StrictModel):
    """``{start, stop, num, spacing}`` or ``{values}`` (a list given as such) of PGA levels."""

    start: Optional[Acceleration] = None
    stop: Optional[Acceleration] = None
    num: Optional[Annotated[StrictInt, Field(ge=2, le=MAX_LEVELS)]] = None
    spacing: Literal["log", "linear"] = "log"
    values: Optional[Annotated[list[Acceleration], Field(min_length=2,
                                                         max_length=MAX_LEVELS)]] = None

    @field_validator("start", "stop")
    @classmethod
    def _positive(cls, q):
        return None if q is None else _absolute(q)

    @field_validator("values")
    @classmethod
    def _positive_values(cls, values):
        return None if values is None else [_absolute(q) for q in values]

    @model_validator(mode="after")
    def _range_or_values(self):
        if self.values is not None:
            errors = [(key, getattr(self, key), "give either values or start/stop/num")
                      for key in ("start", "stop", "num") if getattr(self, key) is not None]
            si = [q.to_si() for q in self.values]
            errors += [(("values", i + 1), str(self.values[i + 1]), "levels must increase")
                       for i in range(len(si) - 1) if not si[i + 1] > si[i]]
        else:
            errors = [(key, MISSING, "required (or a list of levels)")
                      for key in ("start", "stop", "num") if getattr(self, key) is None]
            if not errors and not self.stop.to_si() > self.start.to_si():
                errors.append(("stop", str(self.stop), "must be greater than start"))
        if errors:
            raise FieldError.several(errors)
        return self

    def si(self):
        """The levels [m/s^2], increasing."""
        if self.values is not None:
            return tuple(q.to_si() for q in self.values)
        make = np.geomspace if self.spacing == "log" else np.linspace
        return tuple(float(x) for x in make(self.start.to_si(), self.stop.to_si(), self.num))


class LevelsEntry(StrictModel):
    """``levels: {pga: ...}``: the PGA each member is scaled to."""

    pga: LevelRange

    @field_validator("pga", mode="before")
    @classmethod
    def _list_is_values(cls, value):
        """``pga: [a, b, ...]`` is ``pga: {values: [a, b, ...]}``."""
        return {"values": value} if isinstance(value, list) else value


class SyntheticEntry(StrictModel):
    """An earthquake scenario of ``sweep.groundmotion.stochastic`` (its ranges apply)."""

    model: StrictStr = "boore2003"
    magnitude: Real
    distance: quantity("length", gt=0)
    vs30: quantity("velocity", gt=0)
    dt: Optional[Duration] = None

    def si(self):
        """The scenario in SI units, as ``stochastic.generate`` takes it."""
        return {"model": self.model, "magnitude": float(self.magnitude),
                "distance": self.distance.to_si(), "vs30": self.vs30.to_si(),
                "dt": None if self.dt is None else self.dt.to_si()}


_ARGUMENT = re.compile(r"`(\w+)`")  # the argument a message of stochastic.generate names


def _record_source(entry, base_dir):
    """A bundled record's name, or the absolute path of a readable record file."""
    if entry in records.NAMES:
        return entry
    path = (Path(base_dir) / Path(entry).expanduser()).resolve()
    records.read_record_file(path)  # RecordError says why it cannot be read
    return str(path)


class MotionsEntry(StrictModel):
    """``motions``: ``record`` (a list or a glob) or ``synthetic`` with ``seeds``."""

    record: Optional[Any] = None
    synthetic: Optional[SyntheticEntry] = None
    seeds: Optional[Annotated[StrictInt, Field(ge=1, le=MAX_MEMBERS)]] = None

    @model_validator(mode="after")
    def _one_kind(self, info: ValidationInfo):
        base_dir = (info.context or {}).get("base_dir") or "."
        if (self.record is None) == (self.synthetic is None):
            raise FieldError("record" if self.record is None else "synthetic", MISSING
                             if self.record is None else "both",
                             "give either record: [...] or synthetic: {...} with seeds")
        if self.record is not None:
            if self.seeds is not None:
                raise FieldError("seeds", self.seeds, "seeds go with synthetic motions")
            self.record = _checked_records(self.record, base_dir)
        else:
            if self.seeds is None:
                raise FieldError("seeds", MISSING, "required: the number of synthetic motions")
            _check_scenario(self.synthetic)
        return self


def _checked_records(value, base_dir):
    """The ensemble's records (names or absolute paths) from a list or ``{glob: pattern}``."""
    if isinstance(value, dict):
        pattern = value.get("glob")
        if set(value) != {"glob"} or not isinstance(pattern, str) or not pattern.strip():
            raise FieldError("record", value, "a record glob is {glob: 'folder/*.AT2'} alone")
        found, skipped = find_files(pattern, base_dir)
        if not found:
            held = f"; the folder holds {named(skipped)}" if skipped else ""
            raise FieldError(("record", "glob"), pattern, "matches no file (relative to "
                             f"{Path(base_dir).resolve()}){held}")
        value = found
    if not isinstance(value, list) or not value or len(value) > MAX_MEMBERS:
        raise FieldError("record", value, "must be a list of record names or paths, or "
                                          "{glob: pattern}")
    sources, errors = [], []
    for i, entry in enumerate(value):
        if not isinstance(entry, str) or not entry.strip():
            errors.append((("record", i), entry, "must be a bundled record's name ("
                           f"{', '.join(records.BUNDLED)}) or a file's path"))
            continue
        try:
            source = _record_source(entry, base_dir)
        except records.RecordError as err:
            errors.append((("record", i), entry, str(err)))
            continue
        if source in sources:
            errors.append((("record", i), entry, "given twice"))
        sources.append(source)
    if errors:
        raise FieldError.several(errors)
    return tuple(sources)


def _check_scenario(entry):
    """Check a scenario by drawing its first motion; a range error names its field."""
    from ..groundmotion import stochastic

    scenario = entry.si()
    try:
        stochastic.generate(**{k: v for k, v in scenario.items() if k != "dt"}, seed=0,
                            **({} if scenario["dt"] is None else {"dt": scenario["dt"]}))
    except ValueError as err:
        named = _ARGUMENT.search(str(err))
        field = named.group(1) if named and named.group(1) in scenario else "model"
        raise FieldError(("synthetic", field), getattr(entry, field), str(err)) from None


class ContactEntry(StrictModel):
    """``contact``: friction of the bodies without ``mu``, restitution of all."""

    mu: Optional[Coefficient] = None
    e_x: Optional[Annotated[Real, Field(ge=-1, le=1)]] = None
    e_y: Optional[Annotated[Real, Field(ge=0, le=1)]] = None


def _probabilities(values):
    errors = [(i, q, "must lie strictly between 0 and 1") for i, q in enumerate(values)
              if not 0.0 < q < 1.0]
    errors += [(i, q, "given twice") for i, q in enumerate(values) if q in values[:i]]
    if errors:
        raise FieldError.several(errors)
    return values


class EnsembleEntry(StrictModel):
    """``ensemble``: motions, levels, contact, t_end, probabilities."""

    motions: MotionsEntry
    levels: LevelsEntry
    contact: Optional[ContactEntry] = None
    t_end: Optional[Duration] = None
    probabilities: Optional[Annotated[list[Real], Field(min_length=1,
                                                        max_length=MAX_PROBABILITIES)]] = None

    @field_validator("probabilities")
    @classmethod
    def _in_unit_interval(cls, values):
        return None if values is None else _probabilities(values)

    def resolved(self):
        """The :class:`Ensemble` in SI units."""
        contact = self.contact or ContactEntry()
        return Ensemble(
            records=self.motions.record or (),
            synthetic=None if self.motions.synthetic is None else self.motions.synthetic.si(),
            seeds=self.motions.seeds or 0, levels=self.levels.pga.si(),
            mu=DEFAULT_MU if contact.mu is None else float(contact.mu),
            e_x=contact.e_x, e_y=contact.e_y,
            t_end=None if self.t_end is None else self.t_end.to_si(),
            probabilities=tuple(sorted(self.probabilities or DEFAULT_PROBABILITIES)))


# --- the file ---------------------------------------------------------------------------------

class BodiesFile(StrictModel):
    """A bodies file: ``sites``, or ``site`` and ``bodies``; an optional ``ensemble``.  Which
    format a file uses is checked by :func:`_format_problems`."""

    site: Optional[StrictStr] = None
    bodies: Optional[BodyList] = None
    sites: Optional[Annotated[list[SiteEntry], Field(min_length=1)]] = None
    ensemble: Optional[EnsembleEntry] = None
    _warnings: tuple = PrivateAttr(())

    @model_validator(mode="wrap")
    @classmethod
    def _every_problem(cls, data, handler, info):
        """The fields' problems, then those of the format (:func:`_format_problems`), raised
        at once; a file without problems keeps the values likely not meant as its
        ``_warnings``."""
        checked, errors = fields_checked(handler, data, _FIELD_NAMES)
        errors += [FieldError(*p) for p in _format_problems(data)]
        if errors:
            raise FieldError.every(errors)
        checked._warnings = tuple(_doubts(checked, data, (info.context or {}).get("base_dir")
                                          or "."))
        return checked


def _format_problems(raw):
    """Problems of the choice between ``sites`` and ``site`` + ``bodies``, and of site names
    given twice, from the raw mapping (so that they show with every other problem)."""
    if "sites" not in raw:
        return [] if "bodies" in raw else [
            Problem("bodies", MISSING, "required: bodies (one site) or sites")]
    found = [Problem(key, raw[key], "give either sites or site and bodies")
             for key in ("site", "bodies") if key in raw]
    sites = raw["sites"] if isinstance(raw["sites"], list) else []
    names = [str(s["name"]) if isinstance(s, dict) and isinstance(s.get("name"), (str, int, float))
             else None for s in sites]
    found += [Problem(f"sites[{i}].name", name, "two sites have this name")
              for i, name in enumerate(names) if name is not None and name in names[:i]]
    return found


_MODELS = (BodiesFile, BodyEntry, SiteEntry, EnsembleEntry, MotionsEntry, LevelsEntry,
           LevelRange, SyntheticEntry, ContactEntry)
_FIELD_NAMES = sorted({name for model in _MODELS for name in model.model_fields})


def _bodies(entries):
    return tuple(Body(name=f"body {i + 1}" if b.name is None else str(b.name), B=b.B.to_si(),
                      H=b.H.to_si(), overturned=b.overturned,
                      i_g=None if b.i_g is None else b.i_g.to_si(),
                      mu=None if b.mu is None else float(b.mu), direction=b.direction)
                 for i, b in enumerate(entries))


def _glob_notes(motions, base_dir):
    """The files of its folders that a record glob of the ensemble leaves out (warned of)."""
    if not isinstance(motions.get("record"), dict):
        return []
    pattern = motions["record"]["glob"]
    return glob_notes("ensemble.motions.record.glob", pattern, *find_files(pattern, base_dir))


def _levels_doubts(levels, raw):
    """The doubt of PGA levels written as bare numbers that read like g, at their paths as
    written (``ensemble.levels.pga.start``, ``ensemble.levels.pga[0]`` for a plain list)."""
    path = "ensemble.levels.pga"
    if levels.values is not None:
        listed = f"{path}[{{}}]" if isinstance(raw, list) else f"{path}.values[{{}}]"
        written = [(listed.format(i), q) for i, q in enumerate(levels.values)]
    else:
        written = [(f"{path}.{key}", getattr(levels, key)) for key in ("start", "stop")]
    doubt = levels_doubt(written, path)
    return [] if doubt is None else [doubt]


def _doubts(checked, raw, base_dir):
    """The values likely not meant of a checked file: bodies, globs, levels."""
    entries = ([("bodies", checked.bodies)] if checked.sites is None else
               [(f"sites[{i}].bodies", s.bodies) for i, s in enumerate(checked.sites)])
    doubts = [doubt for where, bodies in entries for j, entry in enumerate(bodies)
              for doubt in body_doubts(entry, f"{where}[{j}]")]
    if checked.ensemble is not None:
        doubts += _glob_notes(raw["ensemble"]["motions"], base_dir)
        doubts += _levels_doubts(checked.ensemble.levels.pga, raw["ensemble"]["levels"]["pga"])
    return doubts


def load_survey(source):
    """Read and check a bodies file (or a dict of the same schema); every problem at once.

    Parameters
    ----------
    source : str, Path or dict
        Relative record paths are taken from the file's folder (a dict: the working
        directory).

    Returns
    -------
    Survey

    Raises
    ------
    FileProblems
        Unknown keys, missing or bad lengths, ``overturned`` not a boolean, levels that do not
        increase, records that cannot be read, ..., each with its dotted path
        (``sites[0].bodies[2].B``, ``ensemble.levels.pga.num``) and the value given.
    """
    checked = load_file(source, BodiesFile, "bodies file",
                        "sites (or site and bodies), ensemble", _FIELD_NAMES)
    warn(checked._warnings)
    if checked.sites is None:
        sites = (Site(name=checked.site, bodies=_bodies(checked.bodies)),)
    else:
        sites = tuple(Site(name=str(s.name), bodies=_bodies(s.bodies),
                           latitude=None if s.latitude is None else float(s.latitude),
                           longitude=None if s.longitude is None else float(s.longitude))
                      for s in checked.sites)
    return Survey(sites=sites, ensemble=None if checked.ensemble is None
                  else checked.ensemble.resolved(),
                  source=None if isinstance(source, dict) else Path(source),
                  one_site_format=checked.sites is None)


def load_bodies(source):
    """The site name and bodies of a one-site bodies file (``site`` + ``bodies``).

    Returns
    -------
    site : str or None
    bodies : tuple of Body

    Raises
    ------
    FileProblems
        As :func:`load_survey`.
    ValueError
        For a file of several sites (read it with :func:`load_survey`).
    """
    survey = load_survey(source)
    if len(survey.sites) != 1:
        raise ValueError(f"{source}: {len(survey.sites)} sites; read it with load_survey")
    return survey.sites[0].name, survey.sites[0].bodies
