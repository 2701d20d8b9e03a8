"""Cells of a study to results: scenes to kernel rows, one compiled call per chunk.

``run_chunk`` knows nothing of ranks or files (the mpi4py demos' ``mandelbrot_line``): it
builds each cell's scene (``grid.cell_scene``), checks and resolves it into SI
(``io.scene_schema``), packs it into a parameter row (``kernels.api.scene_row``), runs the
whole chunk in one ``kernels.api.run_cells`` call and turns the result rows into the per-cell
arrays of ``cf.VARIABLES``.
"""
import hashlib
import os
import sys
from pathlib import Path

import numpy as np

import kernels
from kernels import api, codes

from .. import cf
from ..io.scene_schema import load_scene, resolve_scene
from ..paper import criteria
from . import grid

# A scene that compiles the kernel in a fraction of a second once cached (warm-up).
WARM_UP_SCENE = {"body": {"B": 0.1, "H": 0.3},
                 "excitation": {"horizontal": {"kind": "sine", "amplitude": "1.5 west",
                                               "frequency": 4.0}},
                 "solver": {"t_end": 0.5}}


def _place(records, buffer, offsets):
    """Offsets into the shared buffer of a row's record arrays, each array stored once."""
    found = []
    for samples in records:
        key = id(samples)
        if key not in offsets:
            offsets[key] = (sum(a.size for a in buffer), samples)  # keep the array alive
            buffer.append(samples)
        found.append(offsets[key][0])
    return found


def build_rows(study, cells):
    """Kernel rows, record buffer and bodies of some cells.

    Returns
    -------
    rows : ndarray, shape (n, N_PAR)
    rec : ndarray
        The shared record buffer (a record used by many cells is stored once).
    bodies : ndarray, shape (n, 3)
        B, H [m] and i_g [m] (NaN for a uniform body) of each cell.
    """
    rows = np.empty((len(cells), codes.N_PAR))
    bodies = np.empty((len(cells), 3))
    buffer, offsets = [], {}
    for k, index in enumerate(cells):
        resolved = resolve_scene(load_scene(grid.cell_scene(study, int(index)),
                                            base_dir=study.base_dir))
        records = []
        rows[k] = api.scene_row(resolved, records)
        placed = iter(_place(records, buffer, offsets))
        for start in (codes.P_GX, codes.P_GY):  # scene_row appends horizontal then vertical
            if rows[k, start + codes.G_KIND] == codes.G_RECORD:
                rows[k, start + codes.G_REC_OFF] = next(placed)
        body = resolved["body"]
        bodies[k] = body["B"], body["H"], np.nan if body["i_g"] is None else body["i_g"]
    return rows, api.record_buffer(buffer), bodies


def summarize(results, bodies):
    """Per-cell arrays of ``cf.VARIABLES`` from kernel result rows (n, N_RES)."""
    status = results[:, codes.R_STATUS].astype(np.int8)
    failed = np.isin(status, codes.FAILED_STATUSES)
    overturned = status == codes.OVERTURNED
    theta = results[:, codes.R_MAX_ABS_THETA]
    outcome = np.where(failed, codes.FAILED,
                       np.where(overturned, codes.OVERTURN,
                                np.where(theta > 0, codes.ROCKED, codes.NO_ROCKING)))
    B, H, i_g = bodies.T
    v_H = np.array([criteria.single_shock_velocity(b, h, None if np.isnan(i) else i)
                    for b, h, i in bodies], dtype=np.float64).reshape(-1)
    out = {
        "outcome": outcome,
        "overturned": np.where(failed, -1, overturned),
        "status": status,
        "t_overturn": results[:, codes.R_T_OVERTURN],
        "overturn_direction": results[:, codes.R_DIRECTION],
        "max_abs_theta": theta,
        "impact_count": results[:, codes.R_IMPACTS],
        "mode_time": results[:, codes.R_MODE_TIME:codes.R_MODE_TIME + codes.N_MODES],
        "max_slip": results[:, codes.R_MAX_SLIP],
        "max_lift": results[:, codes.R_MAX_LIFT],
        "t_rest": results[:, codes.R_T_REST],
        "steps": results[:, codes.R_STEPS],
        "f_at_overturn": results[:, codes.R_F_AT_OVERTURN],
        "a_norm_at_overturn": results[:, codes.R_A_AT_OVERTURN] / criteria.west_acceleration(B, H),
        "v_norm_at_overturn": results[:, codes.R_V_AT_OVERTURN] / v_H,
    }
    return {name: np.ascontiguousarray(a, dtype=cf.VARIABLES[name].dtype)
            for name, a in out.items()}


def run_chunk(study, cells):
    """Simulate some cells of a study.

    Parameters
    ----------
    study : Study
    cells : array_like of int, shape (n,)
        Cell ids (flat indices into the grid).

    Returns
    -------
    dict of str to ndarray
        ``cell`` (int64, the ids) and every variable of ``cf.VARIABLES``, first axis = cells.
        A cell whose simulation fails (budget exhausted, non-finite state, Painleve) is
        flagged by ``status`` and ``outcome = -1``; nothing is raised for it.
    """
    cells = np.asarray(cells, dtype=np.int64).reshape(-1)
    rows, rec, bodies = build_rows(study, cells)
    results = api.run_cells(rows, rec)
    return {"cell": cells, **summarize(results, bodies)}


def kernel_digest():
    """Hash of the kernel's sources (parts computed by another kernel are other results)."""
    digest = hashlib.sha256()
    for path in sorted(Path(kernels.__file__).parent.glob("*.py")):
        digest.update(path.name.encode() + path.read_bytes())
    return digest.hexdigest()


def _marker():
    """File saying that this kernel was compiled into the numba cache (see ``kernel_cached``)."""
    base = os.environ.get("NUMBA_CACHE_DIR") or Path(kernels.__file__).parent / "__pycache__"
    version = f"py{sys.version_info[0]}{sys.version_info[1]}"
    return Path(base) / f"sweep-warm-{kernel_digest()[:16]}-{version}"


def kernel_cached():
    """True when a warm-up already compiled these kernel sources into the numba cache.

    Ranks then load the cache at once, side by side; otherwise rank 0 compiles first and the
    others load what it wrote (a cold compile by every rank at once wastes CPU and memory).
    A stale answer costs only time: numba writes its cache files atomically.
    """
    return _marker().exists()


def warm_up():
    """Compile (or load from the numba cache) the chunk kernel with a short scene."""
    row = api.scene_row(resolve_scene(load_scene(WARM_UP_SCENE)), [])
    api.run_cells(row[None, :], api.record_buffer([]))
    try:
        marker = _marker()
        marker.parent.mkdir(parents=True, exist_ok=True)
        marker.touch()
    except OSError:  # a read-only cache folder: ranks warm up one after the other
        pass
