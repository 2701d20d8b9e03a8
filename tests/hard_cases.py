"""Numerically hard scenes (docs/physics.md section 3) and the physics their results must obey.

Shared by ``tests/kernels/test_stability.py`` (assertions) and the report's stability section
(numbers).  Every check compares the kernel with something that does not come from it: the
rocking-only scipy program re-integrating each flight from the kernel's own state after the
previous impact (lockstep), closed forms, conservation of energy, binomial statistics.
Default block B = 0.1 m, H = 0.3 m; SI units; theta > 0 about the left corner.
"""
import math
from dataclasses import dataclass

import numpy as np
from scipy.stats import binomtest

from kernels import api, codes
from sweep.io.scene_schema import load_scene, resolve_scene
from tests import naive as scipy_rocking
from tests.naive import floor_motion

G = scipy_rocking.G
B, H = 0.1, 0.3
BETA = B / H
WEST = BETA * G                        # West's acceleration (b/h) g of the default block
HOUSNER = {"mu": 10.0, "e_x": 0.0, "e_y": 0.0}
PAPER = {"mu": 0.4, "e_x": -0.8, "e_y": 0.2}     # the contact of the paper's Figs 3 and 5
MU_PAINLEVE = 4.0 / 3.0  # docs/physics.md 3.2: no Painleve case below this edge friction


def resolved(scene):
    """A scene-file dict resolved into the SI dict of ``kernels.api``."""
    return resolve_scene(load_scene(scene))


def scene(contact, horizontal=None, vertical=None, initial=None, body=(B, H), **solver):
    """A scene-file dict (SI numbers) of a block on the given floor motion."""
    return {"body": {"B": body[0], "H": body[1]}, "contact": dict(contact),
            "excitation": {"horizontal": horizontal or {"kind": "none"},
                           "vertical": vertical or {"kind": "none"}},
            "initial": dict(initial or {}), "solver": solver}


def sine(amplitude, frequency, **kw):
    return {"kind": "sine", "amplitude": amplitude, "frequency": frequency, **kw}


# --- impact accumulation near West's threshold ---------------------------------------------

def near_threshold(excess, contact, frequency=2.0, forcing=5.0, t_end=8.0, **solver):
    """A sine of (1 + excess) West's acceleration for ``forcing`` s, then a still floor."""
    return scene(contact, sine((1.0 + excess) * WEST, frequency, duration=forcing),
                 t_end=t_end, **solver)


def burst_bound(frequency, zeno_dt, eta):
    """Impacts of one burst (rest to Zeno closure) of free rocking whose first flight lasts
    half a period: flights shrink by eta per impact (docs/physics.md 3.1) down to zeno_dt."""
    return math.ceil(math.log(0.5 / frequency / zeno_dt) / math.log(1.0 / eta)) + 1


@dataclass(frozen=True)
class Lockstep:
    """Flights of a Housner-contact run re-integrated one by one (``lockstep``).

    impacts: how many; max_time_error [s]: largest |t_kernel - t_scipy| of an impact;
    max_ratio_error: largest |omega+ - eta omega-|/|eta omega-| over impacts that go on
    rocking; gained: impacts with |omega+| > |omega-| (energy gained); closures: impacts
    closed to face contact (omega+ = 0); bad_closures: closures whose next flight would
    have lasted >= zeno_dt, plus non-closures whose next flight would have lasted < zeno_dt.
    """

    impacts: int
    max_time_error: float
    max_ratio_error: float
    gained: int
    closures: int
    bad_closures: int


def lockstep(result, resolved_scene, rtol=1e-12, atol=1e-16):
    """Check every impact of a rocking run with Housner's contact against scipy.

    Each flight starts from the kernel's state after the previous impact (theta = 0 and its
    omega+, or rest when it closed to face contact) and is integrated by
    ``scipy_rocking.housner_rocking`` to the next impact, which gives t and omega- there;
    Housner's law (docs/physics.md 2.1) gives omega+ = eta omega-.  A Zeno closure is due when the
    flight after the impact, 2|omega+|/|theta''| at theta = 0 (docs/physics.md 1.2 (3)), would last
    less than ``zeno_dt`` (README, Conventions).
    """
    body, solver = resolved_scene["body"], resolved_scene["solver"]
    b, h, r, alpha, i2, eta, p = scipy_rocking.body_constants(body["B"], body["H"])
    a_x, kinks_x = floor_motion(resolved_scene["excitation"]["horizontal"])
    a_y, kinks_y = floor_motion(resolved_scene["excitation"]["vertical"])
    kinks = tuple(sorted(set(kinks_x) | set(kinks_y)))
    k = r / (i2 + r * r)
    t, w = np.asarray(result.impact_times), np.asarray(result.omega_after)
    time_errors, ratio_errors = [0.0], [0.0]
    gained = closures = bad = 0
    for n in range(t.size):
        t0, w0 = (t[n - 1], w[n - 1]) if n else (0.0, 0.0)
        flight = scipy_rocking.housner_rocking(
            body["B"], body["H"], a_x=a_x, a_y=a_y, omega0=w0, t_start=t0,
            t_end=t[n] + 1.0, a_x_breaks=kinks, max_impacts=1, rtol=rtol, atol=atol)
        if not flight["impact_times"]:
            time_errors.append(math.inf)
            break
        time_errors.append(abs(flight["impact_times"][0] - t[n]))
        w_minus = flight["omega_before"][0]
        w_plus = eta * w_minus
        gained += abs(w[n]) > abs(w_minus)
        side = math.copysign(1.0, w_plus)                # the new pivot's side
        thdd = -k * ((G + a_y(t[n])) * math.sin(alpha * side)
                     - a_x(t[n]) * math.cos(alpha * side))
        next_flight = 2.0 * abs(w_plus) / abs(thdd) if thdd * w_plus < 0.0 else math.inf
        if w[n] == 0.0:
            closures += 1
            bad += next_flight >= solver["zeno_dt"]
        else:
            ratio_errors.append(abs(w[n] - w_plus) / abs(w_plus))
            bad += next_flight < solver["zeno_dt"]
    return Lockstep(int(t.size), max(time_errors), max(ratio_errors), gained, closures, bad)


# --- grazing lift-off -------------------------------------------------------------------------

def grazing_liftoff(delta, frequency=5.0, **solver):
    """One cycle of a_y = -(1 + delta) g sin(2 pi f t): the floor falls just faster than g."""
    return scene({"mu": 0.5, "e_x": -0.8, "e_y": 0.0},
                 vertical=sine(-(1.0 + delta) * G, frequency, duration=1.0 / frequency),
                 t_end=2.0 / frequency, **solver)


def liftoff_closed_form(delta, frequency=5.0):
    """(landing time [s], flight time [s], largest lift [m]) of ``grazing_liftoff``.

    Near the peak, sin = 1 - x^2/2 gives the gap's acceleration g (1 + delta) w^2 s (2c - s)/2
    with s the time since lift-off and c = sqrt(2 delta/(1 + delta))/w: lift-off at
    T/4 - c, largest gap at s = 3c, 9/8 g (1 + delta) w^2 c^4 = 4.5 g delta^2/((1 + delta)
    w^2), landing at s = 4c.  Relative error O(delta) (the x^4 term of the sine).
    """
    w = 2.0 * math.pi * frequency
    c = math.sqrt(2.0 * delta / (1.0 + delta)) / w
    return 0.25 / frequency + 3.0 * c, 4.0 * c, 4.5 * G * delta ** 2 / ((1.0 + delta) * w * w)


# --- stick-slip with friction near b/h, Painleve region, bouncing -------------------------------

def stick_slip(excess, amplitude=1.2 * WEST, frequency=2.0, t_end=10.0):
    """Friction mu = (b/h)(1 + excess) (all four), a sine above both thresholds."""
    return scene({"mu": BETA * (1.0 + excess), "e_x": -0.8, "e_y": 0.2},
                 sine(amplitude, frequency), t_end=t_end)


PAINLEVE_FLOORS = {
    "sine": ({"kind": "sine", "amplitude": "2 west", "frequency": 2.0}, None),
    "El Centro x3": ({"kind": "record", "name": "elcentro1940_ns", "scale": 3},
                     {"kind": "record", "name": "elcentro1940_ud", "scale": 3})}


def painleve_scenes(mus=(1.0, 1.3, 1.34, 1.5, 2.0, 5.0)):
    """(label, scene, mu) over edge friction around 4/3, three blocks, a 2-west sine and El
    Centro NS + UD scaled by 3, e_x in (-1, -0.8, 0), e_y = 0.2, 20 s."""
    out = []
    for mu in mus:
        for body in ((0.1, 0.3), (0.5, 1.0), (1.0, 1.0)):
            for name, (horizontal, vertical) in PAINLEVE_FLOORS.items():
                for e_x in (-1.0, -0.8, 0.0):
                    label = f"mu {mu}, {body[0]} x {body[1]} m, {name}, e_x {e_x}"
                    out.append((label, scene({"mu": mu, "e_x": e_x, "e_y": 0.2}, horizontal,
                                             vertical, body=body, t_end=20.0), mu))
    return out


def bouncing(e_y, e_x=-0.8, mu=0.8, forcing=2.0, t_end=6.0, **solver):
    """1.5 west at 4 Hz for ``forcing`` s, then a still floor; restitution e_y near 1.
    With mu = 0 the block starts tilted at 0.5 alpha (a frictionless block cannot be
    rocked from rest by the floor)."""
    initial = {"theta": "0.5 alpha"} if mu == 0.0 else {}
    return scene({"mu": mu, "e_x": e_x, "e_y": e_y},
                 sine(1.5 * WEST, 4.0, duration=forcing), initial=initial, t_end=t_end,
                 dt_out=1e-3, **solver)


def energy(history, i2):
    """Mechanical energy per unit mass [J/kg] of the history samples, floor frame:
    (u^2 + v^2)/2 + i^2 omega^2/2 + g y (conserved while the floor is still and no contact
    dissipates)."""
    return (0.5 * (history["u"] ** 2 + history["v"] ** 2)
            + 0.5 * i2 * history["omega"] ** 2 + G * history["y"])


def energy_after(result, resolved_scene, t_still):
    """(E at the first sample at or after t_still, largest rise of E between consecutive
    samples after it, E at the end) [J/kg] from a run with history."""
    body = resolved_scene["body"]
    i2 = scipy_rocking.body_constants(body["B"], body["H"])[4]
    hist = result.history
    e = energy(hist, i2)[hist["t"] >= t_still]
    rise = float(np.max(np.diff(e))) if e.size > 1 else 0.0
    return float(e[0]), rise, float(e[-1])


# --- near-threshold chaos: statistics over a phase ensemble -----------------------------------

ENSEMBLE_AMPLITUDE = 0.97 * WEST      # horizontal, 2 Hz
ENSEMBLE_VERTICAL = 0.15 * G          # vertical, 3.3 Hz, random phase
ENSEMBLE_T_END = 15.0


def ensemble_phases(n, seed=1):
    """n phases of the vertical excitation, uniform in [0, 2 pi) (seeded)."""
    return np.random.default_rng(seed).uniform(0.0, 2.0 * math.pi, n)


def tolerance(rtol):
    """Solver settings of the adaptive integrator at ``rtol`` (atol = 1e-2 rtol)."""
    return {"rtol": rtol, "atol": 1e-2 * rtol}


def ensemble_scene(phase, **solver):
    """Housner block under 0.97 west at 2 Hz and 0.15 g at 3.3 Hz (phase ``phase``), 15 s
    from rest: near the overturning threshold, where single trajectories are chaotic."""
    return scene(HOUSNER, sine(ENSEMBLE_AMPLITUDE, 2.0),
                 sine(ENSEMBLE_VERTICAL, 3.3, phase=float(phase)), t_end=ENSEMBLE_T_END,
                 **solver)


def phase_ensemble(phases, **solver):
    """Kernel results (n records of ``codes.RESULT_DTYPE``) of ``ensemble_scene`` over the phases, one compiled
    call."""
    rows = np.array([api.scene_row(resolved(ensemble_scene(ph, **solver))) for ph in phases])
    return api.run_cells(rows, api.record_buffer([]))


def overturned(results):
    return results["status"] == codes.OVERTURNED


def wilson(k, n, z=1.96):
    """Wilson score interval (95 % for z = 1.96) of a binomial fraction k/n."""
    p = k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return centre - half, centre + half


@dataclass(frozen=True)
class PairedFractions:
    """Two overturning fractions over the same trajectories (paired samples).

    only_a / only_b: trajectories that overturn in run a only / b only (the discordant
    pairs); difference = (only_a - only_b)/n with its 95 % interval from the discordant
    pairs (McNemar); p_value: exact two-sided McNemar test of equal fractions.
    """

    n: int
    k_a: int
    k_b: int
    only_a: int
    only_b: int
    difference: float
    half_width: float
    p_value: float


def compare_fractions(a, b):
    """``PairedFractions`` of two boolean outcome arrays over the same trajectories."""
    a, b = np.asarray(a, bool), np.asarray(b, bool)
    n = a.size
    only_a, only_b = int(np.sum(a & ~b)), int(np.sum(b & ~a))
    discordant = only_a + only_b
    diff = (only_a - only_b) / n
    se = math.sqrt(max(discordant - n * diff * diff, 0.0)) / n
    p = binomtest(only_a, discordant, 0.5).pvalue if discordant else 1.0
    return PairedFractions(n, int(a.sum()), int(b.sum()), only_a, only_b, diff, 1.96 * se,
                           float(p))
