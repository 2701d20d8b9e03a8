"""Fingerprints cover every input: the study, the content of its record files, the program;
a resume after any of them changed never mixes cells of old and new inputs."""
import numpy as np
import xarray as xr
from study_helpers import cli, make_study, without_run_attrs, write_study
from test_layers import MODULES, ROOT, imports

from sweep.runner.cell_checks import load_study
from sweep.runner import fingerprint, store
from sweep.runner.cells import run_chunk


def _record(path, peak):
    """A two-column record: a 2 Hz sine of ``peak`` m/s^2 for 3 s, dt 0.01 s."""
    t = np.arange(0, 3.0, 0.01)
    np.savetxt(path, np.column_stack([t, peak * np.sin(2 * np.pi * 2 * t)]))
    return path


def _record_study(tmp_path):
    _record(tmp_path / "a.txt", 4.0)
    _record(tmp_path / "b.txt", 6.0)
    raw = make_study({"excitation.horizontal.path": ["a.txt", "b.txt"],
                      "scale": [round(0.6 + 0.8 * i / 59, 4) for i in range(60)]}, output="r.nc")
    raw["scene"]["excitation"]["horizontal"] = {"kind": "record", "path": "a.txt"}
    raw["scene"]["solver"]["t_end"] = 3.0
    return raw


def test_components_follow_the_content_of_record_files(tmp_path):
    raw = _record_study(tmp_path)
    raw["scene"]["excitation"]["vertical"] = {"kind": "record", "name": "elcentro1940_ud"}
    write_study(tmp_path / "s.yaml", raw)
    study = load_study(tmp_path / "s.yaml", check_cells=False)
    before = fingerprint.components(study)
    assert set(before["records"]) == {"path: a.txt", "path: b.txt", "name: elcentro1940_ud"}
    assert fingerprint.changes(before, fingerprint.components(study)) == []

    with open(tmp_path / "b.txt", "a") as f:  # one sample more at the end
        f.write("3.0 0.5\n")
    after = fingerprint.components(study)
    assert fingerprint.changes(before, after) == ["record file (path: b.txt) changed content"]
    assert fingerprint.combined(before) != fingerprint.combined(after)
    (tmp_path / "a.txt").unlink()
    assert "record file (path: a.txt) changed content" in fingerprint.changes(
        before, fingerprint.components(study))

    other = load_study({**raw, "grid": {**raw["grid"], "scale": [0.5, 1.0]}},
                       check_cells=False)
    assert fingerprint.changes(before, fingerprint.components(other))[0].startswith(
        "the study's scene, grid")


def test_program_digest_reads_every_kernel_source():
    digest = fingerprint.source_digest()
    assert digest == fingerprint.source_digest() and len(digest) == 64
    assert fingerprint.source_digest(("kernels/*.py",)) != fingerprint.source_digest(
        ("kernels/driver.py",))


def test_program_sources_hold_every_module_a_cell_runs():
    """Every module that ``runner.cells`` reaches by its imports (functions included) is one of
    ``PROGRAM_SOURCES``, so that code moved into a new file is still fingerprinted; the
    version is a component of its own (``components``), and package ``__init__`` files only
    hold the packages' docstrings and the public API."""
    held = {path.resolve() for pattern in fingerprint.PROGRAM_SOURCES
            for path in ROOT.glob(pattern)}
    reached, todo = set(), ["sweep.runner.cells"]
    while todo:
        name = todo.pop()
        if name in MODULES and name not in reached:
            reached.add(name)
            todo += [target for _, _, target in imports(name, MODULES[name])]
    assert {"sweep.bodies", "sweep.io.study_grid", "sweep.groundmotion.record"} <= reached
    assert sorted(name for name in reached if MODULES[name].resolve() not in held
                  and MODULES[name].name != "__init__.py") == ["sweep._version"]


def test_record_edited_between_kill_and_resume_is_never_mixed(tmp_path):
    raw = _record_study(tmp_path)
    study_file = write_study(tmp_path / "s.yaml", raw)
    # what a run killed after 5 of its chunks leaves: the manifest and 5 parts
    study = load_study(study_file)
    parts = store.PartStore(store.parts_dir(tmp_path / "r.nc"))
    parts.prepare(study)
    for chunk in np.array_split(np.arange(10), 5):
        parts.write_part(run_chunk(study, chunk))
    _record(tmp_path / "b.txt", 5.0)  # the user edits a record before resuming

    refused = cli([study_file], cwd=tmp_path)
    assert refused.returncode == 2 and "Traceback" not in refused.stderr, refused.stderr
    assert "record file (path: b.txt) changed content" in refused.stderr
    assert "--force" in refused.stderr and not (tmp_path / "r.nc").exists()
    assert len(parts.parts()) == 5  # refused: nothing deleted

    forced = cli([study_file, "--force"], cwd=tmp_path)
    assert forced.returncode == 0, forced.stderr
    assert "resuming" not in forced.stderr  # every cell computed from the new file
    fresh = cli([study_file, "-o", "fresh.nc"], cwd=tmp_path)
    assert fresh.returncode == 0, fresh.stderr
    a, b = xr.open_dataset(tmp_path / "r.nc"), xr.open_dataset(tmp_path / "fresh.nc")
    assert without_run_attrs(a).identical(without_run_attrs(b))
    assert a.attrs["input_fingerprint"] == b.attrs["input_fingerprint"]
    # the old parts held other values: a mixed dataset would differ from the fresh one
    old = store.merge([run_chunk(load_study(_study_with(tmp_path, raw, 6.0)),
                                 np.arange(120))], 120)
    assert not np.array_equal(old["max_abs_theta"], b["max_abs_theta"].values.ravel())


def _study_with(tmp_path, raw, peak):
    """The same study reading a b.txt of another peak (a file of its own)."""
    _record(tmp_path / "b_old.txt", peak)
    other = dict(raw, grid={**raw["grid"], "excitation.horizontal.path": ["a.txt", "b_old.txt"]})
    return write_study(tmp_path / "old.yaml", other)
