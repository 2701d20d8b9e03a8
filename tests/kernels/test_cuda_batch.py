"""The chunk kernel of ``kernels.cuda_batch`` without a GPU, on numba-cuda's simulator
(compiled for the device: tests/kernels/test_ptx.py).  Skipped without numba-cuda
(``make test-cudasim`` installs it; docs/gpu.md)."""
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
