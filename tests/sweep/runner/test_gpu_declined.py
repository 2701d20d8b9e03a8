"""A study too small for the GPU to win runs on the CPU, said in one line, when the GPU is
asked for (``RunOptions.runs_on``; the threshold is 20,000 cells, docs/gpu.md)."""
import pytest
import xarray as xr
from study_helpers import cli, cli_env, make_study, write_study

from sweep.io.study_schema import load_study
from sweep.runner.options import RunOptions

THRESHOLD = 20_000          # cells: the rule as docs/gpu.md writes it down


def _grid(levels, frequencies):
    """A study of ``levels`` x ``frequencies`` cells asking for the GPU (loaded, not run)."""
    raw = make_study({"amplitude": {"start": 0.5, "stop": 3.0, "num": levels, "unit": "west"},
                      "frequency": {"start": 1.0, "stop": 9.0, "num": frequencies}})
    return load_study(dict(raw, run={"backend": "cuda"}))


@pytest.mark.parametrize("levels, frequencies, where", [
    (100, 199, "cpu"),           # 19,900 cells
    (100, 200, "cuda"),          # 20,000 cells: the threshold itself goes to the GPU
    (12, 1, "cpu")])
def test_the_gpu_takes_studies_of_20000_cells_or_more(levels, frequencies, where):
    study = _grid(levels, frequencies)
    assert study.n_cells == levels * frequencies
    assert RunOptions().runs_on(study) == where
    assert RunOptions().gpu_declined(study) == (levels * frequencies < THRESHOLD)
    assert RunOptions().backend_of(study) == "cuda"          # what was asked stays said
    assert RunOptions(backend="cpu").runs_on(study) == "cpu"


def test_a_study_that_does_not_ask_for_the_gpu_is_never_declined(small_study):
    study = load_study(small_study)
    assert not RunOptions().gpu_declined(study) and RunOptions().runs_on(study) == "cpu"


def test_a_small_study_asking_for_the_gpu_runs_on_the_cpu_in_one_line(tmp_path, small_study):
    """On numba-cuda's simulator (a usable GPU as far as the runner knows), 12 cells asked to
    run on CUDA run on the CPU: the dataset is the CPU's, and one line says why."""
    pytest.importorskip("numba_cuda")
    plain = write_study(tmp_path / "a.yaml", dict(small_study, output="a.nc"))
    cuda = write_study(tmp_path / "b.yaml", dict(small_study, output="b.nc",
                                                 run={"backend": "cuda"}))
    env = cli_env(NUMBA_ENABLE_CUDASIM="1")
    said = {}
    for study in (plain, cuda):
        done = cli([study, "--quiet"], cwd=tmp_path, timeout=180, env=env)
        assert done.returncode == 0 and "Traceback" not in done.stderr, done.stderr
        said[study] = done.stderr
    line = f"sweep.run: 12 cells run on the CPU: fewer than {THRESHOLD:,} are too few for " \
           "the GPU to win (docs/gpu.md)\n"
    assert said[cuda] == line and said[plain] == ""
    with xr.open_dataset(tmp_path / "a.nc") as a, xr.open_dataset(tmp_path / "b.nc") as b:
        xr.testing.assert_identical(a.drop_attrs(), b.drop_attrs())
