"""Grids of a study: axes to cells, zip groups, cell ids, chunks and the seeded shuffle.

A study's axes (DESIGN.md section 5) are grouped into dimensions: an axis alone is a
dimension of its own, axes of a ``zip`` group share one.  Cells are numbered 0 .. n-1 in C
order over the dimensions (the last one varies fastest), so a cell id is a flat index into the
dataset's arrays.  Each cell's scene is the study's base scene with the cell's axis values set
at their scene paths (``AXES``), before validation, so unit strings such as ``"1.5 west"``
resolve with the cell's own body.
"""
import math

import numpy as np

from ..io.records import NAMES
from ..io.scene_schema import HOLD_DIMENSIONS, apply_overrides
from ..io.units import parse_quantity

# The contact friction coefficients that the ``mu`` axis sets together.
MU_PATHS = ("contact.mu_s", "contact.mu_k", "contact.mu_edge_s", "contact.mu_edge_k")

# A record axis value is a bundled name or a file's path (see ``record_source``).
RECORD_PATHS = ("excitation.horizontal.name", "excitation.horizontal.path")

# Axis name -> (scene path(s) it sets, dimension of its values, long name).  ``None`` as
# dimension: taken from the base scene (an amplitude's dimension depends on its excitation);
# "name": the values are names, not quantities.  b_over_h and size are computed (see
# ``cell_overrides``): b_over_h keeps B and sets H = B/(b/h); size multiplies B and H.
AXES = {
    "amplitude": (("excitation.horizontal.amplitude",), None, "horizontal floor amplitude"),
    "frequency": (("excitation.horizontal.frequency",), "frequency",
                  "horizontal floor frequency"),
    "phase": (("excitation.horizontal.phase",), "angle", "phase of the horizontal floor motion"),
    "vertical_amplitude": (("excitation.vertical.amplitude",), None, "vertical floor amplitude"),
    "record": (RECORD_PATHS, "name", "ground-motion record (bundled name or file)"),
    "scale": (("excitation.horizontal.scale",), "dimensionless",
              "scale factor on the ground-motion record"),
    "pga": (("excitation.horizontal.pga",), "acceleration",
            "peak ground acceleration the motion is scaled to"),
    "pgv": (("excitation.horizontal.pgv",), "velocity",
            "peak ground velocity the motion is scaled to"),
    "seed": (("excitation.horizontal.seed",), "dimensionless",
             "seed of the horizontal motion (synthetic noise, or a sine's or sweep's phase)"),
    "B": (("body.B",), "length", "full breadth of the body"),
    "H": (("body.H",), "length", "full height of the body"),
    "b_over_h": (("body.H",), "dimensionless", "aspect ratio b/h = B/H (B kept, H = B/(b/h))"),
    "size": (("body.B", "body.H"), "dimensionless", "size factor on B and H"),
    "mu": (MU_PATHS, "dimensionless",
           "friction coefficient (surface and edge, static and kinetic)"),
    "mu_s": (("contact.mu_s",), "dimensionless", "surface static friction coefficient"),
    "mu_k": (("contact.mu_k",), "dimensionless", "surface kinetic friction coefficient"),
    "mu_edge_s": (("contact.mu_edge_s",), "dimensionless", "edge static friction coefficient"),
    "mu_edge_k": (("contact.mu_edge_k",), "dimensionless", "edge kinetic friction coefficient"),
    "e_x": (("contact.e_x",), "dimensionless", "tangential restitution coefficient"),
    "e_y": (("contact.e_y",), "dimensionless", "normal restitution coefficient"),
}
# Axes computed from the cell's B and H, applied after every plain axis.
COMPUTED = ("b_over_h", "size")

# Dimension of a scene field given by a dotted path, by its last key.
FIELD_DIMENSIONS = {
    "B": "length", "H": "length", "i_g": "length", "lift": "length",
    "mu": "dimensionless", "mu_s": "dimensionless", "mu_k": "dimensionless",
    "mu_edge_s": "dimensionless", "mu_edge_k": "dimensionless", "e_x": "dimensionless",
    "e_y": "dimensionless", "rtol": "dimensionless", "atol": "dimensionless",
    "scale": "dimensionless", "max_steps": "dimensionless", "max_events": "dimensionless",
    "frequency": "frequency", "f_start": "frequency", "f_stop": "frequency",
    "phase": "angle", "theta": "angle", "theta_overturn": "angle",
    "omega": "angular_velocity", "x_dot": "velocity", "y_dot": "velocity",
    "pga": "acceleration", "start": "time", "duration": "time", "dt": "time",
    "max_step": "time", "t_end": "time", "zeno_dt": "time", "dt_out": "time",
    "kind": "name", "name": "name", "path": "name", "units": "name", "method": "name",
    "law": "name", "hold": "name", "shape": "name",
}
SCENE_SECTIONS = ("body", "contact", "excitation", "initial", "solver")

DEFAULT_SEED = 0
MAX_CHUNK = 64  # cells per chunk at most by default: a part file every few seconds at worst
CHUNKS_PER_RANK = 16  # default chunk size aims at this many chunks per rank (balance, resume)


def record_source(value):
    """``("name", value)`` for a bundled record's name, else ``("path", value)``."""
    return ("name", value) if value in NAMES else ("path", value)


def targets(name):
    """Scene paths an axis sets: the table's for named axes, the path itself otherwise."""
    return AXES[name][0] if name in AXES else (name,)


def _get(raw, path):
    """Value at a dotted path of a raw scene dict, or None."""
    node = raw
    for key in path.split("."):
        if not isinstance(node, dict):
            return None
        node = node.get(key)
    return node


def value_dimensions(name, scene):
    """Dimensions an axis's values may have, the one of bare numbers first.

    From ``AXES`` or the field name of a dotted path; an amplitude's from its excitation in
    the base scene (a sine takes an acceleration, velocity or displacement amplitude, a sweep
    the quantity it holds).  ``("name",)``: the values are names; None: unknown field.
    """
    path = targets(name)[0]
    field = path.split(".")[-1]
    dimension = AXES[name][1] if name in AXES else FIELD_DIMENSIONS.get(field)
    if dimension is None and field == "amplitude":
        ground = _get(scene, path.rsplit(".", 1)[0])
        kind = ground.get("kind") if isinstance(ground, dict) else None
        if kind == "sweep":
            return (HOLD_DIMENSIONS.get(ground.get("hold", "acceleration"), "acceleration"),)
        if kind == "sine":
            return ("acceleration", "velocity", "length")
        return ("acceleration",)
    return None if dimension is None else (dimension,)


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

    Each dimension needs the coordinate of one of its axes; several given for one zip group
    must point at the same position.
    """
    pos = []
    for dim in study.dims:
        found = set()
        for axis in dim.axes:
            if axis.name in coords:
                hits = np.flatnonzero(axis.coords == coords[axis.name])
                if hits.size == 0:
                    raise KeyError(f"{coords[axis.name]!r} is not a value of axis {axis.name}")
                found.add(int(hits[0]))
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


def cell_scene(study, index):
    """The raw scene dict of cell ``index`` (to be checked by ``io.scene_schema.load_scene``)."""
    return apply_overrides(study.scene, cell_overrides(study, index))


# --- chunks and dealing ---------------------------------------------------------------------

def shuffled(n, seed=DEFAULT_SEED):
    """The cells 0 .. n-1 in a seeded random order (a permutation, the same for any rank count).

    Cost correlates with grid position (high amplitudes overturn early, low ones run to the
    end): a shuffled order gives every rank a fair mix.
    """
    return np.random.default_rng(seed).permutation(n).astype(np.int64)


def sample(n, k, seed=DEFAULT_SEED):
    """``min(n, k)`` distinct cells of 0 .. n-1 in a seeded random order, drawn without
    permuting all n (fast for any grid)."""
    return np.random.default_rng(seed).choice(n, size=min(n, k), replace=False).astype(np.int64)


def default_chunk_size(n, size):
    """Chunk size giving about ``CHUNKS_PER_RANK`` chunks per rank, at most ``MAX_CHUNK``."""
    return max(1, min(MAX_CHUNK, math.ceil(n / (CHUNKS_PER_RANK * max(1, size)))))


def chunks(order, chunk_size):
    """Cut an order of cells into consecutive chunks, each sorted by cell id."""
    if chunk_size < 1:
        raise ValueError(f"`chunk_size` must be >= 1, got {chunk_size}")
    order = np.asarray(order, dtype=np.int64)
    return [np.sort(order[i:i + chunk_size]) for i in range(0, order.size, chunk_size)]


def deal(chunk_list, size):
    """Chunks dealt round-robin to ``size`` ranks: a list of ``size`` lists of chunks."""
    return [chunk_list[rank::size] for rank in range(size)]


def plan(n, done, chunk_size, size, seed=DEFAULT_SEED):
    """Chunks of the cells not yet ``done``, in seeded shuffled order, dealt to ``size`` ranks.

    Parameters
    ----------
    n : int
        Number of cells.
    done : ndarray of int
        Cells already computed (from part files); left out.
    chunk_size, size, seed : int
        Cells per chunk, number of ranks, shuffle seed.

    Returns
    -------
    list of ``size`` lists of ndarray
        The chunks of each rank.
    """
    order = shuffled(n, seed)
    if len(done):
        order = order[~np.isin(order, np.asarray(done, dtype=np.int64))]
    return deal(chunks(order, chunk_size), size)
