"""A warp's divergence measured on the CPU: a lock-step trace of 32 cells' passes.

    python -m benchmarks.warp_trace [--cells N] [--first I] [--t-end T] [--study FILE]...
                                    [--base REV] [-o FILE]

On a GPU the 32 threads of a warp, one cell each, run in lock step: in every pass of
``driver.run_scene``'s loop each lane does its own kind of work, and lanes doing different
kinds wait for each other.  This runs N consecutive cells of each study (a warp's lanes in
grid order, from cell I; default 32 from 0; the scenes' t_end cut to T seconds) through the
plain-Python kernel (``NUMBA_DISABLE_JIT=1``) in a child process that notes, between the
loop's reads of ``ctl[CTL_STOP]`` (one a pass), the calls of ``step``, ``first_event`` (one
that finds an event), ``polish``, ``on_event``, the start of a rest's scan (``rest_begin``,
or ``rest_exit`` that scanned a whole rest) and the scan's intervals (``scan_step``), as
``tests/kernels/test_one_step_per_pass.py`` does.  A pass's kind is ``event`` (a step to a
found event, its polish or its law), else ``step`` (Runge-Kutta steps), else ``rest`` (a
scan), else ``end`` (the pass that ends the loop).  The lanes' passes are then aligned (pass
p of every lane together; a lane that has finished idles) and the table says, for the loop of
this tree and that of commit REV (default c3fab68, the loop before one step per pass: its
``git archive`` run through ``PYTHONPATH``): the warp's passes, the share of divergent passes
(running lanes of more than one kind), of passes in which a lane locates an event or scans a
rest, the most RK steps and scan intervals of one lane in one pass, and the efficiency, the
lanes' own passes over lanes x the warp's passes.  Written to ``-o`` (default
``results/warp_trace.md``).  Default studies: ``benchmarks/sweep_map.yaml`` cut to 10 s
and ``studies/fragility_synthetic.yaml`` as it is.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from .markdown import table, write_text

ROOT = Path(__file__).resolve().parents[1]
# (study, t_end [s] of its scenes cut to; 0: as given): a map cell's 60 s sweep takes about
# 8 s as plain Python, 32 of them 4 minutes a tree
STUDIES = ((ROOT / "benchmarks" / "sweep_map.yaml", 10.0),
           (ROOT / "studies" / "fragility_synthetic.yaml", 0.0))
OUTPUT = Path("results/warp_trace.md")
BASE = "c3fab68"
WARP = 32

# Run in the tree given by PYTHONPATH: argv = study, first cell, cells, t_end (0: as given).
# Marks, "|" before each pass: S a step, F an event found in one, P a polish, E an event's law,
# B a rest's scan begun (or, before, a whole scan), R a scan interval.
TRACE = r"""
import json, sys
import numpy as np
from kernels import api, codes, driver, rest_skipping
from sweep.runner import cells
from sweep.runner.cell_checks import load_study

marks = []


class Control(np.ndarray):
    def __getitem__(self, i):
        if i == codes.CTL_STOP:
            marks.append("|")
        return super().__getitem__(i)


def noting(module, name, mark, found=False):
    f = getattr(module, name, None)
    if f is None:
        return
    def call(*args):
        out = f(*args)
        if not found or out[0] >= 0:
            marks.append(mark)
        return out
    setattr(module, name, call)


control = api.control
api.control = lambda *a: control(*a).view(Control)
for name, mark in (("step", "S"), ("polish", "P"), ("on_event", "E"), ("rest_begin", "B"),
                   ("rest_exit", "B")):
    noting(driver, name, mark)
noting(driver, "first_event", "F", found=True)
noting(rest_skipping, "scan_step", "R")
path, first, n, t_end = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4])
study = load_study(path)
rows, rec = cells.build_rows(study, np.arange(first, min(first + n, study.n_cells)))[:2]
if t_end > 0.0:
    rows["solver"]["t_end"] = np.minimum(rows["solver"]["t_end"], t_end)
lanes = []
for i in range(rows.shape[0]):
    marks.clear()
    r = api.run_cells(rows[i:i + 1], rec)[0]
    lanes.append({"passes": "".join(marks).split("|")[1:], "steps": int(r["steps"]),
                  "events": int(r["events"]), "status": int(r["status"])})
print(json.dumps(lanes))
"""


def trace(tree, study, first, n, t_end):
    """Each lane's passes (strings of marks), steps, events and status: cells first ...
    first + n - 1 of ``study`` on the plain-Python kernel of ``tree``."""
    env = {**os.environ, "NUMBA_DISABLE_JIT": "1", "PYTHONPATH": str(tree)}
    ran = subprocess.run([sys.executable, "-c", TRACE, str(Path(study).resolve()), str(first),
                          str(n), str(t_end)], env=env, cwd=tree, capture_output=True,
                         text=True)
    if ran.returncode != 0:
        last = (ran.stderr.strip().splitlines() or ["no message"])[-1]
        raise RuntimeError(f"{study} in {tree}: {last}")
    lanes = json.loads(ran.stdout)
    if not lanes:
        raise RuntimeError(f"{study}: no cell {first}")
    return lanes


def kind(marks):
    """The kind of work of a pass, from its marks."""
    if "E" in marks or "P" in marks:
        return "event"
    if "S" in marks:
        return "step"
    if "R" in marks or "B" in marks:
        return "rest"
    return "end"


def work(marks):
    """The units of work of a pass: its RK steps and scan intervals, at least one."""
    return max(1, marks.count("S") + marks.count("R"))


def lock_step(lanes):
    """The warp's passes: for each pass, every lane's (kind, work), None where it has
    finished."""
    own = [[(kind(m), work(m)) for m in lane["passes"]] for lane in lanes]
    width = max(len(k) for k in own)
    return [[k[p] if p < len(k) else None for k in own] for p in range(width)]


def serialised(lanes):
    """The units of a pass in lock step: the kinds in it one after the other, each as long
    as its longest lane."""
    longest = {}
    for k, w in filter(None, lanes):
        longest[k] = max(longest.get(k, 0), w)
    return sum(longest.values())


def figures(lanes):
    """The warp's figures: passes, shares of divergent, event and rest passes, most steps
    and intervals of a lane in a pass, efficiency (the lanes' passes over lanes x passes)
    and the same in units of work with the kinds of a pass serialised."""
    passes = lock_step(lanes)
    running = [{k for k, _ in filter(None, p)} for p in passes]
    marks = [m for lane in lanes for m in lane["passes"]]
    n = len(passes)
    return {"passes": n,
            "divergent": sum(len(r) > 1 for r in running) / n,
            "event": sum("event" in r for r in running) / n,
            "rest": sum("rest" in r for r in running) / n,
            "steps": max(m.count("S") for m in marks),
            "intervals": max(m.count("R") for m in marks),
            "efficiency": len(marks) / (len(lanes) * n),
            "work": sum(map(work, marks)) / (len(lanes) * sum(map(serialised, passes)))}


ROWS = (("warp passes", "passes", "{:,}"), ("divergent passes", "divergent", "{:.1%}"),
        ("passes in which a lane locates an event", "event", "{:.1%}"),
        ("passes in which a lane scans a rest", "rest", "{:.1%}"),
        ("most RK steps of a lane in a pass", "steps", "{}"),
        ("most scan intervals of a lane in a pass", "intervals", "{}"),
        ("efficiency (lanes' passes / lanes x warp passes)", "efficiency", "{:.1%}"),
        ("efficiency in units of work, kinds serialised", "work", "{:.1%}"))


def report(columns):
    """The Markdown table: one column per (heading, figures)."""
    return table(["", *(heading for heading, _ in columns)],
                 [[label, *(fmt.format(f[key]) for _, f in columns)]
                  for label, key, fmt in ROWS])


def base_tree(rev, folder):
    """``git archive`` of ``rev`` of this repository, unpacked in ``folder``."""
    archive = subprocess.run(["git", "-C", str(ROOT), "archive", rev], capture_output=True)
    if archive.returncode != 0:
        raise RuntimeError(f"--base {rev}: {archive.stderr.decode().strip()}")
    subprocess.run(["tar", "x", "-C", str(folder)], input=archive.stdout, check=True)
    return Path(folder)


def warp(args):
    """The table's columns: (heading, figures) of each study on each tree."""
    studies = [(s, args.t_end) for s in args.study or ()] or STUDIES
    with tempfile.TemporaryDirectory() as folder, ThreadPoolExecutor(2) as pool:
        trees = ((f"{args.base} (before)", base_tree(args.base, folder)), ("this tree", ROOT))
        runs = [(f"{Path(study).stem}{cut(t_end)}, {name}",
                 pool.submit(trace, tree, study, args.first, args.cells, t_end))
                for study, t_end in studies for name, tree in trees]
        return [(heading, figures(run.result())) for heading, run in runs]


def cut(t_end):
    """What a column's heading says of the scenes' t_end."""
    return f", t_end <= {t_end:g} s" if t_end > 0.0 else ""


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m benchmarks.warp_trace",
                                     description=__doc__.split("\n")[0])
    parser.add_argument("--cells", type=int, default=WARP, help="lanes (default 32)")
    parser.add_argument("--first", type=int, default=0, help="the first cell (default 0)")
    parser.add_argument("--t-end", type=float, default=0.0,
                        help="the t_end of --study's scenes cut to this [s] (default: as given)")
    parser.add_argument("--study", type=Path, action="append",
                        help="a study file (repeatable; default the map and the records)")
    parser.add_argument("--base", default=BASE, help="the commit of the loop before")
    parser.add_argument("-o", "--output", type=Path, default=OUTPUT)
    args = parser.parse_args(argv)
    if args.cells < 1 or args.first < 0:
        parser.error(f"--cells must be >= 1 and --first >= 0, got {args.cells}, {args.first}")
    for study in args.study or ():
        if not study.is_file():
            parser.error(f"--study: no file {study}")
    try:
        columns = warp(args)
    except RuntimeError as e:
        parser.exit(2, f"{parser.prog}: {e}\n")
    text = (f"# A warp in lock step: cells {args.first}-{args.first + args.cells - 1}, "
            f"plain-Python kernel\n\n{report(columns)}\n")
    print(text)
    write_text(args.output, text)


if __name__ == "__main__":
    main()
