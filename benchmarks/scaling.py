"""``python -m benchmarks.scaling [RANKS ...]``: wall time of ``sweep_map.yaml`` on 1, 2, 4,
8 and 16 ranks (those up to the machine's cores, unless named), launch to exit, the speed-up
and efficiency against one rank, and whether every dataset is identical to one rank's."""
import os
import sys
import tempfile
from pathlib import Path

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
    argv = sys.argv[1:] if argv is None else argv
    ranks = [int(k) for k in argv] or default_ranks()
    launcher = mpiexec()
    if launcher is None:
        print("benchmarks.scaling: no mpiexec; nothing was run", file=sys.stderr)
        return 2
    from sweep.io.study_schema import load_study
    measured = measure(STUDY, ranks, launcher)
    print(f"`{STUDY.name}` on {os.cpu_count()} cores (speed-up against {ranks[0]} rank"
          f"{'s' if ranks[0] > 1 else ''} times its count)\n")
    print(table(HEADER, rows(measured, load_study(STUDY).n_cells)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
