"""The checked scenes of a study's cells: the base scene checked once, each axis value once.

A cell's scene is the study's base scene with the cell's values set at their scene paths
(``study_grid.cell_overrides``).  Where every such path is a field that its model checks on its
own (no rule of its model looks at another field: :func:`alone`), checking one cell's scene
once and each axis value once (that scene with the one value set, ``scene_schema.load_scene``)
checks every cell: a cell's :class:`~sweep.io.scene_models.Scene` is the first cell's with its
checked values put in, without validating it again.  Other cells (a value that does not
check, an axis on a record, a synthetic motion, a floor, a rock-form body, ...) are checked
from their raw scene (``study_grid.cell_scene``), so that their problems read as before: each
with its dotted path and the value given.
"""
from .problems import FileProblems
from .scene_schema import load_scene
from .study_grid import apply_overrides, cell_overrides, cell_scene
from .vocabulary import MU_PATHS

# Scene paths checked alone, given the kinds of the base scene's motions that have them.
_MOTION_FIELDS = {"sine": ("amplitude", "frequency", "start", "duration"),
                  "sweep": ("amplitude", "f_start", "f_stop", "start", "duration")}
_CONTACT = ("contact.mu", *MU_PATHS, "contact.e_x", "contact.e_y")
REFUSED = object()  # a value that does not check


def alone(scene):
    """The scene paths that a checked base ``scene`` takes values at, each checked on its own:
    the friction and restitution coefficients, B and H of a body given by them, and the
    amplitude, frequencies, start and duration of a sine or sweep component."""
    paths = set(_CONTACT)
    if scene.body.form == "rectangle":
        paths.update(("body.B", "body.H"))
    for key in ("horizontal", "vertical"):
        motion = getattr(scene.excitation, key)
        paths.update(f"excitation.{key}.{name}" for name in _MOTION_FIELDS.get(motion.kind, ()))
    return frozenset(paths)


def _put(model, values):
    """A copy of ``model`` with ``values`` ({attribute path tuple: value}) set, unchecked."""
    if () in values:
        return values[()]
    heads = {}
    for keys, value in values.items():
        heads.setdefault(keys[0], {})[keys[1:]] = value
    return model.model_copy(update={key: _put(getattr(model, key), rest)
                                    for key, rest in heads.items()})


def _at(model, keys):
    for key in keys:
        model = getattr(model, key)
    return model


class CellScenes:
    """The checked :class:`~sweep.io.scene_models.Scene` of each cell of ``study``.

    ``scene(index)`` raises :class:`~sweep.io.problems.FileProblems` as
    ``load_scene(study_grid.cell_scene(study, index))`` does.
    """

    def __init__(self, study):
        self.study = study
        self.keys = cell_overrides(study, 0).keys()   # the paths every cell sets
        self.checked = {}  # (path, repr of the raw value) -> its checked value, or REFUSED
        try:
            self.base = load_scene(cell_scene(study, 0), base_dir=study.base_dir)
        except FileProblems:
            self.base = None   # every cell is checked from its raw scene
        self.alone = self.base is not None and self.keys <= alone(self.base)

    def value(self, path, value):
        """The checked value of one raw ``value`` at ``path`` (``REFUSED``: it does not
        check), checked in the scene of cell 0 with that value set."""
        key = (path, repr(value))
        if key not in self.checked:
            try:
                scene = load_scene(apply_overrides(cell_scene(self.study, 0), {path: value}),
                                   base_dir=self.study.base_dir)
                self.checked[key] = _at(scene, path.split("."))
            except FileProblems:
                self.checked[key] = REFUSED
        return self.checked[key]

    def scene(self, index):
        """The checked scene of cell ``index``."""
        overrides = cell_overrides(self.study, index)
        if self.alone and overrides.keys() == self.keys:
            values = {tuple(path.split(".")): self.value(path, value)
                      for path, value in overrides.items()}
            if not any(value is REFUSED for value in values.values()):
                return _put(self.base, values)
        return load_scene(cell_scene(self.study, index), base_dir=self.study.base_dir)
