"""Where a study's cells run: ``run: {backend}`` in the study file, ``--backend`` over it.

The backend says how the cells run, not what they compute: it is not part of the inputs'
fingerprint.  A bad value is a file problem (its dotted path, exit status 2); ``cuda`` where
numba-cuda or a GPU is missing is refused before any work, in one line."""
import pytest
import xarray as xr
from study_helpers import cli, write_study

import sweep
from kernels import gpu
from sweep.io.problems import FileProblems
from sweep.io.study_schema import load_study
from sweep.runner.options import RunOptions

NO_CUDA = pytest.mark.skipif(gpu.unavailable() is None, reason="this machine can run CUDA")


@pytest.mark.parametrize("run, said", [
    ({"backend": "gpu"}, "run.backend: must be one of: cpu, cuda (got: 'gpu')"),
    ({"backend": "cuda", "devices": 2}, "run.devices: unknown key"),
    ("cuda", "run: must be a mapping {backend: cpu or cuda} (got: 'cuda')")])
def test_a_bad_run_section_is_a_file_problem(tmp_path, small_study, run, said):
    study = write_study(tmp_path / "s.yaml", dict(small_study, output="r.nc", run=run))
    done = cli([study], cwd=tmp_path, timeout=60)
    assert done.returncode == 2 and "Traceback" not in done.stderr, done.stderr
    assert said in done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.yaml"]


def test_the_option_overrides_the_file_and_the_study_says_the_default(small_study):
    cpu, cuda = (load_study(dict(small_study, run={"backend": b})) for b in ("cpu", "cuda"))
    plain = load_study(small_study)
    assert (plain.backend, cpu.backend, cuda.backend) == (None, "cpu", "cuda")
    assert RunOptions().backend_of(plain) == "cpu"
    assert RunOptions().backend_of(cuda) == "cuda"
    assert RunOptions(backend="cpu").backend_of(cuda) == "cpu"


@NO_CUDA
def test_run_backend_cuda_without_a_gpu_is_refused_in_one_line(tmp_path, small_study):
    study = write_study(tmp_path / "s.yaml", dict(small_study, output="r.nc",
                                                  run={"backend": "cuda"}))
    done = cli([study], cwd=tmp_path, timeout=60)
    assert done.returncode == 2 and "Traceback" not in done.stderr, done.stderr
    assert done.stderr.startswith(f"sweep.run: {study}: run.backend: ")
    assert done.stderr.endswith(" (got: 'cuda'); nothing was run\n")
    assert done.stderr.count("\n") == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.yaml"]
    with pytest.raises(FileProblems, match="run.backend"):
        sweep.run_study(study)


def test_the_backend_leaves_the_fingerprint_alone(tmp_path, small_study):
    """``--backend cpu`` runs a study that asks for CUDA; the dataset is the one of the same
    study without ``run:``, fingerprint included."""
    plain = write_study(tmp_path / "a.yaml", dict(small_study, output="a.nc"))
    cuda = write_study(tmp_path / "b.yaml", dict(small_study, output="b.nc",
                                                 run={"backend": "cuda"}))
    for study in (plain, cuda):
        done = cli([study, "--backend", "cpu", "--quiet"], cwd=tmp_path, timeout=120)
        assert done.returncode == 0, done.stderr
    with xr.open_dataset(tmp_path / "a.nc") as a, xr.open_dataset(tmp_path / "b.nc") as b:
        assert a.attrs["input_fingerprint"] == b.attrs["input_fingerprint"]
        xr.testing.assert_identical(a.drop_attrs(), b.drop_attrs())


def test_a_scene_file_has_no_backend(tmp_path):
    scene = write_study(tmp_path / "scene.yaml", {
        "body": {"B": 0.1, "H": 0.3}, "solver": {"t_end": 0.5, "backend": "cuda"}})
    done = cli([scene], cwd=tmp_path, timeout=60, module="sweep.scene")
    assert done.returncode == 2 and "Traceback" not in done.stderr, done.stderr
    assert "solver.backend" in done.stderr and "unknown key" in done.stderr
