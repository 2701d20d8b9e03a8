"""The words of a study file: its named axes, the scene paths they set, the dimensions of values.

``AXES`` names the axes a study's ``grid`` may vary besides any dotted scene path, with the
scene path(s) each sets, the dimension of its values and its long name; ``COMPUTED`` the axes
computed from the cell's B and H; ``FIELD_DIMENSIONS`` the dimension of a scene field by its
last key.  The study schema (``sweep.io.study_schema``) checks a study in these words, the
schema reference (``sweep.io.reference``) prints them, the grid of cells
(``sweep.io.study_grid``, ``sweep.runner.grid``) applies them and the datasets
(``sweep.cf``) name their coordinates by them; they live in ``io``, below all of these.
"""
from .records import NAMES
from .scene_models import HOLD_DIMENSIONS

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
    "sa": (("excitation.horizontal.sa.value",), "acceleration",
           "5 %-damped Sa at the scene's sa.period the motion is scaled to"),
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
    "period": "time", "damping": "dimensionless", "height_ratio": "dimensionless",
    "seed": "dimensionless", "kind": "name", "name": "name", "path": "name", "units": "name", "method": "name",
    "law": "name", "hold": "name", "shape": "name", "mass": "mass", "strength": "force",
}
SCENE_SECTIONS = ("body", "contact", "excitation", "initial", "solver", "restraint")


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
