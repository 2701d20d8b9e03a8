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


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    ranks = [int(k) for k in argv] or [k for k in RANKS if k <= os.cpu_count()]
    launcher = mpiexec()
    if launcher is None:
        print("benchmarks.scaling: no mpiexec; nothing was run", file=sys.stderr)
        return 2
    cwd = Path(__file__).resolve().parents[1]
    rows = []
    with tempfile.TemporaryDirectory(prefix="bench_scaling_") as tmp:
        outputs = [Path(tmp) / f"ranks{k}.nc" for k in ranks]
        walls = [_launch([launcher, "-n", str(k), sys.executable, "-m", "sweep.run", str(STUDY),
                          "--quiet", "-o", str(out)], cwd)[0] for k, out in zip(ranks, outputs)]
        for k, wall, out in zip(ranks, walls, outputs):
            speedup = walls[0] * ranks[0] / wall
            rows.append([k, f"{wall:.1f}", f"{speedup:.2f}x", f"{speedup / k:.0%}",
                         "yes" if _same(outputs[0], out) else "**no**"])
    print(f"`{STUDY.name}` on {os.cpu_count()} cores (speed-up against {ranks[0]} rank"
          f"{'s' if ranks[0] > 1 else ''} times its count)\n")
    print(table(["ranks", "wall [s]", "speed-up", "efficiency", "identical"], rows))
    return 0


if __name__ == "__main__":
    sys.exit(main())
