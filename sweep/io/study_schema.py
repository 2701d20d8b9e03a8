"""Study files (DESIGN.md section 5): a base scene, the axes to vary, zip groups, the output.

``load_study`` reads a YAML file (or takes a dict) and checks it in two layers: the pydantic
models ``StudyFile``, ``RangeSpec`` and ``RefineSpec`` check its sections and keys, then the
axes, zip groups and refined axis are checked against each other and the base scene, and,
unless told not to, every cell's scene.  All problems are reported at once, through the shared
formatter, as :class:`~sweep.io.problems.FileProblems` with dotted paths
(``grid.amplitude.num``, ``zip[0]``, ``scene.body.B``, ``refine.tolerance``).  A problem that a
cell's scene shows because of an axis value is reported once, at that value
(``grid.amplitude[3]``).  An optional ``refine: {axis, tolerance}`` asks for the overturning
boundary along one axis by bisection (``sweep.runner.refine``).  Coordinates are kept in SI
units, except for body-relative units (``west``, ``v_H``, ``alpha``), whose numbers are kept as
the normalized levels they are (CF units ``1``), and for an axis written wholly in degrees
(``deg``, ``deg/s``: :data:`AS_WRITTEN`), whose numbers are kept as written.  Values that are
valid but likely not what was meant (``sweep.io.plausibility``) are warned of once per axis.
"""
import re
import sys
from dataclasses import dataclass
from pathlib import Path

from typing import Annotated, Any, Optional

import numpy as np
import yaml
from pydantic import (AfterValidator, BeforeValidator, Field, ValidationError, WithJsonSchema,
                      model_validator)

from . import study_grid, units, vocabulary
from .files import find_files, named
from .plausibility import ReadsAsG, glob_notes, levels_read_in_si, scene_doubts
from .scene_schema import (Body, Contact, Initial, NoMotion, PulseMotion, RecordMotion,
                           SineMotion, Solver, SweepMotion, SyntheticMotion, load_scene,
                           resolve_scene)
from .problems import (MISSING, FieldError, FileProblems, Problem, closest, join_path,
                       validation_problems, warn)
from .scene_schema import StrictModel
from .yamlio import parse_yaml, read_text, top_level_problems

SPACINGS = ("linear", "log")
OUTPUT_DIR = "results"  # default output: results/<name>.nc, relative to the working directory
# Largest grid accepted unless the caller lifts the limit (``sweep.run --max-cells``): two
# million cells take days of CPU at the typical 0.1-1 s a cell, and their merged arrays some
# hundreds of MB; a larger count is more likely a typo in ``num`` than a plan.
MAX_CELLS = 2_000_000
MAX_CELL_IDS = np.iinfo(np.int64).max  # cells are numbered by int64 ids, with or without a limit
MAX_AXIS_VALUES = 1_000_000  # values of one axis: far finer than any figure, a bounded list
# Grids up to CHECK_ALL_CELLS cells have every cell's scene checked; larger ones, each value of
# every dimension (at most CHECKED_PER_DIM of them: both ends and a seeded sample) with the other
# dimensions at their first value, and SAMPLED_CELLS seeded random cells (see _checked_cells).
CHECK_ALL_CELLS = 10_000
CHECKED_PER_DIM = 1_000
SAMPLED_CELLS = 1_000

# CF units of coordinates, by dimension (udunits spelling)
CF_UNITS = {"acceleration": "m s-2", "velocity": "m s-1", "length": "m", "angle": "rad",
            "angular_velocity": "rad s-1", "frequency": "Hz", "time": "s",
            "dimensionless": "1", "name": "1"}
# Units whose numbers the coordinates keep when a whole axis is written in them (CF spelling):
# a legend reads 180 deg, not 3.14159
AS_WRITTEN = {"deg": "degree", "deg/s": "degree s-1"}
_INDEX = re.compile(r"\[\d+\]$")  # the index of an axis value in a path: grid.B[3]
RELATIVE_NAMES = {"west": "West's acceleration (B/H) g",
                  "v_h": "single-shock overturning velocity v_H (Eq. 9)",
                  "alpha": "slenderness angle alpha"}


@dataclass(frozen=True, eq=False)
class Axis:
    """One axis of a grid.

    Attributes
    ----------
    name : str
        As in the file: a name of ``grid.AXES`` or a dotted scene path.
    values : tuple
        Raw values set into each cell's scene (numbers, unit strings or names).
    coords : ndarray, shape (n,)
        Coordinates of the dataset: float64 in SI, in the body-relative unit or in the unit
        of :data:`AS_WRITTEN` written, int64 for ``seed``, or str.
    units, long_name : str
        CF attributes of the coordinate.
    unit : str
        The unit written in the study ('' for none).
    dimension : str
        Dimension of the values (``units.DIMENSIONS``), or "name".
    """

    name: str
    values: tuple
    coords: np.ndarray
    units: str
    long_name: str
    unit: str = ""
    dimension: str = "name"

    @property
    def body_relative(self):
        """True when the coordinates are levels of ``west``, ``v_H`` or ``alpha``."""
        return self.units == "1" and self.dimension not in ("name", "dimensionless")

    @property
    def written_coords(self):
        """True when the coordinates are numbers in ``unit`` (body-relative levels, degrees),
        not in SI."""
        return self.body_relative or self.units in AS_WRITTEN.values()

    def coordinate(self, quantity):
        """A :class:`~sweep.io.units.Quantity` of the axis's dimension in the units of its
        coordinates (a body-relative one: of the axis's unit)."""
        if self.body_relative:
            return quantity.value
        si = quantity.to_si()
        return si / units.fixed_factor(self.unit, self.dimension) if self.written_coords else si


@dataclass(frozen=True, eq=False)
class Dim:
    """A dimension of the grid: one axis, or the axes of a zip group varying together."""

    name: str
    axes: tuple

    @property
    def size(self):
        return len(self.axes[0].values)


@dataclass(frozen=True)
class Refine:
    """Bisection of the overturning boundary along one axis (``refine:``, ``runner.refine``).

    Attributes
    ----------
    axis : str
        The refined axis: a dimension of its own, numeric, with increasing values.
    tolerance : float
        Largest width of a final bracket, in the units of the axis's coordinates (SI, or the
        body-relative level).
    """

    axis: str
    tolerance: float


@dataclass(frozen=True, eq=False)
class Study:
    """A checked study; ``scene`` is the raw base scene dict, ``text`` the file's text."""

    name: str
    title: str
    scene: dict
    dims: tuple
    output: Path
    text: str
    source: str = None
    base_dir: Path = Path(".")
    description: str = ""
    refine: Refine = None

    @property
    def axes(self):
        """Every axis, in dimension order."""
        return tuple(axis for dim in self.dims for axis in dim.axes)

    @property
    def shape(self):
        return study_grid.shape(self)

    @property
    def n_cells(self):
        return study_grid.n_cells(self)

    @property
    def excitation(self):
        """The base scene's horizontal excitation (raw dict, may be empty)."""
        exc = (self.scene.get("excitation") or {}).get("horizontal")
        return exc if isinstance(exc, dict) else {}


# --- axes -------------------------------------------------------------------------------------

def _number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _rule(check, message):
    """A validator that keeps a value for which ``check(value)`` holds, else says ``message``."""
    def validate(value):
        if not check(value):
            raise ValueError(message)
        return value
    return validate


def _unit_name(unit):
    """A unit name as written (stripped), checked against every unit of ``units``."""
    if not isinstance(unit, str) or not unit.strip():
        raise ValueError("must be a unit name such as 'west', 'gal', 'Hz'")
    units.parse_quantity(f"1 {unit}", units.DIMENSIONS)  # ValueError names the unit
    return unit.strip()


def _finite(value):
    return _number(value) and abs(value) <= sys.float_info.max  # NaN compares false


def _count(value):
    return isinstance(value, int) and not isinstance(value, bool) and \
        1 <= value <= MAX_AXIS_VALUES


def _non_empty(kind):
    return lambda value: isinstance(value, kind) and bool(value)


def _axis_list(value):
    return isinstance(value, list) and 1 <= len(value) <= MAX_AXIS_VALUES


AXIS_LIST = f"must be a non-empty list of at most {MAX_AXIS_VALUES} values"


Bound = Annotated[Any, AfterValidator(_rule(_finite, "must be a finite number")),
                  WithJsonSchema({"type": "number"})]
AXIS_VALUE = {"type": ["number", "string"]}  # JSON Schema of one value of an axis


class RangeSpec(StrictModel):
    """An axis written as ``{start, stop, num, spacing, unit}`` or ``{values, unit}``."""

    start: Optional[Bound] = Field(None, description="first value, in unit")
    stop: Optional[Bound] = Field(None, description="last value, in unit")
    num: Optional[Annotated[Any, AfterValidator(_rule(
        _count, f"must be an integer >= 1, at most {MAX_AXIS_VALUES}")), WithJsonSchema(
            {"type": "integer", "minimum": 1, "maximum": MAX_AXIS_VALUES})]] = Field(
        None, description="number of values from start to stop")
    spacing: Optional[Annotated[Any, AfterValidator(_rule(
        lambda v: v in SPACINGS, f"must be one of: {', '.join(SPACINGS)}")), WithJsonSchema(
            {"enum": list(SPACINGS)})]] = Field(None, description="linear (default) or log")
    unit: Optional[Annotated[Any, AfterValidator(_unit_name), WithJsonSchema(
        {"type": "string"})]] = Field(None, description="unit of the numbers (a unit of the "
                                                        "axis's dimension)")
    values: Optional[Annotated[Any, AfterValidator(_rule(_axis_list, AXIS_LIST)), WithJsonSchema(
        {"type": "array", "minItems": 1, "maxItems": MAX_AXIS_VALUES, "items": AXIS_VALUE})]] = \
        Field(None, description="the values themselves, numbers in unit")

    @model_validator(mode="after")
    def _values_or_range(self):
        given = {key for key in self.model_fields_set if getattr(self, key) is not None}
        if self.values is not None:
            errors = [(key, getattr(self, key), "give either values or start/stop/num, not both")
                      for key in ("start", "stop", "num", "spacing") if key in given]
            if self.unit:
                errors += [(("values", i), v, f"must be a number (the unit is {self.unit!r})")
                           for i, v in enumerate(self.values) if not _number(v)]
        else:
            errors = [(key, MISSING, "required (or give values: [...])")
                      for key in ("start", "stop", "num") if key not in given]
            if self.spacing == "log":
                errors += [(key, getattr(self, key), "must be > 0 for log spacing")
                           for key in ("start", "stop")
                           if key in given and not getattr(self, key) > 0]
        if errors:
            raise FieldError.several(errors)
        return self

    def raw_values(self):
        """The values of the axis as written, before units: a list."""
        if self.values is not None:
            return list(self.values)
        make = np.geomspace if self.spacing == "log" else np.linspace
        return [float(x) for x in make(float(self.start), float(self.stop), self.num)]


class RefineSpec(StrictModel):
    """``refine: {axis, tolerance}``; what the axis and tolerance mean is checked against the
    grid (:func:`_refine`)."""

    axis: Annotated[Any, WithJsonSchema({"type": "string"})] = Field(
        description="the numeric axis of grid refined")
    tolerance: Annotated[Any, WithJsonSchema(AXIS_VALUE)] = Field(
        description="widest final bracket: a number in the axis's unit, or a quantity "
                    "('0.01 west')")


def _mapping_of(what):
    """A validator for a section that must be a non-empty mapping."""
    return BeforeValidator(_rule(_non_empty(dict), f"required: {what}"))


def _refine_mapping(value):
    if not isinstance(value, dict):
        raise ValueError("must be a mapping {axis: <an axis of grid>, tolerance: <bracket "
                         "width>}")
    return value


def _file_path(value):
    if not isinstance(value, (str, Path)) or not str(value).strip():
        raise ValueError("must be a file path such as results/x.nc")
    return value


NonEmptyText = Annotated[Any, AfterValidator(_rule(
    lambda v: isinstance(v, str) and bool(v.strip()), "must be a non-empty string")),
                         WithJsonSchema({"type": "string", "minLength": 1})]
Text = Annotated[Any, AfterValidator(_rule(lambda v: isinstance(v, str), "must be a string")),
                 WithJsonSchema({"type": "string"})]
AXIS_NAMES = {"type": "array", "minItems": 2, "items": {"type": "string"}}  # a zip group


class StudyFile(StrictModel):
    """The sections of a study file (DESIGN.md section 5); axes, zip groups and the refined axis
    are checked against each other and the scene by :func:`load_study`."""

    name: Optional[NonEmptyText] = Field(None, description="the study's name (default: the "
                                                          "file's); the output is named after it")
    title: Optional[Text] = Field(None, description="title of the dataset and its figures")
    description: Optional[Text] = Field(None, description="what the study is for, kept in the "
                                                          "dataset")
    scene: Annotated[dict, _mapping_of("a scene mapping (body, contact, excitation, ...)")] = \
        Field(description="the scene every cell starts from (a scene file's keys)")
    grid: Annotated[dict, _mapping_of("a mapping of axis names to values")] = Field(
        description="the axes: a name or dotted scene path -> a list of values or a range")
    zip: Optional[Annotated[Any, WithJsonSchema({"anyOf": [
        {"type": "array", "items": AXIS_NAMES},
        {"type": "object", "additionalProperties": AXIS_NAMES}]})]] = Field(
        None, description="axes that vary together: lists of axis names, or a dimension's "
                          "name -> its axes")
    refine: Optional[Annotated[RefineSpec, BeforeValidator(_refine_mapping)]] = Field(
        None, description="find the overturning boundary along one axis by bisection")
    output: Optional[Annotated[Any, AfterValidator(_file_path), WithJsonSchema(
        {"type": "string"})]] = Field(None, description="the netCDF dataset written")


_FIELD_NAMES = sorted(set(StudyFile.model_fields) | set(RangeSpec.model_fields)
                      | set(RefineSpec.model_fields))


def _spec_values(spec, path, problems):
    """Raw values and unit of a mapping ``{start, stop, num, spacing, unit}`` or ``{values}``."""
    try:
        checked = RangeSpec.model_validate(spec)
    except ValidationError as err:
        problems += [p._replace(path=join_path(path, p.path)) if p.path else p._replace(path=path)
                     for p in validation_problems(err, _FIELD_NAMES)]
        return None, None
    return checked.raw_values(), checked.unit


def _long_name(name, dimension, relative_unit):
    text = vocabulary.AXES[name][2] if name in vocabulary.AXES else name
    if dimension in ("velocity", "length") and "amplitude" in name:
        text = f"{text} ({'velocity' if dimension == 'velocity' else 'displacement'})"
    if relative_unit:
        text = f"{text} / {RELATIVE_NAMES[relative_unit]}"
    return text


def _axis(name, spec, path, scene, problems):
    """Check one axis of ``grid``; an :class:`Axis` or None (problems appended)."""
    if isinstance(spec, dict):
        raw, unit = _spec_values(spec, path, problems)
        if raw is None:
            return None
        values = [f"{v!r} {unit}" if unit and _number(v) else v for v in raw]
    elif _axis_list(spec):
        values, unit = list(spec), ""
    else:
        problems.append(Problem(path, spec, f"{AXIS_LIST}, or a mapping "
                                            "{start, stop, num, spacing, unit}"))
        return None
    before = len(problems)
    for i, v in enumerate(values):
        if not (_number(v) or isinstance(v, str)):
            problems.append(Problem(f"{path}[{i}]", v, "must be a number or a string"))
    if len(problems) > before:
        return None
    allowed = vocabulary.value_dimensions(name, scene)
    if allowed == ("name",) or (allowed is None and all(isinstance(v, str) for v in values)
                                and not any(_quantity_or_none(v) for v in values)):
        if unit:
            problems.append(Problem(join_path(path, "unit"), unit, "this axis takes names"))
        for i, v in enumerate(values):
            if not isinstance(v, str):
                problems.append(Problem(f"{path}[{i}]", v, "must be a name (a string)"))
        coords = np.array([str(v) for v in values])
        result = Axis(name, tuple(values), coords, "1", _long_name(name, "name", None), unit)
    else:
        result = _numeric_axis(name, values, unit, allowed, path, problems)
    if result is None or len(problems) > before:
        return None
    if name == "seed":
        result = _integer_axis(result, path, problems)
        if result is None:
            return None
    if name in vocabulary.COMPUTED and not np.all(result.coords > 0):
        problems.append(Problem(path, spec, "values must be positive numbers"))
    unique, counts = np.unique(result.coords, return_counts=True)
    if np.any(counts > 1):  # a coordinate must pick one cell
        problems.append(Problem(path, spec, f"values repeat: {unique[counts > 1][0].item()!r}"))
    return None if len(problems) > before else result


def _record_glob(spec, path, base_dir, problems, notes):
    """The files matching ``{glob: pattern}`` (relative to the study's folder; the extension in
    any case, ``files.find_files``), sorted, as a list of paths as they will be written in the
    cells' scenes; None after a problem.  The files of their folders it skips are put in
    ``notes``."""
    pattern = spec["glob"]
    if set(spec) != {"glob"} or not isinstance(pattern, str) or not pattern.strip():
        problems.append(Problem(path, spec, "a record glob is {glob: 'folder/*.AT2'} alone"))
        return None
    found, skipped = find_files(pattern, base_dir)
    if not found:
        held = f"; the folder holds {named(skipped)}" if skipped else ""
        problems.append(Problem(join_path(path, "glob"), pattern,
                                f"matches no file (relative to {Path(base_dir).resolve()})"
                                + held))
        return None
    notes += glob_notes(join_path(path, "glob"), pattern, found, skipped)
    if len(found) > MAX_AXIS_VALUES:
        problems.append(Problem(join_path(path, "glob"), pattern,
                                f"matches {len(found)} files, more than {MAX_AXIS_VALUES}"))
        return None
    return found


def _integer_axis(axis, path, problems):
    """A ``seed`` axis: whole numbers >= 0, kept as int64 coordinates."""
    coords = axis.coords
    if not np.all((coords >= 0) & (coords == np.round(coords)) & (coords < 2.0 ** 63)):
        bad = coords[~((coords >= 0) & (coords == np.round(coords)))][:1]
        problems.append(Problem(path, bad[0].item() if bad.size else coords[0].item(),
                                "seeds are whole numbers >= 0"))
        return None
    ints = coords.astype(np.int64)
    return Axis(axis.name, tuple(int(v) for v in ints), ints, "1", axis.long_name, "",
                axis.dimension)


def _quantity_or_none(value):
    try:
        return units.parse_quantity(value, units.DIMENSIONS)
    except ValueError:
        return None


def _numeric_axis(name, values, unit, allowed, path, problems):
    """An axis of numbers or quantities; coordinates in SI, or normalized for relative units.

    ``allowed``: dimensions the values may have (bare numbers take the first), or None for
    any (bare numbers dimensionless).
    """
    quantities = []
    for i, v in enumerate(values):
        try:
            q = units.parse_quantity(v, allowed or units.DIMENSIONS)
        except ValueError as err:
            problems.append(Problem(f"{path}[{i}]" if not unit else join_path(path, "unit"),
                                    v, str(err)))
            if unit:
                return None  # one unit for all: one problem
            continue
        if not q.unit:
            q = units.Quantity(q.value, "", allowed[0] if allowed else "dimensionless")
        quantities.append(q)
    if len(quantities) < len(values):
        return None
    dims = {q.dimension for q in quantities}
    relative = {q.unit for q in quantities if q.body_relative}
    if len(dims) > 1 or len(relative) > 1 or (relative and len({q.unit for q in quantities}) > 1):
        problems.append(Problem(path, values,
                                "mixes units of different kinds; give every value in one unit"))
        return None
    if name in vocabulary.COMPUTED and any(q.unit for q in quantities):
        problems.append(Problem(path, values, "takes plain numbers (a ratio), not units"))
        return None
    found = dims.pop()
    rel = relative.pop() if relative else None
    written = {q.unit for q in quantities}
    kept = rel or (written.pop() if len(written) == 1 and written <= set(AS_WRITTEN) else None)
    coords = np.array([q.value if kept else q.to_si() for q in quantities], dtype=np.float64)
    return Axis(name, tuple(values), coords, "1" if rel else AS_WRITTEN.get(kept, CF_UNITS[found]),
                _long_name(name, found, rel), unit or (kept or ""), found)


# Names people write for an axis, and the axis they mean ("did you mean"); keys lower case
SYNONYMS = {"height": "H", "breadth": "B", "width": "B", "size_factor": "size",
            "b/h": "b_over_h", "aspect_ratio": "b_over_h", "slenderness": "b_over_h",
            "friction": "mu", "records": "record", "seeds": "seed", "freq": "frequency",
            "scale_factor": "scale"}
_SECTIONS = {"body": Body, "contact": Contact, "initial": Initial, "solver": Solver}
MOTIONS = {"none": NoMotion, "sine": SineMotion, "sweep": SweepMotion, "record": RecordMotion,
           "pulse": PulseMotion, "synthetic": SyntheticMotion}


def _meant_axis(name):
    """The axis (or dotted scene path) an unknown axis name likely means, or None: the same
    name in other case (``PGA``, ``h``), a synonym (``height`` -> ``H``), a key of a scene
    section (``theta`` -> ``initial.theta``, ``magnitude`` ->
    ``excitation.horizontal.magnitude``), else the closest name or synonym (``hieght``)."""
    text = str(name)
    same = [axis for axis in vocabulary.AXES if axis.lower() == text.lower()]
    if len(same) == 1:
        return same[0]
    if text.lower() in SYNONYMS:
        return SYNONYMS[text.lower()]
    for section, model in _SECTIONS.items():
        if text in model.model_fields:
            return f"{section}.{text}"
    if any(text in model.model_fields for model in MOTIONS.values()) and text != "kind":
        return f"excitation.horizontal.{text}"
    close = closest(text, [*vocabulary.AXES, *SYNONYMS])
    return SYNONYMS.get(close, close)


def _axis_name_ok(name, path, problems):
    if name in vocabulary.AXES:
        return True
    if isinstance(name, str) and "." in name and name.split(".")[0] in vocabulary.SCENE_SECTIONS:
        return True
    close = _meant_axis(name)
    hint = f"did you mean '{close}'? " if close else ""
    problems.append(Problem(path, name, f"unknown axis; {hint}axes are "
                                        f"{', '.join(vocabulary.AXES)} or a dotted scene path "
                                        "such as excitation.horizontal.f_stop"))
    return False


def _instead(field, kind, component):
    """What to vary instead of ``field``, which a motion of ``kind`` lacks; or ''."""
    if field in ("name", "path"):
        return (f"a record axis needs scene.excitation.{component} of kind record "
                "(bundled names, paths or {glob: ...})")
    if field == "amplitude" and kind in ("record", "synthetic"):
        scale = "scale" if component == "horizontal" else "excitation.vertical.scale"
        return (f"scale it with an axis {scale} (a factor on its samples)" +
                (", pga or pgv (the peak it is scaled to)" if component == "horizontal" else
                 " or scale_with: horizontal"))
    if field in ("scale", "pga", "pgv") and kind in ("sine", "sweep", "pulse"):
        return "vary its amplitude instead (axis amplitude, e.g. {values: [0.1, 0.2], unit: g})"
    if field == "seed" and kind == "record":
        return "an ensemble of records is an axis record (names, paths or {glob: ...})"
    if field == "phase" and kind == "synthetic":
        return "its noise is drawn by seed (an axis seed)"
    if kind == "none":
        return f"give scene.excitation.{component} a kind"
    return ""


def _fits_scene(name, path, scene, problems):
    """False (a problem appended) when an axis sets a key that the base scene's motion does
    not have: an amplitude axis on a record (scale, pga or pgv scale it), a pga axis on a
    sine, a record axis on a sine.  A motion of unknown or missing kind is left to the scene
    check."""
    excitation = scene.get("excitation")
    for target in vocabulary.targets(name):
        section, component, field = (target.split(".") + ["", ""])[:3]
        if section != "excitation" or component not in ("horizontal", "vertical") or \
                not field or target.count(".") != 2 or not isinstance(excitation, dict):
            continue
        ground = excitation.get(component)
        kind = "none" if ground == "none" else ground.get("kind") if isinstance(ground, dict) \
            else None
        model = MOTIONS.get(kind) if isinstance(kind, str) else None
        if model is None or field in model.model_fields:
            continue
        instead = _instead(field, kind, component)
        takes = ", ".join(f for f in model.model_fields if f != "kind")
        problems.append(Problem(path, name, f"sets excitation.{component}.{field}, which a "
                                            f"{kind} motion does not have; "
                                            + (instead or f"it takes {takes or 'no key'}")))
        return False
    return True


def _conflicts(axes, problems):
    """Two axes setting the same scene field."""
    owner = {}
    for name in axes:
        paths = () if name == "mu" else vocabulary.targets(name)
        if name == "size":
            continue  # scales whatever B and H are
        for p in paths:
            if p in owner:
                problems.append(Problem(f"grid.{name}", name,
                                        f"sets {p}, which axis '{owner[p]}' sets too"))
            owner.setdefault(p, name)


def _zip(raw, axes, names, problems):
    """Dimensions from zip groups: [(dim name, [axis names])] and the names left alone."""
    if raw is None:
        return []
    if isinstance(raw, dict):
        groups = [(str(k), v, f"zip.{k}") for k, v in raw.items()]
    elif isinstance(raw, list):
        groups = [(None, v, f"zip[{i}]") for i, v in enumerate(raw)]
    else:
        problems.append(Problem("zip", raw, "must be a list of axis lists, or a mapping "
                                            "of a dimension name to an axis list"))
        return []
    out, used = [], {}
    for dim, group, path in groups:
        if not isinstance(group, list) or len(group) < 2 or \
                not all(isinstance(n, str) for n in group):
            problems.append(Problem(path, group, "must be a list of two or more axis names"))
            continue
        ok = True
        for n in group:
            if n not in names:
                problems.append(Problem(path, n, "not an axis of grid"))
                ok = False
            elif n not in axes:
                ok = False  # the axis's own problem is reported
            elif n in used:
                problems.append(Problem(path, n, f"already in the zip group {used[n]}"))
                ok = False
            used.setdefault(n, path)
        if not ok:
            continue
        lengths = {n: len(axes[n].values) for n in group}
        if len(set(lengths.values())) > 1:
            problems.append(Problem(path, group, "axes of a zip group must have equal lengths; "
                                    + ", ".join(f"{n}: {k}" for n, k in lengths.items())))
            continue
        if dim is not None and dim in names and dim not in group:
            problems.append(Problem(path, dim, "a zip dimension cannot take the name of "
                                               "another axis"))
            continue
        out.append((dim or group[0], group))
    return out


def _tolerance(value, axis, path, problems):
    """A refine tolerance in the units of ``axis``'s coordinates, or None (problem appended).

    A bare number is in the unit the axis is written in (its ``unit``), else in the units of
    its coordinates; a string carries its own unit (``5 gal``, ``0.01 west``).
    """
    if not (_number(value) or isinstance(value, str)):
        problems.append(Problem(path, value, "must be a positive number or a quantity "
                                             "such as '0.01 west' or '5 gal'"))
        return None
    raw = f"{value!r} {axis.unit}" if _number(value) and axis.unit else value
    try:
        quantity = units.parse_quantity(raw, axis.dimension)
    except ValueError as err:
        problems.append(Problem(path, value, str(err)))
        return None
    if quantity.body_relative != axis.body_relative:  # one relative unit per dimension
        problems.append(Problem(path, value, f"give it in the unit of grid.{axis.name} "
                                             f"({axis.unit or axis.units})"))
        return None
    tolerance = axis.coordinate(quantity)
    if not tolerance > 0:
        problems.append(Problem(path, value, "must be greater than 0"))
        return None
    return tolerance


def _refined_axis(name, axes, groups, names, problems):
    """The axis that ``refine.axis`` names, or None (problem appended)."""
    if not isinstance(name, str) or name not in names:
        problems.append(Problem("refine.axis", name, "not an axis of grid; axes: "
                                                     + ", ".join(map(str, names))))
        return None
    if any(name in group for _, group in groups):
        problems.append(Problem("refine.axis", name, "an axis of a zip group cannot be "
                                                     "refined alone"))
        return None
    if name not in axes:
        return None  # a malformed axis: its own problem is reported
    axis = axes[name]
    if axis.dimension == "name":
        problems.append(Problem("refine.axis", name, "takes names: refine a numeric axis"))
    elif axis.coords.size < 2:
        problems.append(Problem("refine.axis", name, f"grid.{name} needs at least two values "
                                                     "(the first bracket)"))
    elif not np.all(np.diff(axis.coords) > 0):
        problems.append(Problem("refine.axis", name, f"the values of grid.{name} must "
                                                     "increase (they are scanned upward)"))
    else:
        return axis
    return None


def _refine_spec(raw):
    """The axis and tolerance of ``refine`` as a :class:`RefineSpec`, or None when it is absent
    or lacks them (``StudyFile`` reports why; an unknown key beside them does not stop their
    check)."""
    if not isinstance(raw, dict) or not all(key in raw for key in RefineSpec.model_fields):
        return None
    return RefineSpec.model_validate({key: raw[key] for key in RefineSpec.model_fields})


def _refine(raw, axes, groups, names, problems):
    """The refined axis and tolerance of a well-formed ``refine`` (a :class:`RefineSpec`)
    checked against the grid: a :class:`Refine` or None (problems appended)."""
    before = len(problems)
    axis = _refined_axis(raw.axis, axes, groups, names, problems)
    tolerance = raw.tolerance
    if axis is not None:
        tolerance = _tolerance(tolerance, axis, "refine.tolerance", problems)
    elif not (_number(tolerance) or isinstance(tolerance, str)):
        problems.append(Problem("refine.tolerance", tolerance,
                                "must be a positive number or a quantity"))
    if len(problems) > before or axis is None:
        return None
    return Refine(axis.name, tolerance)


# --- cells ------------------------------------------------------------------------------------

def _blame(study, path):
    """The axis whose scene paths hold ``path``, or None."""
    for axis in study.axes:
        for target in vocabulary.targets(axis.name):
            if path == target or path.startswith(target + ".") or target.startswith(path + "."):
                return axis
    return None


def _checked_cells(study, seed=study_grid.DEFAULT_SEED):
    """The cells whose scenes :func:`cell_problems` checks, a bounded number.

    Every cell of a grid of up to ``CHECK_ALL_CELLS``.  Of a larger grid: every value of each
    dimension with the others at their first value, ``CHECKED_PER_DIM`` values at most (both
    ends and a seeded sample: each scene rule on a number is a range, and the values of an axis
    written as a range lie between its ends), then ``SAMPLED_CELLS`` seeded random cells.
    """
    n = study.n_cells
    if n <= CHECK_ALL_CELLS:
        return range(n)
    rng = np.random.default_rng(seed)
    cells, stride = [], n
    for size in study.shape:
        stride //= size
        picks = np.arange(size) if size <= CHECKED_PER_DIM else np.union1d(
            [0, size - 1], rng.choice(size, CHECKED_PER_DIM - 2, replace=False))
        cells += [int(p) * stride for p in picks]
    cells += study_grid.sample(n, SAMPLED_CELLS, seed).tolist()
    return list(dict.fromkeys(cells))


def _located(study, index, problem):
    """A problem of cell ``index``'s scene at the axis value that causes it
    (``grid.<axis>[i]``, with that value), else at ``scene.<path>``."""
    axis = _blame(study, problem.path)
    if axis is None:
        return Problem(f"scene.{problem.path}", problem.value, problem.message)
    dim_names = [d.name for d in study.dims]
    i = study_grid.positions(study, index)[dim_names.index(_dim_of(study, axis).name)]
    return Problem(f"grid.{axis.name}[{i}]", axis.values[i], problem.message)


def cell_problems(study, limit=50, doubts=None):
    """Problems of the cells' scenes, once per axis value (or once for the base scene).

    Each checked cell's scene (every cell of a small grid, a bounded choice of a large one:
    :func:`_checked_cells`) is checked, resolved and packed into a kernel row, as the run will.

    Parameters
    ----------
    study : Study
    limit : int
        Stop after this many problems.
    doubts : list, optional
        Filled with the values likely not meant (``sweep.io.plausibility``) of the scenes
        that are right, once per axis at its first such value (the message counts the
        others) or once for the base scene.

    Returns
    -------
    list of Problem
        Paths ``grid.<axis>[i]`` (the i-th value of an axis) or ``scene.<path>``.
    """
    found, seen = [], set()
    doubted = {}  # path without the value's index -> (its first doubt, paths of its values)
    for index in _checked_cells(study):
        try:
            scene = load_scene(study_grid.cell_scene(study, index), base_dir=study.base_dir)
            resolved = resolve_scene(scene)
        except FileProblems as err:
            for problem in (_located(study, index, p) for p in err.problems):
                key = (problem.path, repr(problem.value), problem.message)
                if key not in seen:
                    seen.add(key)
                    found.append(problem)
            if len(found) >= limit:
                break
            continue
        for doubt in scene_doubts(scene, resolved) if doubts is not None else ():
            axis = _blame(study, doubt.path)
            if axis is not None and axis.name in vocabulary.COMPUTED:
                continue  # a value computed in metres, not a bare number written
            if isinstance(doubt, ReadsAsG) and axis is not None and \
                    levels_read_in_si(axis.values):
                continue  # bare numbers of 2 and more: the axis is written in m/s^2
            doubt = _located(study, index, doubt)
            doubted.setdefault(_INDEX.sub("", doubt.path), (doubt, set()))[1].add(doubt.path)
    for path, (doubt, paths) in doubted.items():
        more = len(paths) - 1
        doubts.append(doubt if not more else doubt._replace(
            message=f"{doubt.message} (and {more} more value{'s' * (more > 1)} of {path})"))
    return found


def _dim_of(study, axis):
    return next(dim for dim in study.dims if any(a is axis for a in dim.axes))


def _dims(axes, groups):
    """Dimensions in the order of the grid; a zip group sits at the place of its first axis."""
    grouped = {n: dim for dim, names in groups for n in names}
    dims, placed = [], set()
    for axis_name, axis in axes.items():
        if axis_name not in grouped:
            dims.append(Dim(axis_name, (axis,)))
        elif grouped[axis_name] not in placed:
            placed.add(grouped[axis_name])
            names = next(ns for d, ns in groups if d == grouped[axis_name])
            dims.append(Dim(grouped[axis_name], tuple(axes[n] for n in names)))
    return tuple(dims)


# --- loading ----------------------------------------------------------------------------------

def _size_problems(study, max_cells):
    """The problem of a grid of more cells than ``max_cells`` (none for 0 or None) or than
    int64 cell ids can number."""
    n = study.n_cells
    if max_cells and n > max_cells:
        return [Problem("grid", study_grid.shape_text(study),
                        f"{n} cells, more than the limit of {max_cells}; run with "
                        "--max-cells N to allow N cells (0: no limit)")]
    if n > MAX_CELL_IDS:
        return [Problem("grid", study_grid.shape_text(study),
                        f"{n} cells, more than int64 cell ids can number")]
    return []


def load_study(source, *, text=None, output=None, check_cells=True, max_cells=MAX_CELLS):
    """Read and check a study; every problem is reported at once.

    Parameters
    ----------
    source : str, Path, dict or Study
        A YAML file, or a dict of the same schema (a Study is returned as is).
    text : str, optional
        The file's text, when already read (the path is then only its name and folder).
    output : str or Path, optional
        Overrides the study's ``output``.
    check_cells : bool
        Also check the cells' scenes (:func:`cell_problems`) and warn of the values likely
        not meant (``InputWarning``, once per axis) and of the files of a record glob's
        folders that it leaves out.
    max_cells : int or None
        Refuse a grid of more cells (a problem at ``grid``); 0 or None: no limit.

    Returns
    -------
    Study

    Raises
    ------
    FileProblems
        Unknown keys, axes and units, bad ranges, zip groups of unequal lengths, conflicting
        axes, a bad ``refine``, too many cells and every cell scene problem found, with dotted
        paths and the values given.
    """
    if isinstance(source, Study):
        return source
    if isinstance(source, dict):
        raw, problems, src = source, [], None
        text = yaml.safe_dump(source, sort_keys=False) if text is None else text
        base_dir = Path(".")
    else:
        src = str(source)
        text = read_text(source) if text is None else text
        raw, problems = parse_yaml(text)
        base_dir = Path(source).parent
    problems += top_level_problems(raw, problems, "study", "scene, grid")
    if problems:
        raise FileProblems(problems, src)

    try:
        StudyFile.model_validate(raw)
    except ValidationError as err:  # an output given by the caller replaces the file's
        problems += [p for p in validation_problems(err, _FIELD_NAMES)
                     if not (output is not None and p.path == "output")]
    # what is well formed is checked further, so that every problem shows at once
    name = raw.get("name", Path(src).stem if src else "study")
    name = name if isinstance(name, str) and name.strip() else "study"
    scene = raw.get("scene") if isinstance(raw.get("scene"), dict) else {}
    out = output if output is not None else raw.get("output", f"{OUTPUT_DIR}/{name}.nc")
    if not isinstance(out, (str, Path)) or not str(out).strip():
        out = f"{OUTPUT_DIR}/{name}.nc"

    axes, notes = {}, []  # notes: what record globs leave out, warned of
    spec = raw.get("grid")
    if isinstance(spec, dict) and spec:
        for axis_name, axis_spec in spec.items():
            path = join_path("grid", axis_name)
            if axis_name == "record" and isinstance(axis_spec, dict) and "glob" in axis_spec:
                axis_spec = _record_glob(axis_spec, path, base_dir, problems, notes)
                if axis_spec is None:
                    continue
            if _axis_name_ok(axis_name, path, problems) and \
                    _fits_scene(axis_name, path, scene, problems):
                axis = _axis(axis_name, axis_spec, path, scene, problems)
                if axis is not None:
                    axes[axis_name] = axis
        if "b_over_h" in spec and "H" in spec:
            problems.append(Problem("grid.b_over_h", spec["b_over_h"],
                                    "b_over_h keeps B and sets H = B/(b/h), so an H axis "
                                    "conflicts with it: vary B beside b_over_h, or size (a "
                                    "factor on B and H)"))
        else:
            _conflicts(list(spec), problems)
    groups = _zip(raw.get("zip"), axes, list(spec) if isinstance(spec, dict) else [],
                  problems)
    refine, refine_spec = None, _refine_spec(raw.get("refine"))
    if refine_spec is not None:
        refine = _refine(refine_spec, axes, groups,
                         list(spec) if isinstance(spec, dict) else [], problems)
    study = Study(name=name.strip(), title=str(raw.get("title", name)).strip(), scene=scene,
                  dims=_dims(axes, groups), output=Path(out), text=text, source=src,
                  base_dir=base_dir, description=str(raw.get("description", "")).strip(),
                  refine=refine)
    size = _size_problems(study, max_cells)
    problems += size
    doubts = []
    if check_cells and scene and not size:
        # with the axes that are well formed, so that every problem shows at once
        problems += cell_problems(study, doubts=doubts)
    if problems:
        raise FileProblems(problems, src)
    warn(notes + doubts if check_cells else [])
    return study
