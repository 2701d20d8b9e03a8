"""One scene from Python: ``simulate(scene)`` takes a file path or a dict of the scene schema.

The result carries the JSON fields of DESIGN.md section 4 as attributes and, when asked, the
history as an xarray Dataset (``cf.history_dataset``).
"""
from collections import namedtuple

from kernels.api import MAX_LOG, SceneResult

from ..groundmotion import applied
from ..io.problems import FileProblems, Problem
from ..io.scene_schema import load_scene, resolve_scene

MAX_HISTORY = 2_000_000  # samples of a history (about 200 MB): t_end / dt_out at most this

JSON_KEYS = ("status", "overturned", "t_overturn", "overturn_direction", "impact_times",
             "omega_after", "max_abs_theta", "t_rest", "mode_time", "max_slip", "max_lift",
             "steps", "cpu_s")
MOTION_KEYS = ("pga", "pgv", "pgd")

Result = namedtuple("Result", SceneResult._fields + MOTION_KEYS)
Result.__doc__ = """The kernel's ``SceneResult`` and the peaks of the horizontal motion applied:
``pga`` [m/s^2], ``pgv`` [m/s], ``pgd`` [m] (``sweep.groundmotion.applied``)."""


def simulate(scene, history=False, max_log=MAX_LOG):
    """Run one scene (path or dict, units as in scene files) and return a :data:`Result`.

    With ``history=True`` the result's ``history`` is an ``xarray.Dataset`` sampled every
    ``solver.dt_out`` seconds (its ``source`` attribute names the scene file, if any).
    The result lists the first ``max_log`` impacts and counts them all.

    Raises
    ------
    FileProblems
        Every problem of the scene, with dotted paths (nothing is run); with ``history``, a
        history of more than ``MAX_HISTORY`` samples too.
    """
    from kernels import run_scene
    resolved = resolve_scene(load_scene(scene))
    if history:
        _check_history(resolved, None if isinstance(scene, dict) else scene)
    motion = applied.peaks(resolved["excitation"]["horizontal"])
    result = Result(*run_scene(resolved, history=history, max_log=max_log), *motion[:3])
    if history:
        from ..cf import history_dataset
        source = None if isinstance(scene, dict) else str(scene)
        result = result._replace(history=history_dataset(result.history, resolved, source,
                                                         result))
    return result


def _check_history(resolved, source):
    """Refuse a history too long to hold (``t_end / dt_out`` samples)."""
    solver = resolved["solver"]
    samples = solver["t_end"] / solver["dt_out"]
    if samples > MAX_HISTORY:
        raise FileProblems([Problem("solver.dt_out", solver["dt_out"],
                                    f"a history over t_end = {solver['t_end']:g} s every "
                                    f"{solver['dt_out']:g} s has {samples:.3g} samples, more "
                                    f"than {MAX_HISTORY}: give a larger dt_out")], source)


def summary_line(result):
    """One line on what the body did: status, impacts, largest rotation, CPU time."""
    return (f"{result.status}: {result.message}; {result.impact_count} impacts, "
            f"max |theta| {result.max_abs_theta:.4g} rad, cpu {result.cpu_s * 1e3:.2f} ms")


def to_json_dict(result):
    """The JSON contract of DESIGN.md section 4, plus the end status message, the impact
    count (``impact_times`` holds the first ``impact_count`` impacts only when
    ``impact_log_truncated``), the impacts whose restitution was clamped, and the peaks of the
    horizontal motion applied."""
    out = {key: getattr(result, key) for key in JSON_KEYS}
    for key in ("message", "impact_slipped", "impact_count", "impact_log_truncated",
                "energy_clamps", *MOTION_KEYS):
        out[key] = getattr(result, key)
    return out
