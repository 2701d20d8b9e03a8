"""Study files (DESIGN.md section 5): a base scene, the axes to vary, zip groups, the output.

``load_study`` reads a YAML file (or takes a dict), checks it and, unless told not to, every
cell's scene; all problems are reported at once as :class:`~sweep.io.problems.FileProblems` with
dotted paths (``grid.amplitude.num``, ``zip[0]``, ``scene.body.B``, ``refine.tolerance``).
A problem that a cell's scene shows because of an axis value is reported once, at that value
(``grid.amplitude[3]``).  An optional ``refine: {axis, tolerance}`` asks for the overturning
boundary along one axis by bisection (``sweep.runner.refine``).  Coordinates are kept in SI units,
except for body-relative units (``west``, ``v_H``, ``alpha``), whose numbers are kept as the
normalized levels they are (CF units ``1``).
"""
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import yaml

from kernels.api import scene_row

from ..runner import grid
from . import units
from .scene_schema import load_scene, resolve_scene
from .problems import MISSING, FileProblems, Problem, closest, join_path, unknown_key
from .yamlio import parse_yaml, read_text

KEYS = ("name", "title", "description", "scene", "grid", "zip", "refine", "output")
REFINE_KEYS = ("axis", "tolerance")
SPEC_KEYS = ("start", "stop", "num", "spacing", "unit", "values")
SPACINGS = ("linear", "log")
OUTPUT_DIR = "results"  # default output: results/<name>.nc, relative to the working directory

# CF units of coordinates, by dimension (udunits spelling)
CF_UNITS = {"acceleration": "m s-2", "velocity": "m s-1", "length": "m", "angle": "rad",
            "angular_velocity": "rad s-1", "frequency": "Hz", "time": "s",
            "dimensionless": "1", "name": "1"}
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
        Coordinates of the dataset: float64 in SI or in the body-relative unit, or str.
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
        return grid.shape(self)

    @property
    def n_cells(self):
        return grid.n_cells(self)

    @property
    def excitation(self):
        """The base scene's horizontal excitation (raw dict, may be empty)."""
        exc = (self.scene.get("excitation") or {}).get("horizontal")
        return exc if isinstance(exc, dict) else {}


# --- axes -------------------------------------------------------------------------------------

def _unknown_keys(mapping, allowed, path, problems):
    """A problem for every key of ``mapping`` that is not ``allowed``."""
    problems += [unknown_key(join_path(path, key), str(key), value, allowed)
                 for key, value in mapping.items() if key not in allowed]


def _number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _check_unit(unit, path, problems):
    """Parse a unit name: (Quantity of 1 unit) or None with a problem."""
    if not isinstance(unit, str) or not unit.strip():
        problems.append(Problem(path, unit, "must be a unit name such as 'west', 'gal', 'Hz'"))
        return None
    try:
        return units.parse_quantity(f"1 {unit}", units.DIMENSIONS)
    except ValueError as err:
        problems.append(Problem(path, unit, str(err)))
        return None


def _spec_values(spec, path, problems):
    """Raw values and unit of a mapping ``{start, stop, num, spacing, unit}`` or ``{values}``."""
    before = len(problems)
    _unknown_keys(spec, SPEC_KEYS, path, problems)
    unit = spec.get("unit")
    if unit is not None:
        unit = _check_unit(unit, join_path(path, "unit"), problems) and unit.strip()
    if "values" in spec:
        for key in ("start", "stop", "num", "spacing"):
            if key in spec:
                problems.append(Problem(join_path(path, key), spec[key],
                                        "give either values or start/stop/num, not both"))
        values = spec["values"]
        if not isinstance(values, list) or not values:
            problems.append(Problem(join_path(path, "values"), values,
                                    "must be a non-empty list"))
            return None, unit
        if unit:
            for i, v in enumerate(values):
                if not _number(v):
                    problems.append(Problem(f"{path}.values[{i}]", v,
                                            f"must be a number (the unit is {unit!r})"))
        return (None if len(problems) > before else list(values)), unit
    for key in ("start", "stop", "num"):
        if key not in spec:
            problems.append(Problem(join_path(path, key), MISSING,
                                    "required (or give values: [...])"))
    start, stop, num = spec.get("start"), spec.get("stop"), spec.get("num")
    spacing = spec.get("spacing", "linear")
    for key, value in (("start", start), ("stop", stop)):
        if key in spec and not (_number(value) and math.isfinite(value)):
            problems.append(Problem(join_path(path, key), value, "must be a finite number"))
    if "num" in spec and not (isinstance(num, int) and not isinstance(num, bool) and num >= 1):
        problems.append(Problem(join_path(path, "num"), num, "must be an integer >= 1"))
    if spacing not in SPACINGS:
        problems.append(Problem(join_path(path, "spacing"), spacing,
                                f"must be one of: {', '.join(SPACINGS)}"))
    elif spacing == "log":
        for key, value in (("start", start), ("stop", stop)):
            if _number(value) and not value > 0:
                problems.append(Problem(join_path(path, key), value,
                                        "must be > 0 for log spacing"))
    if len(problems) > before:
        return None, unit
    make = np.geomspace if spacing == "log" else np.linspace
    return [float(x) for x in make(float(start), float(stop), num)], unit


def _long_name(name, dimension, relative_unit):
    text = grid.AXES[name][2] if name in grid.AXES else name
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
    elif isinstance(spec, list) and spec:
        values, unit = list(spec), ""
    else:
        problems.append(Problem(path, spec, "must be a non-empty list of values or a mapping "
                                            "{start, stop, num, spacing, unit}"))
        return None
    before = len(problems)
    for i, v in enumerate(values):
        if not (_number(v) or isinstance(v, str)):
            problems.append(Problem(f"{path}[{i}]", v, "must be a number or a string"))
    if len(problems) > before:
        return None
    allowed = grid.value_dimensions(name, scene)
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
    if name in grid.COMPUTED and not np.all(result.coords > 0):
        problems.append(Problem(path, spec, "values must be positive numbers"))
    coords = result.coords.tolist()
    repeated = [c for i, c in enumerate(coords) if c in coords[:i]]
    if repeated:  # a coordinate must pick one cell
        problems.append(Problem(path, spec, f"values repeat: {repeated[0]!r}"))
    return None if len(problems) > before else result


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
    if name in grid.COMPUTED and any(q.unit for q in quantities):
        problems.append(Problem(path, values, "takes plain numbers (a ratio), not units"))
        return None
    found = dims.pop()
    rel = relative.pop() if relative else None
    coords = np.array([q.value if rel else q.to_si() for q in quantities], dtype=np.float64)
    return Axis(name, tuple(values), coords, "1" if rel else CF_UNITS[found],
                _long_name(name, found, rel), unit or (rel or ""), found)


def _axis_name_ok(name, path, problems):
    if name in grid.AXES:
        return True
    if isinstance(name, str) and "." in name and name.split(".")[0] in grid.SCENE_SECTIONS:
        return True
    close = closest(name, grid.AXES)
    hint = f"did you mean '{close}'? " if close else ""
    problems.append(Problem(path, name, f"unknown axis; {hint}axes are "
                                        f"{', '.join(grid.AXES)} or a dotted scene path "
                                        "such as excitation.horizontal.f_stop"))
    return False


def _conflicts(axes, problems):
    """Two axes setting the same scene field."""
    owner = {}
    for name in axes:
        paths = () if name == "mu" else grid.targets(name)
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
    tolerance = quantity.value if axis.body_relative else quantity.to_si()
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


def _refine(raw, axes, groups, names, problems):
    """Check ``refine: {axis, tolerance}``; a :class:`Refine` or None (problems appended)."""
    if not isinstance(raw, dict):
        problems.append(Problem("refine", raw, "must be a mapping {axis: <an axis of grid>, "
                                               "tolerance: <bracket width>}"))
        return None
    before = len(problems)
    _unknown_keys(raw, REFINE_KEYS, "refine", problems)
    for key in REFINE_KEYS:
        if key not in raw:
            problems.append(Problem(join_path("refine", key), MISSING, "required"))
    axis = _refined_axis(raw["axis"], axes, groups, names, problems) if "axis" in raw else None
    tolerance = raw.get("tolerance")
    if axis is not None and "tolerance" in raw:
        tolerance = _tolerance(tolerance, axis, "refine.tolerance", problems)
    elif "tolerance" in raw and not (_number(tolerance) or isinstance(tolerance, str)):
        problems.append(Problem("refine.tolerance", tolerance,
                                "must be a positive number or a quantity"))
    if len(problems) > before or axis is None:
        return None
    return Refine(axis.name, tolerance)


# --- cells ------------------------------------------------------------------------------------

def _blame(study, path):
    """The axis whose scene paths hold ``path``, or None."""
    for axis in study.axes:
        for target in grid.targets(axis.name):
            if path == target or path.startswith(target + ".") or target.startswith(path + "."):
                return axis
    return None


def cell_problems(study, limit=50):
    """Problems of every cell's scene, once per axis value (or once for the base scene).

    Each cell's scene is checked, resolved and packed into a kernel row, as the run will.

    Returns
    -------
    list of Problem
        Paths ``grid.<axis>[i]`` (the i-th value of an axis) or ``scene.<path>``.
    """
    found, seen = [], set()
    dim_names = [d.name for d in study.dims]
    for index in range(study.n_cells):
        try:
            raw = grid.cell_scene(study, index)
            resolved = resolve_scene(load_scene(raw, base_dir=study.base_dir))
            scene_row(resolved, [])
            continue
        except FileProblems as err:
            cell = err.problems
        except (ValueError, KeyError, TypeError) as err:  # kernel packing: `path` in backticks
            text = str(err)
            path = text.split("`")[1] if text.count("`") >= 2 else "(scene)"
            cell = [Problem(path, MISSING, text.replace("`", ""))]
        pos = grid.positions(study, index)
        for p in cell:
            axis = _blame(study, p.path)
            if axis is None:
                problem = Problem(f"scene.{p.path}", p.value, p.message)
            else:
                i = pos[dim_names.index(_dim_of(study, axis).name)]
                problem = Problem(f"grid.{axis.name}[{i}]", axis.values[i], p.message)
            key = (problem.path, repr(problem.value), problem.message)
            if key not in seen:
                seen.add(key)
                found.append(problem)
        if len(found) >= limit:
            break
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

def load_study(source, *, text=None, output=None, check_cells=True):
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
        Also check every cell's scene (:func:`cell_problems`).

    Returns
    -------
    Study

    Raises
    ------
    FileProblems
        Unknown keys, axes and units, bad ranges, zip groups of unequal lengths, conflicting
        axes, a bad ``refine`` and every cell scene problem, with dotted paths and the values
        given.
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
    if raw is None and not problems:
        problems.append(Problem("(file)", MISSING, "the study is empty"))
    elif raw is not None and not isinstance(raw, dict):
        problems.append(Problem("(file)", raw, "a study must be a mapping of scene, grid, ..."))
    if problems or raw is None or not isinstance(raw, dict):
        raise FileProblems(problems, src)

    _unknown_keys(raw, KEYS, "", problems)
    name = raw.get("name", Path(src).stem if src else "study")
    if not isinstance(name, str) or not name.strip():
        problems.append(Problem("name", name, "must be a non-empty string"))
        name = "study"
    for key in ("title", "description"):
        if key in raw and not isinstance(raw[key], str):
            problems.append(Problem(key, raw[key], "must be a string"))
    scene = raw.get("scene")
    if not isinstance(scene, dict) or not scene:
        problems.append(Problem("scene", MISSING if scene is None else scene,
                                "required: a scene mapping (body, contact, excitation, ...)"))
        scene = {}
    out = output if output is not None else raw.get("output", f"{OUTPUT_DIR}/{name}.nc")
    if not isinstance(out, (str, Path)) or not str(out).strip():
        problems.append(Problem("output", out, "must be a file path such as results/x.nc"))
        out = f"{OUTPUT_DIR}/{name}.nc"

    axes = {}
    spec = raw.get("grid")
    if not isinstance(spec, dict) or not spec:
        problems.append(Problem("grid", MISSING if spec is None else spec,
                                "required: a mapping of axis names to values"))
    else:
        for axis_name, axis_spec in spec.items():
            path = join_path("grid", axis_name)
            if _axis_name_ok(axis_name, path, problems):
                axis = _axis(axis_name, axis_spec, path, scene, problems)
                if axis is not None:
                    axes[axis_name] = axis
        if "b_over_h" in spec and "H" in spec:
            problems.append(Problem("grid.b_over_h", spec["b_over_h"],
                                    "b_over_h sets H from B: it cannot go with an H axis"))
        else:
            _conflicts(list(spec), problems)
    groups = _zip(raw.get("zip"), axes, list(spec) if isinstance(spec, dict) else [],
                  problems)
    refine = None
    if "refine" in raw:
        refine = _refine(raw["refine"], axes, groups,
                         list(spec) if isinstance(spec, dict) else [], problems)
    study = Study(name=name.strip(), title=str(raw.get("title", name)).strip(), scene=scene,
                  dims=_dims(axes, groups), output=Path(out), text=text, source=src,
                  base_dir=base_dir, description=str(raw.get("description", "")).strip(),
                  refine=refine)
    if check_cells and scene:
        # with the axes that are well formed, so that every problem shows at once
        problems += cell_problems(study)
    if problems:
        raise FileProblems(problems, src)
    return study
