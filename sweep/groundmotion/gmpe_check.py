"""Synthetic motions against a published ground-motion model: BSSA14 medians of PGA and PGV.

``python -m sweep.groundmotion.gmpe_check [--seeds 100] [--json]`` generates ``--seeds``
motions (:mod:`sweep.groundmotion.stochastic`) per scenario, M 5.5-7.5 x Rrup 10-50 km on
Vs30 760 m/s and 360 m/s, and compares the median simulated PGA and PGV with Boore, Stewart,
Seyhan & Atkinson (2014, Earthquake Spectra 30; BSSA14, from ``pygmm``) as
z = (ln sim - ln BSSA14) / sigma_ln, sigma_ln being BSSA14's total standard deviation.  It
prints a markdown table (or JSON) and the time one motion takes to generate; the exit status
is 1 if some scenario lies more than one sigma away for PGA or PGV.

Assumptions: a vertical strike-slip fault reaching the surface, so Rjb = Rrup and the mechanism
is ``SS``; the simulated median is the geometric mean over the seeds; PGA and PGV of a motion
are those of :func:`sweep.groundmotion.intensity.measures` (PGV after its 0.1 Hz baseline
high-pass).  BSSA14 predicts RotD50, the simulations are one horizontal component.
"""
import argparse
import json
import sys
import time
from collections import namedtuple

import numpy as np

from ..bodies import G
from . import stochastic
from .intensity import measures

MAGNITUDES = (5.5, 6.0, 6.5, 7.0, 7.5)
DISTANCES = (10.0e3, 20.0e3, 30.0e3, 50.0e3)  # Rrup [m]
VS30 = (760.0, 360.0)  # m/s: the reference rock of BSSA14, and a stiff soil

Comparison = namedtuple("Comparison", "magnitude distance vs30 pga pga_bssa14 z_pga "
                                      "pgv pgv_bssa14 z_pgv")
Comparison.__doc__ = """One scenario: M, Rrup [m], Vs30 [m/s]; median simulated and BSSA14 PGA
[m/s^2] and PGV [m/s], each with z = (ln sim - ln BSSA14) / sigma_ln."""


def bssa14(magnitude, distance, vs30):
    """BSSA14 ``(pga [m/s^2], sigma_ln_pga, pgv [m/s], sigma_ln_pgv)`` for a surface-rupturing
    vertical strike-slip fault (Rjb = Rrup = ``distance`` [m])."""
    import pygmm

    distance_km = distance / 1e3
    model = pygmm.BooreStewartSeyhanAtkinson2014(pygmm.Scenario(
        mag=magnitude, dist_jb=distance_km, dist_rup=distance_km, v_s30=vs30, mechanism="SS"))
    return model.pga * G, model.ln_std_pga, model.pgv / 100.0, model.ln_std_pgv


def compare(magnitude, distance, vs30, seeds, model="boore2003"):
    """:class:`Comparison` of ``seeds`` motions (seeds 0, 1, ...) with BSSA14."""
    peaks = np.array([[m.pga, m.pgv] for m in (
        measures(r.samples, r.dt) for r in (
            stochastic.generate(model, magnitude, distance, vs30, seed)
            for seed in range(seeds)))])
    pga, pgv = np.exp(np.mean(np.log(peaks), axis=0))
    pga_gmpe, sigma_pga, pgv_gmpe, sigma_pgv = bssa14(magnitude, distance, vs30)
    return Comparison(magnitude, distance, vs30,
                      pga, pga_gmpe, float(np.log(pga / pga_gmpe) / sigma_pga),
                      pgv, pgv_gmpe, float(np.log(pgv / pgv_gmpe) / sigma_pgv))


def markdown(comparisons, seeds):
    """A markdown table of :class:`Comparison` rows: PGA in g, PGV in cm/s, distance in km."""
    lines = [f"Median of {seeds} motions per scenario against BSSA14 (z in BSSA14 total sigma)",
             "",
             "| M | R [km] | Vs30 [m/s] | PGA sim [g] | PGA BSSA14 [g] | z PGA | "
             "PGV sim [cm/s] | PGV BSSA14 [cm/s] | z PGV | both abs(z) <= 1 |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for c in comparisons:
        within = "yes" if max(abs(c.z_pga), abs(c.z_pgv)) <= 1.0 else "NO"
        lines.append(f"| {c.magnitude:g} | {c.distance / 1e3:g} | {c.vs30:g} | {c.pga / G:.3f} "
                     f"| {c.pga_bssa14 / G:.3f} | {c.z_pga:+.2f} | {100 * c.pgv:.1f} | "
                     f"{100 * c.pgv_bssa14:.1f} | {c.z_pgv:+.2f} | {within} |")
    return "\n".join(lines)


def generation_time(repeats=200):
    """Mean wall time [s] of one :func:`~sweep.groundmotion.stochastic.generate` call for
    M 7, Rrup 20 km, Vs30 760 m/s (dt 0.01 s), over ``repeats`` seeds."""
    start = time.perf_counter()
    for seed in range(repeats):
        stochastic.generate("boore2003", 7.0, 20.0e3, 760.0, seed)
    return (time.perf_counter() - start) / repeats


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="python -m sweep.groundmotion.gmpe_check",
        description="Median PGA and PGV of synthetic motions against BSSA14.")
    parser.add_argument("--seeds", type=int, default=100, help="motions per scenario")
    parser.add_argument("--json", action="store_true", help="print JSON instead of markdown")
    args = parser.parse_args(argv)
    if args.seeds < 1:
        parser.error("--seeds must be at least 1")
    comparisons = [compare(m, r, v, args.seeds)
                   for v in VS30 for m in MAGNITUDES for r in DISTANCES]
    seconds = generation_time()
    if args.json:
        json.dump({"seeds": args.seeds, "generation_s": seconds,
                   "scenarios": [c._asdict() for c in comparisons]}, sys.stdout, indent=1)
        print()
    else:
        print(markdown(comparisons, args.seeds))
        print(f"\nOne motion (M 7, Rrup 20 km, dt 0.01 s): {1e3 * seconds:.2f} ms to generate.")
    return 0 if all(max(abs(c.z_pga), abs(c.z_pgv)) <= 1.0 for c in comparisons) else 1


if __name__ == "__main__":
    sys.exit(main())
