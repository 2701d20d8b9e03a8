"""Boundary refinement (``refine:``) against a dense grid, on two Fig. 11-type maps.

The overturning amplitude along lines of a map is found twice: by a dense grid of amplitudes
spaced at the tolerance, and by ``refine:`` from a coarse grid 16 (quick: 8) times wider.  Both
grids sit on one lattice of exact binary fractions, so every midpoint of the bisection is a
cell of the dense grid, simulated alike: on a line where the body overturns above one
amplitude only, the two brackets must be the same pair of neighbouring amplitudes.  Maps: a
rectangular acceleration pulse (amplitude vs duration, monotone; Housner's Eq. (4) beside it)
and constant-velocity frequency sweeps (velocity amplitude vs b/h, banded near the threshold).
Wall time in one process, after compilation.

    python -m benchmarks.refine [--quick]
"""
import copy
import sys
import time
from collections import namedtuple

import numpy as np
from scipy.optimize import brentq

import sweep
from benchmarks.markdown import Section, table, verdict
from sweep.paper import criteria
from sweep.runner.cells import warm_up

# Housner's impact (docs/physics.md 2.1) and friction enough for rocking without sliding
CONTACT = {"mu": 0.8, "e_x": 0.0, "e_y": 0.0}

Map = namedtuple("Map", "title scene line line_label full quick unit low high coarse "
                        "reference")
Map.__doc__ = """One map: a base ``scene``, the ``line`` axis (values ``full``/``quick``), the
amplitude range ``low``-``high`` and ``coarse`` step in ``unit`` (binary fractions), and an
optional closed-form ``reference(line value)`` of the boundary."""


def _housner_west(duration, B=0.1, H=0.3):
    """Amplitude [west] of a rectangular pulse that just overturns in ``duration``, Eq. (4)."""
    alpha = float(criteria.body_constants(B, H).alpha)
    g_alpha = criteria.G * alpha
    a = brentq(lambda a: criteria.housner_overturn_time(B, H, a) - duration,
               g_alpha * (1 + 1e-12), 20 * g_alpha, xtol=1e-12)
    return a / float(criteria.west_acceleration(B, H))


MAPS = (
    Map("Rectangular acceleration pulse, B x H = 10 x 30 cm: amplitude vs pulse duration",
        {"body": {"B": 0.1, "H": 0.3}, "contact": CONTACT,
         "excitation": {"horizontal": {"kind": "pulse", "shape": "rectangular",
                                       "amplitude": "1 west", "duration": 0.2}},
         "solver": {"t_end": 5.0}},
        "excitation.horizontal.duration", "pulse [s]", [0.1, 0.15, 0.2, 0.3, 0.5, 1.0],
        [0.15, 0.3, 1.0], "west", 0.75, 3.25, 0.25, _housner_west),
    Map("Constant-velocity sweeps up, 0.5 → 16 Hz in 25 s (log), B = 5 cm: velocity amplitude "
        "vs b/h",
        {"body": {"B": "5 cm", "H": "15 cm"}, "contact": CONTACT,
         "excitation": {"horizontal": {"kind": "sweep", "hold": "velocity",
                                       "amplitude": "0.6 v_H", "f_start": 0.5,
                                       "f_stop": 16.0, "duration": 25.0, "law": "log"}},
         "solver": {"max_events": 20000}},
        "b_over_h", "b/h", [0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.5], [0.2, 0.333], "v_H",
        0.25, 1.5, 0.125, None),
)
HALVINGS = {True: 3, False: 4}  # quick, full: tolerance = coarse step / 2**halvings


def _study(m, lines, step, tolerance=None):
    num = round((m.high - m.low) / step) + 1
    study = {"name": "refine_benchmark", "scene": copy.deepcopy(m.scene),
             "grid": {"amplitude": {"start": m.low, "stop": m.high, "num": num, "unit": m.unit},
                      m.line: list(lines)}}
    if tolerance is not None:
        study["refine"] = {"axis": "amplitude", "tolerance": tolerance}
    return study


def _timed(study):
    t0 = time.perf_counter()
    ds = sweep.run_study(study)
    return ds, time.perf_counter() - t0


def _dense_bracket(amplitudes, row):
    """(lower, upper) around the first amplitude that overturned with standing below it;
    NaNs when the line never overturned, overturned at once or failed first."""
    stops = np.flatnonzero(row != 0)
    if stops.size == 0 or stops[0] == 0 or row[stops[0]] != 1:
        return np.nan, np.nan
    return amplitudes[stops[0] - 1], amplitudes[stops[0]]


Result = namedtuple("Result", "map tolerance dense t_dense refined t_refine")


def measure(quick):
    """Both datasets of every map and their wall times [s]."""
    warm_up()
    results = []
    for m in MAPS:
        lines = m.quick if quick else m.full
        tolerance = m.coarse / 2 ** HALVINGS[quick]
        dense, t_dense = _timed(_study(m, lines, tolerance))
        refined, t_refine = _timed(_study(m, lines, m.coarse, tolerance))
        results.append(Result(m, tolerance, dense, t_dense, refined, t_refine))
    return results


def _dataset_name(ds, axis):
    """The dataset's name of a study axis (a dotted axis is named by its last key)."""
    return next(name for name, c in ds.coords.items() if c.attrs.get("study_axis") == axis)


def _compare(r):
    """Table rows of one map and the counts of equal and consistent brackets."""
    m, amplitudes = r.map, r.dense["amplitude"].values
    rows, same, consistent = [], 0, 0
    line_dim = _dataset_name(r.refined, m.line)
    for value in r.refined[line_dim].values:
        row = r.dense["overturned"].sel({line_dim: value}).values
        d_low, d_high = _dense_bracket(amplitudes, row)
        line = r.refined.sel({line_dim: value})
        low, high = float(line["boundary_lower"]), float(line["boundary_upper"])
        equal = d_low == low and d_high == high
        # the refined ends are dense cells: standing at the lower one, overturned at the upper
        ends = bool(np.isfinite(low) and np.isfinite(high) and row[amplitudes == low][0] == 0
                    and row[amplitudes == high][0] == 1)
        same, consistent = same + equal, consistent + ends
        known = row[row >= 0]
        rows.append([f"{value:g}", f"{0.5 * (d_low + d_high):.4f}",
                     f"{float(line['boundary']):.4f}", f"[{low:.4f}, {high:.4f}]",
                     verdict(equal), int(np.count_nonzero(np.diff(known))), int(np.sum(row < 0)),
                     int(line["simulations"])]
                    + ([f"{m.reference(value):.4f}"] if m.reference else []))
    return rows, same, consistent


def section(quick):
    """Markdown: simulations and wall time of refine and of the dense grid; their boundaries."""
    results = measure(quick)
    text = ["## Boundary refinement against a dense grid", "",
            "`refine:` (bisection from a coarse grid) against a dense grid of the same "
            "resolution.  Both grids lie on one lattice of binary fractions, so every midpoint "
            "of the bisection is a cell of the dense grid: where a line overturns above one "
            "amplitude only, both brackets must be the same pair of neighbouring amplitudes.  "
            "Wall time in one process after compilation (machine shared: indicative).", ""]
    totals = []
    for r in results:
        m = r.map
        rows, same, consistent = _compare(r)
        n_dense, n_refine = r.dense["overturned"].size, int(r.refined.attrs["refine_simulations"])
        header = [m.line_label, f"dense boundary [{m.unit}]", f"refine boundary [{m.unit}]",
                  f"refine bracket [{m.unit}]", "same bracket", "dense transitions",
                  "dense failed", "refine simulations"]
        header += ["Eq. (4), linearized [west]"] if m.reference else []
        text += [f"**{m.title}.**  Amplitude {m.low}–{m.high} {m.unit}: dense every "
                 f"{r.tolerance:g}; `refine:` coarse every {m.coarse}, tolerance "
                 f"{r.tolerance:g} ({HALVINGS[quick]} halvings).  Brackets equal on {same} of "
                 f"{len(rows)} lines; on {consistent} of {len(rows)} the refined ends are a "
                 "standing and an overturning cell of the dense grid.", "",
                 table(header, rows), ""]
        totals += [[m.line_label, "dense grid", n_dense, f"{r.t_dense:.1f}", f"{r.tolerance:g}"],
                   [m.line_label, "refine", n_refine, f"{r.t_refine:.1f}",
                    f"≤ {r.tolerance:g}"],
                   [m.line_label, "ratio", f"{n_dense / n_refine:.1f}×",
                    f"{r.t_dense / r.t_refine:.1f}×", ""]]
    text += [table(["map (lines)", "method", "simulations", "wall time [s]",
                    "boundary resolution"], totals), "",
             "Near its threshold a swept block overturns in bands (docs/physics.md 3.4: near-"
             "threshold rocking is sensitive to the amplitude); there `refine:` follows the "
             "lowest bracket its coarse values show and misses an overturning band narrower "
             "than the coarse step, so its boundary can lie above the dense grid's lowest "
             "transition (`coarse_transitions` in its dataset counts the bands the coarse "
             "values see).  Rounds run one after the other and each has one cell per open "
             "line, which bounds how many ranks a round can keep busy.", ""]
    return Section("\n".join(text), [])


if __name__ == "__main__":
    print(section("--quick" in sys.argv[1:]))
