"""What a warm start leaves out: numba's look for a BLAS (``scipy.linalg``) while its
registries load, the COSMOS and K-NET readers a scene without a record file does not use, the
last garbage collections at a command's exit; what it keeps: numba's BLAS for ``np.dot`` when
a function calls it, the readers when a record file's format is looked for."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

from kernels import _jit
from sweep.runner import cells

ROOT = Path(__file__).resolve().parents[3]
SCENE = str(ROOT / "studies" / "steady_rocking.yaml")
READERS = ["sweep.io.formats.cosmos", "sweep.io.formats.knet"]  # imported at first use

pytestmark = pytest.mark.skipif(_jit.DISABLED, reason="numba's compiler is off")


def _python(code):
    """stdout of ``python -c code`` run in the repository."""
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          check=True, cwd=ROOT,
                          env={**os.environ, "PYTHONPATH": str(ROOT)}).stdout


def test_warm_scene_imports_neither_scipy_linalg_nor_a_record_reader():
    cells.warm_up()
    run = subprocess.run([sys.executable, "-X", "importtime", "-m", "sweep.scene", SCENE,
                          "--json"], capture_output=True, text=True, check=True, cwd=ROOT)
    imported = {line.split("|")[-1].strip() for line in run.stderr.splitlines()
                if line.startswith("import time:")}
    assert {"numba.np.arraymath", "sweep.io.formats.base"} <= imported   # they were loaded
    assert not {"scipy.linalg", "scipy.linalg.cython_blas", *READERS} & imported


def test_numba_still_calls_blas_for_np_dot():
    """[[1, 2], [3, 4]] @ [[5, 6], [7, 8]] = [[19, 22], [43, 50]], by scipy's BLAS, which
    numba imports when it compiles the call, not when its registries load."""
    out = _python(
        "import sys, numpy as np, numba\n"
        "from kernels import _jit\n"
        "numba.njit(lambda x: x + 1.0)(1.0)\n"
        "print('scipy.linalg' in sys.modules)\n"
        "from numba.np import arraymath, linalg\n"
        "print(arraymath._HAVE_BLAS, linalg.ensure_blas.__module__)\n"
        "dot = numba.njit(lambda a, b: np.dot(a, b))\n"
        "a = np.array([[1.0, 2.0], [3.0, 4.0]]); b = np.array([[5.0, 6.0], [7.0, 8.0]])\n"
        "print(dot(a, b).ravel().tolist(), 'scipy.linalg.cython_blas' in sys.modules)\n")
    assert out.splitlines() == ["False", "True numba.np.linalg",
                                "[19.0, 22.0, 43.0, 50.0] True"]


def test_the_cosmos_and_knet_readers_are_imported_when_a_format_is_looked_for(tmp_path):
    """A two-column file of three samples 0.01 s apart, in m/s^2, read as ``columns``, needs
    neither; telling the format of ``x.V2`` (COSMOS) by its extension imports both."""
    path = tmp_path / "three.txt"
    path.write_text("0.00 0.5\n0.01 -1.0\n0.02 0.25\n")
    out = _python(
        "import sys\n"
        "from sweep.io import records\n"
        f"rec = records.read_record_file({str(path)!r}, format='columns')\n"
        f"print(rec.dt, rec.samples.tolist(), [m in sys.modules for m in {READERS!r}])\n"
        "print(records.detect_format('x.V2'), records.detect_format('x.NS1'), "
        f"[m in sys.modules for m in {READERS!r}])\n")
    assert out.splitlines() == ["0.01 [0.5, -1.0, 0.25] [False, False]",
                                "cosmos knet [True, True]"]


def test_a_command_ends_with_the_collector_off_the_objects_alive_at_exit():
    """Frozen (``gc.freeze``) at exit, not before: a command called in a process that goes on
    (a test, a notebook) leaves its collector as it was."""
    out = _python(
        "import atexit, gc, os, sys\n"
        "atexit.register(lambda: os.write(1, f'at exit {gc.get_freeze_count() > 0}'.encode()))\n"
        "from sweep.scene import main\n"
        f"status = main([{SCENE!r}, '--json'])\n"
        "sys.stdout.flush()\n"
        "os.write(1, f'\\nstatus {status}, frozen {gc.get_freeze_count()}\\n'.encode())\n")
    assert out.splitlines()[-2:] == ["status 0, frozen 0", "at exit True"]
