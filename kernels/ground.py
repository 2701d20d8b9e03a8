"""Floor acceleration a_x(t), a_y(t) evaluated inside compiled code.

Each component is a record of ``codes.GROUND_DTYPE`` (``scene.floor.x``, ``scene.floor.y``:
kind, amp, freq, phase, start, dur, f0, f1, law, hold, rec_off, rec_n, rec_dt; SI units);
amp is a sine's or pulse's acceleration amplitude, a sweep's held amplitude (m/s^2, m/s or
m after ``hold``) or a record's scale; freq a sine's frequency [Hz] or a sweep's rate
(d ln f/dt for the log law, df/dt for the linear one).  A record component points into
``rec``, the buffer of record samples shared by the scenes of a chunk, passed beside the
scene.  Every kind is zero
outside its window [start, start + duration).  ``next_break`` gives the next instant at
which a component is not smooth (window edges, record samples, the apex of a triangular
pulse) so that the integrator never steps across a kink or a jump.
"""
import math

from ._jit import jit
from .codes import (G, G_NONE, G_PULSE_RECT, G_PULSE_TRI, G_RECORD, G_SINE, G_SWEEP,
                    HOLD_ACCELERATION, HOLD_VELOCITY, LAW_LOG)

TWO_PI = 2.0 * math.pi
SCAN_FRACTION = 0.125   # of a period: an interval this long holds at most one extremum

@jit(inline="always")
def sweep_phase(tau, g):
    """Phase psi, its rate psi' = 2 pi f and psi'' of a sweep at time tau after its start."""
    f0 = g.f0
    if g.law == LAW_LOG:
        k = g.freq                          # ln(f1/f0)/T
        ekt = math.exp(k * tau)
        if k == 0.0:
            psi = TWO_PI * f0 * tau
        else:
            psi = TWO_PI * f0 * (ekt - 1.0) / k
        f = f0 * ekt
        fdot = k * f
    else:
        slope = g.freq                      # (f1 - f0)/T
        psi = TWO_PI * (f0 * tau + 0.5 * slope * tau * tau)
        f = f0 + slope * tau
        fdot = slope
    return psi + g.phase, TWO_PI * f, TWO_PI * fdot


@jit(inline="always")
def component(t, g, rec):
    """Acceleration [m/s^2] of one ground component at time t (zero outside its window)."""
    kind = g.kind
    if kind == G_NONE:
        return 0.0
    tau = t - g.start
    dur = g.dur
    if tau < 0.0 or tau >= dur:
        return 0.0
    amp = g.amp
    if kind == G_SINE:
        return amp * math.sin(TWO_PI * g.freq * tau + g.phase)
    if kind == G_SWEEP:
        psi, dpsi, ddpsi = sweep_phase(tau, g)
        hold = g.hold
        if hold == HOLD_ACCELERATION:
            return amp * math.sin(psi)
        if hold == HOLD_VELOCITY:           # floor velocity -V cos(psi), exactly
            return amp * dpsi * math.sin(psi)
        # floor displacement -D sin(psi), exactly
        return amp * (dpsi * dpsi * math.sin(psi) - ddpsi * math.cos(psi))
    if kind == G_RECORD:
        dt = g.rec_dt
        n = int(g.rec_n)
        k0 = int(g.rec_off)
        s = tau / dt
        i = int(math.floor(s))
        if i >= n - 1:
            return amp * rec[k0 + n - 1] if i == n - 1 and s == n - 1 else 0.0
        frac = s - i
        return amp * (rec[k0 + i] + frac * (rec[k0 + i + 1] - rec[k0 + i]))
    if kind == G_PULSE_RECT:
        return amp
    if kind == G_PULSE_TRI:
        return amp * (1.0 - abs(2.0 * tau / dur - 1.0))
    return math.nan


@jit(inline="always")
def ground(t, floor, rec):
    """(a_x, a_y): horizontal and vertical floor acceleration [m/s^2]."""
    return component(t, floor.x, rec), component(t, floor.y, rec)


@jit
def component_end(g):
    """Time after which the component is zero for good (inf if never)."""
    if g.kind == G_NONE:
        return 0.0
    end = g.start + g.dur
    if g.kind == G_RECORD:
        end = min(end, g.start + (g.rec_n - 1.0) * g.rec_dt)
    return end


@jit
def ground_end(floor):
    """Time after which the floor is still for good."""
    return max(component_end(floor.x), component_end(floor.y))


@jit
def component_break(t, g):
    """Next instant > t at which the component is not smooth (inf if none)."""
    kind = g.kind
    if kind == G_NONE:
        return math.inf
    start = g.start
    if t < start:
        return start
    end = component_end(g)
    if t >= end:
        return math.inf
    nxt = end
    if kind == G_RECORD:
        dt = g.rec_dt
        tb = start + (math.floor((t - start) / dt) + 1.0) * dt
        if tb <= t:
            tb += dt
        nxt = min(nxt, tb)
    elif kind == G_PULSE_TRI:
        apex = start + 0.5 * g.dur
        if apex > t:
            nxt = min(nxt, apex)
    return nxt


@jit
def next_break(t, floor):
    """Next instant > t at which either component is not smooth."""
    return min(component_break(t, floor.x), component_break(t, floor.y))


@jit
def component_frequency(t, g):
    """Current frequency [Hz] of an oscillating component, 0 for the others."""
    if g.kind == G_SINE:
        return g.freq
    if g.kind == G_SWEEP:
        tau = min(max(t - g.start, 0.0), g.dur)
        return sweep_phase(tau, g)[1] / TWO_PI
    return 0.0


@jit
def amplitudes(t, g):
    """(f, A, V): instantaneous frequency [Hz], acceleration [m/s^2] and velocity [m/s]
    amplitudes of a sine or sweep component at time t; NaN for other kinds."""
    amp = g.amp
    if g.kind == G_SINE:
        f = g.freq
        return f, abs(amp), abs(amp) / (TWO_PI * f)
    if g.kind == G_SWEEP:
        tau = min(max(t - g.start, 0.0), g.dur)
        w = sweep_phase(tau, g)[1]
        if g.hold == HOLD_ACCELERATION:
            return w / TWO_PI, abs(amp), abs(amp) / w
        if g.hold == HOLD_VELOCITY:
            return w / TWO_PI, abs(amp) * w, abs(amp)
        return w / TWO_PI, abs(amp) * w * w, abs(amp) * w
    return math.nan, math.nan, math.nan


@jit
def scan_step(t, floor):
    """A time step short enough that a ground component has at most one extremum in it."""
    f = max(component_frequency(t, floor.x), component_frequency(t, floor.y))
    if f <= 0.0:
        return math.inf
    f2 = max(component_frequency(t + SCAN_FRACTION / f, floor.x),
             component_frequency(t + SCAN_FRACTION / f, floor.y))
    return SCAN_FRACTION / max(f, f2)
