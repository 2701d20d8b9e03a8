"""The hazard section of a risk file: a curve file or a source model, and IM levels.

The IM levels are those that curves and stripes share (docs/risk.md, "The risk file"); the
section is checked with the rest of the file by ``sweep.io.risk_schema.RiskFile``.
"""
from typing import Annotated, Any, Literal, Optional, Union

import numpy as np
from pydantic import AfterValidator, Field, StrictInt, StrictStr, WithJsonSchema, \
    field_validator, model_validator

from .fields import Real, StrictModel, quantity
from .imt import normalize_im
from .problems import MISSING, FieldError

GMPE_NAMES = ("BSSA14", "ASK14", "CB14", "CY14")  # sweep.probability.gmpe.MODELS
MECHANISMS = ("SS", "NS", "RS")
FORMATS = ("openquake", "usgs", "columns")
SOURCE_KINDS = ("point", "area")
MAX_LEVELS = 200

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


def level_list(value):
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
            level_list(value) if isinstance(value, list) else value)


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
