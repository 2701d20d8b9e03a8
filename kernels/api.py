"""Python face of the kernel: check and pack a scene, allocate outputs, call, unpack.

A *resolved scene* is a plain nested dict in SI units (what ``sweep.schema`` produces from a
YAML file, or what a notebook writes by hand)::

    {"body": {"B": 0.1, "H": 0.3, "i_g": None, "G": None,  # i_g: radius of gyration about G
              "mass": None},                # G: [x_G, y_G] from the middle of the base; kg
     "contact": {"mu_s", "mu_k", "mu_edge_s", "mu_edge_k", "e_x", "e_y",
                 "landing": "face_friction" | "flat" | "corner"},
     "excitation": {"horizontal": GROUND, "vertical": GROUND},
     "restraint": None | {"kind": "anchor", "strength": N},   # needs body.mass
     "initial": {"theta", "omega", "x_dot", "y_dot", "lift"},
     "solver": {"method": "adaptive" | "fixed", "rtol", "atol", "dt", "max_step", "t_end",
                "max_steps", "max_events", "theta_overturn", "zeno_dt", "dt_out"}}

GROUND is ``{"kind": "none"}`` or, with optional ``start`` [s] and ``duration`` [s or None]:
``{"kind": "sine", "amplitude": m/s^2, "frequency": Hz, "phase": rad}``,
``{"kind": "sweep", "hold": "acceleration"|"velocity"|"displacement", "amplitude": SI of the
held quantity, "f_start": Hz, "f_stop": Hz, "duration": s, "law": "log"|"linear", "phase": rad}``,
``{"kind": "record", "samples": ndarray m/s^2, "dt": s, "scale": 1.0}``,
``{"kind": "pulse", "shape": "rectangular"|"triangular", "amplitude": m/s^2, "duration": s}``.
Missing keys take the values of ``DEFAULTS``.  An anchored body starts flat at rest
(docs/anchors.md).  Sign convention: x and a_x positive to the right, theta > 0 is rotation
about the left corner (docs/physics.md section 1.1).
"""
import math
import time
from collections import namedtuple

import numpy as np

from . import codes
from .record_cache import RecordCache
from .watchdog import Watchdog, control

DEFAULTS = {
    "body": {"i_g": None, "G": None, "mass": None},
    "contact": {"mu_s": 0.4, "mu_k": 0.3, "mu_edge_s": 0.4, "mu_edge_k": 0.3,
                "e_x": -0.8, "e_y": 0.2, "landing": "face_friction"},
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
# scene and result records whose items are read by field name (``row.body.B``), as in np.recarray
_SCENE_RECORD = np.dtype((np.record, codes.SCENE_DTYPE))
_RESULT_RECORD = np.dtype((np.record, codes.RESULT_DTYPE))


def _merged(scene, section):
    out = dict(DEFAULTS.get(section, {}))
    out.update(scene.get(section) or {})
    return out


class PackingError(ValueError):
    """A value of a resolved scene that the kernel cannot take: ``path`` is its dotted path
    (``"excitation.horizontal.frequency"``), ``reason`` what is wrong with it; the message
    is the two together, the path in backticks."""

    def __init__(self, path, reason):
        super().__init__(f"`{path}` {reason}")
        self.path = path
        self.reason = reason


def _number(value, path, positive=False):
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise PackingError(path, f"must be a number, got {value!r}") from None
    if not math.isfinite(x) or (positive and not x > 0.0):
        raise PackingError(path, f"must be a {'positive ' if positive else ''}finite "
                                 f"number, got {value!r}")
    return x


def place_record(samples, records):
    """Offset of ``samples`` in the shared buffer of some scene rows.

    ``records`` is the list of sample arrays of a chunk of scene rows (the buffer is
    ``record_buffer(records)``): ``samples`` is appended to it unless the same array is there
    already, so that a record used by many rows is stored once; or a study's
    ``record_cache.RecordCache``, which places it itself (its ``buffer()``)."""
    if isinstance(records, RecordCache):
        return records.place(samples)
    offset = 0
    for stored in records:
        if stored is samples:
            return offset
        offset += stored.size
    records.append(samples)
    return offset


def _ground_fields(spec, path, records):
    """The fields of one ground component (``codes.GROUND_DTYPE``) that it sets, by name (the
    others stay zero); record samples are placed in ``records`` (``place_record``)."""
    spec = {**DEFAULTS["ground"], **(spec or {"kind": "none"})}
    kind = spec.get("kind", "none")
    if kind == "pulse":
        shape = spec.get("shape", "rectangular")
        if shape not in _SHAPES:
            raise PackingError(f"{path}.shape", f"must be one of {sorted(_SHAPES)}, "
                                                f"got {shape!r}")
        g = {"kind": _SHAPES[shape]}
    elif kind in _KINDS:
        g = {"kind": _KINDS[kind]}
    else:
        raise PackingError(f"{path}.kind", f"must be one of {sorted([*_KINDS, 'pulse'])}, "
                                           f"got {kind!r}")
    if kind == "none":
        return g
    duration = spec.get("duration")
    g["start"] = _number(spec.get("start", 0.0), f"{path}.start")
    g["dur"] = math.inf if duration is None else _number(duration, f"{path}.duration",
                                                         positive=True)
    g["phase"] = _number(spec.get("phase", 0.0), f"{path}.phase")
    if kind == "sine":
        g["amp"] = _number(spec["amplitude"], f"{path}.amplitude")
        g["freq"] = _number(spec["frequency"], f"{path}.frequency", positive=True)
    elif kind == "sweep":
        g["amp"] = _number(spec["amplitude"], f"{path}.amplitude")
        f0 = g["f0"] = _number(spec["f_start"], f"{path}.f_start", positive=True)
        f1 = g["f1"] = _number(spec["f_stop"], f"{path}.f_stop", positive=True)
        if duration is None:
            raise PackingError(f"{path}.duration", "is required for a sweep")
        g["law"] = _LAWS[spec.get("law", "log")]
        g["freq"] = (math.log(f1 / f0) if g["law"] == codes.LAW_LOG else f1 - f0) / g["dur"]
        g["hold"] = _HOLDS[spec.get("hold", "acceleration")]
    elif kind == "record":
        samples = np.ascontiguousarray(spec["samples"], dtype=np.float64)
        if samples.ndim != 1:
            samples = samples.ravel()
        if samples.size < 2 or not np.all(np.isfinite(samples)):
            raise PackingError(f"{path}.samples", "must hold at least two finite values")
        g["amp"] = _number(spec.get("scale", 1.0), f"{path}.scale")
        g["rec_dt"] = _number(spec["dt"], f"{path}.dt", positive=True)
        g["rec_off"] = place_record(samples, records)
        g["rec_n"] = samples.size
    else:  # pulse
        g["amp"] = _number(spec["amplitude"], f"{path}.amplitude")
        if duration is None:
            raise PackingError(f"{path}.duration", "is required for a pulse")
    return g


def centre(body):
    """(x_G, y_G) [m] of a resolved body, from the middle of its base: its ``G``, default
    (0, H/2).  A PackingError when G is not strictly inside the body (docs/bodies.md)."""
    if body.get("G") is None:
        return 0.0, body["H"] / 2
    try:
        x, y = body["G"]
    except (TypeError, ValueError):
        raise PackingError("body.G", f"must be two numbers [x, y], got {body['G']!r}") from None
    x, y = _number(x, "body.G"), _number(y, "body.G")
    B, H = float(body["B"]), float(body["H"])
    if not (abs(x) < B / 2 and 0.0 < y < H):
        raise PackingError("body.G", f"must lie inside the body, |x| < B/2 = {B / 2:g} m and "
                                     f"0 < y < H = {H:g} m, got [{x:g}, {y:g}]")
    return x, y


def scene_rows(n):
    """n zeroed scene records (``codes.SCENE_DTYPE``), read and written by field name."""
    return np.zeros(n, codes.SCENE_DTYPE).view(np.recarray)


def _field_paths(dtype, prefix=""):
    """Dotted paths of the fields of a structured dtype (``"floor.x.amp"``), in memory order;
    a TypeError unless the dtype is float64 fields one after the other (then an array of
    those floats, in that order, is a record of it)."""
    paths = []
    for name in dtype.names:
        if dtype[name].names:
            paths += _field_paths(dtype[name], f"{prefix}{name}.")
        elif dtype[name] == np.float64:
            paths.append(prefix + name)
    if dtype.itemsize != 8 * len(paths):
        raise TypeError(f"{dtype} is not float64 fields one after the other")
    return paths


_ZERO_ROW = dict.fromkeys(_field_paths(codes.SCENE_DTYPE), 0.0)  # field path -> value
# (key of the resolved scene, its path there, the field of the scene record)
_FRICTION = tuple((key, f"contact.{key}", f"contact.{key}")
                  for key in ("mu_s", "mu_k", "mu_edge_s", "mu_edge_k"))
_INITIAL = tuple((key, f"initial.{key}", f"initial.{field}") for key, field in (
    ("theta", "theta"), ("omega", "omega"), ("x_dot", "u"), ("y_dot", "v"), ("lift", "lift")))
_SOLVER = tuple((key, f"solver.{key}", f"solver.{field}") for key, field in (
    ("rtol", "rtol"), ("atol", "atol"), ("dt", "dt"), ("max_step", "max_step"),
    ("t_end", "t_end"), ("max_steps", "max_steps"), ("max_events", "max_events"),
    ("theta_overturn", "theta_over"), ("zeno_dt", "zeno_dt"), ("dt_out", "dt_out")))


def scene_row(scene, records=None):
    """Pack a resolved scene into a record of ``codes.SCENE_DTYPE``.

    ``records`` is the list of record sample arrays shared by the rows of a chunk, or a
    study's ``record_cache.RecordCache``: the scene's records are placed in it
    (``place_record``: a record already there is not stored again) and the row's ``rec_off``
    point into ``record_buffer(records)`` (the cache's ``buffer()``).

    Raises
    ------
    PackingError
        A value the kernel cannot take, with its dotted path.
    """
    records = [] if records is None else records
    body = _merged(scene, "body")
    contact = _merged(scene, "contact")
    initial = _merged(scene, "initial")
    solver = _merged(scene, "solver")
    excitation = scene.get("excitation") or {}
    row = dict(_ZERO_ROW)
    B = row["body.B"] = _number(body.get("B"), "body.B", positive=True)
    H = row["body.H"] = _number(body.get("H"), "body.H", positive=True)
    b, h = B / 2, H / 2
    i_g = body.get("i_g")
    row["body.i2"] = (b * b + h * h) / 3 if i_g is None else \
        _number(i_g, "body.i_g", positive=True) ** 2
    row["body.x_g"], row["body.y_g"] = centre(body)
    for key, path, field in _FRICTION:
        value = row[field] = _number(contact[key], path)
        if value < 0:
            raise PackingError(path, f"must be >= 0, got {contact[key]!r}")
    e_x = row["contact.e_x"] = _number(contact["e_x"], "contact.e_x")
    e_y = row["contact.e_y"] = _number(contact["e_y"], "contact.e_y")
    if not -1 <= e_x <= 1 or not 0 <= e_y <= 1:
        raise PackingError("contact.e_x", "must lie in [-1, 1] and `contact.e_y` in [0, 1]")
    if contact["landing"] not in codes.LANDING_NAMES:
        raise PackingError("contact.landing", f"must be one of {codes.LANDING_NAMES}, "
                                              f"got {contact['landing']!r}")
    row["contact.landing"] = codes.LANDING_NAMES.index(contact["landing"])
    for key, path, field in _INITIAL:
        row[field] = _number(initial[key], path)
    method = solver["method"]
    if method not in codes.METHOD_NAMES:
        raise PackingError("solver.method", f"must be one of {codes.METHOD_NAMES}, "
                                            f"got {method!r}")
    row["solver.method"] = codes.METHOD_NAMES.index(method)
    for key, path, field in _SOLVER:
        row[field] = _number(solver[key], path, positive=True)
    for axis, component in (("x", "horizontal"), ("y", "vertical")):
        ground = _ground_fields(excitation.get(component), f"excitation.{component}", records)
        row.update({f"floor.{axis}.{name}": value for name, value in ground.items()})
    row.update(_restraint_fields(scene.get("restraint"), body, initial))
    return np.frombuffer(np.fromiter(row.values(), np.float64), _SCENE_RECORD)[0]


def _restraint_fields(restraint, body, initial):
    """The ``restraint`` fields of a scene row: its kind and the strength of a tie per unit
    mass, T/m (docs/anchors.md)."""
    if not restraint:
        return {}
    if restraint.get("kind") != "anchor":
        raise PackingError("restraint.kind", f"must be 'anchor', got {restraint.get('kind')!r}")
    strength = _number(restraint.get("strength"), "restraint.strength")
    if strength < 0:
        raise PackingError("restraint.strength", f"must be >= 0, got {strength!r}")
    if body.get("mass") is None:
        raise PackingError("body.mass", "is required by an anchor (its strength is a force)")
    mass = _number(body["mass"], "body.mass", positive=True)
    if any(initial[key] != 0 for key, _, _ in _INITIAL):
        raise PackingError("initial", "must be rest, flat on the floor, for an anchored body")
    return {"restraint.kind": float(codes.RESTRAINT_ANCHOR), "restraint.tie": strength / mass}


def as_records(rows):
    """Scene rows (records of ``codes.SCENE_DTYPE``, any number of them, or one) as a
    C-contiguous one-dimensional recarray: compiled code and plain Python read them by
    name (``row.body.B``).  A ValueError names ``rows`` when they are not such records."""
    rows = np.asarray(rows)
    if rows.dtype.names != codes.SCENE_DTYPE.names:
        raise ValueError(f"`rows` must be records of codes.SCENE_DTYPE, got dtype {rows.dtype}")
    rows = np.ascontiguousarray(rows.reshape(-1).astype(codes.SCENE_DTYPE, copy=False))
    return rows.view(np.recarray)


def record_buffer(records):
    """Concatenate record sample arrays into the shared buffer (never empty)."""
    if not records:
        return np.zeros(1)
    return np.ascontiguousarray(np.concatenate(records), dtype=np.float64)


SceneResult = namedtuple("SceneResult", [
    "status", "message", "overturned", "t_overturn", "overturn_direction", "impact_times",
    "omega_after", "impact_slipped", "impact_count", "impact_log_truncated", "max_abs_theta",
    "t_rest", "mode_time", "max_slip", "max_travel", "max_lift", "steps", "events", "energy_clamps",
    "t_final", "f_at_overturn", "a_at_overturn", "v_at_overturn", "cpu_s", "history",
    "restraint_broken", "t_broken"])
SceneResult.__doc__ = """Result of one scene: the JSON contract of docs/design.md section 4 plus
extras.  ``impact_times``, ``omega_after`` and ``impact_slipped`` hold the first ``max_log``
impacts of ``impact_count`` (``impact_log_truncated`` when fewer); ``history`` is None or a
dict of arrays named by ``codes.HISTORY_NAMES``.  ``max_slip`` is how far the base moved along
the floor (``extremes.footprint``), ``max_travel`` the largest |x - x0| of G, rotation
included.  ``restraint_broken`` is whether a restraint gave way, at ``t_broken`` [s] (None
when it held or there is none)."""


def _nan_to_none(x):
    return x if math.isfinite(x) else None


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
    from .state import WORK_DTYPE
    records = []
    row = scene_row(scene, records)
    rec = record_buffer(records)
    res = np.zeros(1, _RESULT_RECORD)[0]
    log = np.empty((max_log, codes.N_LOG))  # rows [:n_log] are written
    n_hist = int(row.solver.t_end / row.solver.dt_out) + 2 if history else 0
    hist = np.zeros((n_hist, codes.N_HIST))
    work = np.zeros(1, (np.record, WORK_DTYPE))  # the scene's buffers (state.new_work)
    args = (row, rec, res, log, hist, control(cell=0), work[0])
    run = _compiled(_run_scene, args)
    t0 = time.process_time()
    n_log, n_h = run(*args)
    cpu = time.process_time() - t0
    out = dict(zip(codes.RESULT_DTYPE.names, res.item()))  # Python numbers, by field name
    status, impacts, clamps = out["status"], out["impacts"], out["energy_clamps"]
    overturned = status == codes.OVERTURNED
    slipped = log[:n_log, codes.LOG_FLAGS].astype(np.int64) & codes.SLIPPED
    return SceneResult(
        status=codes.STATUS_NAMES[status], message=_message(status, impacts, n_log, clamps),
        overturned=overturned, t_overturn=_nan_to_none(out["t_overturn"]),
        overturn_direction=out["direction"] if overturned else None,
        impact_times=log[:n_log, codes.LOG_T].tolist(),
        omega_after=log[:n_log, codes.LOG_OMEGA].tolist(),
        impact_slipped=slipped.astype(bool).tolist(),
        impact_count=impacts, impact_log_truncated=n_log < impacts,
        max_abs_theta=out["max_abs_theta"], t_rest=_nan_to_none(out["t_rest"]),
        mode_time=dict(zip(codes.MODE_NAMES, out["mode_time"].tolist())),
        max_slip=out["max_slip"], max_travel=out["max_travel"], max_lift=out["max_lift"],
        steps=out["steps"], events=out["events"], energy_clamps=clamps, t_final=out["t_end"],
        f_at_overturn=_nan_to_none(out["f_at_overturn"]),
        a_at_overturn=_nan_to_none(out["a_at_overturn"]),
        v_at_overturn=_nan_to_none(out["v_at_overturn"]),
        cpu_s=cpu, restraint_broken=math.isfinite(out["t_broken"]),
        t_broken=_nan_to_none(out["t_broken"]),
        history={name: hist[:n_h, j].copy() for j, name in enumerate(codes.HISTORY_NAMES)}
        if history else None)


def run_cells(rows, rec, budget=None):
    """Run a chunk of scene rows (n records of ``codes.SCENE_DTYPE``) in one compiled call.

    Returns an array of n records of ``codes.RESULT_DTYPE``.  ``budget``: seconds of wall
    time a cell may run before a watchdog thread stops it with status ``TIME_BUDGET`` (the
    next cell then starts); None or 0: no limit.
    """
    from .driver import run_cells as _run_cells
    rows = as_records(rows)
    if budget is not None and not budget >= 0:
        raise ValueError(f"`budget` must be None or >= 0 seconds, got {budget!r}")
    rec = np.ascontiguousarray(rec, dtype=np.float64)
    results = np.zeros(rows.shape[0], codes.RESULT_DTYPE)
    ctl = control()
    with Watchdog(ctl, budget):
        _run_cells(rows, rec, results.view(np.recarray), ctl)
    return results


def not_run(n, status=codes.INVALID_SCENE):
    """Results (n records of ``codes.RESULT_DTYPE``) of scenes that never ran: ``status``,
    no impacts, steps or events, no overturning direction, NaN for every other result."""
    results = np.zeros(n, codes.RESULT_DTYPE)
    for name in codes.RESULT_DTYPE.names:
        if codes.RESULT_DTYPE[name].base.kind == "f":
            results[name] = np.nan
    results["status"] = status
    return results
