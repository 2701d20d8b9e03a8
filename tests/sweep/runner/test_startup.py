"""A warm ``python -m sweep.scene`` loads the one compiled function it calls and imports
nothing it does not use; ``cpu_s`` is the simulation's own time; the warm-up marker lives in
the kernel's cache folder."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

from kernels import _jit
from sweep.runner import cells, fingerprint

ROOT = Path(__file__).resolve().parents[3]
SCENE = str(ROOT / "studies" / "steady_rocking.yaml")

pytestmark = pytest.mark.skipif(_jit.DISABLED, reason="numba's compiler is off")


@pytest.fixture(scope="module")
def warm():
    """The kernel compiled into its cache folder (at once when ``make install`` did it)."""
    cells.warm_up()


def _scene(*options, env=None):
    return subprocess.run([sys.executable, *options, "-m", "sweep.scene", SCENE, "--json"],
                          capture_output=True, text=True, check=True, cwd=ROOT,
                          env={**os.environ, **(env or {})})


def test_marker_in_the_cache_folder_keyed_by_the_kernel_sources():
    assert _jit.SOURCE_DIGEST == fingerprint.source_digest(("kernels/*.py",))
    assert cells._marker().parent == Path(_jit.CACHE_DIR)
    assert _jit.SOURCE_DIGEST[:16] in cells._marker().name


def test_warm_scene_loads_only_the_function_it_calls(warm):
    run = _scene(env={"NUMBA_DEBUG_CACHE": "1"})
    loaded = [line for line in run.stdout.splitlines() if line.startswith("[cache] data loaded")]
    assert [Path(line.split("'")[1]).name.split("-")[0] for line in loaded] == ["driver.run_scene"]
    assert "data saved" not in run.stdout and "compiling" not in run.stderr


def test_scene_imports_no_dataset_or_plotting_library(warm):
    imported = {line.split("|")[-1].strip() for line in _scene("-X", "importtime").stderr
                .splitlines() if line.startswith("import time:")}
    assert "numba" in imported
    assert not {"xarray", "matplotlib", "netCDF4", "tqdm", "mpi4py"} & imported


def test_cpu_s_is_the_simulation_alone(warm):
    code = ("import time, sweep; t = time.process_time(); first = sweep.simulate(%r); "
            "t = time.process_time() - t; second = sweep.simulate(%r); "
            "print(first.cpu_s, second.cpu_s, t)" % (SCENE, SCENE))
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, cwd=ROOT).stdout.split()
    first, second, call = map(float, out)
    assert first < 0.1 * call          # the first call also loaded the kernel
    assert first < 5 * second          # but its cpu_s did not count that


def test_a_rank_with_numba_imported_still_compiles():
    """Under MPI each rank runs one numba thread; where numba was imported (its pool sized
    from ``NUMBA_NUM_THREADS=2``) before the runner says so, a later compilation (a cold
    kernel cache) must not meet a changed ``NUMBA_NUM_THREADS``, which numba refuses."""
    code = ("import numba\n"
            "from sweep.runner.mpi import communicator\n"
            "communicator._threads_off()\n"
            "print(numba.njit(lambda x: x + 1)(1), numba.get_num_threads())\n")
    env = {**os.environ, "NUMBA_NUM_THREADS": "2", "PYTHONPATH": str(ROOT)}
    ran = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True,
                         text=True, timeout=120)
    assert ran.returncode == 0, ran.stderr[-2000:]
    assert ran.stdout.split() == ["2", "1"]
