"""The runner in one process: failed cells, overwrite refusal, dry run, kill and resume."""
import signal
import subprocess
import time

import numpy as np
import pytest
import xarray as xr
from study_helpers import (PY, cli, cli_env, make_study, slow_study, start, wait_for_parts,
                           without_run_attrs, write_study)

import sweep
from kernels import codes
from sweep.runner.cell_checks import load_study
from sweep.runner import store
from sweep.runner.cells import run_chunk


def test_failing_cell_is_flagged_and_the_study_goes_on(tmp_path):
    # a step budget of 20 is used up long before t_end by a rocking block
    raw = make_study({"amplitude": {"values": [0.5, 1.5, 2.5], "unit": "west"},
                      "solver.max_steps": [20, 1_000_000]}, output="out/fail.nc")
    ds = sweep.run_study(raw)
    assert ds["outcome"].dims == ("amplitude", "max_steps")  # a dotted axis: its last key
    tiny = ds.sel(max_steps=20)
    big = ds.sel(max_steps=1_000_000)
    assert tiny["outcome"].values.tolist() == [0, -1, -1]  # at rest: no steps needed
    assert tiny["status"].values.tolist() == [codes.OK] + [codes.BUDGET_EXHAUSTED] * 2
    assert tiny["overturned"].values.tolist() == [0, -1, -1]
    assert np.all(big["outcome"].values >= 0) and np.all(big["status"].values != 2)

    # the command line lists the failed cells at the end, and keeps the result
    study = write_study(tmp_path / "fail.yaml", raw)
    done = cli([study], cwd=tmp_path, timeout=120)
    assert done.returncode == 0, done.stderr
    assert "2 cells failed" in done.stderr and "budget_exhausted" in done.stderr
    assert "amplitude=1.5, solver.max_steps=20" in done.stderr
    result = tmp_path / "out" / "fail.nc"
    on_disk = xr.open_dataset(result)
    assert without_run_attrs(on_disk).identical(without_run_attrs(ds).assign_attrs(
        study_file=str(study)))  # the dict's YAML is the file's text
    assert not store.parts_dir(result).exists()  # parts removed once the dataset is written
    stamp = result.stat().st_mtime_ns
    again = cli([study], cwd=tmp_path, timeout=60)  # the same inputs: nothing to do
    assert again.returncode == 0 and "already complete for these inputs" in again.stderr
    assert result.stat().st_mtime_ns == stamp
    forced = cli([study, "--force", "--quiet"], cwd=tmp_path, timeout=120)
    assert forced.returncode == 0 and result.stat().st_mtime_ns != stamp
    assert "cells in" not in forced.stdout  # --quiet: no summary


def test_dry_run_counts_and_estimates(tmp_path, small_study):
    study = write_study(tmp_path / "s.yaml", small_study)
    done = cli([study, "--dry-run"], cwd=tmp_path, timeout=60)
    assert done.returncode == 0, done.stderr
    assert "12 cells (amplitude 4 x frequency 3)" in done.stdout
    assert "estimated run time" in done.stdout
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.yaml"]


def _kill_when_parts(process, parts_dir, n_parts, signum, timeout=60.0):
    """Send ``signum`` to ``process`` once ``n_parts`` part files exist; the count then."""
    end = time.monotonic() + timeout
    while time.monotonic() < end and process.poll() is None:
        if parts_dir.exists() and len(list(parts_dir.glob("part-*.npz"))) >= n_parts:
            process.send_signal(signum)
            process.wait(timeout=30)
            return len(list(parts_dir.glob("part-*.npz")))
        time.sleep(0.005)
    process.kill()
    pytest.fail(f"the run ended before {n_parts} parts were written: {process.communicate()}")


def test_sigkill_then_resume_gives_the_same_dataset(tmp_path):
    _, study = slow_study(tmp_path, 8.0)
    process = subprocess.Popen([PY, "-m", "sweep.run", str(study), "--chunk-size", "1"],
                               cwd=tmp_path, env=cli_env(), stdout=subprocess.DEVNULL,
                               stderr=subprocess.PIPE)
    parts_dir = store.parts_dir(tmp_path / "r.nc")
    n_parts = _kill_when_parts(process, parts_dir, 20, signal.SIGKILL)
    assert process.returncode == -signal.SIGKILL
    assert 20 <= n_parts < 240 and not (tmp_path / "r.nc").exists()

    resumed = cli([study, "--chunk-size", "7"], cwd=tmp_path, timeout=240)
    assert resumed.returncode == 0, resumed.stderr
    assert f"resuming: {n_parts} cells already done" in resumed.stderr
    reference = cli([study, "-o", "ref.nc"], cwd=tmp_path, timeout=240)
    assert reference.returncode == 0, reference.stderr
    a, b = xr.open_dataset(tmp_path / "r.nc"), xr.open_dataset(tmp_path / "ref.nc")
    assert without_run_attrs(a).identical(without_run_attrs(b))


def test_ctrl_c_says_what_is_saved_and_the_resume_is_exact(tmp_path):
    _, study = slow_study(tmp_path, 12.0)
    process = start([study, "--chunk-size", "2"], tmp_path)
    parts_dir = store.parts_dir(tmp_path / "r.nc")
    wait_for_parts(process, parts_dir, 5)
    process.send_signal(signal.SIGINT)
    _, err = process.communicate(timeout=60)
    assert process.returncode == 130 and "Traceback" not in err, err
    saved = 2 * len(list(parts_dir.glob("part-*.npz")))
    assert f"interrupted: {saved} of 240 cells are saved in {parts_dir.name}" in err
    assert f"run the same command again to resume (python -m sweep.run {study}" in err
    resumed = cli([study], cwd=tmp_path, timeout=240)
    assert resumed.returncode == 0 and f"resuming: {saved} cells" in resumed.stderr
    reference = cli([study, "-o", "ref.nc"], cwd=tmp_path, timeout=240)
    assert reference.returncode == 0, reference.stderr
    a, b = xr.open_dataset(tmp_path / "r.nc"), xr.open_dataset(tmp_path / "ref.nc")
    assert without_run_attrs(a).identical(without_run_attrs(b))


def test_leftovers_of_killed_writes_and_removals_are_cleaned(tmp_path, small_study):
    study = write_study(tmp_path / "s.yaml", dict(small_study, output="r.nc"))
    tmp = tmp_path / ".r.nc.4242.tmp"           # a final write killed half way
    tmp.write_bytes(b"CDF\x01 half a file")
    trash = tmp_path / ".r.nc.parts.4242.trash"  # a removal of the parts killed half way
    (trash / "round-000").mkdir(parents=True)
    (trash / "part-000000003.npz").write_bytes(b"")
    done = cli([study], cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert ".r.nc.4242.tmp" in done.stderr and ".r.nc.parts.4242.trash" in done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.nc", "s.yaml"]


def test_a_run_killed_after_its_dataset_was_written_finishes_its_clean_up(tmp_path,
                                                                         small_study):
    study = write_study(tmp_path / "s.yaml", dict(small_study, output="r.nc"))
    assert cli([study], cwd=tmp_path).returncode == 0
    stamp = (tmp_path / "r.nc").stat().st_mtime_ns
    # the state a kill between the dataset's rename and the parts' removal leaves
    parts = store.PartStore(store.parts_dir(tmp_path / "r.nc"))
    parts.prepare(load_study(study))
    parts.write_part(run_chunk(load_study(study), np.arange(4)))
    again = cli([study], cwd=tmp_path)
    assert again.returncode == 0, again.stderr
    assert "already complete for these inputs; removed the part files" in again.stderr
    assert not parts.directory.exists() and (tmp_path / "r.nc").stat().st_mtime_ns == stamp
    # parts of other inputs beside the dataset are no such leftover: kept
    other_grid = {"amplitude": {"values": [0.5, 1.0], "unit": "west"}}
    parts.prepare(load_study(dict(small_study, grid=other_grid)))
    kept = cli([study], cwd=tmp_path)
    assert kept.returncode == 0 and "removed" not in kept.stderr and parts.directory.exists()
    # a dataset of other inputs is never taken for done
    other = write_study(tmp_path / "s.yaml", dict(small_study, output="r.nc", grid=other_grid))
    refused = cli([other], cwd=tmp_path)
    assert refused.returncode == 2 and "exists; run with --force" in refused.stderr


@pytest.mark.parametrize("output, reason", [
    ("README/x.nc", "README is a file, not a folder"),
    ("/proc/x.nc", "is not writable"),
    ("sub", "is an existing folder"),
    ("a\x00b.nc", None),  # a NUL byte (escaped in the YAML file; no command line carries one)
])
def test_unusable_outputs_are_refused_before_any_work(tmp_path, small_study, output, reason):
    (tmp_path / "README").write_text("a file")
    (tmp_path / "sub").mkdir()
    study = write_study(tmp_path / "s.yaml", dict(small_study, output=output))
    done = cli([study], cwd=tmp_path, timeout=60)
    assert done.returncode == 2 and "Traceback" not in done.stderr, done.stderr
    assert "output:" in done.stderr
    if reason:
        assert reason in done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["README", "s.yaml", "sub"]
    assert list((tmp_path / "sub").iterdir()) == []


def test_backend_cuda_without_a_gpu_is_refused_before_any_work(tmp_path, small_study):
    from kernels import gpu
    if gpu.unavailable() is None:
        pytest.skip("this machine can run the CUDA kernel")
    study = write_study(tmp_path / "s.yaml", dict(small_study, output="r.nc"))
    done = cli([study, "--backend", "cuda"], cwd=tmp_path, timeout=60)
    assert done.returncode == 2 and "Traceback" not in done.stderr, done.stderr
    assert done.stderr.startswith("sweep.run: --backend cuda: ") and "nothing was run" in done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.yaml"]


def test_a_parts_folder_taken_by_a_file_is_refused(tmp_path, small_study):
    study = write_study(tmp_path / "s.yaml", dict(small_study, output="r.nc"))
    (tmp_path / "r.nc.parts").write_text("not a folder")
    done = cli([study], cwd=tmp_path, timeout=60)
    assert done.returncode == 2 and "Traceback" not in done.stderr, done.stderr
    assert "r.nc.parts (the folder of the part files) is taken by a file" in done.stderr
    assert not (tmp_path / "r.nc").exists()


@pytest.mark.slow
def test_kills_at_random_moments_resume_to_the_same_dataset(tmp_path):
    """SIGKILL at uniformly random moments of a run's life (start-up, cells, the final write,
    the clean-up), again and again until a run completes: always the reference dataset."""
    _, study = slow_study(tmp_path, 8.0, output="ref.nc")
    t0 = time.monotonic()
    assert cli([study, "--quiet"], cwd=tmp_path, timeout=240).returncode == 0
    whole = time.monotonic() - t0
    reference = without_run_attrs(xr.open_dataset(tmp_path / "ref.nc"))
    rng = np.random.default_rng(7)
    outputs, kills = 10, 0
    for k in range(outputs):
        while True:
            run = subprocess.Popen([PY, "-m", "sweep.run", str(study), "-o", f"k{k}.nc",
                                    "--chunk-size", "3", "--quiet"], cwd=tmp_path,
                                   env=cli_env(), stdout=subprocess.DEVNULL,
                                   stderr=subprocess.PIPE, text=True)
            try:
                _, err = run.communicate(timeout=rng.uniform(0.0, 1.1 * whole))
                assert run.returncode == 0, err
                break
            except subprocess.TimeoutExpired:
                run.kill()
                run.communicate()
                kills += 1
        result = without_run_attrs(xr.open_dataset(tmp_path / f"k{k}.nc"))
        assert result.identical(reference), k
        assert sorted(p.name for p in tmp_path.glob(f"*k{k}.nc*")) == [f"k{k}.nc"]
    print(f"{kills} kills at random moments, {outputs}/{outputs} datasets identical")


def test_a_cell_over_the_budget_is_flagged_and_the_study_goes_on(tmp_path):
    # a fixed step of 0.1 us over 100 s would run for hours; the 1 ms one takes milliseconds
    raw = make_study({"solver.dt": [1e-3, 1e-7]}, output="r.nc")
    raw["scene"]["solver"] = {"method": "fixed", "t_end": 100.0}
    study = write_study(tmp_path / "s.yaml", raw)
    t0 = time.monotonic()
    done = cli([study, "--cell-budget", "1"], cwd=tmp_path, timeout=120)
    assert done.returncode == 0 and "Traceback" not in done.stderr, done.stderr
    assert time.monotonic() - t0 < 30
    assert "1 cell failed" in done.stderr and "time_budget" in done.stderr
    ds = xr.open_dataset(tmp_path / "r.nc")
    assert ds["status"].values.tolist() == [codes.OK, codes.TIME_BUDGET]
    assert ds["outcome"].values.tolist()[1] == codes.FAILED


def test_the_command_hands_the_runner_frozen_options():
    import dataclasses

    from sweep.runner.command import parse_args, run_options
    from sweep.runner.options import RunOptions

    argv = ["s.yaml", "--quiet", "--chunk-size", "3", "-o", "x.nc"]
    options = run_options(parse_args(argv))
    assert options == RunOptions(output="x.nc", quiet=True, chunk_size=3, argv=tuple(argv))
    assert options.command_line(2) == "python -m sweep.run " + " ".join(argv) + " (2 ranks)"
    with pytest.raises(dataclasses.FrozenInstanceError):
        options.force = True
