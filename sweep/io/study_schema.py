"""Study files (docs/design.md section 5): a base scene, the axes to vary, zip groups, the output.

``load_study`` reads a YAML file (or takes a dict) and validates it as one model,
:class:`StudyFile`: its fields check the sections and keys (with ``RangeSpec`` and
``RefineSpec``), its model validator checks the axes against the base scene and each other,
the zip groups and the refined axis against the axes (``sweep.io.study_axes``), the size of the
grid and, when the caller gives a cell check (``sweep.runner.cell_checks``), every cell's scene.
All problems are reported at once, through the shared formatter, as
:class:`~sweep.io.problems.FileProblems` with dotted paths (``grid.amplitude.num``, ``zip[0]``,
``scene.body.B``, ``refine.tolerance``).  An optional ``refine: {axis, tolerance}`` asks for
the overturning boundary along one axis by bisection (``sweep.runner.refine``); an optional
``run: {backend}`` says where the cells run (``sweep.run --backend`` overrides it).
"""
import sys
from dataclasses import dataclass
from pathlib import Path

from typing import Annotated, Any, Optional

import numpy as np
import yaml
from pydantic import (AfterValidator, BeforeValidator, Field, PrivateAttr, WithJsonSchema,
                      model_validator)

from . import study_grid, units
from .loader import load_file
from .problems import MISSING, FieldError, fields_checked, join_path, warn
from .fields import StrictModel
from .study_axes import (AXIS_LIST, MAX_AXIS_VALUES, Refine, axis, axis_list, dims, distinct,
                         fits_scene, known_name, no_conflicts, number, record_glob, refine,
                         zip_entries, zip_group)
from .yamlio import read_text

SPACINGS = ("linear", "log")
BACKENDS = ("cpu", "cuda")  # where a study's cells run (docs/gpu.md)
OUTPUT_DIR = "results"  # default output: results/<name>.nc, relative to the working directory
# Largest grid accepted unless the caller lifts the limit (``sweep.run --max-cells``): two
# million cells take days of CPU at the typical 0.1-1 s a cell, and their merged arrays some
# hundreds of MB; a larger count is more likely a typo in ``num`` than a plan.
MAX_CELLS = 2_000_000
MAX_CELL_IDS = np.iinfo(np.int64).max  # cells are numbered by int64 ids, with or without a limit


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
    backend: str = None  # run.backend; None: not said (the CPU)

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


# --- sections ---------------------------------------------------------------------------------

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
    return number(value) and abs(value) <= sys.float_info.max  # NaN compares false


def _count(value):
    return isinstance(value, int) and not isinstance(value, bool) and \
        1 <= value <= MAX_AXIS_VALUES


def _non_empty(kind):
    return lambda value: isinstance(value, kind) and bool(value)


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
    values: Optional[Annotated[Any, AfterValidator(_rule(axis_list, AXIS_LIST)), WithJsonSchema(
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
                           for i, v in enumerate(self.values) if not number(v)]
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


class RunSpec(StrictModel):
    """``run: {backend}``: how the study's cells run, not what they compute, so not part of
    the inputs' fingerprint (a run may resume on the other backend; docs/gpu.md)."""

    backend: Optional[Annotated[Any, AfterValidator(_rule(
        lambda v: v in BACKENDS, f"must be one of: {', '.join(BACKENDS)}")), WithJsonSchema(
            {"enum": list(BACKENDS)})]] = Field(
        None, description="where the cells run: cpu, or cuda (an NVIDIA GPU per rank; "
                          "sweep.run --backend overrides it)")


def _mapping_of(what):
    """A validator for a section that must be a non-empty mapping."""
    return BeforeValidator(_rule(_non_empty(dict), f"required: {what}"))


def _refine_mapping(value):
    if not isinstance(value, dict):
        raise ValueError("must be a mapping {axis: <an axis of grid>, tolerance: <bracket "
                         "width>}")
    return value


def _run_mapping(value):
    if not isinstance(value, dict):
        raise ValueError("must be a mapping {backend: cpu or cuda}")
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
    """The sections of a study file (docs/design.md section 5); axes, zip groups and the refined
    axis are checked against each other and the scene by :func:`load_study`."""

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
    run: Optional[Annotated[RunSpec, BeforeValidator(_run_mapping)]] = Field(
        None, description="how the cells run (not what they compute)")
    output: Optional[Annotated[Any, AfterValidator(_file_path), WithJsonSchema(
        {"type": "string"})]] = Field(None, description="the netCDF dataset written")


    _study: Study = PrivateAttr(None)
    _warnings: tuple = PrivateAttr(())

    @model_validator(mode="wrap")
    @classmethod
    def _every_problem(cls, data, handler, info):
        """The sections checked by the fields, then, on what is well formed, the axes, zip
        groups, refined axis and size of the grid and the cells' scenes (``cells`` of the
        context): every problem raised at once, in that order.

        The context holds ``base_dir``, ``source`` and ``text`` of the file, the ``output``
        given by the caller (it replaces the file's), ``max_cells`` and ``cells``, a function
        ``cells(study, doubts=list)`` returning the problems of the cells' scenes.
        """
        context = {**_CONTEXT, **(info.context or {})}
        checked, errors = fields_checked(handler, data, _FIELD_NAMES)
        if context["output"] is not None:  # it replaces the file's
            errors = [e for e in errors if e.field != "output"]
        scene = data["scene"] if isinstance(data.get("scene"), dict) else {}
        grid = data["grid"] if isinstance(data.get("grid"), dict) else {}
        axes, notes = {}, []  # notes: what record globs leave out, warned of
        for name, spec in grid.items():
            found = _kept(errors, grid_axis, name, spec, scene, context["base_dir"], notes)
            if found is not None:
                axes[name] = found
        _kept(errors, no_conflicts, grid)
        groups = _zip(data.get("zip"), axes, list(grid), errors)
        refined = _refine(data.get("refine"), axes, groups, list(grid), errors)
        study = _study(data, scene, context, dims(axes, groups), refined)
        _kept(errors, distinct, study.dims, grid)
        sized = _kept(errors, _size, study, context["max_cells"])
        doubts = []
        if context["cells"] is not None and scene and sized:
            errors += [FieldError(*p) for p in context["cells"](study, doubts=doubts)]
        if errors:
            raise FieldError.every(errors)
        checked._study = study
        checked._warnings = tuple(notes + doubts) if context["cells"] is not None else ()
        return checked


_FIELD_NAMES = sorted(set(StudyFile.model_fields) | set(RangeSpec.model_fields)
                      | set(RefineSpec.model_fields) | set(RunSpec.model_fields))
_CONTEXT = {"base_dir": Path("."), "source": None, "text": "", "output": None,
            "max_cells": MAX_CELLS, "cells": None}  # the context of a StudyFile by default


def _kept(errors, check, *args):
    """``check(*args)``, or None with the :class:`FieldError` it raised put in ``errors``."""
    try:
        return check(*args)
    except FieldError as err:
        errors.append(err)
        return None


def _written(spec, path):
    """The raw values of an axis (unit strings for numbers of a ``unit``) and its unit: a list,
    or a mapping ``{start, stop, num, spacing, unit}`` or ``{values, unit}``."""
    if isinstance(spec, dict):
        checked, errors = fields_checked(RangeSpec.model_validate, spec, _FIELD_NAMES)
        if errors:
            raise FieldError.every([FieldError(join_path(path, e.field) if e.field else path,
                                               e.value, str(e)) for e in errors])
        unit = checked.unit
        return [f"{v!r} {unit}" if unit and number(v) else v for v in checked.raw_values()], unit
    if axis_list(spec):
        return list(spec), ""
    raise FieldError(path, spec, f"{AXIS_LIST}, or a mapping {{start, stop, num, spacing, "
                                 "unit}")


def grid_axis(name, spec, scene, base_dir, notes):
    """The :class:`Axis` of ``grid.<name>``; a record glob's notes are put in ``notes``."""
    path = join_path("grid", name)
    if name == "record" and isinstance(spec, dict) and "glob" in spec:
        spec, found = record_glob(spec, path, base_dir)
        notes += found
    known_name(name, path)
    fits_scene(name, path, scene)
    values, unit = _written(spec, path)
    return axis(name, values, unit, spec, path, scene)


def _zip(raw, axes, names, errors):
    """The zip groups ``[(dimension name, axis names)]`` that are well formed."""
    groups, used = [], {}  # used: axis name -> the path of its group
    for dim, group, path in _kept(errors, zip_entries, raw) or ():
        found = _kept(errors, zip_group, dim, group, path, axes, names, used)
        if found is not None:
            groups.append(found)
    return groups


def _refine(raw, axes, groups, names, errors):
    """The :class:`Refine` of ``refine``, or None (absent, or lacking its axis or tolerance:
    the fields say why; an unknown key beside them does not stop their check)."""
    if not isinstance(raw, dict) or not all(key in raw for key in RefineSpec.model_fields):
        return None
    return _kept(errors, refine, raw["axis"], raw["tolerance"], axes, groups, names)


def _study(data, scene, context, dims, refined):
    """The :class:`Study` of the file's sections that are well formed (defaults for the
    others)."""
    source = context["source"]
    name = data.get("name", Path(source).stem if source else "study")
    name = name if isinstance(name, str) and name.strip() else "study"
    out = context["output"] if context["output"] is not None else \
        data.get("output", f"{OUTPUT_DIR}/{name}.nc")
    if not isinstance(out, (str, Path)) or not str(out).strip():
        out = f"{OUTPUT_DIR}/{name}.nc"
    run = data.get("run")
    backend = run.get("backend") if isinstance(run, dict) else None
    return Study(name=name.strip(), title=str(data.get("title", name)).strip(), scene=scene,
                 dims=dims, output=Path(out), text=context["text"], source=source,
                 base_dir=context["base_dir"],
                 description=str(data.get("description", "")).strip(), refine=refined,
                 backend=backend if backend in BACKENDS else None)


def _size(study, max_cells):
    """Refuse a grid of more cells than ``max_cells`` (none for 0 or None) or than int64 cell
    ids can number; True otherwise."""
    n = study.n_cells
    if max_cells and n > max_cells:
        raise FieldError("grid", study_grid.shape_text(study),
                         f"{n} cells, more than the limit of {max_cells}; run with "
                         "--max-cells N to allow N cells (0: no limit)")
    if n > MAX_CELL_IDS:
        raise FieldError("grid", study_grid.shape_text(study),
                         f"{n} cells, more than int64 cell ids can number")
    return True


def load_study(source, *, text=None, output=None, max_cells=MAX_CELLS, cells=None):
    """Read and check a study; every problem is reported at once.

    Parameters
    ----------
    source : str, Path, dict or Study
        A YAML file, or a dict of the same schema (a Study is returned as is).
    text : str, optional
        The file's text, when already read (the path is then only its name and folder).
    output : str or Path, optional
        Overrides the study's ``output``.
    max_cells : int or None
        Refuse a grid of more cells (a problem at ``grid``); 0 or None: no limit.
    cells : callable, optional
        ``cells(study, doubts=list)``: the problems of the cells' scenes, the values likely
        not meant put in ``doubts`` (``sweep.runner.cell_checks.cell_problems``).  With it,
        those doubts and the files of a record glob's folders that it leaves out are warned
        of (``InputWarning``).

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
    if text is None:
        text = yaml.safe_dump(source, sort_keys=False) if isinstance(source, dict) else \
            read_text(source)
    checked = load_file(source, StudyFile, "study", "scene, grid", _FIELD_NAMES, text=text,
                        context={"text": text, "output": output, "max_cells": max_cells,
                                 "cells": cells})
    warn(checked._warnings)
    return checked._study
