"""Intensity measures of the horizontal motion a cell applies, from its resolved component.

Records and synthetic motions: the measures of the accelerogram
(:mod:`sweep.groundmotion.intensity`, computed once per record) times the magnitude of the
scale.  Analytic motions: the peaks of the steady motion the kernel applies, in closed form
(a sinusoid of acceleration amplitude A at omega = 2 pi f has velocity and displacement
amplitudes A/omega and A/omega^2; a sweep takes the largest over its frequency range; a pulse
of length T changes the floor velocity by A T, or A T/2 for the triangle, after which the floor
drifts, so its PGD is NaN).  The significant duration is that of accelerograms only.
"""
import math
from collections import namedtuple

from kernels.api import DEFAULTS

Peaks = namedtuple("Peaks", "pga pgv pgd d5_95")
Peaks.__doc__ = """PGA [m/s^2], PGV [m/s], PGD [m] and 5-95 % duration [s] of one motion."""
NAN = float("nan")
_HOLD_POWER = {"acceleration": 0, "velocity": 1, "displacement": 2}  # A = amplitude omega^k


def _sinusoid(acceleration, omega):
    return Peaks(acceleration, acceleration / omega, acceleration / omega ** 2, NAN)


def _sweep(ground):
    """Largest amplitudes over the frequencies of a sweep holding one of them."""
    k = _HOLD_POWER[ground.get("hold", DEFAULTS["ground"]["hold"])]
    held = abs(ground["amplitude"])
    omegas = [2.0 * math.pi * ground[key] for key in ("f_start", "f_stop")]
    # the amplitude of order j (acceleration 0, velocity 1, displacement 2) is held * omega^(k-j)
    peak = [max(held * w ** (k - j) for w in omegas) for j in range(3)]
    return Peaks(*peak, NAN)


def peaks(ground):
    """:class:`Peaks` of a resolved horizontal component (``io.scene_schema.resolve_scene``)."""
    kind = ground["kind"]
    if kind == "none":
        return Peaks(0.0, 0.0, 0.0, NAN)
    if kind == "sine":
        return _sinusoid(abs(ground["amplitude"]), 2.0 * math.pi * ground["frequency"])
    if kind == "sweep":
        return _sweep(ground)
    if kind == "pulse":
        a, T = abs(ground["amplitude"]), ground["duration"]
        return Peaks(a, a * T * (0.5 if ground["shape"] == "triangular" else 1.0), NAN, NAN)
    measured, scale = ground["source"].intensity, abs(ground["scale"])
    return Peaks(measured.pga * scale, measured.pgv * scale, measured.pgd * scale,
                 measured.d5_95)
