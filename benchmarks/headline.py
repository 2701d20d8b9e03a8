"""The report's first tables: cells per second on the CPU (one rank, every core) and on the
GPU, the scaling by rank count, and the cost of a map cell against the floor.

All on the map of 60 s sweeps ``sweep_map.yaml`` (quick: two values per axis,
``throughput.quick_study``).  Cells per second and scaling: ``python -m sweep.run`` under
``mpiexec -n K`` for K = 1, 2, 4, ... up to the cores (``scaling``), launch to exit, the
datasets compared with one rank's.  GPU: ``benchmarks.gpu.on_gpu``, the kernel alone, compile
left out, when numba-cuda and a GPU are there.  Map cell: kernel CPU per cell in this process
(``throughput.kernel_cpu_per_cell``) against the floor (``benchmarks/floor.py``: the same
body and sweep in a rocking-only loop on the kernel's tableau, Housner's impact, no event
search beyond the impact's), both at the map's rtol, atol and zeno_dt.
"""
import os
import tempfile
import time
from pathlib import Path

import numpy as np
import yaml

from kernels import gpu as door

from . import floor, gpu, scaling
from .markdown import Section, ms, table
from .throughput import STUDY, kernel_cpu_per_cell, mpiexec, quick_study


def floor_cpu_per_cell(study):
    """CPU [s] of the floor loop on each cell of ``study`` (compiled first)."""
    from sweep.io.scene_schema import load_scene, resolve_scene
    from sweep.runner import grid

    scenes = [resolve_scene(load_scene(grid.cell_scene(study, i), base_dir=study.base_dir))
              for i in range(study.n_cells)]
    for scene in scenes:
        if not floor.takes(scene):
            raise ValueError("the floor loop does not take the cells of this study")

    def run(scene):
        solver = scene["solver"]
        floor.run(scene, solver["rtol"], solver["atol"], zeno_dt=solver["zeno_dt"])

    run(scenes[0])
    cpu = np.empty(len(scenes))
    for k, scene in enumerate(scenes):
        t0 = time.process_time()
        run(scene)
        cpu[k] = time.process_time() - t0
    return cpu


def _gpu_row(path):
    """The GPU's row: cells/s of the kernel alone, or why there is none."""
    why = door.unavailable()
    if why is not None:
        return ["GPU", "no GPU on this machine" if not list(Path("/dev").glob("nvidia[0-9]*"))
                else f"not run: {why}", "–"]
    rows, rec = gpu._rows(path)
    _, wall = gpu.on_gpu(rows, rec)
    return ["GPU (1)", f"{rows.shape[0] / wall:,.0f} cells/s",
            "the kernel alone, compile left out (`benchmarks.gpu.on_gpu`)"]


def section(quick):
    """Markdown of the headline tables."""
    from sweep.io.study_schema import load_study
    raw = yaml.safe_load(STUDY.read_text())
    cores, launcher = os.cpu_count(), mpiexec()
    with tempfile.TemporaryDirectory(prefix="bench_headline_") as tmp:
        path = Path(tmp) / STUDY.name
        path.write_text(yaml.safe_dump(quick_study(raw) if quick else raw, sort_keys=False))
        study = load_study(path)
        n = study.n_cells
        kernel, _, _ = kernel_cpu_per_cell(path)
        floor_cpu = floor_cpu_per_cell(study)
        gpu_row = _gpu_row(path)
        measured = [] if launcher is None else \
            scaling.measure(path, scaling.default_ranks(), launcher)
    ends = measured[:1] + measured[1:][-1:]      # one rank and the most ranks
    rows = [[f"CPU, {k} rank{'s' if k > 1 else ''}" + (" (every core)" if k == cores else ""),
             f"{n / wall:,.1f} cells/s", f"`mpiexec -n {k} python -m sweep.run`, launch to exit"]
            for k, wall, _ in ends] or [["CPU", "not run: no mpiexec", "–"]]
    rows += [gpu_row,
             ["map cell, one core", f"{ms(kernel.mean())} ms",
              f"kernel CPU per cell, mean of {n} (median {ms(np.median(kernel))} ms)"],
             ["floor, same cells", f"{ms(floor_cpu.mean())} ms",
              f"the kernel costs {kernel.mean() / floor_cpu.mean():.1f}x the floor "
              "(`benchmarks/floor.py`)"]]
    scaling_text = "no mpiexec: not run" if not measured else \
        table(scaling.HEADER, scaling.rows(measured, n))
    return Section("\n".join([
        "## Headline: cells per second, scaling, map-cell cost", "",
        f"`benchmarks/sweep_map.yaml`{' reduced to two values per axis' if quick else ''}: "
        f"{n} cells of 60 s sweeps on {cores} cores.  Cells per second from launch to exit "
        "(start-up, merge and netCDF writing included); the map cell's CPU in one process "
        "after compilation, against the floor: the same bodies and sweeps in a rocking-only "
        "loop on the kernel's tableau with Housner's impact and the map's Zeno closure (no "
        "sliding, flight or other modes' events), at the map's rtol, atol and zeno_dt.", "",
        table(["measure", "value", "how"], rows), "",
        "Scaling by rank count (speed-up against one rank; datasets compared with one "
        "rank's):", "", scaling_text, ""]), [])
