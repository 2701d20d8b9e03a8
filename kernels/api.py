"""Python face of the kernel: check and pack a scene, allocate outputs, call, unpack.

A *resolved scene* is a plain nested dict in SI units (what ``sweep.schema`` produces from a
YAML file, or what a notebook writes by hand)::

    {"body": {"B": 0.1, "H": 0.3, "i_g": None},            # i_g: radius of gyration about G
     "contact": {"mu_s", "mu_k", "mu_edge_s", "mu_edge_k", "e_x", "e_y",
                 "landing": "flat" | "face_friction" | "corner"},
     "excitation": {"horizontal": GROUND, "vertical": GROUND},
     "initial": {"theta", "omega", "x_dot", "y_dot", "lift"},
     "solver": {"method": "adaptive" | "fixed", "rtol", "atol", "dt", "max_step", "t_end",
                "max_steps", "max_events", "theta_overturn", "zeno_dt", "dt_out"}}

GROUND is ``{"kind": "none"}`` or, with optional ``start`` [s] and ``duration`` [s or None]:
``{"kind": "sine", "amplitude": m/s^2, "frequency": Hz, "phase": rad}``,
``{"kind": "sweep", "hold": "acceleration"|"velocity"|"displacement", "amplitude": SI of the
held quantity, "f_start": Hz, "f_stop": Hz, "duration": s, "law": "log"|"linear", "phase": rad}``,
``{"kind": "record", "samples": ndarray m/s^2, "dt": s, "scale": 1.0}``,
``{"kind": "pulse", "shape": "rectangular"|"triangular", "amplitude": m/s^2, "duration": s}``.
Missing keys take the values of ``DEFAULTS``.  Sign convention: x and a_x positive to the
right, theta > 0 is rotation about the left corner (PHYSICS.md section 1.1).
"""
import math
import time
from collections import namedtuple

import numpy as np

from . import codes
from .watchdog import Watchdog, control

DEFAULTS = {
    "body": {"i_g": None},
    "contact": {"mu_s": 0.4, "mu_k": 0.3, "mu_edge_s": 0.4, "mu_edge_k": 0.3,
                "e_x": -0.8, "e_y": 0.2, "landing": "flat"},
    "initial": {"theta": 0.0, "omega": 0.0, "x_dot": 0.0, "y_dot": 0.0, "lift": 0.0},
    "solver": {"method": "adaptive", "rtol": 1e-8, "atol": 1e-10, "dt": 1e-3,
               "max_step": 0.05, "t_end": 10.0, "max_steps": 5_000_000,
               "max_events": 1_000_000, "theta_overturn": math.pi / 2,
               "zeno_dt": 1e-6, "dt_out": 0.02},
    "ground": {"start": 0.0, "duration": None, "phase": 0.0, "law": "log",
               "hold": "acceleration", "scale": 1.0},
}

MAX_LOG = 100_000  # impacts kept in a scene's log by default (all are counted)

_KINDS = {"none": codes.G_NONE, "sine": codes.G_SINE, "sweep": codes.G_SWEEP,
          "record": codes.G_RECORD}
_SHAPES = {"rectangular": codes.G_PULSE_RECT, "triangular": codes.G_PULSE_TRI}
_LAWS = {"log": codes.LAW_LOG, "linear": codes.LAW_LINEAR}
_HOLDS = {"acceleration": codes.HOLD_ACCELERATION, "velocity": codes.HOLD_VELOCITY,
          "displacement": codes.HOLD_DISPLACEMENT}


def _merged(scene, section):
    out = dict(DEFAULTS.get(section, {}))
    out.update(scene.get(section) or {})
    return out


def _number(value, path, positive=False, finite=True):
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"`{path}` must be a number, got {value!r}") from None
    if (finite and not np.isfinite(x)) or (positive and not x > 0.0):
        raise ValueError(f"`{path}` must be a {'positive ' if positive else ''}finite "
                         f"number, got {value!r}")
    return x


def _ground_row(spec, path, records):
    """Pack one ground component into G_SIZE floats; append record samples to records."""
    row = np.zeros(codes.G_SIZE)
    spec = {**DEFAULTS["ground"], **(spec or {"kind": "none"})}
    kind = spec.get("kind", "none")
    if kind == "pulse":
        shape = spec.get("shape", "rectangular")
        if shape not in _SHAPES:
            raise ValueError(f"`{path}.shape` must be one of {sorted(_SHAPES)}, got {shape!r}")
        row[codes.G_KIND] = _SHAPES[shape]
    elif kind in _KINDS:
        row[codes.G_KIND] = _KINDS[kind]
    else:
        raise ValueError(f"`{path}.kind` must be one of "
                         f"{sorted([*_KINDS, 'pulse'])}, got {kind!r}")
    if kind == "none":
        return row
    duration = spec.get("duration")
    row[codes.G_START] = _number(spec.get("start", 0.0), f"{path}.start")
    row[codes.G_DUR] = math.inf if duration is None else _number(duration, f"{path}.duration",
                                                                 positive=True)
    row[codes.G_PHASE] = _number(spec.get("phase", 0.0), f"{path}.phase")
    if kind == "sine":
        row[codes.G_AMP] = _number(spec["amplitude"], f"{path}.amplitude")
        row[codes.G_FREQ] = _number(spec["frequency"], f"{path}.frequency", positive=True)
    elif kind == "sweep":
        row[codes.G_AMP] = _number(spec["amplitude"], f"{path}.amplitude")
        row[codes.G_F0] = _number(spec["f_start"], f"{path}.f_start", positive=True)
        row[codes.G_F1] = _number(spec["f_stop"], f"{path}.f_stop", positive=True)
        if duration is None:
            raise ValueError(f"`{path}.duration` is required for a sweep")
        row[codes.G_LAW] = _LAWS[spec.get("law", "log")]
        f0, f1, T = row[codes.G_F0], row[codes.G_F1], row[codes.G_DUR]
        row[codes.G_FREQ] = (math.log(f1 / f0) if row[codes.G_LAW] == codes.LAW_LOG
                             else f1 - f0) / T
        row[codes.G_HOLD] = _HOLDS[spec.get("hold", "acceleration")]
    elif kind == "record":
        samples = np.ascontiguousarray(spec["samples"], dtype=np.float64).ravel()
        if samples.size < 2 or not np.all(np.isfinite(samples)):
            raise ValueError(f"`{path}.samples` must hold at least two finite values")
        row[codes.G_AMP] = _number(spec.get("scale", 1.0), f"{path}.scale")
        row[codes.G_REC_DT] = _number(spec["dt"], f"{path}.dt", positive=True)
        row[codes.G_REC_OFF] = sum(r.size for r in records)
        row[codes.G_REC_N] = samples.size
        records.append(samples)
    else:  # pulse
        row[codes.G_AMP] = _number(spec["amplitude"], f"{path}.amplitude")
        if duration is None:
            raise ValueError(f"`{path}.duration` is required for a pulse")
    return row


def scene_row(scene, records=None):
    """Pack a resolved scene into a parameter row (shape (N_PAR,)).

    ``records`` is a list that record samples are appended to; their concatenation is the
    buffer the row's offsets point into (see ``record_buffer``).
    """
    records = [] if records is None else records
    body = _merged(scene, "body")
    contact = _merged(scene, "contact")
    initial = _merged(scene, "initial")
    solver = _merged(scene, "solver")
    excitation = scene.get("excitation") or {}
    row = np.zeros(codes.N_PAR)
    B = _number(body.get("B"), "body.B", positive=True)
    H = _number(body.get("H"), "body.H", positive=True)
    b, h = B / 2, H / 2
    i_g = body.get("i_g")
    row[codes.P_B], row[codes.P_H] = B, H
    row[codes.P_I2] = (b * b + h * h) / 3 if i_g is None else \
        _number(i_g, "body.i_g", positive=True) ** 2
    for key, index in (("mu_s", codes.P_MU_S), ("mu_k", codes.P_MU_K),
                       ("mu_edge_s", codes.P_MU_EDGE_S), ("mu_edge_k", codes.P_MU_EDGE_K)):
        row[index] = _number(contact[key], f"contact.{key}")
        if row[index] < 0:
            raise ValueError(f"`contact.{key}` must be >= 0, got {contact[key]!r}")
    row[codes.P_E_X] = _number(contact["e_x"], "contact.e_x")
    row[codes.P_E_Y] = _number(contact["e_y"], "contact.e_y")
    if not -1 <= row[codes.P_E_X] <= 1 or not 0 <= row[codes.P_E_Y] <= 1:
        raise ValueError("`contact.e_x` must lie in [-1, 1] and `contact.e_y` in [0, 1]")
    if contact["landing"] not in codes.LANDING_NAMES:
        raise ValueError(f"`contact.landing` must be one of {codes.LANDING_NAMES}, "
                         f"got {contact['landing']!r}")
    row[codes.P_LANDING] = codes.LANDING_NAMES.index(contact["landing"])
    for key, index in (("theta", codes.P_THETA0), ("omega", codes.P_OMEGA0),
                       ("x_dot", codes.P_U0), ("y_dot", codes.P_V0), ("lift", codes.P_LIFT0)):
        row[index] = _number(initial[key], f"initial.{key}")
    method = solver["method"]
    if method not in codes.METHOD_NAMES:
        raise ValueError(f"`solver.method` must be one of {codes.METHOD_NAMES}, got {method!r}")
    row[codes.P_METHOD] = codes.METHOD_NAMES.index(method)
    for key, index in (("rtol", codes.P_RTOL), ("atol", codes.P_ATOL), ("dt", codes.P_DT),
                       ("max_step", codes.P_MAX_STEP), ("t_end", codes.P_T_END),
                       ("max_steps", codes.P_MAX_STEPS), ("max_events", codes.P_MAX_EVENTS),
                       ("theta_overturn", codes.P_THETA_OVER), ("zeno_dt", codes.P_ZENO_DT),
                       ("dt_out", codes.P_DT_OUT)):
        row[index] = _number(solver[key], f"solver.{key}", positive=True)
    row[codes.P_GX:codes.P_GX + codes.G_SIZE] = _ground_row(
        excitation.get("horizontal"), "excitation.horizontal", records)
    row[codes.P_GY:codes.P_GY + codes.G_SIZE] = _ground_row(
        excitation.get("vertical"), "excitation.vertical", records)
    return row


def as_records(rows):
    """Scene rows (shape (n, N_PAR) or (N_PAR,)) viewed, without a copy, as n records of
    ``codes.SCENE_DTYPE``: the compiled code reads them by name (``row.body.B``)."""
    rows = np.ascontiguousarray(rows, dtype=np.float64).reshape(-1, codes.N_PAR)
    return rows.view(codes.SCENE_DTYPE).view(np.recarray)[:, 0]


def record_buffer(records):
    """Concatenate record sample arrays into the shared buffer (never empty)."""
    if not records:
        return np.zeros(1)
    return np.ascontiguousarray(np.concatenate(records), dtype=np.float64)


SceneResult = namedtuple("SceneResult", [
    "status", "message", "overturned", "t_overturn", "overturn_direction", "impact_times",
    "omega_after", "impact_slipped", "impact_count", "impact_log_truncated", "max_abs_theta",
    "t_rest", "mode_time", "max_slip", "max_travel", "max_lift", "steps", "events", "energy_clamps",
    "t_final", "f_at_overturn", "a_at_overturn", "v_at_overturn", "cpu_s", "history"])
SceneResult.__doc__ = """Result of one scene: the JSON contract of DESIGN.md section 4 plus
extras.  ``impact_times``, ``omega_after`` and ``impact_slipped`` hold the first ``max_log``
impacts of ``impact_count`` (``impact_log_truncated`` when fewer); ``history`` is None or a
dict of arrays named by ``codes.HISTORY_NAMES``.  ``max_slip`` is how far the base moved along
the floor (``extremes.footprint``), ``max_travel`` the largest |x - x0| of G, rotation
included."""


def _nan_to_none(x):
    return None if not np.isfinite(x) else float(x)


def _message(status, impacts, logged, clamps):
    """The status message, with what was cut (the impact log) or changed (restitution)."""
    text = codes.STATUS_MESSAGES[status]
    if logged < impacts:
        text += f"; impact log truncated at {logged} of {impacts} impacts"
    if impacts and clamps == impacts:
        text += (f"; all {impacts} impact{'s' if impacts != 1 else ''} had their "
                 "restitution clamped to gain no energy (check e_x, e_y)")
    return text


_COMPILED = {}  # (dispatcher, kinds of the arguments) -> compiled function


def _kind(value):
    """What numba's type of an argument depends on, found without typing it (typing a record
    of ``SCENE_DTYPE`` takes about 1.8 ms in Python, more than a steady-rocking scene)."""
    if isinstance(value, np.ndarray):
        flags = value.flags
        return (value.dtype, value.ndim, flags.c_contiguous, flags.f_contiguous,
                flags.writeable, flags.aligned)
    return type(value), getattr(value, "dtype", None)


def _compiled(dispatcher, args):
    """The compiled function of ``dispatcher`` for the types of ``args``, compiled or loaded
    from the cache once per kind of arguments, to be called without numba's dispatch (which
    types a record argument in Python on every call); ``dispatcher`` itself under
    ``NUMBA_DISABLE_JIT``."""
    if not hasattr(dispatcher, "compile"):
        return dispatcher
    key = (dispatcher, *map(_kind, args))
    if key not in _COMPILED:
        _COMPILED[key] = dispatcher.compile(tuple(dispatcher.typeof_pyval(a) for a in args))
    return _COMPILED[key]


def run_scene(scene, history=False, max_log=MAX_LOG):
    """Simulate one resolved scene (dict in SI units) and return a ``SceneResult``.

    The impact log keeps the first ``max_log`` impacts; the kernel counts them all.
    ``cpu_s`` is the CPU time of the simulation alone (not of compiling or loading it)."""
    from .driver import run_scene as _run_scene
    records = []
    row = scene_row(scene, records)
    rec = record_buffer(records)
    res = np.zeros(codes.N_RES)
    log = np.empty((max_log, codes.N_LOG))  # rows [:n_log] are written
    n_hist = int(row[codes.P_T_END] / row[codes.P_DT_OUT]) + 2 if history else 0
    hist = np.zeros((n_hist, codes.N_HIST))
    args = (as_records(row)[0], rec, res, log, hist, control(cell=0))
    run = _compiled(_run_scene, args)
    t0 = time.process_time()
    n_log, n_h = run(*args)
    cpu = time.process_time() - t0
    status = int(res[codes.R_STATUS])
    overturned = status == codes.OVERTURNED
    impacts, clamps = int(res[codes.R_IMPACTS]), int(res[codes.R_ENERGY_CLAMPS])
    return SceneResult(
        status=codes.STATUS_NAMES[status], message=_message(status, impacts, n_log, clamps),
        overturned=overturned, t_overturn=_nan_to_none(res[codes.R_T_OVERTURN]),
        overturn_direction=int(res[codes.R_DIRECTION]) if overturned else None,
        impact_times=log[:n_log, codes.LOG_T].tolist(),
        omega_after=log[:n_log, codes.LOG_OMEGA].tolist(),
        impact_slipped=[bool(int(f) & codes.SLIPPED) for f in log[:n_log, codes.LOG_FLAGS]],
        impact_count=impacts, impact_log_truncated=n_log < impacts,
        max_abs_theta=float(res[codes.R_MAX_ABS_THETA]),
        t_rest=_nan_to_none(res[codes.R_T_REST]),
        mode_time={name: float(res[codes.R_MODE_TIME + m])
                   for m, name in enumerate(codes.MODE_NAMES)},
        max_slip=float(res[codes.R_MAX_SLIP]), max_travel=float(res[codes.R_MAX_TRAVEL]),
        max_lift=float(res[codes.R_MAX_LIFT]),
        steps=int(res[codes.R_STEPS]), events=int(res[codes.R_EVENTS]),
        energy_clamps=clamps, t_final=float(res[codes.R_T_END]),
        f_at_overturn=_nan_to_none(res[codes.R_F_AT_OVERTURN]),
        a_at_overturn=_nan_to_none(res[codes.R_A_AT_OVERTURN]),
        v_at_overturn=_nan_to_none(res[codes.R_V_AT_OVERTURN]),
        cpu_s=cpu,
        history={name: hist[:n_h, j].copy() for j, name in enumerate(codes.HISTORY_NAMES)}
        if history else None)


def run_cells(rows, rec, budget=None):
    """Run a chunk of scene rows (shape (n, N_PAR)) in one compiled call: (n, N_RES).

    ``budget``: seconds of wall time a cell may run before a watchdog thread stops it with
    status ``TIME_BUDGET`` (the next cell then starts); None or 0: no limit.
    """
    from .driver import run_cells as _run_cells
    rows = np.ascontiguousarray(rows, dtype=np.float64)
    if rows.ndim != 2 or rows.shape[1] != codes.N_PAR:
        raise ValueError(f"`rows` must have shape (n, {codes.N_PAR}), got {rows.shape}")
    if budget is not None and not budget >= 0:
        raise ValueError(f"`budget` must be None or >= 0 seconds, got {budget!r}")
    rec = np.ascontiguousarray(rec, dtype=np.float64)
    results = np.zeros((rows.shape[0], codes.N_RES))
    ctl = control()
    with Watchdog(ctl, budget):
        _run_cells(as_records(rows), rec, results, ctl)
    return results


def not_run(n, status=codes.INVALID_SCENE):
    """Result rows (n, N_RES) of scenes that never ran: ``status``, no impacts, steps or
    events, no overturning direction, NaN for every other result."""
    results = np.full((n, codes.N_RES), np.nan)
    results[:, codes.R_STATUS] = status
    for index in (codes.R_DIRECTION, codes.R_IMPACTS, codes.R_STEPS, codes.R_EVENTS,
                  codes.R_ENERGY_CLAMPS):
        results[:, index] = 0.0
    return results
