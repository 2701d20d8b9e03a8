"""The absolute acceleration of a floor of a linear building, from the ground's.

Each mode n of the building (period T_n, damping ratio zeta_n, participation Gamma_n phi_n at
the floor) is a single-degree-of-freedom oscillator driven by the ground,
u_n'' + 2 zeta_n omega_n u_n' + omega_n^2 u_n = -a_g, and the floor moves with

    a_f = a_g + sum_n Gamma_n phi_n u_n''                          (docs/floors.md (F1))

(u_n'' relative to the ground).  A mode of period 0 is rigid: u_n'' = 0.  The building starts
at rest when the ground starts.

* A piecewise-linear ground (a record) is integrated exactly by the recursion of Nigam &
  Jennings (1969), Chopra (2017) section 5.2, Table 5.2.1 (``oscillator.response``): the
  floor is exact at the record's samples and is read, like the ground, linearly between them.  After the ground's last sample
  the ground is still and the building rings down for ``decay_time``.
* A sine is solved in closed form (steady state plus the free vibration that starts the
  building from rest, Chopra 2017 section 3.2), evaluated on a grid fine enough
  (``SAMPLES_PER_PERIOD``) to be read linearly.
* A sweep or a pulse is sampled on such a grid as the kernel applies it
  (``kernels.ground.component``) and integrated exactly as piecewise linear: exact at the
  samples up to the linear reading of the ground between them, O((omega dt)^2).

Default modes (``shear_beam_modes``): those of a uniform shear beam fixed at its base,
phi_n(z) = sin((2n - 1) pi z/2H), T_n = T_1/(2n - 1), Gamma_n = 4/((2n - 1) pi), so that the
first mode's participation is (4/pi) sin(pi z/2H), 1.273 at the top, and the modes' sum is 1
at every height (Chopra 2017; the shear-beam limit of Miranda & Taghavi 2005).

References: Nigam, N.C. & Jennings, P.C. (1969), BSSA 59(2), 909-922.  Chopra, A.K. (2017),
Dynamics of Structures, 5th ed., Pearson.  Miranda, E. & Taghavi, S. (2005), Approximate floor
acceleration demands in multistory buildings, J. Struct. Eng. 131(2), 203-211.
"""
import hashlib
import math
from collections import namedtuple
from functools import lru_cache

import numpy as np

from kernels import api
from kernels._jit import jit
from kernels.ground import component

from .oscillator import response
from .record import Record

Mode = namedtuple("Mode", "period damping participation")
Mode.__doc__ = """A mode: period [s] (0: rigid), damping ratio, participation Gamma phi at the
floor."""
DECAY = 0.01  # the building rings down after the ground until its slowest mode is at 1 %
SAMPLES_PER_PERIOD = 100  # of a sine's floor: read linearly, its peaks within 0.05 %


def shear_beam_modes(period, damping, height_ratio, count=1):
    """The first ``count`` modes of a uniform shear beam of fundamental period ``period`` at
    the height ``height_ratio`` = z/H, each with the damping ratio ``damping``."""
    return tuple(Mode(period / (2 * n - 1), damping,
                      4.0 / ((2 * n - 1) * math.pi)
                      * math.sin((2 * n - 1) * math.pi * height_ratio / 2.0))
                 for n in range(1, count + 1))


def _flexible(modes):
    return [m for m in modes if m.period > 0.0 and m.participation != 0.0]


def decay_time(modes):
    """Time [s] for the free vibration of every mode to fall to ``DECAY`` of its amplitude."""
    rates = [m.damping * 2.0 * math.pi / m.period for m in _flexible(modes)]
    return math.log(1.0 / DECAY) / min(rates) if rates else 0.0


def record_response(samples, dt, modes):
    """Floor acceleration at the samples of a piecewise-linear ground acceleration."""
    ground = np.ascontiguousarray(samples, dtype=np.float64)
    floor = ground.copy()
    for m in _flexible(modes):
        omega, zeta = 2.0 * math.pi / m.period, m.damping
        u, v = response(-ground, dt, omega, zeta)  # u'' = -a_g - 2 zeta omega u' - omega^2 u
        floor += m.participation * (-ground - 2.0 * zeta * omega * v - omega * omega * u)
    return floor


def _free(u0, v0, tau, omega, zeta):
    """Displacement and velocity of the free vibration from (u0, v0) after ``tau``."""
    wd = omega * math.sqrt(1.0 - zeta * zeta)
    e = np.exp(-zeta * omega * tau)
    c1, c2 = u0, (v0 + zeta * omega * u0) / wd
    cos, sin = np.cos(wd * tau), np.sin(wd * tau)
    return (e * (c1 * cos + c2 * sin),
            e * ((c2 * wd - zeta * omega * c1) * cos - (c1 * wd + zeta * omega * c2) * sin))


def sine_response(times, frequency, phase, duration, modes):
    """Floor acceleration at ``times`` [s from the start] under the ground acceleration
    sin(2 pi f t + phase) for 0 <= t < ``duration`` (inf: for ever), from rest."""
    t = np.asarray(times, dtype=np.float64)
    w = 2.0 * math.pi * frequency
    forced = t < duration
    ground = np.where(forced, np.sin(w * t + phase), 0.0)
    floor = ground.copy()
    for m in _flexible(modes):
        omega, zeta = 2.0 * math.pi / m.period, m.damping
        h = 1.0 / (omega * omega - w * w + 2j * zeta * omega * w)   # steady state of -e^{iwt}

        def steady(tau):
            z = -h * np.exp(1j * (w * tau + phase))
            return z.imag, (1j * w * z).imag

        up, vp = steady(np.minimum(t, duration))
        u0, v0 = steady(0.0)
        uh, vh = _free(-u0, -v0, np.minimum(t, duration), omega, zeta)
        u, v = up + uh, vp + vh
        if math.isfinite(duration):
            ue, ve = (x + y for x, y in zip(steady(duration), _free(-u0, -v0, duration, omega,
                                                                     zeta)))
            after = _free(ue, ve, np.maximum(t - duration, 0.0), omega, zeta)
            u, v = np.where(forced, u, after[0]), np.where(forced, v, after[1])
        floor += m.participation * (-ground - 2.0 * zeta * omega * v - omega * omega * u)
    return floor


class _Samples:
    """A sample array hashed by its content: equal grounds share one floor motion."""

    def __init__(self, samples):
        self.samples = samples
        self.key = hashlib.blake2b(np.ascontiguousarray(samples).tobytes(),
                                   digest_size=16).digest()

    def __hash__(self):
        return hash(self.key)

    def __eq__(self, other):
        return self.key == other.key


def _record(name, dt, floor, provenance):
    floor.setflags(write=False)
    return Record(name=name, dt=dt, samples=floor, provenance=provenance)


@lru_cache(maxsize=256)
def _floor_of_samples(ground, dt, modes, name):
    padded = np.concatenate([ground.samples, np.zeros(math.ceil(decay_time(modes) / dt))])
    return _record(f"floor over {name}", dt, record_response(padded, dt, modes),
                   f"floor of a linear building {modes} over {name} (Nigam & Jennings 1969)")


def floor_of_record(record, modes, duration=None):
    """The floor's :class:`Record` over a ground ``record`` (scale 1) cut at ``duration`` [s]
    (None: its end), computed once per ground samples and modes, padded with the building's
    free vibration (``decay_time``)."""
    samples = record.samples
    if duration is not None:  # the ground's last sample at or just after its window's end
        steps = duration / record.dt
        samples = samples[:max(2, (round(steps) if math.isclose(steps, round(steps))
                                   else math.ceil(steps)) + 1)]
    return _floor_of_samples(_Samples(samples), record.dt, tuple(modes), record.name)


@lru_cache(maxsize=256)
def floor_of_sine(frequency, phase, duration, span, modes):
    """The floor's :class:`Record` over a ground sine of unit amplitude (``sine_response``),
    sampled ``SAMPLES_PER_PERIOD`` times per period of the sine or of the shortest mode, over
    ``duration`` and the ring-down, or over ``span`` [s] for a sine without end."""
    periods = [1.0 / frequency] + [m.period for m in _flexible(modes)]
    dt = min(periods) / SAMPLES_PER_PERIOD
    length = duration + decay_time(modes) if math.isfinite(duration) else span
    times = dt * np.arange(math.ceil(length / dt) + 1)
    return _record(f"floor over a {frequency:g} Hz sine", dt,
                   sine_response(times, frequency, phase, duration, modes),
                   f"floor of a linear building {modes} over a sine (closed form)")


@jit(runtime=True)
def _sampled(g, rec, dt, n):
    """The ground component ``g`` (``codes.GROUND_DTYPE``) at the times k dt, k < n."""
    out = np.empty(n)
    for k in range(n):
        out[k] = component(k * dt, g, rec)
    return out


@lru_cache(maxsize=256)
def floor_of_motion(spec, modes):
    """The floor's :class:`Record` over a resolved sweep or pulse (kernels/api.py) given as
    the sorted ``(key, value)`` pairs of its dict at amplitude 1 and start 0, sampled
    ``SAMPLES_PER_PERIOD`` times per period of its highest frequency (a pulse: per its length)
    or of the shortest mode, over its duration and the ring-down."""
    ground = dict(spec)
    periods = ([1.0 / ground["f_start"], 1.0 / ground["f_stop"]] if ground["kind"] == "sweep"
               else [ground["duration"]]) + [m.period for m in _flexible(modes)]
    dt = min(periods) / SAMPLES_PER_PERIOD
    row = api.scene_row({"body": {"B": 1.0, "H": 1.0}, "excitation": {"horizontal": ground}})
    n = math.ceil((ground["duration"] + decay_time(modes)) / dt) + 1
    samples = _sampled(row.floor.x, np.zeros(1), dt, n)
    return _record(f"floor over a {ground['kind']}", dt, record_response(samples, dt, modes),
                   f"floor of a linear building {modes} over a {ground['kind']} (sampled, "
                   "Nigam & Jennings 1969)")
