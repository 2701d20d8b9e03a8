"""One writer per output: the lock itself, and two runs started on one output."""
import json
import os
import signal
import subprocess
import time

import pytest
import xarray as xr
from study_helpers import (PY, cli, cli_env, slow_study, start, wait_for_parts,
                           without_run_attrs, write_study)

import sweep
from sweep.runner import store
from sweep.runner.lock import LockHeld, OutputLock, lock_path

HOLD = """
import sys, time
from sweep.runner.lock import OutputLock
OutputLock(sys.argv[1], command="holder").acquire()
print("held", flush=True)
time.sleep(60)
"""


def _holder(output):
    """A process that holds the lock of ``output`` until killed."""
    process = subprocess.Popen([PY, "-c", HOLD, str(output)], stdout=subprocess.PIPE,
                               text=True, env=cli_env())
    assert process.stdout.readline().strip() == "held"
    return process


def test_a_second_holder_is_refused_with_the_holders_name(tmp_path):
    out = tmp_path / "x.nc"
    holder = _holder(out)
    try:
        with pytest.raises(LockHeld) as refused:
            OutputLock(out).acquire()
        assert f"pid {holder.pid} on host {os.uname().nodename}" in str(refused.value)
        assert "(holder)" in str(refused.value) and "started 20" in str(refused.value)
    finally:
        holder.kill()
        holder.wait()
    # its holder is gone (killed, no clean-up): the lock is taken over
    with OutputLock(out, command="second"):
        assert json.loads(lock_path(out).read_text())["pid"] == os.getpid()
        with pytest.raises(LockHeld):  # a second open file is a second holder, even here
            OutputLock(out).acquire()
    assert not lock_path(out).exists()  # released: the file is removed


def test_a_lock_released_while_another_waits_on_the_old_file_is_not_shared(tmp_path):
    out = tmp_path / "x.nc"
    first = OutputLock(out).acquire()
    stale_fd = os.open(lock_path(out), os.O_RDWR)  # a racer that opened the file before ...
    first.release()                                  # ... its holder removed it
    second = OutputLock(out).acquire()               # a new file, a new lock
    import fcntl
    fcntl.flock(stale_fd, fcntl.LOCK_EX | fcntl.LOCK_NB)  # the racer locks only the old inode
    assert os.fstat(stale_fd).st_ino != os.stat(lock_path(out)).st_ino
    with pytest.raises(LockHeld):
        OutputLock(out).acquire()
    os.close(stale_fd)
    second.release()


def test_two_runs_on_one_output_the_second_refused_the_first_intact(tmp_path):
    raw, study = slow_study(tmp_path, 6.0)
    first = start([study, "--chunk-size", "2"], tmp_path)
    parts = store.parts_dir(tmp_path / "r.nc")
    wait_for_parts(first, parts, 1)
    first.send_signal(signal.SIGSTOP)  # alive but paused, however fast this machine is
    try:
        # the study edited and relaunched with --force while the first runs: refused at once
        edited = dict(raw, grid={"amplitude": {"values": [1.3, 1.9], "unit": "west"},
                                 "frequency": [7.0]})
        write_study(tmp_path / "edited.yaml", edited)
        for args in ([study], [tmp_path / "edited.yaml", "--force"]):
            t0 = time.monotonic()
            second = cli(args, cwd=tmp_path, timeout=60)
            assert second.returncode == 2, second.stderr
            assert f"being written by another run: pid {first.pid}" in second.stderr
            assert "Traceback" not in second.stderr and time.monotonic() - t0 < 20
            assert parts.is_dir()  # the first run's parts are intact
    finally:
        first.send_signal(signal.SIGCONT)
    out, err = first.communicate(timeout=240)
    assert first.returncode == 0, err
    on_disk = without_run_attrs(xr.open_dataset(tmp_path / "r.nc"))
    alone = without_run_attrs(sweep.run_study(raw)).assign_attrs(study_file=str(study))
    assert on_disk.identical(alone)  # as if it had run alone
    assert not lock_path(tmp_path / "r.nc").exists() and not parts.exists()


def test_a_run_whose_predecessor_was_killed_takes_the_lock_over(tmp_path):
    _, study = slow_study(tmp_path, 6.0)
    first = start([study, "--chunk-size", "4"], tmp_path)
    parts = store.parts_dir(tmp_path / "r.nc")
    wait_for_parts(first, parts, 1)
    first.send_signal(signal.SIGKILL)
    first.wait()
    assert lock_path(tmp_path / "r.nc").exists()  # left behind by the killed holder
    again = cli([study], cwd=tmp_path, timeout=240)
    assert again.returncode == 0 and "resuming" in again.stderr, again.stderr
