"""Cells of a study to results: scenes to kernel rows, one compiled call per chunk.

``run_chunk`` knows nothing of ranks or files (the mpi4py demos' ``mandelbrot_line``): it
builds the chunk's scene records together from the axis values (``runner.cell_rows``: the
base scene and each axis value checked once), or else resolves each cell's checked scene into
SI and packs it once (``io.scene_schema.resolve_and_pack``), runs the
whole chunk in one ``kernels.api.run_cells`` call and turns the result records into the
per-cell arrays of ``cf.VARIABLES``.  A :class:`ChunkRunner` does the same for the chunks of
one study on one rank, keeping the study's records (``kernels.record_cache``, and their copy
in device memory on the GPU) from chunk to chunk.  One cell never stops the others: a scene
that cannot be built is flagged ``invalid_scene``, one that runs longer than the wall-time
budget is stopped and flagged ``time_budget`` (both with a warning naming the cell, and
``outcome = -1``).
"""
import sys
import warnings
from pathlib import Path

import numpy as np

from kernels import api, codes, gpu
from kernels.record_cache import RecordCache

from .. import cf
from ..bodies import body_constants, body_sides, single_shock_velocity, west_acceleration
from ..io.problems import FileProblems
from ..io.scene_schema import load_scene, resolve_and_pack
from ..groundmotion import applied
from .cell_rows import CellRows

# A scene that compiles the kernel in a fraction of a second once cached (warm-up).
WARM_UP_SCENE = {"body": {"B": 0.1, "H": 0.3},
                 "excitation": {"horizontal": {"kind": "sine", "amplitude": "1.5 west",
                                               "frequency": 4.0}},
                 "solver": {"t_end": 0.5}}

CELL_BUDGET = 300.0  # s of wall time one cell may run before it is stopped (run_chunk)


def build_rows(study, cells, records=None, scenes=None):
    """Kernel rows, record buffer, bodies and horizontal motions of some cells.

    The cells' records are placed in ``records``, a ``kernels.record_cache.RecordCache`` (a
    record used by many cells is stored once; default: a new one for these cells).  Their
    rows come from ``scenes``, the study's ``runner.cell_rows.CellRows`` (default: a new
    one): built together as one array on the plain axes, else each cell's checked scene
    resolved and packed once.

    Returns
    -------
    rows : ndarray of ``codes.SCENE_DTYPE``, shape (n,)
    rec : ndarray
        The record buffer the rows point into (``records.buffer()``).
    bodies : ndarray, shape (n, 5)
        B, H [m], i_g [m] (NaN for a uniform body) and G = (x_G, y_G) [m] (NaN for G in the
        middle) of each cell.
    motions : ndarray, shape (n, 5)
        PGA, PGV, PGD and significant duration of each cell's horizontal motion
        (``groundmotion.applied.peaks``), and the largest displacement of its isolator
        (NaN without one, or a linear one: ``io.floors.resolve_isolated``).
    problems : dict of int to str
        Position in ``cells`` to the problem of each cell whose scene cannot be built
        (loaded, resolved or packed); its row (every field) and body are NaN.
    """
    rows = api.scene_rows(len(cells))
    bodies = np.empty((len(cells), 5))
    motions = np.full((len(cells), len(applied.Peaks._fields) + 1), np.nan)
    records = RecordCache() if records is None else records
    scenes = CellRows(study) if scenes is None else scenes
    together, built_bodies, built_motions, built = scenes.build(cells)
    if built.any():
        rows[built], bodies[built], motions[built, :-1] = (together[built], built_bodies[built],
                                                           built_motions[built])
    problems = {}
    for k in np.flatnonzero(~built):
        try:
            resolved, rows[k] = resolve_and_pack(scenes.scenes.scene(int(cells[k])), records)
        except (FileProblems, ValueError) as err:
            rows[k], bodies[k], problems[k] = np.nan, np.nan, str(err)
            continue
        body = resolved["body"]
        bodies[k] = (body["B"], body["H"], np.nan if body["i_g"] is None else body["i_g"],
                     *((np.nan, np.nan) if body["G"] is None else body["G"]))
        horizontal = resolved["excitation"]["horizontal"]
        isolator = horizontal.get("isolator") or {}
        motions[k] = (*applied.peaks(horizontal),
                      np.nan if isolator.get("max_displacement") is None
                      else isolator["max_displacement"])
    return rows, records.buffer(), bodies, motions, problems


def _body_scales(bodies):
    """West's acceleration g tan(alpha), v_H and p (one number per body: the smaller side's,
    ``sweep.bodies``) and the angles alpha_1, alpha_2 of each body of ``build_rows``, each
    computed once per distinct body (rows equal byte for byte)."""
    ids = {}
    inverse = np.array([ids.setdefault(row.tobytes(), len(ids)) for row in bodies], np.intp)
    distinct = bodies[np.unique(inverse, return_index=True)[1]]
    B, H = distinct[:, 0], distinct[:, 1]
    i_g = [None if np.isnan(i) else i for i in distinct[:, 2]]
    centre = [None if np.isnan(x) else (x, y) for x, y in distinct[:, 3:]]
    sides = [body_sides(*body) for body in zip(B, H, centre, i_g)]
    west = [west_acceleration(b, h, centre=c) for b, h, c in zip(B, H, centre)]
    v_H = [single_shock_velocity(b, h, i, centre=c) for b, h, i, c in zip(B, H, i_g, centre)]
    p = [body_constants(b, h, i).p if c is None else (s.p1 if s.alpha_1 <= s.alpha_2 else s.p2)
         for b, h, i, c, s in zip(B, H, i_g, centre, sides)]
    alpha_1, alpha_2 = [s.alpha_1 for s in sides], [s.alpha_2 for s in sides]
    return [np.array(x, dtype=np.float64).reshape(-1)[inverse]
            for x in (west, v_H, p, alpha_1, alpha_2)]


def summarize(results, bodies, motions, restraints):
    """Per-cell arrays of ``cf.VARIABLES`` from kernel results (n records of
    ``codes.RESULT_DTYPE``), the cells' bodies and motions (``build_rows``) and the kinds of
    their restraints (a ``codes.RESTRAINT_*`` code each: the rows' ``restraint.kind``)."""
    status = results["status"].astype(np.int8)
    failed = np.isin(status, codes.FAILED_STATUSES)
    overturned = status == codes.OVERTURNED
    theta = results["max_abs_theta"]
    outcome = np.where(failed, codes.FAILED,
                       np.where(overturned, codes.OVERTURN,
                                np.where(theta > 0, codes.ROCKED, codes.NO_ROCKING)))
    west, v_H, p, alpha_1, alpha_2 = _body_scales(bodies)
    pga, pgv, pgd, d5_95, isolator = motions.T
    out = {
        "outcome": outcome,
        "overturned": np.where(failed, -1, overturned),
        "status": status,
        "t_overturn": results["t_overturn"],
        "overturn_direction": results["direction"],
        "max_abs_theta": theta,
        "impact_count": results["impacts"],
        "mode_time": results["mode_time"],
        "max_slip": results["max_slip"],
        "max_travel": results["max_travel"],
        "max_lift": results["max_lift"],
        "t_rest": results["t_rest"],
        "steps": results["steps"],
        "energy_clamps": results["energy_clamps"],
        "f_at_overturn": results["f_at_overturn"],
        "a_norm_at_overturn": results["a_at_overturn"] / west,
        "v_norm_at_overturn": results["v_at_overturn"] / v_H,
        "slid": np.where(failed, -1, results["max_slip"] > cf.SLID_THRESHOLD),
        "pga": pga, "pgv": pgv, "pgd": pgd, "significant_duration": d5_95,
        "pga_norm": pga / west, "pgv_norm": pgv * p / west,
        "alpha_1": alpha_1, "alpha_2": alpha_2, "isolator_max_displacement": isolator,
        "restraint_broken": np.where(failed | (restraints == codes.RESTRAINT_NONE), -1,
                                     np.isfinite(results["t_broken"])),
    }
    return {name: np.ascontiguousarray(a, dtype=cf.VARIABLES[name].dtype)
            for name, a in out.items()}


class ChunkRunner:
    """``run_chunk(study, cells)`` for the chunks of one study on one rank: the study's records
    are stored once (``kernels.record_cache.RecordCache``) and, on the GPU, sent to device
    memory once (``kernels.gpu.device_records``).

    Parameters
    ----------
    budget : float or None
        Seconds of wall time a cell may run before it is stopped (``time_budget``);
        None or 0: no limit (on the CPU: a GPU thread runs its cell to the end).
    backend : {"cpu", "cuda"}
        Where the kernel runs: ``kernels.api.run_cells`` or ``kernels.gpu.run_cells``.
    """

    def __init__(self, *, budget=CELL_BUDGET, backend="cpu"):
        self.budget, self.backend = budget, backend
        self.records = RecordCache()
        self.scenes = None  # the CellRows of the study of the last chunk
        self.device = None  # the records' DeviceRecords, once a chunk ran on the GPU

    def __call__(self, study, cells):
        """Simulate some cells of ``study``: :func:`run_chunk`'s result."""
        cells = np.asarray(cells, dtype=np.int64).reshape(-1)
        self.records.restart_if_full()
        if self.scenes is None or self.scenes.study is not study:
            self.scenes = CellRows(study)
        rows, rec, bodies, motions, problems = build_rows(study, cells, self.records,
                                                          self.scenes)
        built = np.ones(cells.size, dtype=bool)
        built[list(problems)] = False
        results = api.not_run(cells.size)
        if self.backend == "cuda":
            self.device = self.device or gpu.device_records()
            results[built] = gpu.run_cells(rows[built], self.device.update(self.records))
        else:
            results[built] = api.run_cells(rows[built], rec, budget=self.budget)
        for k, problem in problems.items():
            _warn(cells[k], f"its scene cannot be built: {problem}")
        for k in np.flatnonzero(results["status"] == codes.TIME_BUDGET):
            _warn(cells[k], f"stopped after the per-cell wall-time budget of {self.budget:g} s")
        return {"cell": cells, **summarize(results, bodies, motions,
                                           rows["restraint"]["kind"])}


def run_chunk(study, cells, *, budget=CELL_BUDGET, backend="cpu"):
    """Simulate some cells of a study (one :class:`ChunkRunner` call).

    Parameters
    ----------
    study : Study
    cells : array_like of int, shape (n,)
        Cell ids (flat indices into the grid).
    budget, backend
        As :class:`ChunkRunner`'s.

    Returns
    -------
    dict of str to ndarray
        ``cell`` (int64, the ids) and every variable of ``cf.VARIABLES``, first axis = cells.
        A cell whose simulation fails (budget exhausted, non-finite state, Painleve, wall-time
        budget, a scene that cannot be built) is flagged by ``status`` and ``outcome = -1``;
        nothing is raised for it (a ``RuntimeWarning`` names the last two kinds).
    """
    return ChunkRunner(budget=budget, backend=backend)(study, cells)


def _warn(cell, text):
    warnings.warn(f"cell {int(cell)}: {text}", RuntimeWarning, stacklevel=3)


def _marker():
    """File saying that this kernel was compiled into its cache folder (see ``kernel_cached``).

    The folder is ``kernels._jit.CACHE_DIR``; the name carries the digest of the kernel
    sources too, for a ``NUMBA_CACHE_DIR`` that is not keyed by them."""
    from kernels import _jit
    version = f"py{sys.version_info[0]}{sys.version_info[1]}"
    return Path(_jit.CACHE_DIR) / f"sweep-warm-{_jit.SOURCE_DIGEST[:16]}-{version}"


def kernel_cached():
    """True when a warm-up already compiled these kernel sources into the numba cache.

    Ranks then load the cache at once, side by side; otherwise rank 0 compiles first and the
    others load what it wrote (a cold compile by every rank at once wastes CPU and memory).
    A stale answer costs only time: numba writes its cache files atomically.
    """
    return _marker().exists()


def warm_up():
    """Compile (or load from the numba cache) the chunk kernel with a short scene."""
    _, row = resolve_and_pack(load_scene(WARM_UP_SCENE), [])
    api.run_cells(row, api.record_buffer([]))
    try:
        marker = _marker()
        marker.parent.mkdir(parents=True, exist_ok=True)
        marker.touch()
    except OSError:  # a read-only cache folder: ranks warm up one after the other
        pass
