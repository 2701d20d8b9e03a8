"""A floor of a scene (``kind: floor``) resolved into the record the kernel reads.

The building's modes (``sweep.groundmotion.floor``) filter the resolved ground: a record or a
synthetic motion through the exact recursion, a sine through its closed form, a sweep or a
pulse sampled finely through the recursion, each computed
once per ground and building at scale 1 (the building is linear), so the record's ``scale`` is
the ground's scale or the sine's amplitude.  The floor starts with its ground and rings down
after it (docs/floors.md).
"""
import math

from ..groundmotion.floor import (Mode, floor_of_motion, floor_of_record, floor_of_sine,
                                  shear_beam_modes)


def modes(building):
    """The :class:`~sweep.groundmotion.floor.Mode` s of a checked ``Building`` (SI)."""
    damping = building.damping
    if isinstance(building.modes, list):
        return tuple(Mode(m.period.to_si(), damping if m.damping is None else m.damping,
                          float(m.participation)) for m in building.modes)
    return shear_beam_modes(building.period.to_si(), damping, building.height_ratio,
                            building.modes)


def resolve_floor(building, ground, t_end):
    """Resolved SI dict of a floor: a record (kernels/api.py) with ``ground``, the resolved
    ground, and ``modes``; a floor over a ground that never ends is computed up to ``t_end``."""
    if ground["kind"] == "none":
        return ground
    found = modes(building)
    if ground["kind"] == "sine":
        duration = math.inf if ground["duration"] is None else ground["duration"]
        span = 0.0 if math.isfinite(duration) else max(t_end - ground["start"], 0.0)
        source = floor_of_sine(ground["frequency"], ground["phase"], duration, span, found)
        scale = ground["amplitude"]
    elif ground["kind"] in ("sweep", "pulse"):
        unit = {key: value for key, value in ground.items() if key != "amplitude"}
        source = floor_of_motion(tuple(sorted({**unit, "amplitude": 1.0, "start": 0.0}.items())),
                                 found)
        scale = ground["amplitude"]
    else:
        source = floor_of_record(ground["source"], found, ground["duration"])
        scale = ground["scale"]
    return {"kind": "record", "start": ground["start"], "duration": None,
            "samples": source.samples, "dt": source.dt, "scale": scale, "source": source,
            "ground": ground, "modes": found}
