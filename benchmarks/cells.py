"""The cells phase against the kernel's own time, and the start-up of a large study.

``cells_phase.yaml`` holds 20,000 cells of 0.2 s scenes: the kernel's time is small, so the
work around it shows (each cell's checked scene, its kernel row, the summary of its results).
In this process the study is run chunk by chunk (``sweep.runner.cells.ChunkRunner``, chunks of
2,000 cells) and the wall time of the chunks is set against that of the kernel calls inside
them (``kernels.api.run_cells``).  The start-up is the one ``python -m sweep.run`` reports
for that study on one rank (launch to the first chunk: the study read and its cells checked,
the kernel loaded from the numba cache).
"""
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from .markdown import Section, table, verdict

ROOT = Path(__file__).resolve().parents[1]
STUDY = Path(__file__).with_name("cells_phase.yaml")
CHUNK = 2000
TARGET_RATIO = 1.5      # wall time of the cells phase / the kernel's within it
TARGET_STARTUP = 0.5    # s of start-up of sweep.run on the 20,000 cells


def cells_phase(every):
    """(wall time of the chunks, of the kernel calls within them) [s] over every ``every``-th
    cell of the study."""
    from kernels import api
    from sweep.runner import cells
    from sweep.runner.cell_checks import load_study

    study = load_study(STUDY, check_cells=False)
    cells.warm_up()
    kernel, run_cells = [0.0], api.run_cells

    def timed(*args, **kwargs):
        t0 = time.perf_counter()
        try:
            return run_cells(*args, **kwargs)
        finally:
            kernel[0] += time.perf_counter() - t0
    index = np.arange(0, study.n_cells, every)
    runner = cells.ChunkRunner()
    api.run_cells = timed
    try:
        t0 = time.perf_counter()
        for start in range(0, index.size, CHUNK):
            runner(study, index[start:start + CHUNK])
        wall = time.perf_counter() - t0
    finally:
        api.run_cells = run_cells
    return wall, kernel[0]


def startup():
    """The start-up [s] that ``python -m sweep.run`` reports for the study on one rank."""
    with tempfile.TemporaryDirectory(prefix="bench_cells_") as folder:
        done = subprocess.run([sys.executable, "-m", "sweep.run", str(STUDY), "--force",
                               "-o", str(Path(folder) / "cells.nc")], cwd=ROOT,
                              capture_output=True, text=True)
    found = re.search(r"start-up ([0-9.]+) s", done.stdout + done.stderr)
    if done.returncode != 0 or found is None:
        raise RuntimeError(f"sweep.run failed: {done.stderr[-2000:]}")
    return float(found.group(1))


def section(quick):
    """Markdown of the cells-phase benchmark."""
    every = 10 if quick else 1
    wall, kernel = cells_phase(every)
    start = startup()
    rows = [[f"cells phase <= {TARGET_RATIO:g}x the kernel's time (20,000 cells of 0.2 s)",
             f"{wall:.2f} s against {kernel:.2f} s: {wall / kernel:.2f}x",
             verdict(wall <= TARGET_RATIO * kernel)],
            [f"start-up of `sweep.run` on those cells <= {TARGET_STARTUP:g} s",
             f"{start:.2f} s", verdict(start <= TARGET_STARTUP)]]
    n = len(range(0, 20_000, every))
    return Section("\n".join([
        "## Cells phase: the work around the kernel", "",
        f"`benchmarks/{STUDY.name}`: {n} cells of 0.2 s scenes run in chunks of {CHUNK} "
        "(`ChunkRunner`), the chunks' wall time against the kernel calls' within them; the "
        "start-up as `python -m sweep.run` reports it for the whole study on one rank.", "",
        table(["target", "measured", "met"], rows), ""]), rows)


if __name__ == "__main__":
    print(section("--quick" in sys.argv).text)
