"""The grid of a study as numbers: its cells and the lines of a refine study.

Cells are numbered 0 .. n-1 in C order over the study's dimensions (the last one varies
fastest), so a cell id is a flat index into the dataset's arrays.  Each cell's scene is the
study's base scene with the cell's axis values set at their scene paths
(``sweep.io.vocabulary.AXES``) by :func:`apply_overrides`, before validation.  A refine
study's *lines* are the combinations of the other axes' values (``sweep.runner.refine`` bisects along each); how many
simulations it may take is counted here.  The study schema checks a study's shape with these,
the runner's cell checks a sample of its cells' scenes, and the datasets (``sweep.cf``) are
shaped by them, so they live in ``io``; ``sweep.runner.grid`` and ``sweep.runner.refine``
import them under the same names.
"""
import copy
import math

import numpy as np

from .problems import FileProblems, Problem
from .units import parse_quantity
from .vocabulary import COMPUTED, MU_PATHS, RECORD_PATHS, _get, record_source, targets

DEFAULT_SEED = 0  # seed of the shuffled order of the cells and of the sampled ones


# --- cells --------------------------------------------------------------------------------

def shape(study):
    """Grid shape: one entry per dimension, in the study's order."""
    return tuple(dim.size for dim in study.dims)


def n_cells(study):
    """Number of cells of the grid."""
    return math.prod(shape(study))


def shape_text(study):
    """'amplitude 9 x frequency 5': the study's dimensions and sizes."""
    return " x ".join(f"{dim.name} {dim.size}" for dim in study.dims)


def positions(study, index):
    """Position of cell ``index`` along each dimension (C order)."""
    n = n_cells(study)
    if not 0 <= index < n:
        raise IndexError(f"cell index {index} outside 0 .. {n - 1}")
    return tuple(int(i) for i in np.unravel_index(index, shape(study)))


def cell_values(study, index):
    """The raw value of every axis in cell ``index``: {axis name: value as set in the scene}."""
    return {axis.name: axis.values[i]
            for dim, i in zip(study.dims, positions(study, index)) for axis in dim.axes}


def cell_coords(study, index):
    """The coordinate of every axis in cell ``index`` (as in the dataset)."""
    return {axis.name: axis.coords[i].item()
            for dim, i in zip(study.dims, positions(study, index)) for axis in dim.axes}


def cell_index(study, coords):
    """Flat index of the cell with the given coordinates ({axis: coordinate}).

    Each dimension needs coordinates of its axes that together point at one position (a
    zipped axis may repeat a value: give another axis of its group beside it).
    """
    pos = []
    for dim in study.dims:
        found = None
        for axis in dim.axes:
            if axis.name in coords:
                hits = set(np.flatnonzero(axis.coords == coords[axis.name]).tolist())
                if not hits:
                    raise KeyError(f"{coords[axis.name]!r} is not a value of axis {axis.name}")
                found = hits if found is None else found & hits
        found = found or set()
        if len(found) != 1:
            raise KeyError(f"give one position along dimension {dim.name}: got {sorted(found)}")
        pos.append(found.pop())
    return int(np.ravel_multi_index(pos, shape(study)))


def _length_si(value):
    """A raw length (number in m or a unit string) in m, or None when it does not parse."""
    try:
        quantity = parse_quantity(value, "length")
    except ValueError:
        return None
    return None if quantity.body_relative else quantity.to_si()


def cell_overrides(study, index):
    """{scene path: raw value} that turns the base scene into cell ``index``'s scene.

    Plain axes first (a ``record`` sets the component's ``name`` or ``path``, and clears the
    other); ``mu`` sets the four friction coefficients unless an axis sets one of
    them explicitly; then b_over_h (H = B/(b/h)) and size (B, H times the factor), computed
    in metres from the cell's B and H.
    """
    values = cell_values(study, index)
    overrides = {}
    for name, value in values.items():
        if name == "record":
            key, _ = record_source(value)
            overrides.update({path: value if path.endswith(key) else None
                              for path in RECORD_PATHS})
        elif name not in COMPUTED and name != "mu":
            for path in targets(name):
                overrides[path] = value
    if "mu" in values:
        for path in MU_PATHS:
            overrides.setdefault(path, values["mu"])
    if any(name in values for name in COMPUTED):
        B = _length_si(overrides.get("body.B", _get(study.scene, "body.B")))
        H = _length_si(overrides.get("body.H", _get(study.scene, "body.H")))
        if "b_over_h" in values and B is not None:
            H = B / float(values["b_over_h"])
        if "size" in values:
            factor = float(values["size"])
            B = None if B is None else B * factor
            H = None if H is None else H * factor
        # a B or H that does not parse stays as written, for the scene check to report
        for key, length in (("body.B", B), ("body.H", H)):
            if length is not None:
                overrides[key] = length
    return overrides


def apply_overrides(raw, overrides):
    """A copy of the raw scene dict with values set by dotted path, before validation.

    ``apply_overrides(raw, {"excitation.horizontal.amplitude": "1.2 west", "body.H": 0.4})``.
    Missing intermediate mappings are created; the values are raw (numbers or unit strings), so
    that ``io.scene_schema.load_scene`` checks them like values written in the file.  Note that the ``mu``
    shorthand loses to explicit ``mu_s`` ... keys: a study axis on ``mu`` must not meet them.

    Raises
    ------
    FileProblems
        When a path goes through a value that is not a mapping.
    """
    new = copy.deepcopy(raw)
    problems = []
    for dotted, value in overrides.items():
        keys = dotted.split(".")
        node = new
        for i, key in enumerate(keys[:-1]):
            if node.get(key) is None:  # absent, or a section left empty in the file
                node[key] = {}
            child = node[key]
            if not isinstance(child, dict):
                problems.append(Problem(".".join(keys[:i + 1]), child,
                                        f"cannot set '{dotted}': not a mapping"))
                break
            node = child
        else:
            node[keys[-1]] = copy.deepcopy(value)
    if problems:
        raise FileProblems(problems)
    return new


def cell_scene(study, index):
    """The raw scene dict of cell ``index`` (to be checked by ``io.scene_schema.load_scene``)."""
    return apply_overrides(study.scene, cell_overrides(study, index))


def sample(n, k, seed=DEFAULT_SEED):
    """``min(n, k)`` distinct cells of 0 .. n-1 in a seeded random order, drawn without
    permuting all n (fast for any grid)."""
    return np.random.default_rng(seed).choice(n, size=min(n, k), replace=False).astype(np.int64)


# --- the lines of a refine study ----------------------------------------------------------

# A bracket wider than the tolerance by less than this fraction is closed: midpoints round.
SLACK = 1e-9


def refined_axis(study):
    """Position of the refined dimension in ``study.dims`` and its axis."""
    k = next(i for i, dim in enumerate(study.dims) if dim.name == study.refine.axis)
    return k, study.dims[k].axes[0]


def line_shape(study):
    """Shape of the lines: the study's shape without the refined dimension."""
    k, _ = refined_axis(study)
    return tuple(dim.size for i, dim in enumerate(study.dims) if i != k)


def wide(width, tolerance):
    """True for a bracket that still needs a midpoint."""
    return width > tolerance * (1.0 + SLACK)


def rounds_needed(width, tolerance):
    """Halvings that take a bracket of ``width`` down to ``tolerance``."""
    n = 0
    while wide(width / 2.0 ** n, tolerance):
        n += 1
    return n


def max_rounds(study):
    """Bisection rounds after the coarse one, at most (the widest coarse gap sets it)."""
    _, axis = refined_axis(study)
    return max(rounds_needed(w, study.refine.tolerance) for w in np.diff(axis.coords))


def max_simulations(study):
    """Most simulations a refine study can take: the grid, one midpoint per line and round."""
    return study.n_cells + math.prod(line_shape(study)) * max_rounds(study)


def dense_simulations(study):
    """Cells of the grid of the same resolution: the refined axis spaced at the tolerance."""
    _, axis = refined_axis(study)
    span = float(axis.coords[-1] - axis.coords[0])
    per_line = math.ceil(span / study.refine.tolerance * (1.0 - SLACK)) + 1
    return math.prod(line_shape(study)) * per_line
