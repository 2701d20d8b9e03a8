"""Two ranks under mpiexec (a subprocess with a timeout): exact equality with one rank,
any chunk size; abort on an exception; resume of a terminated job with another rank count;
the launcher/library mismatch message."""
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
import xarray as xr
from study_helpers import PY, cli, cli_env, make_study, without_run_attrs, write_study

from sweep.runner import store

pytestmark = pytest.mark.mpi

SCRIPT = Path(__file__).resolve().parents[1] / "mpi_two_ranks.py"
MPIEXEC = shutil.which("mpiexec", path=str(Path(sys.executable).parent)) or \
    shutil.which("mpiexec")
if MPIEXEC is None:
    pytest.skip("no mpiexec", allow_module_level=True)


def _mpiexec(*args, timeout=180, **kwargs):
    return subprocess.run([MPIEXEC, "-n", "2", *map(str, args)], env=cli_env(),
                          capture_output=True, text=True, timeout=timeout, **kwargs)


def _open(path):
    return without_run_attrs(xr.open_dataset(path))


def test_two_ranks_equal_one_rank_for_any_chunk_size(tmp_path):
    raw = make_study({"amplitude": {"start": 0.8, "stop": 3.0, "num": 9, "unit": "west"},
                      "frequency": {"start": 1.0, "stop": 8.0, "num": 5, "spacing": "log"},
                      "b_over_h": [0.333, 0.2]})
    study = write_study(tmp_path / "s.yaml", raw)
    serial = cli([study, "-o", "serial.nc", "--chunk-size", "5"], cwd=tmp_path)
    assert serial.returncode == 0, serial.stderr
    two = _mpiexec(PY, SCRIPT, "run", study, tmp_path, cwd=tmp_path)
    assert two.returncode == 0, two.stderr
    reference = _open(tmp_path / "serial.nc")
    assert set(reference["outcome"].values.ravel()) >= {0, 1, 2}
    for name in ("chunk3.nc", "chunk7.nc"):
        assert _open(tmp_path / name).identical(reference), name


def test_exception_on_one_rank_aborts_the_job(tmp_path):
    start = time.monotonic()
    done = _mpiexec(PY, SCRIPT, "abort", cwd=tmp_path, timeout=60)
    assert done.returncode != 0
    assert time.monotonic() - start < 30
    assert "rank 1 of 2 failed" in done.stderr and "Traceback" in done.stderr
    assert "RuntimeError: boom on rank 1" in done.stderr


def test_terminated_job_resumes_on_one_rank(tmp_path):
    raw = make_study({"amplitude": {"start": 1.2, "stop": 2.0, "num": 12, "unit": "west"},
                      "frequency": {"start": 6.0, "stop": 10.0, "num": 20}}, output="r.nc")
    raw["scene"]["solver"]["t_end"] = 8.0
    study = write_study(tmp_path / "slow.yaml", raw)
    job = subprocess.Popen([MPIEXEC, "-n", "2", PY, "-m", "sweep.run", str(study),
                            "--chunk-size", "2"], cwd=tmp_path, env=cli_env(),
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    parts = store.parts_dir(tmp_path / "r.nc")
    end = time.monotonic() + 120
    while len(list(parts.glob("part-*.npz"))) < 10:
        assert job.poll() is None and time.monotonic() < end, "the job ended too early"
        time.sleep(0.005)
    job.send_signal(signal.SIGTERM)
    job.wait(timeout=30)
    assert not (tmp_path / "r.nc").exists()
    resumed = cli([study], cwd=tmp_path)
    assert resumed.returncode == 0 and "resuming" in resumed.stderr, resumed.stderr
    reference = cli([study, "-o", "ref.nc", "--chunk-size", "11"], cwd=tmp_path)
    assert reference.returncode == 0, reference.stderr
    assert _open(tmp_path / "r.nc").identical(_open(tmp_path / "ref.nc"))


def test_launcher_library_mismatch(tmp_path, small_study):
    study = write_study(tmp_path / "s.yaml", small_study)
    # an Open MPI launcher's variables, but mpi4py on MPICH: a world of size 1
    done = cli([study], cwd=tmp_path, timeout=60,
               env=cli_env(OMPI_COMM_WORLD_SIZE="2", OMPI_COMM_WORLD_RANK="0"))
    assert done.returncode == 2, done.stderr
    assert "launcher/library mismatch" in done.stderr and "OMPI_COMM_WORLD_SIZE=2" in done.stderr
    assert "Traceback" not in done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.yaml"]
