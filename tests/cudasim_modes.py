"""Started by ``tests/kernels/test_cuda_batch.py`` with ``NUMBA_ENABLE_CUDASIM=1`` and
``NUMBA_DISABLE_JIT=1``: the chunk kernel of ``kernels.cuda_batch`` on numba-cuda's simulator
(the device source run thread by thread with device-array semantics) against
``kernels.api.run_cells`` on the same rows, for cells of every mode and a record, and a
record ensemble over several chunks, whose records go to the device once.

    python tests/cudasim_modes.py     # prints one line per study; exit 1 on a difference
"""
import sys
from pathlib import Path

_ROOT = Path(__file__).resolve().parents[1]
sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != _ROOT / "tests"]

import numpy as np  # noqa: E402

from kernels import api, codes, cuda_batch  # noqa: E402
from sweep.runner.cell_checks import load_study  # noqa: E402
from sweep.runner.cells import ChunkRunner, build_rows, run_chunk  # noqa: E402

T_END = 1.5  # s: every mode of these cells is reached by then
# (study, cells, friction or None): rock and overturn, slide, both jumps, rest, a record
CASES = (("studies/smoke.yaml", (47, 300), None), ("studies/smoke.yaml", (47, 300), 0.15),
         ("studies/fig05_landing_map.yaml", (0, 5), None),
         ("studies/precarious_rock.yaml", (0,), None),
         ("studies/fig18_elcentro_ns.yaml", (3,), None))
ENSEMBLE = {"name": "records", "scene": {
    "body": {"B": 0.2, "H": 0.8}, "contact": {"mu": 0.8, "e_x": -0.8, "e_y": 0.2},
    "excitation": {"horizontal": {"kind": "record", "name": "elcentro1940_ns"}},
    "solver": {"t_end": 1.0}},
    "grid": {"record": ["elcentro1940_ns", "taft1952_ew_s69e"],
             "excitation.horizontal.scale": [2.0, 6.0]}}


def rows_of(study, cells, mu):
    rows, rec, *_ = build_rows(load_study(_ROOT / study, check_cells=False), np.array(cells))
    rows["solver"]["t_end"] = np.minimum(rows["solver"]["t_end"], T_END)
    if mu is not None:
        for name in ("mu_s", "mu_k", "mu_edge_s", "mu_edge_k"):
            rows["contact"][name] = mu
    return rows, rec


def main():
    seen = np.zeros(codes.N_MODES, dtype=bool)
    same = True
    for study, cells, mu in CASES:
        rows, rec = rows_of(study, cells, mu)
        gpu = cuda_batch.run_cells(rows, rec, batch=1)   # one launch per row: batches too
        cpu = api.run_cells(rows, rec)
        seen |= (cpu["mode_time"] > 0).any(axis=0)
        agree = gpu.tobytes() == cpu.tobytes()
        same &= agree
        print(f"{study} mu={mu}: {'same' if agree else 'DIFFERENT'}; statuses "
              f"{[codes.STATUS_NAMES[s] for s in cpu['status']]}")
    study = load_study(_ROOT / "studies/precarious_rock.yaml", check_cells=False)
    on_gpu, on_cpu = (run_chunk(study, [0, 1], backend=b) for b in ("cuda", "cpu"))
    agree = all(np.array_equal(on_gpu[k], on_cpu[k], equal_nan=True) for k in on_cpu)
    same &= agree
    print(f"run_chunk(backend='cuda'): {'same' if agree else 'DIFFERENT'}")
    same &= ensemble()
    missing = [name for name, s in zip(codes.MODE_NAMES, seen) if not s]
    print("modes not reached:", missing or "none")
    return 0 if same and not missing else 1


def ensemble():
    """A record ensemble in three chunks: the CPU's results, each record sent once."""
    study = load_study(ENSEMBLE, check_cells=False)
    gpu, cpu = ChunkRunner(backend="cuda"), ChunkRunner()
    agree = True
    for chunk in ([3], [0, 2], [1]):
        on_gpu, on_cpu = gpu(study, chunk), cpu(study, chunk)
        agree &= all(on_gpu[k].tobytes() == on_cpu[k].tobytes() for k in on_cpu)
    sent, stored = gpu.device.sent, gpu.records.size
    print(f"record ensemble in 3 chunks: {'same' if agree else 'DIFFERENT'}; samples sent to "
          f"the device {sent}, of records {stored}: {'once' if sent == stored else 'AGAIN'}")
    return agree and sent == stored


if __name__ == "__main__":
    sys.exit(main())
