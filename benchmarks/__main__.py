"""``python -m benchmarks [--quick]``: run every section, write the report and the plot.

Sections are the modules named in ``SECTIONS``, each with ``section(quick) -> str``
(Markdown); a section whose module is absent is left out.  The work-precision section also
draws the plot.  The report starts with the machine, its load and the run time, because every
number in it is a measurement on that machine at that time; then come the first section's
tables (``headline``: cells per second, scaling by rank count, map-cell cost), the targets side
by side and the other sections.
"""
import argparse
import importlib
import importlib.util
import os
import platform
import sys
import time
from datetime import datetime, timezone
from pathlib import Path

from .markdown import table, write_text

SECTIONS = ("headline", "startup", "cells", "work_precision", "throughput", "stability",
            "refine")
OUTPUT = Path("results/bench.md")
FIGURE = Path("figures/bench_work_precision.png")


def _versions():
    import numba
    import numpy
    import scipy
    return (f"Python {platform.python_version()}, numpy {numpy.__version__}, "
            f"numba {numba.__version__}, scipy {scipy.__version__}")


def _header(quick, figure, output, wall, load_start, load_end, names):
    link = os.path.relpath(figure, output.parent)
    return "\n".join([
        "# Benchmarks: speed against error, throughput, stability" + (" (quick)" if quick
                                                                      else ""), "",
        f"Written by `python -m benchmarks{' --quick' if quick else ''}` on "
        f"{datetime.now(timezone.utc).strftime('%Y-%m-%d %H:%M UTC')}; {wall:.0f} s. "
        f"Machine: {platform.machine()}, {os.cpu_count()} cores, {_versions()}. "
        f"Load average (1 min) {load_start:.2f} at the start, {load_end:.2f} at the end: "
        "on a shared machine every time below is an upper bound of what the code needs.", "",
        f"Sections: {', '.join(names)}. Targets are those of docs/design.md section 10.", "",
        f"![work-precision plot]({link})", ""])


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="python -m benchmarks",
        description="Speed against error, throughput and stability of the kernel "
                    "(docs/design.md section 10): writes a Markdown report and a plot.")
    parser.add_argument("--quick", action="store_true",
                        help="a fast smoke run: fewer scenes, rungs, cells and repeats")
    parser.add_argument("-o", "--output", type=Path, default=OUTPUT,
                        help="report file (default %(default)s)")
    parser.add_argument("--figure", type=Path, default=FIGURE,
                        help="work-precision plot (default %(default)s)")
    args = parser.parse_args(argv)
    t0 = time.perf_counter()
    load_start = os.getloadavg()[0]
    parts, names, targets = [], [], []
    for name in SECTIONS:
        if importlib.util.find_spec(f"{__package__}.{name}") is None:
            continue
        print(f"benchmarks: {name} ...", file=sys.stderr, flush=True)
        module = importlib.import_module(f"{__package__}.{name}")
        part = (module.section(args.quick, figure=args.figure) if name == "work_precision"
                else module.section(args.quick))
        parts.append(part.text)
        targets += part.targets
        names.append(name)
    header = _header(args.quick, args.figure, args.output, time.perf_counter() - t0,
                     load_start, os.getloadavg()[0], names)
    summary = "\n".join(["## Targets, side by side", "",
                         table(["target (docs/design.md 10)", "measured", "met"], targets), ""])
    parts = [p.rstrip() + "\n" for p in parts]
    write_text(args.output, "\n".join([header, *parts[:1], summary, *parts[1:]]))
    print(f"wrote {args.output} and {args.figure}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
