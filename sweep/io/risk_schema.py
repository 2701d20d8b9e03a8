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
    # options: {as it stands: {}, ground floor: {excitation.horizontal: none}}   # or these

One pydantic model (:class:`RiskFile`), loaded by ``sweep.io.loader.load_file`` as scene,
study and bodies files are, checks it: its fields, then in one validator the choice of its
sections (stripes or a known fragility, and what stripes need) and the IM's dimensions; every
problem is reported at once with its dotted path (``hazard.source.sources[0].recurrence.m_max``)
and the value given.  What needs the hazard
itself (a curve file that cannot be read, stripes outside the curve) is checked by the same
model with a ``hazard`` function of its validation context (``sweep.probability.risk_inputs``
gives it: the layer above builds curves), which keeps the curve it built.  The hazard
section's models are in ``sweep.io.hazard_schema``.
"""
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any, Optional

from pydantic import (Field, PrivateAttr, StrictInt, StrictStr,
                      WithJsonSchema, field_validator, model_validator)

from .fields import Real, Seed, StrictModel, quantity
from .hazard_schema import (LEVELS_SCHEMA, SOURCE_KINDS, AreaSource, CurveFile, Hazard,
                            IMLevel, LevelList, LevelRange, PointSource, Positive, Recurrence,
                            SourceHazard, level_list)
from .imt import im_dimension
from .loader import load_file
from .problems import (MISSING, FieldError, FileProblems, dotted_path, fields_checked,
                       join_path)
from .records import NAMES as RECORD_NAMES
from .scene_schema import KINDS, load_scene
from .study_axes import no_conflicts
from .study_schema import grid_axis
from .vocabulary import targets

FLOOR_AXES = "excitation.horizontal.building."  # the motion a risk map's axis may set
MAX_MOTIONS = 10_000
STRIPES_GIVE = "the stripes give the ground motion"  # why a scene's own motion is refused


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
        return (LevelList.model_validate(level_list(value)) if isinstance(value, list)
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
    options: Optional[dict[StrictStr, dict[StrictStr, Any]]] = Field(
        None, description="named options side by side: each a mapping of dotted scene paths "
                          "(body.B, restraint, excitation.horizontal) to the values that "
                          "replace the scene's; every option under the same stripes")
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
    errors += _options_problems(raw)
    if _motion_axes(_section(raw, "scene")) and _mixed_records(stripes.get("records")):
        under = "a building's floor" if _motion_axes(_section(raw, "scene")) == (FLOOR_AXES,) \
            else "an isolator"
        errors.append(("stripes.records", stripes["records"], f"under {under}, give bundled "
                       "records or files, not both (the ground takes a name or a path)"))
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


def _scene_problems(scene, prefix="scene"):
    """``(path, value, message)`` of a risk file's raw ``scene``, checked as a scene file is
    (``scene.body.B``; ``prefix`` for an option's), with stripes or a known fragility.  The
    stripes give its motion: the horizontal one may only be a building's floor over it
    (``kind: floor`` without a ``ground``) or an isolated platform over it or over such a
    floor (``kind: isolated`` without ``under``, or with a floor's), the vertical one none;
    another motion is refused, not replaced."""
    if not isinstance(scene, dict):
        return []  # none given, or not a mapping: the field's problem
    errors, checked = [], scene
    excitation = scene.get("excitation")
    if isinstance(excitation, dict):
        kept = dict(excitation)
        vertical, horizontal = excitation.get("vertical"), excitation.get("horizontal")
        if _kind(vertical) in KINDS and _kind(vertical) != "none":
            errors.append((f"{prefix}.excitation.vertical.kind", _kind(vertical),
                           f"not supported in a risk file: {STRIPES_GIVE}, horizontal only"))
            kept.pop("vertical")
        path = f"{prefix}.excitation.horizontal"
        if _kind(horizontal) == "isolated":
            kept["horizontal"] = {**horizontal, "under": _open_ground(
                horizontal.get("under"), f"{path}.under", errors)}
        elif _kind(horizontal) == "floor":
            kept["horizontal"] = _open_ground(horizontal, path, errors)
        elif _kind(horizontal) in KINDS and _kind(horizontal) != "none":
            errors.append((f"{path}.kind", _kind(horizontal),
                           f"not supported in a risk file: {STRIPES_GIVE} (a building's "
                           "floor over it: kind floor)"))
            kept.pop("horizontal")
        checked = {**scene, "excitation": kept}
    try:
        load_scene(checked)
    except FileProblems as problems:
        errors += [tuple(p) for p in problems.with_prefix(prefix).problems]
    return errors


def _open_ground(motion, path, errors):
    """The raw ``motion`` at ``path`` that the stripes' motion goes in (a floor: its
    ``ground``; else, under an isolator, the motion itself), that place left empty for
    checking; a motion written there is appended to ``errors`` (it would be replaced)."""
    if _kind(motion) == "floor":
        if "ground" in motion:
            errors.append((f"{path}.ground", motion["ground"],
                           f"leave it out: {STRIPES_GIVE} under the building"))
        return {**motion, "ground": "none"}
    if _kind(motion) != "none":
        errors.append((path, motion, f"leave it out (or a building's floor: kind floor): "
                                     f"{STRIPES_GIVE} under the isolator"))
    return "none"


def option_scene(scene, overrides):
    """The raw ``scene`` with each dotted path of ``overrides`` replaced by its value (a
    mapping made where the path goes through none): one option's scene."""
    import copy

    option = copy.deepcopy(scene if isinstance(scene, dict) else {})
    for path, value in overrides.items():
        *above, last = str(path).split(".")
        place = option
        for key in above:
            if not isinstance(place.get(key), dict):
                place[key] = {}
            place = place[key]
        place[last] = copy.deepcopy(value)
    return option


def _options_problems(raw):
    """``(path, value, message)`` of a risk file's raw ``options``: given with stripes and
    without a grid, each option's scene checked as the scene is (``options.<name>.<path>``,
    its own problems only: the base scene's are said at ``scene``)."""
    options = raw.get("options") if isinstance(raw, dict) else None
    if options == {}:
        return [("options", options, "give at least one option")]
    if not isinstance(options, dict):
        return []  # none given, or the field's problem
    errors = []
    if raw.get("grid") is not None:
        errors.append(("options", "...", "give either a grid or options, not both (an "
                                         "option may set any axis of a grid)"))
    if raw.get("stripes") is None:
        errors.append(("options", "...", "needs stripes: each option is simulated"))
    scene = _section(raw, "scene")
    base = {path.removeprefix("scene") for path, *_ in _scene_problems(scene)}
    for name, overrides in options.items():
        if not isinstance(overrides, dict):
            continue  # the field's problem
        prefix = join_path("options", name)
        errors += [(path, value, message) for path, value, message in _scene_problems(
            option_scene(scene, overrides), prefix) if path.removeprefix(prefix) not in base]
    return errors


def _motion_axes(scene):
    """The prefixes of the axes that may set the raw ``scene``'s motion in a risk map: a
    floor's building, an isolator's keys and its floor's building."""
    horizontal = _section(scene, "excitation").get("horizontal")
    if _kind(horizontal) == "floor":
        return (FLOOR_AXES,)
    if _kind(horizontal) == "isolated":
        return ("excitation.horizontal.isolator.", "excitation.horizontal.under.building.")
    return ()


def _grid_problems(grid, scene):
    """``(path, value, message)`` of a risk map's raw ``grid``: each axis checked as a study's
    (``grid.<axis>``, against the raw ``scene``), and refused where it sets a motion, which the
    stripes give (a floor's building, an isolator and its floor's building excepted)."""
    if not isinstance(grid, dict):
        return []  # the field's problem
    allowed = _motion_axes(scene)
    errors = []
    for name, spec in ((n, s) for n, s in grid.items() if isinstance(n, str)):
        path = join_path("grid", name)
        motion = [t for t in targets(name) if t.startswith("excitation")
                  and not t.startswith(allowed)]
        if isinstance(spec, list) and any(isinstance(v, (list, dict)) for v in spec):
            errors.append((path, spec, "an axis takes one number or name per value, not a "
                           "vector: compare such values as named options (options: {G "
                           f"low: {{{name}: [...]}}, G high: {{{name}: [...]}}}}; "
                           "docs/options.md)"))
            continue
        if motion:
            errors.append((path, name, f"sets {motion[0]}: {STRIPES_GIVE}; a risk map varies "
                           "the body, its contact, its solver or, on a floor, its building "
                           f"({FLOOR_AXES}*), on an isolator, the isolator "
                           "(excitation.horizontal.isolator.*)"))
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
