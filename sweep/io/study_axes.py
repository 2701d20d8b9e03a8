"""The axes of a study, checked against the base scene and each other.

The validators of ``StudyFile`` (``sweep.io.study_schema``).

Each check returns what it builds (an :class:`Axis`, the zip groups, a :class:`Refine`) or
raises :class:`~sweep.io.problems.FieldError` s whose ``field`` is the dotted path of the
problem (``grid.amplitude[3]``, ``zip[0]``, ``refine.axis``); the model validator runs each on
what is well formed and reports them all at once.  Coordinates are kept in SI units, except
for body-relative units (``west``, ``v_H``, ``alpha``), whose numbers are kept as the
normalized levels they are (CF units ``1``), and for an axis written wholly in degrees
(``deg``, ``deg/s``: :data:`AS_WRITTEN`), whose numbers are kept as written.
"""
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import units, vocabulary
from .files import find_files, named
from .plausibility import glob_notes
from .problems import FieldError, closest, join_path
from .scene_schema import (Body, Contact, Initial, NoMotion, PulseMotion, RecordMotion,
                           Restraint, SineMotion, Solver, SweepMotion, SyntheticMotion)

MAX_AXIS_VALUES = 1_000_000  # values of one axis: far finer than any figure, a bounded list
AXIS_LIST = f"must be a non-empty list of at most {MAX_AXIS_VALUES} values"
# CF units of coordinates, by dimension (udunits spelling)
CF_UNITS = {"acceleration": "m s-2", "velocity": "m s-1", "length": "m", "angle": "rad",
            "angular_velocity": "rad s-1", "frequency": "Hz", "time": "s",
            "mass": "kg", "force": "N", "dimensionless": "1", "name": "1"}
# Units whose numbers the coordinates keep when a whole axis is written in them (CF spelling):
# a legend reads 180 deg, not 3.14159
AS_WRITTEN = {"deg": "degree", "deg/s": "degree s-1"}
RELATIVE_NAMES = {"west": "West's acceleration (B/H) g",
                  "v_h": "single-shock overturning velocity v_H (Eq. 9)",
                  "alpha": "slenderness angle alpha"}
# Names people write for an axis, and the axis they mean ("did you mean"); keys lower case
SYNONYMS = {"height": "H", "breadth": "B", "width": "B", "size_factor": "size",
            "b/h": "b_over_h", "aspect_ratio": "b_over_h", "slenderness": "b_over_h",
            "friction": "mu", "records": "record", "seeds": "seed", "freq": "frequency",
            "scale_factor": "scale"}
_SECTIONS = {"body": Body, "contact": Contact, "initial": Initial, "solver": Solver,
             "restraint": Restraint}
MOTIONS = {"none": NoMotion, "sine": SineMotion, "sweep": SweepMotion, "record": RecordMotion,
           "pulse": PulseMotion, "synthetic": SyntheticMotion}


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


def number(value):
    """True for an int or float that is not a bool."""
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def axis_list(value):
    """True for a list that can be an axis's values."""
    return isinstance(value, list) and 1 <= len(value) <= MAX_AXIS_VALUES


def _raise(errors):
    if errors:
        raise FieldError.every(errors)


# --- one axis ---------------------------------------------------------------------------------

def _long_name(name, dimension, relative_unit):
    text = vocabulary.AXES[name][2] if name in vocabulary.AXES else name
    if dimension in ("velocity", "length") and "amplitude" in name:
        text = f"{text} ({'velocity' if dimension == 'velocity' else 'displacement'})"
    if relative_unit:
        text = f"{text} / {RELATIVE_NAMES[relative_unit]}"
    return text


def axis(name, values, unit, spec, path, scene):
    """The :class:`Axis` of ``values`` (raw, in ``unit`` when given) written as ``spec`` at
    ``path``, of the dimensions its scene paths take in ``scene``."""
    _raise([FieldError(f"{path}[{i}]", v, "must be a number or a string")
            for i, v in enumerate(values) if not (number(v) or isinstance(v, str))])
    allowed = vocabulary.value_dimensions(name, scene)
    if allowed == ("name",) or (allowed is None and all(isinstance(v, str) for v in values)
                                and not any(_quantity_or_none(v) for v in values)):
        errors = [FieldError(join_path(path, "unit"), unit, "this axis takes names")] if unit \
            else []
        errors += [FieldError(f"{path}[{i}]", v, "must be a name (a string)")
                   for i, v in enumerate(values) if not isinstance(v, str)]
        _raise(errors)
        coords = np.array([str(v) for v in values])
        result = Axis(name, tuple(values), coords, "1", _long_name(name, "name", None), unit)
    else:
        result = _numeric_axis(name, values, unit, allowed, path)
    if name == "seed":
        result = _integer_axis(result, path)
    if name in vocabulary.COMPUTED and not np.all(result.coords > 0):
        raise FieldError(path, spec, "values must be positive numbers")
    return result


def _integer_axis(axis, path):
    """A ``seed`` axis: whole numbers >= 0, kept as int64 coordinates."""
    coords = axis.coords
    if not np.all((coords >= 0) & (coords == np.round(coords)) & (coords < 2.0 ** 63)):
        bad = coords[~((coords >= 0) & (coords == np.round(coords)))][:1]
        raise FieldError(path, bad[0].item() if bad.size else coords[0].item(),
                         "seeds are whole numbers >= 0")
    ints = coords.astype(np.int64)
    return Axis(axis.name, tuple(int(v) for v in ints), ints, "1", axis.long_name, "",
                axis.dimension)


def _quantity_or_none(value):
    try:
        return units.parse_quantity(value, units.DIMENSIONS)
    except ValueError:
        return None


def _numeric_axis(name, values, unit, allowed, path):
    """An axis of numbers or quantities; coordinates in SI, or normalized for relative units.

    ``allowed``: dimensions the values may have (bare numbers take the first), or None for
    any (bare numbers dimensionless).
    """
    quantities, errors = [], []
    for i, v in enumerate(values):
        try:
            q = units.parse_quantity(v, allowed or units.DIMENSIONS)
        except ValueError as err:
            if unit:  # one unit for all: one problem
                raise FieldError(join_path(path, "unit"), v, str(err)) from None
            errors.append(FieldError(f"{path}[{i}]", v, str(err)))
            continue
        if not q.unit:
            q = units.Quantity(q.value, "", allowed[0] if allowed else "dimensionless")
        quantities.append(q)
    _raise(errors)
    dims = {q.dimension for q in quantities}
    relative = {q.unit for q in quantities if q.body_relative}
    if len(dims) > 1 or len(relative) > 1 or (relative and len({q.unit for q in quantities}) > 1):
        raise FieldError(path, values, "mixes units of different kinds; give every value in "
                                       "one unit")
    if name in vocabulary.COMPUTED and any(q.unit for q in quantities):
        raise FieldError(path, values, "takes plain numbers (a ratio), not units")
    found = dims.pop()
    rel = relative.pop() if relative else None
    written = {q.unit for q in quantities}
    kept = rel or (written.pop() if len(written) == 1 and written <= set(AS_WRITTEN) else None)
    coords = np.array([q.value if kept else q.to_si() for q in quantities], dtype=np.float64)
    return Axis(name, tuple(values), coords, "1" if rel else AS_WRITTEN.get(kept, CF_UNITS[found]),
                _long_name(name, found, rel), unit or (kept or ""), found)


def record_glob(spec, path, base_dir):
    """The files matching ``{glob: pattern}`` (relative to the study's folder; the extension in
    any case, ``files.find_files``), sorted, as a list of paths as they will be written in the
    cells' scenes, and the notes of the files of their folders it skips."""
    pattern = spec["glob"]
    if set(spec) != {"glob"} or not isinstance(pattern, str) or not pattern.strip():
        raise FieldError(path, spec, "a record glob is {glob: 'folder/*.AT2'} alone")
    found, skipped = find_files(pattern, base_dir)
    if not found:
        held = f"; the folder holds {named(skipped)}" if skipped else ""
        raise FieldError(join_path(path, "glob"), pattern,
                         f"matches no file (relative to {Path(base_dir).resolve()})" + held)
    notes = glob_notes(join_path(path, "glob"), pattern, found, skipped)
    if len(found) > MAX_AXIS_VALUES:
        raise FieldError(join_path(path, "glob"), pattern,
                         f"matches {len(found)} files, more than {MAX_AXIS_VALUES}")
    return found, notes


# --- axis names -------------------------------------------------------------------------------

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


def known_name(name, path):
    """Refuse an axis name that is neither of ``vocabulary.AXES`` nor a dotted scene path."""
    if name in vocabulary.AXES or (isinstance(name, str) and "." in name and
                                   name.split(".")[0] in vocabulary.SCENE_SECTIONS):
        return
    close = _meant_axis(name)
    hint = f"did you mean '{close}'? " if close else ""
    raise FieldError(path, name, f"unknown axis; {hint}axes are "
                                 f"{', '.join(vocabulary.AXES)} or a dotted scene path "
                                 "such as excitation.horizontal.f_stop")


def _instead(field, kind, component):
    """What to vary instead of ``field``, which a motion of ``kind`` lacks; or ''."""
    if field in ("name", "path"):
        return (f"a record axis needs scene.excitation.{component} of kind record "
                "(bundled names, paths or {glob: ...})")
    if field == "amplitude" and kind in ("record", "synthetic"):
        scale = "scale" if component == "horizontal" else "excitation.vertical.scale"
        return (f"scale it with an axis {scale} (a factor on its samples)" +
                (", pga, pgv or sa (the peak it is scaled to)" if component == "horizontal" else
                 " or scale_with: horizontal"))
    if field in ("scale", "pga", "pgv", "sa") and kind in ("sine", "sweep", "pulse"):
        return "vary its amplitude instead (axis amplitude, e.g. {values: [0.1, 0.2], unit: g})"
    if field == "seed" and kind == "record":
        return "an ensemble of records is an axis record (names, paths or {glob: ...})"
    if field == "phase" and kind == "synthetic":
        return "its noise is drawn by seed (an axis seed)"
    if kind == "none":
        return f"give scene.excitation.{component} a kind"
    return ""


def fits_scene(name, path, scene):
    """Refuse an axis that sets a key that the base scene's motion does not have: an
    amplitude axis on a record (scale, pga or pgv scale it), a pga axis on a sine, a record
    axis on a sine.  A motion of unknown or missing kind is left to the scene check."""
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
        raise FieldError(path, name, f"sets excitation.{component}.{field}, which a "
                                     f"{kind} motion does not have; "
                                     + (instead or f"it takes {takes or 'no key'}"))


# --- the axes together ------------------------------------------------------------------------

def no_conflicts(grid):
    """Refuse two axes of ``grid`` that set the same scene field, and an H axis beside
    b_over_h."""
    if "b_over_h" in grid and "H" in grid:
        raise FieldError("grid.b_over_h", grid["b_over_h"],
                         "b_over_h keeps B and sets H = B/(b/h), so an H axis conflicts with "
                         "it: vary B beside b_over_h, or size (a factor on B and H)")
    owner, errors = {}, []
    for name in grid:
        paths = () if name == "mu" else vocabulary.targets(name)
        if name == "size":
            continue  # scales whatever B and H are
        for p in paths:
            if p in owner:
                errors.append(FieldError(f"grid.{name}", name,
                                         f"sets {p}, which axis '{owner[p]}' sets too"))
            owner.setdefault(p, name)
    _raise(errors)


_NAME_THE_ZIP = ("; the axis that names a zip group is its dimension's coordinate: name the "
                 "group (zip: {member: [...]}) to let its values repeat")


def zip_entries(raw):
    """``(dimension name or None, axis names, path)`` of each group of ``zip``."""
    if raw is None:
        return []
    if isinstance(raw, dict):
        return [(str(k), v, f"zip.{k}") for k, v in raw.items()]
    if isinstance(raw, list):
        return [(None, v, f"zip[{i}]") for i, v in enumerate(raw)]
    raise FieldError("zip", raw, "must be a list of axis lists, or a mapping of a dimension "
                                 "name to an axis list")


def zip_group(dim, group, path, axes, names, used):
    """The dimension ``(name, axis names)`` of a zip group, given the well-formed ``axes`` and
    every axis name of the grid; ``used`` (axis name -> path of its group) is filled in."""
    if not isinstance(group, list) or len(group) < 2 or \
            not all(isinstance(n, str) for n in group):
        raise FieldError(path, group, "must be a list of two or more axis names")
    errors, ok = [], True
    for n in group:
        if n not in names:
            errors.append(FieldError(path, n, "not an axis of grid"))
            ok = False
        elif n not in axes:
            ok = False  # the axis's own problem is reported
        elif n in used:
            errors.append(FieldError(path, n, f"already in the zip group {used[n]}"))
            ok = False
        used.setdefault(n, path)
    _raise(errors)
    if not ok:
        return None
    lengths = {n: len(axes[n].values) for n in group}
    if len(set(lengths.values())) > 1:
        raise FieldError(path, group, "axes of a zip group must have equal lengths; "
                         + ", ".join(f"{n}: {k}" for n, k in lengths.items()))
    if dim is not None and dim in names and dim not in group:
        raise FieldError(path, dim, "a zip dimension cannot take the name of another axis")
    return dim or group[0], group


def distinct(dims, grid):
    """Refuse repeated values of an axis that is the coordinate of its dimension (an axis of its
    own, or the one that names its zip group), as written in ``grid``: a dimension coordinate
    must pick one cell.  The other axes of a zip group are coordinates along its members, and
    two members may share a value (two records of one magnitude)."""
    errors = []
    for dim in dims:
        for axis in (a for a in dim.axes if a.name == dim.name):
            unique, counts = np.unique(axis.coords, return_counts=True)
            if np.any(counts > 1):
                errors.append(FieldError(join_path("grid", axis.name), grid[axis.name],
                                         f"values repeat: {unique[counts > 1][0].item()!r}"
                                         + ("" if len(dim.axes) == 1 else _NAME_THE_ZIP)))
    _raise(errors)


def dims(axes, groups):
    """Dimensions in the order of the grid; a zip group sits at the place of its first axis."""
    grouped = {n: dim for dim, names in groups for n in names}
    out, placed = [], set()
    for axis_name, axis in axes.items():
        if axis_name not in grouped:
            out.append(Dim(axis_name, (axis,)))
        elif grouped[axis_name] not in placed:
            placed.add(grouped[axis_name])
            names = next(ns for d, ns in groups if d == grouped[axis_name])
            out.append(Dim(grouped[axis_name], tuple(axes[n] for n in names)))
    return tuple(out)


# --- refine -----------------------------------------------------------------------------------

def _tolerance(value, axis):
    """A refine tolerance in the units of ``axis``'s coordinates.

    A bare number is in the unit the axis is written in (its ``unit``), else in the units of
    its coordinates; a string carries its own unit (``5 gal``, ``0.01 west``).
    """
    path = "refine.tolerance"
    if not (number(value) or isinstance(value, str)):
        raise FieldError(path, value, "must be a positive number or a quantity such as "
                                      "'0.01 west' or '5 gal'")
    raw = f"{value!r} {axis.unit}" if number(value) and axis.unit else value
    try:
        quantity = units.parse_quantity(raw, axis.dimension)
    except ValueError as err:
        raise FieldError(path, value, str(err)) from None
    if quantity.body_relative != axis.body_relative:  # one relative unit per dimension
        raise FieldError(path, value, f"give it in the unit of grid.{axis.name} "
                                      f"({axis.unit or axis.units})")
    tolerance = axis.coordinate(quantity)
    if not tolerance > 0:
        raise FieldError(path, value, "must be greater than 0")
    return tolerance


def _refined_axis(name, axes, groups, names):
    """The axis that ``refine.axis`` names, or None when it is a malformed axis (whose own
    problem is reported)."""
    path = "refine.axis"
    if not isinstance(name, str) or name not in names:
        raise FieldError(path, name, "not an axis of grid; axes: " + ", ".join(map(str, names)))
    if any(name in group for _, group in groups):
        raise FieldError(path, name, "an axis of a zip group cannot be refined alone")
    if name not in axes:
        return None
    axis = axes[name]
    if axis.dimension == "name":
        raise FieldError(path, name, "takes names: refine a numeric axis")
    if axis.coords.size < 2:
        raise FieldError(path, name, f"grid.{name} needs at least two values (the first "
                                     "bracket)")
    if not np.all(np.diff(axis.coords) > 0):
        raise FieldError(path, name, f"the values of grid.{name} must increase (they are "
                                     "scanned upward)")
    return axis


def refine(name, tolerance, axes, groups, names):
    """The :class:`Refine` of a well-formed ``refine: {axis, tolerance}`` checked against the
    grid, or None when its axis is malformed."""
    try:
        axis, errors = _refined_axis(name, axes, groups, names), []
    except FieldError as err:
        axis, errors = None, [err]
    if axis is not None:
        return Refine(axis.name, _tolerance(tolerance, axis))
    if not (number(tolerance) or isinstance(tolerance, str)):
        errors.append(FieldError("refine.tolerance", tolerance,
                                 "must be a positive number or a quantity"))
    _raise(errors)
    return None
