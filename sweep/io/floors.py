"""A floor or an isolated platform of a scene resolved into the record the kernel reads.

The building's modes (``sweep.groundmotion.floor``) filter the resolved ground: a record or a
synthetic motion through the exact recursion, a sine through its closed form, a sweep or a
pulse sampled finely through the recursion, each computed
once per ground and building at scale 1 (the building is linear), so the record's ``scale`` is
the ground's scale or the sine's amplitude.  The floor starts with its ground and rings down
after it (docs/floors.md).  A linear isolator is one mode of participation 1 over the motion
under it, its largest displacement that of the oscillator over the motion under it sampled
(``groundmotion.oscillator``); a friction pendulum (``sweep.groundmotion.isolator``) is not
linear and is computed at the motion's scale (docs/isolation.md).
"""
import math

from functools import lru_cache

import numpy as np

from ..groundmotion import oscillator
from ..groundmotion.floor import (Mode, _Samples, floor_of_motion, floor_of_record,
                                  floor_of_sine, shear_beam_modes)
from ..groundmotion.isolator import Pendulum, response
from ..groundmotion.record import Record


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
    return filtered(modes(building), ground, t_end)


def filtered(found, ground, t_end):
    """Resolved SI dict of the absolute motion of the modes ``found`` over a resolved
    ``ground`` (:func:`resolve_floor`); no flexible mode: the ground sampled as a record."""
    if ground["kind"] == "none":
        return ground
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


@lru_cache(maxsize=256)
def _platform(under, dt, pendulum):
    out = response(under.samples, dt, pendulum)
    out.acceleration.setflags(write=False)
    return out


@lru_cache(maxsize=256)
def _linear_drift(under, dt, period, damping):
    """Largest |u| [m] of a linear isolator (period [s], damping ratio) over the unit motion
    ``under`` sampled every ``dt`` [s], from rest, with one period of still ground after it
    (its free vibration passes its first peak within half a period)."""
    still = np.zeros(math.ceil(period / dt) + 1)
    u, _ = oscillator.response(-np.concatenate([under.samples, still]), dt,
                               2.0 * math.pi / period, damping)
    return float(np.max(np.abs(u)))


def resolve_isolated(isolator, under, t_end):
    """Resolved SI dict of a platform on a checked ``isolator`` over the resolved motion
    ``under`` it: a record (kernels/api.py) with ``ground`` (``under``) and ``isolator``, a
    dict with ``max_displacement`` [m] (the largest displacement relative to ``under``),
    ``capacity`` [m] (None: none given) and ``exceeded``."""
    if under["kind"] == "none":
        return under
    sampled = filtered((), under, t_end)
    if isolator.kind == "linear":
        period = isolator.period.to_si()
        out = filtered((Mode(period, isolator.damping, 1.0),), under, t_end)
        drift = abs(sampled["scale"]) * _linear_drift(_Samples(sampled["samples"]),
                                                      sampled["dt"], period, isolator.damping)
        return {**out, "ground": under, "isolator": {"max_displacement": drift,
                                                     "capacity": None, "exceeded": False}}
    pendulum = Pendulum(isolator.radius.to_si(), float(isolator.mu))
    motion = _platform(_Samples(sampled["scale"] * sampled["samples"]), sampled["dt"], pendulum)
    capacity = (None if isolator.displacement_capacity is None
                else isolator.displacement_capacity.to_si())
    source = Record(name=f"platform over {sampled['source'].name}", dt=motion.dt,
                    samples=motion.acceleration,
                    provenance=f"platform of a friction pendulum {pendulum} over "
                               f"{sampled['source'].name} (stick-slip, closed form)")
    return {"kind": "record", "start": under["start"], "duration": None,
            "samples": source.samples, "dt": source.dt, "scale": 1.0, "source": source,
            "ground": under,
            "isolator": {"max_displacement": motion.max_displacement, "capacity": capacity,
                         "exceeded": capacity is not None and motion.max_displacement > capacity}}
