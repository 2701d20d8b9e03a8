"""Throughput: a map of 60 s sweeps (``sweep_map.yaml``) on 1 and on 2 MPI ranks.

Kernel CPU per cell is timed in this process, cell by cell (``time.process_time`` around
``kernels.api.run_cells`` of one row, after compilation); the study is then run as a user runs
it, ``python -m sweep.run`` and ``mpiexec -n 2 python -m sweep.run``, timed by the wall clock
from launch to exit (start-up, kernel cache load, merge and netCDF writing included), and the
two datasets are compared.  Quick mode keeps two values of every axis.
"""
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import yaml

from kernels import api

from .markdown import Section, ms, table, verdict

STUDY = Path(__file__).with_name("sweep_map.yaml")
TARGET_CELL_CPU = 5e-3      # s per 60 s sweep cell (docs/design.md 10)
TARGET_MAP_WALL = 5.0       # s for 1,000 cells on 2 ranks
TARGET_SPEEDUP = 1.8
TIMEOUT = 1800              # s per sweep.run launch


def quick_study(raw, keep=2):
    """The study with the first and last (keep = 2) or the first (keep = 1) value of every
    axis."""
    grid = {}
    for name, spec in raw["grid"].items():
        values = spec if isinstance(spec, list) else spec.get("values")
        if values is not None:
            kept = [values[0], values[-1]][:keep]
            grid[name] = kept if isinstance(spec, list) else {**spec, "values": kept}
        elif keep == 2:
            grid[name] = {**spec, "num": 2}
        else:
            grid[name] = {**spec, "stop": spec["start"], "num": 1}
    return {**raw, "name": f"{raw['name']}_{keep}", "grid": grid}


def mpiexec():
    """The launcher named by ``$MPIEXEC``, else the mpiexec next to this Python (the venv's
    MPI), else the one on PATH, else None."""
    return os.environ.get("MPIEXEC") or \
        shutil.which("mpiexec", path=str(Path(sys.executable).parent)) or \
        shutil.which("mpiexec")


def _environment():
    """This environment without MPI launcher variables (a run under a launcher stays sane)."""
    return {k: v for k, v in os.environ.items()
            if not k.startswith(("PMI_", "OMPI_", "PMIX_", "MPI_LOCAL", "MV2_"))}


def _children_cpu():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _launch(command, cwd):
    """(wall time, CPU time of all its processes) [s] of a command, from launch to exit;
    raises with its stderr on failure."""
    cpu0, t0 = _children_cpu(), time.perf_counter()
    done = subprocess.run(command, cwd=cwd, env=_environment(), capture_output=True,
                          text=True, timeout=TIMEOUT)
    wall, cpu = time.perf_counter() - t0, _children_cpu() - cpu0
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(map(str, command))} failed ({done.returncode}):\n"
                           f"{done.stderr[-2000:]}")
    return wall, cpu


def kernel_cpu_per_cell(study_path):
    """(kernel CPU [s] of each cell, scene-building CPU [s] per cell, outcome codes)."""
    from sweep.runner.cell_checks import load_study
    from sweep.runner import cells

    study = load_study(study_path)
    ids = np.arange(study.n_cells)
    cells.warm_up()
    t0 = time.process_time()
    rows, rec, bodies, motions, _ = cells.build_rows(study, ids)  # the bench map has no invalid cell
    build = (time.process_time() - t0) / ids.size
    cpu = np.empty(ids.size)
    results = api.not_run(ids.size)
    for k in range(ids.size):
        t0 = time.process_time()
        results[k] = api.run_cells(rows[k:k + 1], rec)[0]
        cpu[k] = time.process_time() - t0
    return cpu, build, cells.summarize(results, bodies, motions,
                                       rows["restraint"]["kind"])["outcome"]


def _same(path_a, path_b):
    """True when two study datasets have equal coordinates and data (attributes aside)."""
    import xarray as xr
    with xr.open_dataset(path_a) as a, xr.open_dataset(path_b) as b:
        return a.equals(b)


def _runs(study, tmp, tag):
    """(wall, CPU) of the study on 1 rank and on 2 ranks (None without mpiexec), and whether
    the two datasets are identical."""
    run = [sys.executable, "-m", "sweep.run", str(study), "--quiet", "-o"]
    cwd = Path(__file__).resolve().parents[1]
    one = _launch([*run, str(tmp / f"{tag}_one.nc")], cwd)
    launcher = mpiexec()
    if launcher is None:
        return one, None, None
    two = _launch([launcher, "-n", "2", *run, str(tmp / f"{tag}_two.nc")], cwd)
    return one, two, _same(tmp / f"{tag}_one.nc", tmp / f"{tag}_two.nc")


def measure(quick):
    """Dict of the measurements (see ``section``)."""
    raw = yaml.safe_load(STUDY.read_text())
    with tempfile.TemporaryDirectory(prefix="bench_sweep_") as tmp:
        tmp = Path(tmp)
        study, single = tmp / "sweep_map.yaml", tmp / "one_cell.yaml"
        study.write_text(yaml.safe_dump(quick_study(raw) if quick else raw, sort_keys=False))
        single.write_text(yaml.safe_dump(quick_study(raw, keep=1), sort_keys=False))
        cpu, build, outcome = kernel_cpu_per_cell(study)
        one, two, same = _runs(study, tmp, "map")
        startup = _runs(single, tmp, "single")
    return {"cells": cpu.size, "cpu": cpu, "build": build, "outcome": outcome, "one": one,
            "two": two, "identical": same, "startup": startup}


def targets(m):
    """Rows (target, measured, met) of docs/design.md 10."""
    n, cpu = m["cells"], m["cpu"]
    rows = [["60 s sweep <= 5 ms CPU on average over a map",
             f"{ms(cpu.mean())} ms (kernel, {n} cells)", verdict(cpu.mean() <= TARGET_CELL_CPU)]]
    if m["two"] is None:
        rows.append(["2 ranks", "not run: no mpiexec", verdict(None)])
        return rows
    wall_one, wall_two = m["one"][0], m["two"][0]
    per_1000 = wall_two * 1000 / n
    met = verdict(per_1000 <= TARGET_MAP_WALL)
    rows.append(["1,000-cell map of 60 s sweeps <= 5 s on 2 ranks, start-up included",
                 f"{wall_two:.2f} s for {n} cells"
                 + ("" if n == 1000 else f" ({per_1000:.1f} s per 1,000)"),
                 met if n >= 1000 else f"({met})"])
    speedup = wall_one / wall_two
    rows.append(["2 ranks >= 1.8x one rank on the same study, identical results",
                 f"{speedup:.2f}x; datasets {'identical' if m['identical'] else 'DIFFER'}",
                 verdict(speedup >= TARGET_SPEEDUP and m["identical"])])
    return rows


def _run_rows(m):
    n = m["cells"]
    rows = []
    for label, cells, (one, two) in ((f"the map, {n} cells", n, (m["one"], m["two"])),
                                     ("one cell (start-up)", 1, m["startup"][:2])):
        rows.append([label, 1, f"{one[0]:.2f}", f"{one[1]:.2f}", f"{cells / one[0]:.3g}",
                     "1.00"])
        if two is not None:
            rows.append([label, 2, f"{two[0]:.2f}", f"{two[1]:.2f}",
                         f"{cells / two[0] / 2:.3g}", f"{one[0] / two[0]:.2f}"])
    return rows


def section(quick):
    """Markdown of the throughput benchmark."""
    m = measure(quick)
    n, cpu, outcome = m["cells"], m["cpu"], m["outcome"]
    per_outcome = []
    for code, name in ((1, "rocked, still standing at 60 s"), (2, "overturned"),
                       (0, "never rocked"), (-1, "failed")):
        chosen = cpu[outcome == code]
        if chosen.size:
            per_outcome.append([name, chosen.size, ms(chosen.mean()), ms(np.median(chosen)),
                                ms(chosen.max())])
    rows = targets(m)
    same = "" if m["identical"] is None else (
        f"\nThe datasets of 1 and 2 ranks are {'identical' if m['identical'] else 'NOT identical'}"
        " (coordinates and data; `Dataset.equals`).")
    return Section("\n".join([
        "## Throughput (a map of 60 s sweeps)", "",
        f"`benchmarks/sweep_map.yaml`{' reduced to two values per axis' if quick else ''}: "
        f"{n} cells. Kernel CPU per cell timed in one process after compilation; "
        f"building a cell's scene from the study costs {ms(m['build'])} ms more. Wall times "
        "from launch to exit of `python -m sweep.run` (1 rank) and `mpiexec -n 2 python -m "
        "sweep.run` (2 ranks), start-up, merge and netCDF writing included; the CPU time of "
        "their processes shows how much of the wall time went to other work on the machine. "
        "The one-cell study (first value of every axis) measures the start-up.", "",
        table(["target (docs/design.md 10)", "measured", "met"], rows), "",
        table(["cells", "count", "kernel CPU mean [ms]", "median [ms]", "max [ms]"],
              [["all", n, ms(cpu.mean()), ms(np.median(cpu)), ms(cpu.max())],
               *per_outcome]), "",
        table(["study", "ranks", "wall [s]", "CPU of its processes [s]", "cells/s per core",
               "speed-up"], _run_rows(m)),
        same, ""]), rows)
