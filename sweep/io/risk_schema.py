"""Risk files of ``python -m sweep.risk``: a hazard, a body, its stripes, period and target.

A site's hazard, a body (or a grid of bodies), the stripes of motions that give its fragility,
the period and the target (docs/risk.md)::

    name: risk_example
    hazard:
      source:                                  # or file: {path, format, im, units, ...}
        model: BSSA14
        im: pga
        vs30: 760 m/s
        levels: {start: 0.02 g, stop: 2 g, num: 30}
        sources:
          - {kind: point, distance: 15 km, depth: 8 km,
             recurrence: {rate: 0.05, m_min: 5.0, m_max: 7.5, b: 1.0}}
    scene: {body: {B: 20 cm, H: 80 cm}, contact: {mu: 0.8, e_x: -0.8, e_y: 0.2}}
    stripes: {levels: [1 m/s^2, 2 m/s^2, 4 m/s^2], motions: 10, seed: 0}
    years: 50
    target: 0.02
    grid: {H: [40 cm, 80 cm], b_over_h: [0.2, 0.3]}     # optional: a risk map

One pydantic model (:class:`RiskFile`), loaded by ``sweep.io.loader.load_file`` as scene,
study and bodies files are, checks it: its fields, then in one validator the choice of its
sections (stripes or a known fragility, and what stripes need) and the IM's dimensions; every
problem is reported at once with its dotted path (``hazard.source.sources[0].recurrence.m_max``)
and the value given.  What needs the hazard
itself (a curve file that cannot be read, stripes outside the curve) is checked by the same
model with a ``hazard`` function of its validation context (``sweep.probability.risk_inputs``
gives it: the layer above builds curves), which keeps the curve it built.
"""
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any, Literal, Optional, Union

import numpy as np
from pydantic import (AfterValidator, Field, PrivateAttr, StrictInt, StrictStr,
                      WithJsonSchema, field_validator, model_validator)

from .fields import Real, Seed, StrictModel, quantity
from .imt import im_dimension, normalize_im
from .loader import load_file
from .problems import (MISSING, FieldError, FileProblems, dotted_path, fields_checked,
                       join_path)
from .records import NAMES as RECORD_NAMES
from .scene_schema import KINDS, load_scene
from .study_axes import no_conflicts
from .study_schema import grid_axis
from .vocabulary import targets

GMPE_NAMES = ("BSSA14", "ASK14", "CB14", "CY14")  # sweep.probability.gmpe.MODELS
MECHANISMS = ("SS", "NS", "RS")
FORMATS = ("openquake", "usgs", "columns")
FLOOR_AXES = "excitation.horizontal.building."  # the motion a risk map's axis may set
SOURCE_KINDS = ("point", "area")
MAX_LEVELS = 200
MAX_MOTIONS = 10_000
STRIPES_GIVE = "the stripes give the ground motion"  # why a scene's own motion is refused

Positive = quantity("length", gt=0)
MAX_CRUSTAL_DEPTH = 80e3  # m: below the thickest crust, about 75 km (Mooney et al. 1998)


def _absolute(q):
    if q.body_relative:
        raise ValueError("must be in m/s^2, gal, g (or m/s, cm/s for pgv): IM levels are "
                         "shared by every body")
    return q


IMLevel = Annotated[quantity("acceleration", "velocity", gt=0), AfterValidator(_absolute)]


class LevelRange(StrictModel):
    """IM levels: ``{start, stop, num}`` (log-spaced) or a list."""

    start: IMLevel = Field(description="first level")
    stop: IMLevel = Field(description="last level")
    num: Annotated[StrictInt, Field(ge=2, le=MAX_LEVELS)] = Field(
        description="number of levels, log-spaced")

    @model_validator(mode="after")
    def _increasing(self):
        if self.start.dimension != self.stop.dimension:
            raise FieldError("stop", str(self.stop), "start and stop must have one dimension")
        if not self.stop.to_si() > self.start.to_si():
            raise FieldError("stop", str(self.stop), "must be greater than start")
        return self

    def si(self):
        return np.geomspace(self.start.to_si(), self.stop.to_si(), self.num)


_LEVEL_SCHEMA = {k: v for k, v in LevelRange.model_json_schema()["properties"]["start"].items()
                 if k not in ("title", "description")}
LEVELS_SCHEMA = {"anyOf": [LevelRange.model_json_schema(),  # a mapping, or a list
                           {"type": "array", "minItems": 2, "items": _LEVEL_SCHEMA}]}


def _level_list(value):
    return value if not isinstance(value, list) else {"values": value}


class LevelList(StrictModel):
    """IM levels written as a list, increasing."""

    values: Annotated[list[IMLevel], Field(min_length=2, max_length=MAX_LEVELS)] = Field(
        description="the levels, increasing")

    @model_validator(mode="after")
    def _increasing(self):
        si = [q.to_si() for q in self.values]
        errors = [(i + 1, str(self.values[i + 1]), "levels must increase")
                  for i in range(len(si) - 1) if not si[i + 1] > si[i]]
        if errors:
            raise FieldError.several(errors)
        return self

    def si(self):
        return np.array([q.to_si() for q in self.values])


Levels = Union[LevelList, LevelRange]


def _im(value):
    return normalize_im(value)


class Recurrence(StrictModel):
    """Truncated Gutenberg-Richter: ``rate`` of M >= ``m_min`` (or OpenQuake's ``a``), ``b``,
    ``m_max``; or ``characteristic: true``: ``rate`` of M = ``m_min``."""

    rate: Optional[Annotated[Real, Field(gt=0)]] = Field(
        None, description="annual rate of earthquakes of M >= m_min [1/yr]")
    a: Optional[Real] = Field(None, description="a-value, instead of rate, as OpenQuake's "
                                                "truncatedGutenbergRichterMFD aValue: the "
                                                "rate of m_min <= M <= m_max is "
                                                "10^(a - b m_min) - 10^(a - b m_max) "
                                                "(characteristic: 10^(a - b m_min))")
    b: Annotated[Real, Field(gt=0, le=3)] = Field(1.0, description="Gutenberg-Richter b-value")
    m_min: Annotated[Real, Field(ge=4.0, le=8.5)] = Field(description="smallest magnitude")
    m_max: Optional[Annotated[Real, Field(ge=4.0, le=8.5)]] = Field(
        None, description="largest magnitude")
    characteristic: bool = Field(False, description="every earthquake of magnitude m_min")

    @model_validator(mode="after")
    def _consistent(self):
        errors = []
        if (self.rate is None) == (self.a is None):
            errors.append(("rate", MISSING if self.rate is None else self.rate,
                           "give either rate (of M >= m_min) or a"))
        if self.characteristic:
            if self.m_max is not None:
                errors.append(("m_max", self.m_max, "a characteristic source has one "
                                                    "magnitude, m_min"))
        elif self.m_max is None:
            errors.append(("m_max", MISSING, "required (or characteristic: true)"))
        elif not self.m_max > self.m_min:
            errors.append(("m_max", self.m_max, "must be greater than m_min"))
        if errors:
            raise FieldError.several(errors)
        return self

    def si(self):
        """The law of the magnitudes (the rate is ``rate``, or that of ``a``)."""
        return {"m_min": float(self.m_min),
                "m_max": None if self.m_max is None else float(self.m_max),
                "b": float(self.b), "characteristic": self.characteristic}


def _crustal(q):
    if q.to_si() > MAX_CRUSTAL_DEPTH:
        raise ValueError(f"deeper than any crust ({MAX_CRUSTAL_DEPTH / 1e3:g} km): not a "
                         "crustal earthquake, which the ground-motion models are of")
    return q


Depth = Annotated[Positive, AfterValidator(_crustal)]


class PointSource(StrictModel):
    """A point at an epicentral ``distance`` from the site."""

    kind: Literal["point"] = Field(description="the kind of source")
    distance: quantity("length", ge=0) = Field(description="epicentral distance to the site")
    depth: Depth = Field(description="depth of the hypocentre (at most 80 km; warned "
                                     "beyond 20 km)")
    mechanism: Literal[MECHANISMS] = Field("SS", description="strike-slip, normal or reverse")
    recurrence: Recurrence = Field(description="how often it breaks, at which magnitudes")


class AreaSource(StrictModel):
    """A rectangle ``east: [x0, x1]``, ``north: [y0, y1]`` from the site (the site at 0, 0),
    epicentres uniform in it: integrated over distance to convergence, in steps no longer than
    ``spacing`` if given."""

    kind: Literal["area"] = Field(description="the kind of source")
    east: Annotated[list[quantity("length")], Field(min_length=2, max_length=2)] = Field(
        description="[west edge, east edge] from the site")
    north: Annotated[list[quantity("length")], Field(min_length=2, max_length=2)] = Field(
        description="[south edge, north edge] from the site")
    spacing: Optional[Positive] = Field(
        None, description="longest step of the integration over distance (default: none; "
                          "the steps are chosen to converge)")
    depth: Depth = Field(description="depth of the hypocentres (at most 80 km; warned beyond "
                                     "20 km)")
    mechanism: Literal[MECHANISMS] = Field("SS", description="strike-slip, normal or reverse")
    recurrence: Recurrence = Field(description="of the whole area")

    @model_validator(mode="after")
    def _ordered(self):
        errors = [(key, [str(q) for q in side], "must be [lower, upper], lower < upper")
                  for key, side in (("east", self.east), ("north", self.north))
                  if not side[1].to_si() > side[0].to_si()]
        if errors:
            raise FieldError.several(errors)
        return self


SourceEntry = Annotated[Union[PointSource, AreaSource], Field(discriminator="kind")]


class SourceHazard(StrictModel):
    """A source model computed in the package (``sweep.probability.source_hazard``)."""

    model: Literal[GMPE_NAMES] = Field("BSSA14", description="the ground-motion model")
    im: StrictStr = Field("pga", description="intensity measure: pga, pgv or sa(T)")
    vs30: quantity("velocity", gt=0) = Field(
        description="mean shear-wave velocity of the site's top 30 m")
    levels: Optional[Annotated[Any, WithJsonSchema(LEVELS_SCHEMA)]] = Field(
        None, description="IM levels of the curve: {start, stop, num} or a list (default: "
                          "40 from 0.005 to 3 g, or 0.5 to 300 cm/s)")
    sources: Annotated[list[SourceEntry], Field(min_length=1)] = Field(
        description="the earthquake sources")
    distance_bins: Optional[Annotated[list[quantity("length", ge=0)], Field(min_length=2)]] \
        = Field(None, description="Rrup bin edges of the disaggregation")
    truncation_level: Optional[Annotated[Real, Field(gt=0)]] = Field(
        None, description="the ground-motion model's epsilon truncated at +- this many "
                          "sigma, as OpenQuake's truncation_level (default: none, "
                          "untruncated)")

    @field_validator("im")
    @classmethod
    def _name(cls, value):
        return _im(value)

    @field_validator("levels")
    @classmethod
    def _levels(cls, value):
        if value is None:
            return None
        return (LevelList if isinstance(value, list) else LevelRange).model_validate(
            _level_list(value) if isinstance(value, list) else value)


class CurveFile(StrictModel):
    """A hazard curve file: OpenQuake CSV, USGS JSON or two columns."""

    path: StrictStr = Field(description="the file, relative to the risk file's folder")
    format: Literal[FORMATS] = Field(description="OpenQuake CSV, USGS JSON or two columns")
    im: Optional[StrictStr] = Field(None, description="intensity measure: pga, pgv or sa(T) "
                                                      "(default: the file's; must agree with "
                                                      "it)")
    units: Optional[StrictStr] = Field(None, description="unit of the IM levels (default: "
                                                         "the file's: a two-column file's "
                                                         "'# units: g' or a header such as "
                                                         "pga_g, OpenQuake's and the USGS's "
                                                         "g or cm/s; must agree with it)")
    kind: Optional[Literal["annual_rate", "poe"]] = Field(
        None, description="second column of a two-column file: annual rates, or "
                          "probabilities of exceedance in investigation_time (default: what "
                          "its header says, else annual_rate; must agree with it)")
    investigation_time: Optional[Annotated[Real, Field(gt=0)]] = Field(
        None, description="years of the probabilities (default: the file's, poe_50yr or "
                          "'# investigation_time: 50'; must agree with it)")
    site: Annotated[StrictInt, Field(ge=0)] = Field(
        0, description="row of an OpenQuake file of several sites")

    @field_validator("im")
    @classmethod
    def _name(cls, value):
        return None if value is None else _im(value)

    @model_validator(mode="after")
    def _columns(self):
        """What only a two-column file takes; what a file states itself is checked when it
        is read (``risk_inputs.read_curve``)."""
        if self.format == "columns":
            if self.kind == "annual_rate" and self.investigation_time is not None:
                raise FieldError("investigation_time", self.investigation_time,
                                 "only with kind: poe")
            return self
        errors = [(key, getattr(self, key), f"read from the {self.format} file itself")
                  for key in ("kind", "investigation_time") if getattr(self, key) is not None]
        if errors:
            raise FieldError.several(errors)
        return self


class Hazard(StrictModel):
    """``file:`` or ``source:``."""

    file: Optional[CurveFile] = Field(None, description="a hazard curve file")
    source: Optional[SourceHazard] = Field(None, description="a source model, its curve "
                                                             "computed here")

    @model_validator(mode="after")
    def _one(self):
        if (self.file is None) == (self.source is None):
            raise FieldError("file", MISSING, "give either file or source")
        return self


class Scenario(StrictModel):
    """One earthquake for every motion of the stripes (instead of the disaggregation)."""

    magnitude: Annotated[Real, Field(ge=4.0, le=8.5)] = Field(description="moment magnitude")
    distance: Positive = Field(description="distance to the rupture (Rrup)")


class Stripes(StrictModel):
    """Multiple stripes: ``motions`` synthetic motions at each IM level, or the ``records``
    of an ensemble (bundled names or files) scaled to each level."""

    levels: Annotated[Any, WithJsonSchema(LEVELS_SCHEMA)] = Field(
        description="IM levels of the stripes: {start, stop, num} or a list")
    motions: Annotated[StrictInt, Field(ge=2, le=MAX_MOTIONS)] = Field(
        10, description="synthetic motions per stripe")
    records: Optional[Annotated[list[StrictStr], Field(min_length=2, max_length=MAX_MOTIONS)]] \
        = Field(None, description="bundled records' names or files' paths, the motions of "
                                  "every stripe")
    seed: Seed = Field(0, description="seed of the first synthetic motion")
    scenario: Optional[Scenario] = Field(None, description="one earthquake for every motion "
                                                           "(default: the disaggregation)")
    vs30: Optional[quantity("velocity", gt=0)] = Field(
        None, description="of the synthetic motions (default: the source model's)")
    model: StrictStr = Field("boore2003", description="the stochastic ground-motion model")

    @field_validator("levels")
    @classmethod
    def _levels(cls, value):
        return (LevelList.model_validate(_level_list(value)) if isinstance(value, list)
                else LevelRange.model_validate(value))

    @model_validator(mode="after")
    def _records_or_synthetic(self):
        if self.records is not None:
            errors = [(key, str(getattr(self, key)), "synthetic motions only: the records are "
                                                     "the motions")
                      for key in ("scenario", "vs30") if getattr(self, key) is not None]
            if len(set(self.records)) < len(self.records):
                errors.append(("records", self.records, "a record is given twice"))
            if errors:
                raise FieldError.several(errors)
        return self


class Fragility(StrictModel):
    """A known lognormal fragility: ``median`` (an IM with units) and ``beta``."""

    median: IMLevel = Field(description="median, in the units of the hazard's IM")
    beta: Annotated[Real, Field(ge=0, le=3)] = Field(description="lognormal dispersion")


class RiskFile(StrictModel):
    """A risk file: a site's hazard, a body (or a grid of bodies), the stripes of motions
    that give its fragility (or a known fragility), the period and the target."""

    name: Optional[StrictStr] = Field(None, description="names the outputs (default: the "
                                                        "file's name)")
    title: Optional[StrictStr] = Field(None, description="one line for people")
    site: Optional[StrictStr] = Field(None, description="name of the site")
    hazard: Hazard = Field(description="the site's hazard: a curve file or a source model")
    scene: Optional[dict] = Field(None, description="the body simulated: a scene without "
                                                    "excitation, or on a building's floor "
                                                    "(kind floor without ground)")
    stripes: Optional[Stripes] = Field(None, description="the motions that give the "
                                                         "fragility")
    fragility: Optional[Fragility] = Field(None, description="a known lognormal fragility "
                                                             "instead of stripes")
    years: Annotated[Real, Field(gt=0, le=1e6)] = Field(50.0, description="period of the "
                                                                          "probability")
    target: Optional[Annotated[Real, Field(gt=0, lt=1)]] = Field(
        None, description="the largest acceptable probability of overturning in years")
    grid: Optional[dict[StrictStr, Any]] = Field(
        None, description="a risk map: axes of a study's grid that set the body, its contact "
                          "or its building (B, H, b_over_h, mu, body.B, contact.mu, "
                          "excitation.horizontal.building.period), each a list or a range")
    confidence: Annotated[Real, Field(gt=0, lt=1)] = Field(
        0.95, description="of the intervals")
    replicates: Annotated[StrictInt, Field(ge=0, le=100_000)] = Field(
        1000, description="bootstrap replicates of the fit")
    output: Optional[StrictStr] = Field(None, description="the netCDF dataset written")
    _curve: Any = PrivateAttr(None)

    @model_validator(mode="wrap")
    @classmethod
    def _every_problem(cls, data, handler, info):
        """The fields' problems, the choice of the sections (from the raw mapping, so that
        they show with the fields'), the dimensions of the levels against the hazard's IM,
        raised at once; then, with a ``hazard`` function in the context
        (``hazard(checked, base_dir) -> curve``, raising :class:`FieldError` for a curve that
        cannot be built or stripes outside it), the hazard curve, kept as ``_curve``."""
        checked, errors = fields_checked(handler, data, _FIELD_NAMES, dotted=_dotted,
                                         tags=SOURCE_KINDS)
        errors += [FieldError(*e) for e in _section_problems(data)]
        if checked is not None:
            errors += [FieldError(*e) for e in im_problems(checked)]
        if errors:
            raise FieldError.every(errors)
        context = info.context or {}
        if context.get("hazard") is not None:
            checked._curve = context["hazard"](checked, context.get("base_dir") or Path("."))
        return checked

    @property
    def im(self):
        return self.hazard.source.im if self.hazard.source is not None else self.hazard.file.im


def _section(raw, key):
    """The mapping ``raw[key]``, or an empty one (its own problems are the fields')."""
    value = raw.get(key) if isinstance(raw, dict) else None
    return value if isinstance(value, dict) else {}


def _section_problems(raw):
    """``(path, value, message)`` of the choice between stripes and a known fragility, of
    what stripes need (a scene; with a curve file, a scenario and vs30) and of the scene
    (:func:`_scene_problems`), from the raw mapping.
    """
    given = {key: isinstance(raw, dict) and raw.get(key) is not None
             for key in ("stripes", "fragility", "scene")}
    stripes = _section(raw, "stripes")
    errors = _scene_problems(raw.get("scene") if isinstance(raw, dict) else None)
    errors += _grid_problems(raw.get("grid") if isinstance(raw, dict) else None,
                             _section(raw, "scene"))
    if _kind(_section(_section(raw, "scene"), "excitation").get("horizontal")) == "floor" and \
            _mixed_records(stripes.get("records")):
        errors.append(("stripes.records", stripes["records"], "under a building's floor, give "
                       "bundled records or files, not both (the ground takes a name or a path)"))
    if not given["stripes"] and not given["fragility"]:
        errors.append(("stripes", MISSING, "required (or a known fragility)"))
    if given["stripes"] and given["fragility"]:
        errors.append(("fragility", "...", "give either stripes or fragility"))
    if given["stripes"]:
        if not given["scene"]:
            errors.append(("scene", MISSING, "required with stripes: the body simulated"))
        if _section(_section(raw, "hazard"), "file") and stripes.get("records") is None:
            if stripes.get("scenario") is None:
                errors.append(("stripes.scenario", MISSING,
                               "required with a hazard curve file (no disaggregation)"))
            if stripes.get("vs30") is None:
                errors.append(("stripes.vs30", MISSING, "required with a hazard curve file"))
    return errors


def _kind(component):
    """The kind of a raw excitation component: ``none`` for none or an empty entry."""
    if component is None or component == "none":
        return "none"
    return component.get("kind") if isinstance(component, dict) else None


def _mixed_records(records):
    """True when ``records`` (raw) holds both bundled records' names and files."""
    return isinstance(records, list) and len({isinstance(r, str) and r in RECORD_NAMES
                                              for r in records}) > 1


def _scene_problems(scene):
    """``(path, value, message)`` of a risk file's raw ``scene``, checked as a scene file is
    (``scene.body.B``), with stripes or a known fragility.  The stripes give its motion: the
    horizontal one may only be a building's floor over it (``kind: floor`` without a
    ``ground``), the vertical one none; another motion is refused, not replaced."""
    if not isinstance(scene, dict):
        return []  # none given, or not a mapping: the field's problem
    errors, checked = [], scene
    excitation = scene.get("excitation")
    if isinstance(excitation, dict):
        kept = dict(excitation)
        vertical, horizontal = excitation.get("vertical"), excitation.get("horizontal")
        if _kind(vertical) in KINDS and _kind(vertical) != "none":
            errors.append(("scene.excitation.vertical.kind", _kind(vertical),
                           f"not supported in a risk file: {STRIPES_GIVE}, horizontal only"))
            kept.pop("vertical")
        if _kind(horizontal) == "floor":
            if "ground" in horizontal:
                errors.append(("scene.excitation.horizontal.ground", horizontal["ground"],
                               f"leave it out: {STRIPES_GIVE} under the building"))
            kept["horizontal"] = {**horizontal, "ground": "none"}
        elif _kind(horizontal) in KINDS and _kind(horizontal) != "none":
            errors.append(("scene.excitation.horizontal.kind", _kind(horizontal),
                           f"not supported in a risk file: {STRIPES_GIVE} (a building's "
                           "floor over it: kind floor)"))
            kept.pop("horizontal")
        checked = {**scene, "excitation": kept}
    try:
        load_scene(checked)
    except FileProblems as problems:
        errors += [tuple(p) for p in problems.with_prefix("scene").problems]
    return errors


def _grid_problems(grid, scene):
    """``(path, value, message)`` of a risk map's raw ``grid``: each axis checked as a study's
    (``grid.<axis>``, against the raw ``scene``), and refused where it sets a motion, which the
    stripes give (a floor's building excepted)."""
    if not isinstance(grid, dict):
        return []  # the field's problem
    floor = _kind(_section(scene, "excitation").get("horizontal")) == "floor"
    errors = []
    for name, spec in ((n, s) for n, s in grid.items() if isinstance(n, str)):
        path = join_path("grid", name)
        motion = [t for t in targets(name) if t.startswith("excitation")
                  and not (floor and t.startswith(FLOOR_AXES))]
        if motion:
            errors.append((path, name, f"sets {motion[0]}: {STRIPES_GIVE}; a risk map varies "
                           "the body, its contact, its solver or, on a floor, its building "
                           f"({FLOOR_AXES}*)"))
            continue
        try:
            grid_axis(name, spec, scene, Path("."), [])
        except FieldError as err:
            errors += [(e.field, e.value, str(e)) for e in (err, *err.also)]
    if not errors:
        try:
            no_conflicts(grid)
        except FieldError as err:
            errors += [(e.field, e.value, str(e)) for e in (err, *err.also)]
    return errors


def _article(word):
    return "an" if word[0] in "aeiou" else "a"


def im_problems(checked, im=None):
    """``(path, value, message)`` of a fragility's median or stripe levels not of the
    dimension of the hazard's IM (``im``, else the file's: none when a curve file names it,
    checked again once it is read)."""
    im = im or checked.im
    if im is None:
        return []
    errors = []
    if checked.fragility is not None and checked.fragility.median.dimension != im_dimension(im):
        errors.append(("fragility.median", str(checked.fragility.median),
                       f"must be {_article(im_dimension(im))} {im_dimension(im)}, as {im}"))
    if checked.stripes is not None:
        levels = checked.stripes.levels
        levels = levels.values if isinstance(levels, LevelList) else [levels.start]
        if any(q.dimension != im_dimension(im) for q in levels):
            errors.append(("stripes.levels", str(levels[0]),
                           f"must be {im_dimension(im)}s, as {im}"))
    return errors


_MODELS = (RiskFile, Hazard, CurveFile, SourceHazard, PointSource, AreaSource, Recurrence,
           Stripes, Scenario, Fragility, LevelRange, LevelList)
_FIELD_NAMES = sorted({name for model in _MODELS for name in model.model_fields})


@dataclass(frozen=True)
class RiskSpec:
    """A checked risk file: the model, where it was read (relative paths from there) and its
    hazard curve (None when loaded without a ``hazard`` function)."""

    checked: RiskFile
    source: Path = None
    curve: Any = None

    @property
    def folder(self):
        return Path(".") if self.source is None else self.source.parent

    @property
    def name(self):
        if self.checked.name:
            return self.checked.name
        return "risk" if self.source is None else self.source.stem


def _union_tag(loc, i):
    """The tag of a source's kind (``sources[0].point``) or the ``values`` of levels written
    as a list."""
    if not i:
        return False
    key = loc[i]
    return (key in SOURCE_KINDS and isinstance(loc[i - 1], int)) or \
        (key == "values" and loc[i - 1] == "levels")


def _dotted(loc):
    """The dotted path of a pydantic location, without union tags."""
    return dotted_path(loc, _union_tag)


def load_risk(source, *, hazard=None):
    """Read and check a risk file (or a dict of its schema); every problem at once.

    Parameters
    ----------
    source : str, Path or dict
    hazard : callable, optional
        ``hazard(checked, base_dir)``: the file's hazard curve, raising ``FieldError``
        (``sweep.probability.risk_inputs.checked_hazard``); without it the curve is neither
        built nor checked.

    Returns
    -------
    RiskSpec

    Raises
    ------
    FileProblems
        With dotted paths and the values given.
    """
    checked = load_file(source, RiskFile, "risk file", "hazard, scene, stripes, years",
                        _FIELD_NAMES, context={"hazard": hazard})
    return RiskSpec(checked, None if isinstance(source, dict) else Path(source),
                    checked._curve)
