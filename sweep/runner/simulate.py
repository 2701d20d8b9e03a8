"""One scene from Python: ``simulate(scene)`` takes a file path or a dict of the scene schema.

The result carries the JSON fields of docs/design.md section 4 as attributes and, when asked, the
history as an xarray Dataset (``cf.history_dataset``).
"""
import math
from collections import namedtuple

from kernels.api import MAX_LOG, SceneResult

from ..bodies import G, describe, slenderness
from ..groundmotion import applied
from ..io.plausibility import scene_doubts
from ..io.problems import FileProblems, Problem, warn
from ..io.records import floor_provenance
from ..io.scene_schema import MAX_HISTORY, load_scene, resolve_scene
from .verdict import fall_side, verdict

# The keys of docs/design.md section 4 that scripts read: every one is in the JSON.
JSON_KEYS = ("status", "overturned", "t_overturn", "overturn_direction", "impact_times",
             "omega_after", "max_abs_theta", "t_rest", "mode_time", "max_slip", "max_lift",
             "steps", "cpu_s")
MOTION_KEYS = ("pga", "pgv", "pgd")
# The JSON's order: the verdict and the numbers that sum the scene up, then the per-impact arrays.
SUMMARY_KEYS = ("status", "overturned", "t_overturn", "overturn_direction", "overturn_towards",
                "message", "max_abs_theta", "alpha", "body", "max_slip", "max_travel", "max_lift",
                *MOTION_KEYS, "t_rest", "mode_time", "impact_count", "impact_log_truncated",
                "energy_clamps", "steps", "cpu_s")
IMPACT_KEYS = ("impact_times", "omega_after", "impact_slipped")
PROVENANCE_KEY = "provenance"  # after the summary keys: how each record file was read

Result = namedtuple("Result", SceneResult._fields + MOTION_KEYS
                    + ("B", "H", "alpha", "body", "overturn_towards", PROVENANCE_KEY, "on_floor",
                       "isolator", "restraint"))
Result.__doc__ = """The kernel's ``SceneResult``, the peaks of the horizontal motion applied:
``pga`` [m/s^2], ``pgv`` [m/s], ``pgd`` [m] (``sweep.groundmotion.applied``), the body:
breadth ``B`` and height ``H`` [m], slenderness angle ``alpha`` = atan(B/H) [rad] (the
smaller side's with G off the middle), the ``body`` in both forms (``bodies.describe``),
``overturn_towards``: the way the body fell, ``"-x"`` (to the left, ``overturn_direction``
+1) or ``"+x"``, None when it stands (``verdict.fall_side``), the ``provenance`` of each
floor component that is a record (``records.floor_provenance``), and ``on_floor``: True when
the horizontal motion is a building's floor (``kind: floor``; its peaks are the floor's),
``isolator``: on an isolated platform (``kind: isolated``; its peaks are the platform's), the
isolator's ``max_displacement`` [m], ``capacity`` [m] and ``exceeded``
(``sweep.io.floors.resolve_isolated``), else None; ``restraint``: for a restrained body
(docs/anchors.md), its ``kind``, ``strength`` [N], ``broken`` (whether it gave way) and
``t_broken`` [s] (None when it held), else None."""


def simulate(scene, history=False, max_log=MAX_LOG):
    """Run one scene (path or dict, units as in scene files) and return a :data:`Result`.

    With ``history=True`` the result's ``history`` is an ``xarray.Dataset`` sampled every
    ``solver.dt_out`` seconds (its ``source`` attribute names the scene file, if any, and
    ``body_form`` how the body was given: ``rectangle`` or ``rock``).
    The result lists the first ``max_log`` impacts and counts them all.

    Values that are likely not what was meant (``B: 30``, a bare number in m) are warned of
    as ``InputWarning`` s (``sweep.io.plausibility``).

    Raises
    ------
    FileProblems
        Every problem of the scene, with dotted paths (nothing is run); with ``history``, a
        history of more than ``MAX_HISTORY`` samples too.
    """
    from kernels import run_scene
    checked = load_scene(scene)
    resolved = resolve_scene(checked)
    warn(scene_doubts(checked, resolved))
    if history:
        _check_history(resolved, None if isinstance(scene, dict) else scene)
    motion = applied.peaks(resolved["excitation"]["horizontal"])
    body = resolved["body"]
    B, H = body["B"], body["H"]
    ran = run_scene(resolved, history=history, max_log=max_log)
    alpha = math.atan2(B, H) if body["G"] is None else float(slenderness(B, H, body["G"]))
    result = Result(*ran, *motion[:3], B, H, alpha, describe(B, H, body["G"], body["i_g"]),
                    fall_side(ran.overturn_direction), floor_provenance(resolved["excitation"]),
                    checked.excitation.horizontal.kind == "floor",
                    resolved["excitation"]["horizontal"].get("isolator"),
                    _restraint(resolved.get("restraint"), ran))
    if history:
        from ..cf import history_dataset
        source = None if isinstance(scene, dict) else str(scene)
        result = result._replace(history=history_dataset(result.history, resolved, source,
                                                         result))
        result.history.attrs["body_form"] = checked.body.form  # how the plots draw it
    return result


def _restraint(restraint, ran):
    """The ``restraint`` of a :data:`Result`: the scene's, with what became of it in ``ran``
    (the kernel's ``SceneResult``); None without one."""
    if restraint is None:
        return None
    return {**restraint, "broken": ran.restraint_broken, "t_broken": ran.t_broken}


def _check_history(resolved, source):
    """Refuse a history too long to hold (``t_end / dt_out`` samples)."""
    solver = resolved["solver"]
    samples = solver["t_end"] / solver["dt_out"]
    if samples > MAX_HISTORY:
        raise FileProblems([Problem("solver.dt_out", solver["dt_out"],
                                    f"a history over t_end = {solver['t_end']:g} s every "
                                    f"{solver['dt_out']:g} s has {samples:.3g} samples, more "
                                    f"than {MAX_HISTORY}: give a larger dt_out")], source)


def summary(result):
    """Two lines: what the body did (``verdict.verdict``), then the end status with its
    message, the peaks of the horizontal motion (``floor PGA`` on a building's floor, ``PGA``
    on the ground, ``platform PGA`` on an isolator) and the CPU time; for a restrained body a
    third line, :func:`_restraint_line`."""
    where = "platform " if result.isolator else "floor " if result.on_floor else ""
    floor = (f"{where}PGA {result.pga / G:.3g} g, PGV {result.pgv * 100:.3g} cm/s"
             if result.pga > 0 else "horizontal floor still")
    return (f"{verdict(result._asdict())}\n{result.status}: {result.message}; {floor}; "
            f"cpu {result.cpu_s * 1e3:.2f} ms" + _restraint_line(result.restraint))


def _restraint_line(restraint):
    """A third line for a restrained body: whether its anchor held or broke, and when; else
    ''."""
    if restraint is None:
        return ""
    said = (f"broke at t = {restraint['t_broken']:.6g} s" if restraint["broken"]
            else "held throughout")
    return f"\n{restraint['kind']} of strength {restraint['strength']:g} N: {said}"


def to_json_dict(result):
    """The JSON of a scene, in the order of ``SUMMARY_KEYS`` then ``IMPACT_KEYS``: the contract
    of docs/design.md section 4 (``JSON_KEYS``) plus the end status message, the slenderness angle,
    the impact count (``impact_times`` holds the first ``impact_count`` impacts only when
    ``impact_log_truncated``), the impacts whose restitution was clamped, the peaks of the
    horizontal motion applied, how each record was read (``provenance``: reader, unit and
    where it came from, dt, samples, header), whether each impact slipped, on an isolated
    platform the ``isolator`` and for a restrained body the ``restraint``."""
    out = {key: getattr(result, key) for key in SUMMARY_KEYS + (PROVENANCE_KEY,) + IMPACT_KEYS}
    extras = {key: getattr(result, key) for key in ("isolator", "restraint")}
    return {**out, **{key: value for key, value in extras.items() if value is not None}}
