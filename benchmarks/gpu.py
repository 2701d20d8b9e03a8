"""``make bench-gpu`` (``python -m benchmarks.gpu [--quick]``): the CUDA kernel against every
CPU core of the same machine, on a 10,000-cell map and an ensemble of records.

The map is ``sweep_map.yaml`` with 400 amplitude levels (10,000 sweeps of 60 s), the
ensemble ``studies/fragility_synthetic.yaml`` (1,920 synthetic motions scaled in PGA).  Each
runs three times, compile and cache loading left out of the clock: on every CPU core (a
process pool over chunks of ``kernels.api.run_cells``), on the GPU
(``kernels.gpu.run_cells``), and on every CPU core again with the kernel compiled with
floating-point contraction (``KERNEL_CONTRACT=1``, ``kernels._jit``).  The last is the
yardstick: GPU compilers fuse a*b + c into one rounding, so the GPU's overturning times may
differ from the CPU's by as much as the CPU's own do when only that changes (chaotic rocking
amplifies the last bit).  Statuses must be identical.  Writes a Markdown report
(``-o``, default ``results/bench_gpu.md``); refuses, with exit status 2, without a GPU.

``--ptx FILE`` needs no GPU: it writes the kernel's PTX for sm_90 and prints its figures
(lines, byte loads, ``bfi``) and, where the CUDA toolkit's ``ptxas`` is installed (the cuda
extra's ``nvidia-cuda-nvcc``), those of ``ptxas -v``: registers per thread, spills, stack;
``--max-registers N`` gives ptxas's under that limit (numba-cuda's ``max_registers``).
"""
import argparse
import collections
import importlib.util
import multiprocessing
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import yaml

from kernels import api, codes, gpu as door

from .markdown import table, write_text

ROOT = Path(__file__).resolve().parents[1]
MAP = Path(__file__).with_name("sweep_map.yaml")
ENSEMBLE = ROOT / "studies" / "fragility_synthetic.yaml"
MAP_LEVELS = 400                  # amplitude levels: 400 x 5 b/h x 5 sizes = 10,000 cells
OUTPUT = Path("results/bench_gpu.md")
CHUNKS_PER_CORE = 8               # the pool's chunks: late chunks balance the cores' load


def _rows(path, raw=None, cells=None):
    """(rows, rec) of the cells of a study file, or of ``raw`` (a study dict) written beside it."""
    from sweep.runner.cell_checks import load_study
    from sweep.runner.cells import build_rows
    with tempfile.TemporaryDirectory(dir=path.parent, prefix=".bench_gpu_") as tmp:
        if raw is not None:
            path = Path(tmp) / path.name
            path.write_text(yaml.safe_dump(raw, sort_keys=False))
        study = load_study(path, check_cells=False)
        ids = np.arange(study.n_cells if cells is None else min(cells, study.n_cells))
        rows, rec, _, _, problems = build_rows(study, ids)
    assert not problems, problems
    return rows, rec


def _ready(barrier):
    from sweep.runner.cells import warm_up
    warm_up()                     # compile or load the kernel before the clock starts
    barrier.wait()


def _chunk(args):
    rows, rec = args
    return api.run_cells(rows, rec)


def on_cpu(rows, rec, contract=False):
    """(results, wall [s]) of the rows on every core: a pool of fresh processes, with the
    kernel compiled with contraction when ``contract``."""
    cores = os.cpu_count()
    ctx = multiprocessing.get_context("spawn")   # children import kernels._jit anew
    barrier = ctx.Barrier(cores + 1)
    os.environ["KERNEL_CONTRACT"] = "1" if contract else "0"
    try:
        with ctx.Pool(cores, initializer=_ready, initargs=(barrier,)) as pool:
            barrier.wait()
            size = max(1, rows.shape[0] // (CHUNKS_PER_CORE * cores))
            parts = [(rows[i:i + size], rec) for i in range(0, rows.shape[0], size)]
            t0 = time.perf_counter()
            results = np.concatenate(pool.map(_chunk, parts, chunksize=1))
            return results, time.perf_counter() - t0
    finally:
        del os.environ["KERNEL_CONTRACT"]


def on_gpu(rows, rec):
    """(results, wall [s]) of the rows on the GPU, after a launch that compiles."""
    door.run_cells(rows[:1], rec)
    t0 = time.perf_counter()
    results = door.run_cells(rows, rec)
    return results, time.perf_counter() - t0


def differences(a, b):
    """(cells whose status differs, |t_overturn differences| [s] where both overturned)."""
    both = (a["status"] == codes.OVERTURNED) & (b["status"] == codes.OVERTURNED)
    return int((a["status"] != b["status"]).sum()), np.abs(a["t_overturn"] - b["t_overturn"])[both]


def status_changes(a, b):
    """How the statuses of ``a`` differ from those of the CPU's ``b``: "3 overturned ->
    budget_exhausted, ..." (most frequent first), or "none"."""
    changed = a["status"] != b["status"]
    pairs = collections.Counter(zip(b["status"][changed].tolist(), a["status"][changed].tolist()))
    return ", ".join(f"{n} {codes.STATUS_NAMES[cpu]} -> {codes.STATUS_NAMES[other]}"
                     for (cpu, other), n in pairs.most_common()) or "none"


def _spread(dt):
    if dt.size == 0:
        return "no cell overturned in both"
    return (f"median {np.median(dt):.2e}, 95 % {np.quantile(dt, 0.95):.2e}, "
            f"max {dt.max():.2e} (of {dt.size})")


def within_noise(dt_gpu, dt_fused):
    """The GPU's time differences no larger than the CPU's contraction noise (medians, with
    a factor of two for the sampling of a few chaotic cells)."""
    if dt_gpu.size == 0 or np.median(dt_gpu) == 0.0:
        return True
    return dt_fused.size > 0 and np.median(dt_gpu) <= 2.0 * np.median(dt_fused)


def compare(name, rows, rec):
    """Table rows of one ensemble, a line saying how statuses differ, and whether the GPU
    met both criteria."""
    cpu, wall_cpu = on_cpu(rows, rec)
    fused, _ = on_cpu(rows, rec, contract=True)
    gpu, wall_gpu = on_gpu(rows, rec)
    flips_gpu, dt_gpu = differences(gpu, cpu)
    flips_fused, dt_fused = differences(fused, cpu)
    n = rows.shape[0]
    changes = (f"{name}: statuses CPU -> GPU: {status_changes(gpu, cpu)}; CPU -> CPU with "
               f"contraction: {status_changes(fused, cpu)}.")
    return [[name, f"{n:,}", f"{n / wall_cpu:,.0f}", f"{n / wall_gpu:,.0f}",
             f"{wall_cpu / wall_gpu:.1f}x", f"{flips_gpu} ({flips_fused})",
             f"GPU {_spread(dt_gpu)}; contraction {_spread(dt_fused)}"]], changes, \
        flips_gpu == 0 and within_noise(dt_gpu, dt_fused)


PTX_CC = (9, 0)                   # the H100's and H200's compute capability
# a load of one byte from memory: ld.u8, ld.global.u8, ld.local.nc.u8, ... (not ld.param.u8,
# a byte-sized argument of a function that was not inlined: a boolean, no record field)
BYTE_LOAD = re.compile(r"\bld(?:\.(?:global|local|shared|const|nc))*\.[us]8\b")
_ENTRY = re.compile(r"Compiling entry function '(\S+)'")


def ptx_figures(ptx):
    """Lines, byte loads (:data:`BYTE_LOAD`) and ``bfi`` (bit-field inserts: the bytes of a
    byte-wise load put together) of a PTX text."""
    return {"lines": ptx.count("\n"), "byte loads": len(BYTE_LOAD.findall(ptx)),
            "bfi": len(re.findall(r"\bbfi\.", ptx))}


def ptxas_path():
    """The ``ptxas`` of the cuda extra (nvidia-cuda-nvcc's bin), else one on PATH, else None."""
    spec = importlib.util.find_spec("nvidia.cuda_nvcc")
    for folder in (spec.submodule_search_locations if spec else ()):
        if (Path(folder) / "bin" / "ptxas").is_file():
            return str(Path(folder) / "bin" / "ptxas")
    return shutil.which("ptxas")


def ptxas_figures(path, ptxas, max_registers=None):
    """Registers per thread and stack frame [bytes] of the entry function of the PTX file
    ``path``, spill stores and loads [bytes] of all its functions (the entry and the device
    functions it calls), from ``ptxas -v`` for sm_90 (with ``-maxrregcount``, numba-cuda's
    ``max_registers``, where given), and its seconds."""
    t0 = time.perf_counter()
    limit = [f"-maxrregcount={max_registers}"] if max_registers else []
    said = subprocess.run([ptxas, "-v", f"-arch=sm_{PTX_CC[0]}{PTX_CC[1]}", *limit, str(path),
                           "-o", os.devnull], capture_output=True, text=True, check=True).stderr
    entry = re.escape(_ENTRY.search(said).group(1))
    stack = re.search(rf"Function properties for {entry}\s+(\d+) bytes stack frame", said)[1]
    registers = re.search(rf"Function properties for {entry}\s+.*\n.*Used (\d+) registers",
                          said).group(1)
    spills = re.findall(r"(\d+) bytes spill stores, (\d+) bytes spill loads", said)
    return {"registers": int(registers), "spill stores [B]": sum(int(s) for s, _ in spills),
            "spill loads [B]": sum(int(n) for _, n in spills), "stack frame [B]": int(stack),
            "ptxas [s]": round(time.perf_counter() - t0, 1)}


def write_ptx(path, max_registers=None):
    """Write the kernel's PTX for sm_90 to ``path`` and print its figures (0), ptxas's with
    ``max_registers`` where given, or say in one line why it cannot be compiled (2)."""
    if importlib.util.find_spec("numba_cuda") is None:
        print("benchmarks.gpu: --ptx needs numba-cuda (pip install '.[cuda]'); nothing was "
              "written", file=sys.stderr)
        return 2
    t0 = time.process_time()
    text = door.ptx(PTX_CC)
    figures = {"PTX compile [CPU s]": round(time.process_time() - t0, 1), **ptx_figures(text)}
    path.write_text(text)
    ptxas = ptxas_path()
    figures.update(ptxas_figures(path, ptxas, max_registers) if ptxas else
                   {"ptxas": "not found"})
    print(f"{path}: " + ", ".join(f"{name} {value:,}" if isinstance(value, int) else
                                  f"{name} {value}" for name, value in figures.items()))
    return 0


def _device_name(device):
    """The GPU's name (bytes in older numba-cuda, str in newer)."""
    name = device.name
    return name.decode() if isinstance(name, bytes) else name


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m benchmarks.gpu", description=__doc__.split(
        "\n\n")[0].replace("``", "`"))
    parser.add_argument("--quick", action="store_true",
                        help="1,000 map cells and 240 of the ensemble (a smoke run)")
    parser.add_argument("-o", "--output", type=Path, default=OUTPUT,
                        help="report file (default %(default)s)")
    parser.add_argument("--ptx", type=Path, metavar="FILE",
                        help="no GPU needed: write the kernel's PTX for sm_90 to FILE and print "
                             "its figures (and ptxas -v's, where ptxas is installed)")
    parser.add_argument("--max-registers", type=int, metavar="N",
                        help="with --ptx: ptxas's figures with at most N registers per thread "
                             "(numba-cuda's max_registers; default: no limit)")
    args = parser.parse_args(argv)
    if args.ptx:
        return write_ptx(args.ptx, args.max_registers)
    why = door.unavailable()
    if why is not None:
        print(f"benchmarks.gpu: needs an NVIDIA GPU and numba-cuda: {why}; nothing was run",
              file=sys.stderr)
        return 2
    raw = yaml.safe_load(MAP.read_text())
    raw["grid"]["amplitude"]["num"] = 40 if args.quick else MAP_LEVELS
    rows, changes, met = [], [], True
    for name, (cells, rec) in (("map of 60 s sweeps", _rows(MAP, raw)),
                               ("synthetic records", _rows(ENSEMBLE, cells=240 if args.quick
                                                           else None))):
        lines, changed, ok = compare(name, cells, rec)
        print(" | ".join(lines[0]), changed, sep="\n", flush=True)   # each as it is measured
        rows += lines
        changes.append(changed)
        met &= ok
    from numba import cuda
    text = "\n".join([
        "# The CUDA kernel against every CPU core", "",
        f"{_device_name(cuda.get_current_device())} against {os.cpu_count()} CPU cores; "
        "compile and cache loading left out.  Status differences in brackets and the "
        "spread in brackets: the CPU kernel with contraction against without (the yardstick).",
        "", table(["ensemble", "cells", "CPU cells/s", "GPU cells/s", "GPU/CPU",
                   "statuses differing (contraction)", "|t_overturn GPU - CPU| [s]"], rows),
        "", *changes, "", f"Statuses identical and times within the contraction noise: "
            f"{'yes' if met else 'NO'}.", ""])
    write_text(args.output, text)
    print(text)
    return 0 if met else 1


if __name__ == "__main__":
    sys.exit(main())
