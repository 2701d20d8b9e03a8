"""Floor acceleration a_x(t), a_y(t) evaluated inside compiled code.

Each component is described by ``G_SIZE`` floats of the scene row starting at ``off``
(layout in ``codes.py``) and, for records, by a slice of the shared sample buffer ``rec``.
Every kind is zero outside its window [start, start + duration).  ``next_break`` gives the
next instant at which a component is not smooth (window edges, record samples, the apex of
a triangular pulse) so that the integrator never steps across a kink or a jump.
"""
import math



from ._jit import jit
from .codes import (G_AMP, G_DUR, G_F0, G_FREQ, G_HOLD, G_KIND, G_LAW, G_NONE,
                    G_PHASE, G_PULSE_RECT, G_PULSE_TRI, G_REC_DT, G_REC_N, G_REC_OFF,
                    G_RECORD, G_SINE, G_START, G_SWEEP, HOLD_ACCELERATION, HOLD_VELOCITY,
                    LAW_LOG, P_GX, P_GY)

TWO_PI = 2.0 * math.pi
G = 9.80665  # standard gravity [m/s^2]


@jit(inline="always")
def sweep_phase(tau, par, off):
    """Phase psi, its rate psi' = 2 pi f and psi'' of a sweep at time tau after its start."""
    f0 = par[off + G_F0]
    if par[off + G_LAW] == LAW_LOG:
        k = par[off + G_FREQ]              # ln(f1/f0)/T
        ekt = math.exp(k * tau)
        if k == 0.0:
            psi = TWO_PI * f0 * tau
        else:
            psi = TWO_PI * f0 * (ekt - 1.0) / k
        f = f0 * ekt
        fdot = k * f
    else:
        slope = par[off + G_FREQ]          # (f1 - f0)/T
        psi = TWO_PI * (f0 * tau + 0.5 * slope * tau * tau)
        f = f0 + slope * tau
        fdot = slope
    return psi + par[off + G_PHASE], TWO_PI * f, TWO_PI * fdot


@jit(inline="always")
def component(t, par, off, rec):
    """Acceleration [m/s^2] of one ground component at time t (zero outside its window)."""
    kind = par[off + G_KIND]
    if kind == G_NONE:
        return 0.0
    tau = t - par[off + G_START]
    dur = par[off + G_DUR]
    if tau < 0.0 or tau >= dur:
        return 0.0
    amp = par[off + G_AMP]
    if kind == G_SINE:
        return amp * math.sin(TWO_PI * par[off + G_FREQ] * tau + par[off + G_PHASE])
    if kind == G_SWEEP:
        psi, dpsi, ddpsi = sweep_phase(tau, par, off)
        hold = par[off + G_HOLD]
        if hold == HOLD_ACCELERATION:
            return amp * math.sin(psi)
        if hold == HOLD_VELOCITY:           # floor velocity -V cos(psi), exactly
            return amp * dpsi * math.sin(psi)
        # floor displacement -D sin(psi), exactly
        return amp * (dpsi * dpsi * math.sin(psi) - ddpsi * math.cos(psi))
    if kind == G_RECORD:
        dt = par[off + G_REC_DT]
        n = int(par[off + G_REC_N])
        k0 = int(par[off + G_REC_OFF])
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
def ground(t, par, rec):
    """(a_x, a_y): horizontal and vertical floor acceleration [m/s^2]."""
    return component(t, par, P_GX, rec), component(t, par, P_GY, rec)


@jit
def component_end(par, off):
    """Time after which the component is zero for good (inf if never)."""
    kind = par[off + G_KIND]
    if kind == G_NONE:
        return 0.0
    end = par[off + G_START] + par[off + G_DUR]
    if kind == G_RECORD:
        end = min(end, par[off + G_START] + (par[off + G_REC_N] - 1.0) * par[off + G_REC_DT])
    return end


@jit
def ground_end(par):
    """Time after which the floor is still for good."""
    return max(component_end(par, P_GX), component_end(par, P_GY))


@jit
def component_break(t, par, off):
    """Next instant > t at which the component is not smooth (inf if none)."""
    kind = par[off + G_KIND]
    if kind == G_NONE:
        return math.inf
    start = par[off + G_START]
    if t < start:
        return start
    end = component_end(par, off)
    if t >= end:
        return math.inf
    nxt = end
    if kind == G_RECORD:
        dt = par[off + G_REC_DT]
        tb = start + (math.floor((t - start) / dt) + 1.0) * dt
        if tb <= t:
            tb += dt
        nxt = min(nxt, tb)
    elif kind == G_PULSE_TRI:
        apex = start + 0.5 * par[off + G_DUR]
        if apex > t:
            nxt = min(nxt, apex)
    return nxt


@jit
def next_break(t, par):
    """Next instant > t at which either component is not smooth."""
    return min(component_break(t, par, P_GX), component_break(t, par, P_GY))


@jit
def component_frequency(t, par, off):
    """Current frequency [Hz] of an oscillating component, 0 for the others."""
    kind = par[off + G_KIND]
    if kind == G_SINE:
        return par[off + G_FREQ]
    if kind == G_SWEEP:
        tau = min(max(t - par[off + G_START], 0.0), par[off + G_DUR])
        return sweep_phase(tau, par, off)[1] / TWO_PI
    return 0.0


@jit
def amplitudes(t, par, off):
    """(f, A, V): instantaneous frequency [Hz], acceleration [m/s^2] and velocity [m/s]
    amplitudes of a sine or sweep component at time t; NaN for other kinds."""
    kind = par[off + G_KIND]
    amp = par[off + G_AMP]
    if kind == G_SINE:
        f = par[off + G_FREQ]
        return f, abs(amp), abs(amp) / (TWO_PI * f)
    if kind == G_SWEEP:
        tau = min(max(t - par[off + G_START], 0.0), par[off + G_DUR])
        w = sweep_phase(tau, par, off)[1]
        hold = par[off + G_HOLD]
        if hold == HOLD_ACCELERATION:
            return w / TWO_PI, abs(amp), abs(amp) / w
        if hold == HOLD_VELOCITY:
            return w / TWO_PI, abs(amp) * w, abs(amp)
        return w / TWO_PI, abs(amp) * w * w, abs(amp) * w
    return math.nan, math.nan, math.nan


@jit
def scan_step(t, par):
    """A time step short enough that a ground component has at most one extremum in it."""
    f = max(component_frequency(t, par, P_GX), component_frequency(t, par, P_GY))
    if f <= 0.0:
        return math.inf
    f2 = max(component_frequency(t + 0.125 / f, par, P_GX),
             component_frequency(t + 0.125 / f, par, P_GY))
    return 0.125 / max(f, f2)


