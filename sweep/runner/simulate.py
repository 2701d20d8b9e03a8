"""One scene from Python: ``simulate(scene)`` takes a file path or a dict of the scene schema.

The result carries the JSON fields of DESIGN.md section 4 as attributes and, when asked, the
history as an xarray Dataset (``cf.history_dataset``).
"""
from ..io.scene_schema import load_scene, resolve_scene

JSON_KEYS = ("status", "overturned", "t_overturn", "overturn_direction", "impact_times",
             "omega_after", "max_abs_theta", "t_rest", "mode_time", "max_slip", "max_lift",
             "steps", "cpu_s")


def simulate(scene, history=False):
    """Run one scene (path or dict, units as in scene files) and return a ``SceneResult``.

    With ``history=True`` the result's ``history`` is an ``xarray.Dataset`` sampled every
    ``solver.dt_out`` seconds (its ``source`` attribute names the scene file, if any).

    Raises
    ------
    FileProblems
        Every problem of the scene, with dotted paths (nothing is run).
    """
    from kernels import run_scene
    resolved = resolve_scene(load_scene(scene))
    result = run_scene(resolved, history=history)
    if history:
        from ..cf import history_dataset
        source = None if isinstance(scene, dict) else str(scene)
        result = result._replace(history=history_dataset(result.history, resolved, source))
    return result


def summary_line(result):
    """One line on what the body did: status, impacts, largest rotation, CPU time."""
    return (f"{result.status}: {result.message}; {len(result.impact_times)} impacts, "
            f"max |theta| {result.max_abs_theta:.4g} rad, cpu {result.cpu_s * 1e3:.2f} ms")


def to_json_dict(result):
    """The JSON contract of DESIGN.md section 4 (plus the end status message)."""
    out = {key: getattr(result, key) for key in JSON_KEYS}
    out["message"] = result.message
    out["impact_slipped"] = result.impact_slipped
    out["energy_clamps"] = result.energy_clamps
    return out
