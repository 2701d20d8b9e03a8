"""Stability on hard cases: the report's numbers for the scenes of ``hard_cases``.

The same scenes and checks as ``tests/kernels/test_stability.py`` (which asserts them), here
measured over wider ranges: event counts, CPU, lockstep errors against scipy, closed-form
errors, energy after the floor stops, and overturning statistics of chaotic rocking.
"""
import math
from collections import Counter

import numpy as np

from kernels.api import run_scene

from tests import hard_cases as hc
from .markdown import Section, ms, sci, table
from .references import zeno_time

EXCESSES = (1e-9, 1e-6, 1e-4, 1e-3, 3e-3, 1e-2, 2e-2, 3e-2, 5e-2)
QUICK_EXCESSES = (1e-6, 1e-2)


def _run(scene, history=False):
    sc = hc.resolved(scene)
    return sc, run_scene(sc, history=history)


def zeno_table(quick):
    rows = []
    for name, contact in (("Housner", hc.HOUSNER), ("paper", hc.PAPER)):
        for excess in QUICK_EXCESSES if quick else EXCESSES:
            sc, r = _run(hc.near_threshold(excess, contact))
            check = hc.lockstep(r, sc) if contact is hc.HOUSNER and excess >= 1e-3 else None
            rest_bound = 5.0 + zeno_time(hc.B, hc.H, r.max_abs_theta) \
                if contact is hc.HOUSNER and r.max_abs_theta > 0 else None
            rows.append([name, f"{excess:.0e}", r.status, len(r.impact_times), r.events,
                         r.steps, ms(r.cpu_s),
                         "–" if r.t_rest is None else f"{r.t_rest:.4f}",
                         "–" if rest_bound is None else f"{rest_bound:.4f}",
                         "–" if check is None else sci(check.max_time_error),
                         "–" if check is None else f"{check.gained} / {check.bad_closures}"])
    header = ["contact", "excess", "status", "impacts", "events", "steps", "CPU ms",
              "t_rest [s]", "A4 bound [s]", "lockstep dt [s]", "gained / bad closures"]
    return ("### Impact accumulation near West's threshold\n\n"
            "A sine at (1 + excess) West's acceleration, 2 Hz, for 5 s, then a still floor "
            "(t_end 8 s), B = 0.1 m, H = 0.3 m. 'A4 bound': forcing end + the A4 accumulation "
            "time of free rocking from the run's largest amplitude (t_rest must not exceed "
            "it). Lockstep (Housner contact, excess >= 1e-3): each flight re-integrated by "
            "scipy (rtol 1e-12) from the kernel's state after the previous impact; largest "
            "impact-time difference; impacts that gained energy (|omega+| > |omega-|) / Zeno "
            "closures against the rule 'next flight < zeno_dt'.\n\n" + table(header, rows))


def grazing_table(quick):
    rows = []
    for excess in (-1e-9, 1e-9, 1e-6):
        _, r = _run(hc.near_threshold(excess, hc.HOUSNER))
        rows.append([f"sine at (1 {'+' if excess > 0 else '-'} {abs(excess):.0e}) West",
                     r.status, len(r.impact_times), sci(r.max_abs_theta) + " rad",
                     "–", ms(r.cpu_s)])
    for delta in (1e-2, 1e-4) if quick else (1e-1, 1e-2, 1e-3, 1e-4, 1e-6):
        t_land, flight, lift = hc.liftoff_closed_form(delta)
        _, r = _run(hc.grazing_liftoff(delta, rtol=1e-10, atol=1e-12))
        error = (f"landing {sci(r.impact_times[0] - t_land)} s of {sci(flight)} s flight, "
                 f"lift {sci(r.max_lift)} m vs {sci(lift)} m") if r.impact_times else "no landing"
        rows.append([f"a_y = -(1 + {delta:.0e}) g sin(2 pi 5 t)", r.status,
                     len(r.impact_times), sci(r.max_lift) + " m", error, ms(r.cpu_s)])
    return ("### Grazing\n\nA horizontal sine that barely reaches (or misses) West's "
            "threshold, 5 s: one impact per half period expected above it, none below. A "
            "vertical sine that barely exceeds g (rtol 1e-10): closed form of "
            "`hard_cases.liftoff_closed_form`, exact to O(delta).\n\n"
            + table(["scene", "status", "impacts", "largest motion",
                     "against the closed form", "CPU ms"], rows))


def stick_slip_table(quick):
    rows = []
    for excess in (-1e-2, 0.0, 1e-6) if quick else (-1e-2, -1e-6, 0.0, 1e-6, 1e-4, 1e-2):
        _, r = _run(hc.stick_slip(excess))
        rows.append([f"{excess:+.0e}" if excess else "0", r.status, r.events,
                     len(r.impact_times), r.steps, ms(r.cpu_s), sci(r.max_abs_theta),
                     ", ".join(f"{k} {v:.2f}" for k, v in r.mode_time.items() if v)])
    return ("### Stick-slip with friction near b/h\n\nmu = (b/h)(1 + excess) for all four "
            "coefficients, e_x = -0.8, e_y = 0.2, 1.2 West at 2 Hz, 10 s. With mu <= b/h the "
            "block can only slide (docs/physics.md 1.2 (2), 1.3).\n\n"
            + table(["excess", "status", "events", "impacts", "steps", "CPU ms",
                     "max |theta| [rad]", "time per mode [s]"], rows))


def painleve_table(quick):
    mus = (1.3, 2.0) if quick else (1.0, 1.3, 1.34, 1.5, 2.0, 5.0)
    by_mu = {}
    for label, sc, mu in hc.painleve_scenes(mus):
        _, r = _run(sc)
        finite = all(math.isfinite(v) for v in (r.max_abs_theta, r.max_slip, r.max_lift,
                                                 r.t_final, *r.omega_after))
        entry = by_mu.setdefault(mu, {"status": Counter(), "events": 0, "cpu": 0.0,
                                      "non_finite": 0})
        entry["status"][r.status] += 1
        entry["events"] = max(entry["events"], r.events)
        entry["cpu"] = max(entry["cpu"], r.cpu_s)
        entry["non_finite"] += not finite
    rows = [[mu, ", ".join(f"{n} {s}" for s, n in sorted(e["status"].items())),
             e["non_finite"], e["events"], ms(e["cpu"])] for mu, e in by_mu.items()]
    return ("### The Painleve region\n\nEdge friction around 4/3 (docs/physics.md 3.2: no "
            "Painleve case below it), blocks 0.1 x 0.3, 0.5 x 1.0 and 1 x 1 m, a 2-west sine at "
            "2 Hz and El Centro NS + UD x 3, e_x = -1, -0.8, 0, e_y = 0.2, 20 s: 18 runs per "
            "mu.\n\n" + table(["mu", "statuses", "non-finite results", "max events",
                               "max CPU ms"], rows))


def bouncing_table(quick):
    rows = []
    cases = [(0.9, -0.8, 0.8), (1.0, -1.0, 0.0)] if quick else \
        [(0.2, -0.8, 0.8), (0.9, -0.8, 0.8), (0.99, -0.8, 0.8), (1.0, -0.8, 0.8),
         (1.0, -1.0, 0.0)]
    for e_y, e_x, mu in cases:
        sc, r = _run(hc.bouncing(e_y, e_x=e_x, mu=mu, rtol=1e-10, atol=1e-12), history=True)
        e0, rise, e1 = hc.energy_after(r, sc, 2.0)
        rows.append([e_y, e_x, mu, r.status, len(r.impact_times), r.energy_clamps,
                     f"{r.mode_time['rotation_jump']:.2f}", f"{e0:.9f}", f"{e1:.9f}",
                     sci(rise / e0), ms(r.cpu_s)])
    return ("### Bouncing with e_y near 1\n\n1.5 West at 4 Hz for 2 s, then a still floor to "
            "6 s (rtol 1e-10); the mechanical energy per unit mass from the history every 1 ms "
            "after the floor stops must never rise (e_y = 1, e_x = -1, mu = 0: no dissipation "
            "at all, constant). 'clamps': impacts whose restitution law would have gained "
            "energy, clamped by the kernel (docs/physics.md 2.2 step 6).\n\n"
            + table(["e_y", "e_x", "mu", "status", "impacts", "clamps", "jump time [s]",
                     "E at 2 s [J/kg]", "E at 6 s [J/kg]", "largest rise / E", "CPU ms"], rows))


def ensemble_table(quick):
    n = 50 if quick else 1000
    phases = hc.ensemble_phases(n, seed=2)
    settings = [("rtol 1e-9", hc.tolerance(1e-9)), ("rtol 1e-6", hc.tolerance(1e-6)),
                ("rtol 1e-6, zeno_dt 1e-4 (map settings)",
                 {**hc.tolerance(1e-6), "zeno_dt": 1e-4})]
    if not quick:
        settings.append(("fixed dt 1 ms", {"method": "fixed", "dt": 1e-3}))
    runs = [(name, hc.phase_ensemble(phases, **solver)) for name, solver in settings]
    reference = runs[0][1]
    rows = []
    for name, run in runs:
        k = int(hc.overturned(run).sum())
        low, high = hc.wilson(k, n)
        if run is reference:
            rows.append([name, f"{k}/{n} = {k / n:.3f} [{low:.3f}, {high:.3f}]", "–", "–",
                         "–", "–"])
            continue
        stats = hc.compare_fractions(hc.overturned(run), hc.overturned(reference))
        both = hc.overturned(run) & hc.overturned(reference)
        shifted = int(np.sum(np.abs(run["t_overturn"][both]
                                    - reference["t_overturn"][both]) > 1e-3))
        rows.append([name, f"{k}/{n} = {k / n:.3f} [{low:.3f}, {high:.3f}]",
                     f"{stats.only_a} / {stats.only_b}",
                     f"{stats.difference:+.3f} ± {stats.half_width:.3f}",
                     f"{stats.p_value:.2f}", shifted])
    return ("### Chaotic rocking: overturning statistics over a phase ensemble\n\n"
            f"{n} random phases (seeded) of a vertical 0.15 g sine at 3.3 Hz added to 0.97 "
            "West at 2 Hz, Housner contact, 15 s from rest: near the overturning threshold, "
            "where single trajectories depend on the tolerance (docs/physics.md 3.4). "
            "Fractions with Wilson 95 % intervals; against the first row: trajectories "
            "overturning only in this run / only in the first, difference of fractions with "
            "its 95 % interval from the discordant pairs, exact McNemar p-value, and "
            "trajectories overturning in both whose overturning times differ by more than "
            "1 ms.\n\n"
            + table(["setting", "overturned", "only here / only first", "difference",
                     "p", "t_overturn differs > 1 ms"], rows))


def section(quick):
    """Markdown of the stability benchmark."""
    parts = [zeno_table, grazing_table, stick_slip_table, painleve_table, bouncing_table,
             ensemble_table]
    run_scene(hc.resolved(hc.near_threshold(0.5, hc.HOUSNER)))   # compile (or load) first
    return Section("\n\n".join(["## Stability on hard cases",
                                 "Asserted by `tests/kernels/test_stability.py`; measured here "
                                 "over wider ranges. CPU of single runs (the compiled call).",
                                 *[part(quick) for part in parts]]) + "\n", [])
