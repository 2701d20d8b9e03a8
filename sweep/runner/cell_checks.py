"""Every cell's scene of a study checked, resolved into SI and packed before any cell runs.

Each is packed into a kernel row, as the run will.

A problem that a cell's scene shows because of an axis value is reported once, at that value
(``grid.amplitude[3]``), else once at the base scene (``scene.body.B``); values that are valid
but likely not what was meant (``sweep.io.plausibility``) are warned of once per axis.
:func:`load_study` is ``io.study_schema.load_study`` with these checks, as ``python -m
sweep.run`` and ``sweep.run_study`` load a study.
"""
import re

import numpy as np

from ..io import study_grid, study_schema, vocabulary
from ..io.plausibility import ReadsAsG, levels_read_in_si, scene_doubts
from ..io.problems import FileProblems, Problem
from ..io.scene_schema import resolve_scene
from ..io.study_cells import CellScenes

# Grids up to CHECK_ALL_CELLS cells have every cell's scene checked; larger ones, each value of
# every dimension (at most CHECKED_PER_DIM of them: both ends and a seeded sample) with the other
# dimensions at their first value, and SAMPLED_CELLS seeded random cells (see checked_cells).
CHECK_ALL_CELLS = 10_000
CHECKED_PER_DIM = 1_000
SAMPLED_CELLS = 1_000
_INDEX = re.compile(r"\[\d+\]$")  # the index of an axis value in a path: grid.B[3]


def load_study(source, *, check_cells=True, cells=None, **options):
    """``io.study_schema.load_study(source, **options)``, with every cell's scene checked
    (:func:`cell_problems`, or ``cells`` with its signature) unless ``check_cells`` is
    false."""
    return study_schema.load_study(source, cells=(cells or cell_problems) if check_cells
                                   else None, **options)


def _blame(study, path):
    """The axis whose scene paths hold ``path``, or None."""
    for axis in study.axes:
        for target in vocabulary.targets(axis.name):
            if path == target or path.startswith(target + ".") or target.startswith(path + "."):
                return axis
    return None


def checked_cells(study, seed=study_grid.DEFAULT_SEED):
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


def _dim_of(study, axis):
    return next(dim for dim in study.dims if any(a is axis for a in dim.axes))


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
    :func:`checked_cells`) is checked, resolved and packed into a kernel row, as the run will.

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
    picks = list(enumerate(checked_cells(study)))
    return combined(findings(study, picks, limit, doubts is not None), limit, doubts)


def _key(problem):
    return problem.path, repr(problem.value), problem.message


def findings(study, picks, limit=50, with_doubts=True):
    """What the checks of some cells found: ``(position, problems, doubts)`` for each
    ``(position, cell)`` of ``picks`` (positions in :func:`checked_cells`), in their order,
    up to the cell that brings the distinct problems found to ``limit`` (no cell after it
    can be among the first ``limit`` problems of all cells: :func:`combined`)."""
    out, seen, scenes = [], set(), CellScenes(study)
    for position, index in picks:
        try:
            scene = scenes.scene(index)
            resolved = resolve_scene(scene)
        except FileProblems as err:
            problems = [_located(study, index, p) for p in err.problems]
            out.append((position, problems, ()))
            seen.update(map(_key, problems))
            if len(seen) >= limit:
                break
            continue
        out.append((position, (), _doubts(study, index, scene, resolved) if with_doubts
                    else ()))
    return out


def _doubts(study, index, scene, resolved):
    """The values of a right cell's scene likely not meant, at their axis values."""
    out = []
    for doubt in scene_doubts(scene, resolved):
        axis = _blame(study, doubt.path)
        if axis is not None and axis.name in vocabulary.COMPUTED:
            continue  # a value computed in metres, not a bare number written
        if isinstance(doubt, ReadsAsG) and axis is not None and levels_read_in_si(axis.values):
            continue  # bare numbers of 2 and more: the axis is written in m/s^2
        out.append(_located(study, index, doubt))
    return out


def combined(found_in_cells, limit=50, doubts=None):
    """The problems of :func:`cell_problems` from :func:`findings` in the order of the
    checked cells (those of several ranks put together): each problem once, the first
    ``limit`` (whole cells); the doubts put in ``doubts``, once per axis."""
    found, seen = [], set()
    doubted = {}  # path without the value's index -> (its first doubt, paths of its values)
    for _, problems, cell_doubts in found_in_cells:
        for problem in problems:
            if _key(problem) not in seen:
                seen.add(_key(problem))
                found.append(problem)
        if problems and len(found) >= limit:
            break
        for doubt in cell_doubts:
            doubted.setdefault(_INDEX.sub("", doubt.path), (doubt, set()))[1].add(doubt.path)
    for path, (doubt, paths) in doubted.items():
        more = len(paths) - 1
        doubts.append(doubt if not more else doubt._replace(
            message=f"{doubt.message} (and {more} more value{'s' * (more > 1)} of {path})"))
    return found
