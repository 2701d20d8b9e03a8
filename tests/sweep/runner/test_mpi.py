"""Two ranks under mpiexec (a subprocess with a timeout): exact equality with one rank,
any chunk size, and of ``sweep.risk``'s report; chunks dealt to the rank that is free; abort
on an exception; resume of a terminated job with another rank count; Ctrl-C, and ranks left
mid-exchange; a stopped rank detected and named; the launcher/library mismatch message."""
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from study_helpers import (PY, cli, cli_env, make_study, sigint_default, slow_study,
                           wait_for_parts, without_run_attrs, write_study)

from sweep.runner import store

pytestmark = pytest.mark.mpi

SCRIPT = Path(__file__).resolve().parents[2] / "mpi_two_ranks.py"
MPIEXEC = shutil.which("mpiexec", path=str(Path(sys.executable).parent)) or \
    shutil.which("mpiexec")
if MPIEXEC is None:
    pytest.skip("no mpiexec", allow_module_level=True)


def _mpiexec(*args, ranks=("-n", "2"), timeout=180, **kwargs):
    return subprocess.run([MPIEXEC, *ranks, *map(str, args)], env=cli_env(),
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


def test_chunks_go_to_the_rank_that_is_free(tmp_path):
    """Dynamic dealing: a rank three times slower takes about a quarter of the chunks, and
    both ranks end within a few chunks of each other (a fixed deal would give each half, and
    rank 1 would end 1.2 s after rank 0)."""
    import json

    done = _mpiexec(PY, SCRIPT, "deal", tmp_path / "parts", cwd=tmp_path, timeout=120)
    assert done.returncode == 0, done.stderr
    stats = {int(r): s for r, s in json.loads(done.stdout).items()}
    cells = np.concatenate([np.load(p)["cell"] for p in (tmp_path / "parts").glob("part-*")])
    np.testing.assert_array_equal(np.sort(cells), np.arange(120))  # each cell once
    assert stats[0][0] + stats[1][0] == 120
    assert 2.0 < stats[0][0] / stats[1][0] < 4.5, stats  # speeds 1/10 ms : 1/30 ms = 3
    assert abs(stats[0][1] - stats[1][1]) < 0.3, stats


def test_cells_checked_by_two_ranks_say_what_one_says(tmp_path):
    """The cells' checks shared by the ranks: the same problems (exit 2, nothing written) and
    the same warnings as one process, line for line."""
    bad = make_study({"frequency": [-2.0, 1.0, 2.0, -3.0], "B": [0.1, -0.2]}, output="b.nc")
    doubted = make_study({"frequency": [1.0, 2.0], "excitation.horizontal.phase": [0.0, 90.0]},
                         output="d.nc")
    for raw, status in ((bad, 2), (doubted, 0)):
        study = write_study(tmp_path / "s.yaml", raw)
        one = cli([study, "--quiet", "--force"], cwd=tmp_path)
        two = _mpiexec(PY, "-m", "sweep.run", study, "--quiet", "--force", cwd=tmp_path)
        assert one.returncode == two.returncode == status, (one.stderr, two.stderr)
        assert two.stderr == one.stderr and ("problems" if status else "warning") in one.stderr
    assert not (tmp_path / "b.nc").exists()


def test_exception_on_one_rank_aborts_the_job(tmp_path):
    start = time.monotonic()
    done = _mpiexec(PY, SCRIPT, "abort", cwd=tmp_path, timeout=60)
    assert done.returncode != 0
    assert time.monotonic() - start < 30
    assert "rank 1 of 2 failed" in done.stderr and "Traceback" in done.stderr
    assert "RuntimeError: boom on rank 1" in done.stderr


def test_ranks_left_mid_exchange_end_by_themselves(tmp_path):
    """What Ctrl-C leaves (messages not taken, a rank in a barrier) is settled: each rank
    ends MPI and then the process with 130, none killed by the launcher for another's end."""
    if "HYDRA" not in subprocess.run([MPIEXEC, "--version"], capture_output=True,
                                     text=True).stdout:
        pytest.skip("each rank's exit status is shown by MPICH's launcher (Hydra)")
    done = _mpiexec(PY, SCRIPT, "leave", ranks=("-print-all-exitcodes", "-n", "2"),
                    cwd=tmp_path, timeout=60)
    codes = re.search(r"Exit codes: \[[^\]]*\] ([\d,]+)", done.stdout)
    assert done.returncode == 130 and codes, (done.stdout, done.stderr)
    assert codes[1] == f"{130 << 8},{130 << 8}", done.stdout  # wait statuses: exit(130) twice


def test_terminated_job_resumes_on_one_rank(tmp_path):
    _, study = slow_study(tmp_path, 8.0)
    job = subprocess.Popen([MPIEXEC, "-n", "2", PY, "-m", "sweep.run", str(study),
                            "--chunk-size", "2"], cwd=tmp_path, env=cli_env(),
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    parts = store.parts_dir(tmp_path / "r.nc")
    wait_for_parts(job, parts, 10)
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


def _slow_job(tmp_path, *extra):
    _, study = slow_study(tmp_path, 20.0)  # ~3 s on 2 ranks: stopped long before its end
    job = subprocess.Popen([MPIEXEC, "-n", "2", PY, "-m", "sweep.run", str(study),
                            "--chunk-size", "2", *extra], cwd=tmp_path, env=cli_env(),
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                           preexec_fn=sigint_default)
    return study, job, store.parts_dir(tmp_path / "r.nc")


def _parent(pid):
    """The parent of process ``pid`` (0 when it is gone)."""
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return 0
    return int(stat.rsplit(")", 1)[1].split()[1])


def _rank_pid(job, rank):
    """The pid of a rank of the running ``job`` (a process under its mpiexec), from its
    launcher's PMI_RANK; other jobs on the machine are not looked at."""
    for proc in Path("/proc").iterdir():
        if not proc.name.isdigit():
            continue
        try:
            env = (proc / "environ").read_bytes().split(b"\0")
            cmd = (proc / "cmdline").read_bytes()
        except OSError:
            continue
        if b"sweep.run" not in cmd or f"PMI_RANK={rank}".encode() not in env:
            continue
        pid = int(proc.name)
        while pid > 1 and pid != job.pid:
            pid = _parent(pid)
        if pid == job.pid:
            return int(proc.name)
    raise AssertionError(f"no process of rank {rank}")


def test_ctrl_c_under_mpiexec_saves_and_resumes(tmp_path):
    study, job, parts = _slow_job(tmp_path)
    wait_for_parts(job, parts, 6)
    job.send_signal(signal.SIGINT)  # what Ctrl-C in the terminal does to mpiexec
    _, err = job.communicate(timeout=60)
    assert job.returncode == 130 and "Traceback" not in err, err
    lines = [line for line in err.splitlines() if "sweep.run: interrupted" in line]
    assert len(lines) == 1 and "cells are saved in r.nc.parts" in lines[0], err
    saved = 2 * len(list(parts.glob("part-*.npz")))
    assert f"interrupted: {saved} of 240 cells" in lines[0]
    resumed = cli([study], cwd=tmp_path)
    assert resumed.returncode == 0 and f"resuming: {saved} cells" in resumed.stderr
    reference = cli([study, "-o", "ref.nc"], cwd=tmp_path)
    assert reference.returncode == 0, reference.stderr
    assert _open(tmp_path / "r.nc").identical(_open(tmp_path / "ref.nc"))


def test_a_stopped_rank_is_detected_and_named(tmp_path):
    study, job, parts = _slow_job(tmp_path, "--rank-timeout", "2")
    wait_for_parts(job, parts, 4)
    rank1 = _rank_pid(job, 1)
    os.kill(rank1, signal.SIGSTOP)
    stopped = time.monotonic()
    try:
        _, err = job.communicate(timeout=90)
    finally:
        try:
            os.kill(rank1, signal.SIGKILL)
        except ProcessLookupError:
            pass
    detected = time.monotonic() - stopped
    assert job.returncode != 0 and "rank 1 sent nothing for" in err, err
    assert "it is stopped or stuck" in err and "cells not yet saved" in err
    assert "Traceback" not in err and not (tmp_path / "r.nc").exists()
    assert detected < 30, detected
    print(f"stopped rank detected after {detected:.1f} s")
    resumed = cli([study], cwd=tmp_path)  # the parts of both ranks are kept
    assert resumed.returncode == 0 and "resuming" in resumed.stderr, resumed.stderr


def test_risk_on_two_ranks_gives_the_numbers_of_one(tmp_path):
    """``mpiexec -n 2 python -m sweep.risk``: the ranks share the stripes' simulations; the
    report and the dataset are those of one rank, to the bit."""
    import json

    import yaml

    risk = {"name": "r", "hazard": {"source": {
        "vs30": "760 m/s", "levels": {"start": "0.02 g", "stop": "2.5 g", "num": 20},
        "sources": [{"kind": "point", "distance": "10 km", "depth": "8 km",
                     "recurrence": {"rate": 0.02, "m_min": 5.5, "m_max": 7.5}}]}},
        "scene": {"body": {"B": "15 cm", "H": "60 cm"}, "contact": {"mu": 0.8}},
        "stripes": {"levels": ["3 m/s^2", "6 m/s^2", "10 m/s^2"], "motions": 4},
        "grid": {"b_over_h": [0.25, 0.3]}, "replicates": 50}
    reports = {}
    for ranks in (1, 2):
        folder = tmp_path / f"ranks{ranks}"
        folder.mkdir()
        (folder / "r.yaml").write_text(yaml.safe_dump(risk))
        args = ("-m", "sweep.risk", "r.yaml", "--json")
        done = cli(args[2:], cwd=folder, module="sweep.risk") if ranks == 1 else \
            _mpiexec(PY, *args, cwd=folder)
        assert done.returncode == 0, done.stderr
        reports[ranks] = json.loads(done.stdout)
        reports[ranks].pop("written")
    assert reports[2] == reports[1]
    assert reports[1]["bodies"][0]["fragility"]["stripes"]["motions"] == [4, 4, 4]
    one, two = (_open(tmp_path / f"ranks{n}" / "results" / "r" / "risk.nc") for n in (1, 2))
    assert two.identical(one)
