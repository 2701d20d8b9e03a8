"""``python -m benchmarks.scaling [--levels N] [RANKS ...]``: wall time of ``sweep_map.yaml``
on 1, 2, 4, 8 and 16 ranks (those up to the machine's cores, unless named), launch to exit, the
speed-up and efficiency against one rank, and whether every dataset is identical to one rank's.
``--levels 160`` makes the map 4,000 cells (160 amplitude levels in place of 40)."""
import argparse
import os
import sys
import tempfile
from pathlib import Path

import yaml

from .markdown import table
from .throughput import STUDY, _launch, _same, mpiexec

RANKS = (1, 2, 4, 8, 16)
HEADER = ["ranks", "wall [s]", "cells/s", "speed-up", "efficiency", "identical"]


def default_ranks():
    """The rank counts of ``RANKS`` up to the machine's cores."""
    return [k for k in RANKS if k <= os.cpu_count()]


def measure(study, ranks, launcher):
    """[(ranks, wall [s], dataset identical to the first's)] of ``study`` run by
    ``mpiexec -n RANKS python -m sweep.run``, launch to exit."""
    cwd = Path(__file__).resolve().parents[1]
    with tempfile.TemporaryDirectory(prefix="bench_scaling_") as tmp:
        outputs = [Path(tmp) / f"ranks{k}.nc" for k in ranks]
        walls = [_launch([launcher, "-n", str(k), sys.executable, "-m", "sweep.run", str(study),
                          "--quiet", "-o", str(out)], cwd)[0] for k, out in zip(ranks, outputs)]
        return [(k, wall, _same(outputs[0], out)) for k, wall, out in zip(ranks, walls, outputs)]


def rows(measured, cells):
    """Table rows of :func:`measure`: speed-up against the first count times its ranks."""
    k0, wall0, _ = measured[0]
    out = []
    for k, wall, same in measured:
        speedup = wall0 * k0 / wall
        out.append([k, f"{wall:.1f}", f"{cells / wall:,.0f}", f"{speedup:.2f}x",
                    f"{speedup / k:.0%}", "yes" if same else "**no**"])
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m benchmarks.scaling",
                                     description=__doc__.split("\n\n")[0].replace("``", "`"))
    parser.add_argument("ranks", nargs="*", type=int, help="rank counts (default: "
                        f"{', '.join(map(str, RANKS))} up to the cores)")
    parser.add_argument("--levels", type=int, help="amplitude levels of the map (default 40)")
    args = parser.parse_args(argv)
    ranks = args.ranks or default_ranks()
    launcher = mpiexec()
    if launcher is None:
        print("benchmarks.scaling: no mpiexec; nothing was run", file=sys.stderr)
        return 2
    from sweep.io.study_schema import load_study
    with tempfile.TemporaryDirectory(prefix="bench_scaling_study_") as tmp:
        study = STUDY
        if args.levels is not None:
            raw = yaml.safe_load(STUDY.read_text())
            raw["grid"]["amplitude"]["num"] = args.levels
            study = Path(tmp) / STUDY.name
            study.write_text(yaml.safe_dump(raw, sort_keys=False))
        cells = load_study(study).n_cells
        measured = measure(study, ranks, launcher)
    print(f"`{STUDY.name}`, {cells:,} cells, on {os.cpu_count()} cores (speed-up against "
          f"{ranks[0]} rank{'s' if ranks[0] > 1 else ''} times its count)\n")
    print(table(HEADER, rows(measured, cells)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
