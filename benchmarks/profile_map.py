"""Where a sweep-map cell spends its time: kernel CPU against a baseline kernel, and counts.

    python -m benchmarks.profile_map time [--every N] [--base DIR] [--repeat R]
    NUMBA_DISABLE_JIT=1 python -m benchmarks.profile_map counts [--every N]
    python -m benchmarks.profile_map steady [--repeat R]
    python -m benchmarks.profile_map ensemble

``time`` runs every N-th cell of ``sweep_map.yaml`` with the kernel of this tree and, with
``--base``, with a copy of an earlier ``kernels`` package (DIR holds ``kernels_base/``, the
package copied under that name; it must take the scene records of this tree's
``codes.SCENE_DTYPE``), alternating the two cell by cell in this process, so that
the load of a shared machine falls on both alike: CPU per cell (``time.process_time``), the
median of the per-cell ratios, mean ms per cell, the fit cpu ~ a steps + b events and whether
the results are identical.  ``counts`` (plain Python) counts what a cell does inside its
steps: rejected steps, event-function evaluations, root-finder calls, re-integrations to an
event, polishes, impacts and Zeno closures.  ``steady``: CPU of the steady-rocking scene
(median of R runs) at rtol 1e-6 and 1e-8 with its impact-time error against the kernel at
rtol 1e-13 (as the work-precision benchmark measures it).  ``ensemble``: overturnings of the
1,000-phase ensemble of the stability benchmark at rtol 1e-9, 1e-6 and map settings.
"""
import argparse
import importlib
import sys
import time
from pathlib import Path

import numpy as np

STUDY = Path(__file__).with_name("sweep_map.yaml")


def map_rows(every):
    """(rows, rec) of every ``every``-th cell of the bench map."""
    from sweep.runner.cell_checks import load_study
    from sweep.runner import cells

    study = load_study(STUDY)
    rows, rec, _, _, _ = cells.build_rows(study, np.arange(0, study.n_cells, every))
    return rows, rec


def _run(pkg, rows, rec):
    api, codes = pkg
    return api.run_cells(rows, rec)


def time_cells(every, base, repeat):
    from kernels import api, codes
    kernels = [("this tree", (api, codes))]
    if base:
        sys.path.insert(0, base)
        kernels.append(("base", (importlib.import_module("kernels_base.api"),
                                 importlib.import_module("kernels_base.codes"))))
    rows, rec = map_rows(every)
    for _, pkg in kernels:                                  # compile (or load) first
        _run(pkg, rows[:1], rec)
    n = rows.shape[0]
    cpu = np.full((len(kernels), repeat, n), np.inf)
    res = np.zeros((len(kernels), n), codes.RESULT_DTYPE)
    for r in range(repeat):
        for k in range(n):
            order = range(len(kernels)) if (k + r) % 2 == 0 else reversed(range(len(kernels)))
            for j in order:
                t0 = time.process_time()
                res[j, k] = _run(kernels[j][1], rows[k:k + 1], rec)[0]
                cpu[j, r, k] = time.process_time() - t0
    cpu = np.median(cpu, axis=1)
    steps, events, impacts = (res[0][name] for name in ("steps", "events", "impacts"))
    print(f"{n} cells (every {every}-th), median of {repeat} runs per cell")
    for j, (name, _) in enumerate(kernels):
        print(f"  {name:10s} mean {1e3 * cpu[j].mean():7.3f} ms/cell, "
              f"median {1e3 * np.median(cpu[j]):7.3f} ms")
    print(f"  per cell: steps {steps.mean():8.0f}  events {events.mean():7.0f}  "
          f"impacts {impacts.mean():7.0f}  overturned "
          f"{int(np.sum(res[0]['status'] == codes.OVERTURNED))}")
    a, b = np.linalg.lstsq(np.c_[steps, events], cpu[0], rcond=None)[0]
    print(f"  fit: {1e6 * a:.2f} us/step, {1e6 * b:.2f} us/event -> steps "
          f"{a * steps.sum() / cpu[0].sum():.0%}, events {b * events.sum() / cpu[0].sum():.0%}")
    if base:
        ratio = cpu[1] / cpu[0]
        same = res[0].tobytes() == res[1].tobytes()
        print(f"  base / this tree: median per-cell ratio {np.median(ratio):.3f}, "
              f"ratio of means {cpu[1].mean() / cpu[0].mean():.3f}; results identical: {same}")
        if not same:
            overturned = [int(np.sum(r["status"] == codes.OVERTURNED)) for r in res]
            impacts = [int(r["impacts"].sum()) for r in res]
            print(f"    overturned: this tree {overturned[0]}, base {overturned[1]}")
            print(f"    impacts: this tree {impacts[0]}, base {impacts[1]}")


class Counter(dict):
    def wrap(self, module, name, counted=None):
        """Count the calls of module.name (under ``counted``, default name)."""
        f = getattr(module, name)
        key = counted or name

        def counting(*args, **kwargs):
            self[key] = self.get(key, 0) + 1
            return f(*args, **kwargs)
        setattr(module, name, counting)


def count_cells(every):
    from kernels import (api, codes, driver, event_search, transitions,  # noqa: F401
                         zeno)
    if not getattr(driver.run_scene, "py_func", None) is None:
        raise SystemExit("counts needs NUMBA_DISABLE_JIT=1")
    rows, rec = map_rows(every)
    c = Counter()
    c.wrap(driver, "step")
    c.wrap(driver, "polish")
    c.wrap(event_search, "event_values", "event_values (sample)")
    c.wrap(event_search, "event_value", "event_value (root finding)")
    c.wrap(event_search, "_locate", "brent")
    c.wrap(event_search, "_peak", "peak search")
    c.wrap(driver, "observe_turns")
    c.wrap(transitions, "stop_corner", "zeno stop_corner")
    c.wrap(transitions, "rocking_closes")
    res = api.run_cells(rows, rec)
    n = rows.shape[0]
    print(f"{n} cells (every {every}-th); per cell:")
    for name, field in (("steps (taken + rejected + re-steps)", "steps"),
                        ("events", "events"), ("impacts", "impacts")):
        print(f"  {name:40s} {res[field].sum() / n:10.1f}")
    for key in sorted(c):
        print(f"  calls {key:34s} {c[key] / n:10.1f}")


def steady(repeat):
    import statistics

    from . import scenes, work_precision as wp
    from kernels.api import run_scene
    scene = next(sc for sc in scenes.SCENES if sc.key == "steady_rocking")
    reference, _ = wp._reference(scene)
    for rtol in (1e-6, 1e-8):
        resolved = wp._adaptive(scene.resolved, rtol)
        run_scene(resolved)
        runs = [run_scene(resolved) for _ in range(repeat)]
        err, note = scenes.error(scenes.Outcome.of_kernel(runs[-1]), reference, scene)
        print(f"steady rocking rtol {rtol:.0e}: {1e3 * statistics.median(r.cpu_s for r in runs):.3f}"
              f" ms (median of {repeat}), impact-time error {err:.2e} s {note}, "
              f"{len(runs[-1].impact_times)} impacts, {runs[-1].steps} steps")


def ensemble():
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
    import hard_cases as hc
    phases = hc.ensemble_phases(1000, seed=2)
    for name, solver in (("rtol 1e-9", hc.tolerance(1e-9)), ("rtol 1e-6", hc.tolerance(1e-6)),
                         ("map settings", {**hc.tolerance(1e-6), "zeno_dt": 1e-4})):
        print(f"{name}: {int(hc.overturned(hc.phase_ensemble(phases, **solver)).sum())}/1000 "
              "overturned")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("what", choices=("time", "counts", "steady", "ensemble"))
    parser.add_argument("--every", type=int, default=10)
    parser.add_argument("--base", help="directory holding kernels_base/")
    parser.add_argument("--repeat", type=int, default=1)
    args = parser.parse_args()
    if args.what == "time":
        time_cells(args.every, args.base, args.repeat)
    elif args.what == "counts":
        count_cells(args.every)
    elif args.what == "steady":
        steady(args.repeat)
    else:
        ensemble()


if __name__ == "__main__":
    main()
