"""One scene from Python: ``simulate(scene)`` takes a file path or a dict of the scene schema.

The result carries the JSON fields of DESIGN.md section 4 as attributes and, when asked, the
history as an xarray Dataset (``cf.history_dataset``).
"""
from kernels.api import MAX_LOG

from ..io.scene_schema import load_scene, resolve_scene

JSON_KEYS = ("status", "overturned", "t_overturn", "overturn_direction", "impact_times",
             "omega_after", "max_abs_theta", "t_rest", "mode_time", "max_slip", "max_lift",
             "steps", "cpu_s")


def simulate(scene, history=False, max_log=MAX_LOG):
    """Run one scene (path or dict, units as in scene files) and return a ``SceneResult``.

    With ``history=True`` the result's ``history`` is an ``xarray.Dataset`` sampled every
    ``solver.dt_out`` seconds (its ``source`` attribute names the scene file, if any).
    The result lists the first ``max_log`` impacts and counts them all.

    Raises
    ------
    FileProblems
        Every problem of the scene, with dotted paths (nothing is run).
    """
    from kernels import run_scene
    resolved = resolve_scene(load_scene(scene))
    result = run_scene(resolved, history=history, max_log=max_log)
    if history:
        from ..cf import history_dataset
        source = None if isinstance(scene, dict) else str(scene)
        result = result._replace(history=history_dataset(result.history, resolved, source,
                                                         result))
    return result


def summary_line(result):
    """One line on what the body did: status, impacts, largest rotation, CPU time."""
    return (f"{result.status}: {result.message}; {result.impact_count} impacts, "
            f"max |theta| {result.max_abs_theta:.4g} rad, cpu {result.cpu_s * 1e3:.2f} ms")


def to_json_dict(result):
    """The JSON contract of DESIGN.md section 4, plus the end status message, the impact
    count (``impact_times`` holds the first ``impact_count`` impacts only when
    ``impact_log_truncated``) and the impacts whose restitution was clamped."""
    out = {key: getattr(result, key) for key in JSON_KEYS}
    for key in ("message", "impact_slipped", "impact_count", "impact_log_truncated",
                "energy_clamps"):
        out[key] = getattr(result, key)
    return out
