"""The persistent grid of ``kernels.cuda_batch``: as many threads as the device holds
resident, each taking rows from an atomic counter.  Its size from the occupancy (any machine
with numba-cuda), and on numba-cuda's simulator more rows than threads give the CPU's results
(this file run as a script with ``NUMBA_ENABLE_CUDASIM=1``; docs/gpu.md)."""
import os
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import pytest

ROOT = Path(__file__).resolve().parents[2]
T_END = 1.0    # s
# ten rows of studies/smoke.yaml for one launch of three threads: at rest, rocking (49 to 283
# steps by T_END), overturned
CELLS = (40, 56, 49, 98, 168, 77, 196, 147, 126, 41)


def _h100(**attrs):
    """An H100 SXM's attributes (compute capability 9.0: 132 SMs, 65,536 registers, 2,048
    threads and 32 blocks per SM)."""
    return SimpleNamespace(**{"MULTIPROCESSOR_COUNT": 132, "MAX_REGISTERS_PER_MULTIPROCESSOR":
                              65536, "MAX_THREADS_PER_MULTIPROCESSOR": 2048,
                              "MAX_BLOCKS_PER_MULTIPROCESSOR": 32, **attrs})


@pytest.mark.parametrize("regs, blocks", [
    (244, 65536 // (248 * 128)),     # 244 rounded up to 248 (256 registers a warp): 2 blocks
    (248, 2), (249, 65536 // (256 * 128)),
    (168, 65536 // (168 * 128)),     # 3
    (128, 65536 // (128 * 128)),     # 4
    (32, 2048 // 128),               # registers would allow 16; threads per SM allow 16
    (16, 2048 // 128)])              # registers would allow 32; threads per SM bound it
def test_resident_blocks_follow_the_occupancy_calculation(regs, blocks):
    pytest.importorskip("numba_cuda")
    from kernels import cuda_batch
    assert cuda_batch.resident_blocks(regs, _h100()) == blocks


def test_blocks_per_sm_bound_the_resident_blocks():
    pytest.importorskip("numba_cuda")
    from kernels import cuda_batch
    assert cuda_batch.resident_blocks(16, _h100(MAX_BLOCKS_PER_MULTIPROCESSOR=5)) == 5


def test_a_launch_holds_the_resident_threads_or_as_many_as_the_rows_fill():
    pytest.importorskip("numba_cuda")
    from kernels import cuda_batch
    assert cuda_batch.launch_grid(1 << 20, 244, _h100()) == (132 * 2, 128)   # 33,792 threads
    assert cuda_batch.launch_grid(20_000, 244, _h100()) == (157, 128)        # 157 x 128 >= 20,000
    assert cuda_batch.launch_grid(1, 244, _h100()) == (1, 128)


def test_on_the_simulator_three_threads_run_ten_rows_as_the_cpu():
    """One launch of 1 block of 3 threads over 10 rows: every thread takes several rows, each
    row's result is the CPU's byte for byte, and the counter ends at 10 + 3 (each thread's
    last take finds no row)."""
    pytest.importorskip("numba_cuda")
    env = {**os.environ, "NUMBA_ENABLE_CUDASIM": "1", "NUMBA_DISABLE_JIT": "1",
           "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])}
    ran = subprocess.run([sys.executable, __file__], env=env, capture_output=True, text=True,
                         timeout=300)
    assert ran.returncode == 0, ran.stdout + ran.stderr
    assert ran.stdout.split() == ["same", str(len(CELLS) + 3)], ran.stdout


def _on_the_simulator():
    """Print whether a launch of 1 x 3 threads over the rows :data:`CELLS` of the smoke study
    gives the CPU's results, and the counter's final value."""
    import numpy as np

    from kernels import api, codes, cuda_batch
    from kernels.watchdog import control
    from numba import cuda
    from sweep.runner.cell_checks import load_study
    from sweep.runner.cells import build_rows
    study = load_study(ROOT / "studies/smoke.yaml", check_cells=False)
    rows, rec, *_ = build_rows(study, np.array(CELLS))
    rows["solver"]["t_end"] = np.minimum(rows["solver"]["t_end"], T_END)
    rows = np.ascontiguousarray(api.as_records(rows).view(np.ndarray))
    results = cuda.to_device(np.zeros(len(CELLS), codes.RESULT_DTYPE))
    taken = cuda.to_device(np.zeros(1, np.int64))
    cuda_batch._run_rows[1, 3](cuda.to_device(rows), cuda.to_device(rec), results,
                               cuda.to_device(np.zeros((0, codes.N_LOG))),
                               cuda.to_device(np.zeros((0, codes.N_HIST))),
                               cuda.to_device(control(cell=0)), taken)
    same = results.copy_to_host().tobytes() == api.run_cells(rows, rec).tobytes()
    print("same" if same else "DIFFERENT", int(taken.copy_to_host()[0]))


if __name__ == "__main__":
    sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != Path(__file__).parent]
    _on_the_simulator()
