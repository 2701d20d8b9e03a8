"""The chunk kernel of ``kernels.cuda_batch`` without a GPU: on numba-cuda's simulator, and
compiled for the device (PTX) where the CUDA toolkit's compilers are installed.  Skipped
without numba-cuda (``make test-cudasim`` installs it; docs/gpu.md)."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("numba_cuda")

ROOT = Path(__file__).resolve().parents[2]


def test_the_runner_s_gpu_chunk_is_one_launch():
    from kernels import cuda_batch
    from sweep.runner import grid
    assert grid.CUDA_CHUNK <= cuda_batch.BATCH


def test_simulator_runs_every_mode_as_the_cpu():
    env = {**os.environ, "NUMBA_ENABLE_CUDASIM": "1", "NUMBA_DISABLE_JIT": "1",
           "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])}
    ran = subprocess.run([sys.executable, str(ROOT / "tests" / "cudasim_modes.py")], env=env,
                         capture_output=True, text=True, timeout=600)
    assert ran.returncode == 0, ran.stdout + ran.stderr
    assert "DIFFERENT" not in ran.stdout and "modes not reached: none" in ran.stdout
    assert "record ensemble in 3 chunks: same" in ran.stdout and ": once" in ran.stdout


@pytest.mark.slow
def test_device_code_compiles_to_ptx(monkeypatch):
    """numba-cuda types, lowers and compiles the whole kernel for sm_90 (about 40 s)."""
    from kernels import codes
    from kernels.cuda_batch import _run_rows      # first: it shims numpy for numba-cuda
    from kernels.state import WORK_DTYPE
    from numba import cuda, float64, from_dtype, int64
    import numba.cuda.dispatcher

    class Device:                       # device functions ask the current GPU for its
        compute_capability = (9, 0)     # compute capability, even to compile only
    monkeypatch.setattr(numba.cuda.dispatcher, "get_current_device", Device)
    try:
        cuda.compile_ptx(lambda a: None, (float64[::1],), cc=(9, 0))
    except Exception as err:            # no NVVM/NVRTC: nothing to compile with
        pytest.skip(f"the CUDA compilers are not usable: {err}")
    row, res, work = (from_dtype(d) for d in (codes.SCENE_DTYPE, codes.RESULT_DTYPE,
                                              WORK_DTYPE))
    ptx, _ = cuda.compile_ptx(_run_rows.py_func, (row[::1], float64[::1], res[::1],
                                                  work[::1], float64[:, ::1], float64[:, ::1],
                                                  int64[::1]), cc=(9, 0))
    assert ".entry" in ptx and "run_scene" in ptx
