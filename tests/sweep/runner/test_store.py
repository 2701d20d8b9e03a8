"""Part files, merge and the dataset contract of docs/design.md section 6, variable by variable."""
import json

import numpy as np
import pytest
import xarray as xr
from study_helpers import make_study, without_run_attrs

from kernels import codes
from sweep import cf, netcdf
from sweep.runner.cell_checks import load_study
from sweep.runner import grid, store
from sweep.runner.cells import run_chunk

# docs/design.md section 6: variable -> (dtype, units, extra dims)
CONTRACT = {
    "outcome": ("int8", "1", ()),
    "overturned": ("int8", "1", ()),
    "t_overturn": ("float64", "s", ()),
    "max_abs_theta": ("float64", "rad", ()),
    "impact_count": ("int32", "1", ()),
    "mode_time": ("float32", "s", ("mode",)),
    "max_slip": ("float32", "m", ()),
    "max_lift": ("float32", "m", ()),
    "status": ("int8", "1", ()),
    "f_at_overturn": ("float64", "Hz", ()),
    "a_norm_at_overturn": ("float64", "1", ()),
    "v_norm_at_overturn": ("float64", "1", ()),
}


def _parts(study, tmp_path, chunk_size, seed):
    parts = store.PartStore(tmp_path / f"parts{chunk_size}")
    parts.prepare(study)
    for chunk in grid.plan(study.n_cells, [], chunk_size, seed):
        parts.write_part(run_chunk(study, chunk))
    return parts


def test_parts_merge_identical_for_any_chunking(study, whole, tmp_path):
    reference = cf.to_dataset(study, store.merge([whole], study.n_cells))
    for chunk_size, seed in ((1, 0), (5, 1), (7, 2)):
        parts = _parts(study, tmp_path, chunk_size, seed)
        assert len(parts.parts()) == -(-study.n_cells // chunk_size)
        np.testing.assert_array_equal(parts.done_cells(), np.arange(study.n_cells))
        ds = cf.to_dataset(study, parts.merge(study.n_cells))
        assert without_run_attrs(ds).identical(without_run_attrs(reference))


def test_merge_reports_missing_cells(study, whole):
    half = {k: v[:5] for k, v in whole.items()}
    with pytest.raises(store.StoreError, match="19 cells have no results"):
        store.merge([half], study.n_cells)


def test_prepare_resume_and_stale_parts(study, whole, tmp_path):
    parts = store.PartStore(tmp_path / "p")
    parts.prepare(study)
    parts.write_part({k: v[3:9] for k, v in whole.items()})
    (parts.directory / ".part-000000000.npz.123.tmp").write_bytes(b"half a part")
    parts.prepare(study)  # the same study: parts kept, leftovers of a killed run removed
    np.testing.assert_array_equal(parts.done_cells(), np.arange(3, 9))
    assert [p.name for p in parts.directory.iterdir() if p.name.startswith(".")] == []
    other = load_study(make_study({"amplitude": {"values": [0.5, 1.5], "unit": "west"}}))
    with pytest.raises(store.StoreError, match="parts of other inputs"):
        parts.prepare(other)
    parts.prepare(other, discard=True)
    assert parts.parts() == []
    assert json.loads((parts.directory / store.MANIFEST).read_text())["n_cells"] == 2


def test_output_refused_without_force(tmp_path):
    out = tmp_path / "r.nc"
    store.check_output(out, force=False)
    out.write_bytes(b"x")
    with pytest.raises(store.StoreError, match="--force"):
        store.check_output(out, force=False)
    store.check_output(out, force=True)


def test_netcdf_round_trip_contract(study, whole, tmp_path):
    ds = cf.to_dataset(study, store.merge([whole], study.n_cells))
    path = netcdf.write_netcdf(ds, tmp_path / "sub" / "r.nc")
    assert sorted(p.name for p in path.parent.iterdir()) == ["r.nc"]  # no temporary left
    back = xr.open_dataset(path)
    dims = ("amplitude", "frequency", "b_over_h")
    assert back["outcome"].dims == dims and back.sizes["mode"] == 6
    assert list(back["mode"].values) == list(codes.MODE_NAMES)
    for name, (dtype, units, extra) in CONTRACT.items():
        da = back[name]
        assert da.dtype == np.dtype(dtype), name
        assert da.dims == dims + extra, name
        assert da.attrs["units"] == units, name
        assert da.attrs["long_name"], name
        assert da.encoding["zlib"] and da.encoding["complevel"] == 1, name
        if da.dtype.kind == "i":
            assert "_FillValue" not in da.encoding and "_FillValue" not in da.attrs, name
    for name in list(back.data_vars) + list(back.coords):
        assert back[name].attrs.get("units") and back[name].attrs.get("long_name"), name
    for name in back.coords:
        assert "_FillValue" not in back[name].encoding, name
    assert back["amplitude"].attrs["study_unit"] == "west"
    # the flags are the kernel's codes
    assert back["outcome"].attrs["flag_meanings"].split() == list(codes.OUTCOME_NAMES)
    np.testing.assert_array_equal(back["outcome"].attrs["flag_values"], [-1, 0, 1, 2])
    assert back["outcome"].attrs["flag_values"].dtype == np.int8
    assert back["status"].attrs["flag_meanings"].split() == list(codes.STATUS_NAMES)
    np.testing.assert_array_equal(back["status"].attrs["flag_values"],
                                  np.arange(len(codes.STATUS_NAMES)))
    for key in ("Conventions", "title", "study", "version", "sweep_law", "history",
                "date_created"):
        assert back.attrs[key], key
    assert back.attrs["Conventions"] == "CF-1.11" and back.attrs["study"] == study.text
    assert back.load().identical(ds)  # values, attributes and dtypes survive


def test_outcomes_follow_the_kernel(study, whole):
    status, theta = whole["status"], whole["max_abs_theta"]
    expect = np.where(np.isin(status, codes.FAILED_STATUSES), -1,
                      np.where(status == codes.OVERTURNED, 2, np.where(theta > 0, 1, 0)))
    np.testing.assert_array_equal(whole["outcome"], expect)
    assert set(np.unique(whole["outcome"])) == {0, 1, 2}  # this grid has all three
    over = whole["outcome"] == 2
    assert np.all(np.isfinite(whole["t_overturn"][over]))
    assert np.all(np.isnan(whole["t_overturn"][~over]))
    # a sine at constant amplitude: the normalized acceleration at overturning is the level
    amplitude = np.array([grid.cell_coords(study, i)["amplitude"] for i in range(study.n_cells)])
    np.testing.assert_allclose(whole["a_norm_at_overturn"][over], amplitude[over], rtol=1e-9)


def test_a_part_of_other_inputs_is_never_merged(study, whole, tmp_path):
    parts = store.PartStore(tmp_path / "p")
    parts.prepare(study)
    parts.write_part({k: v[:6] for k, v in whole.items()})
    foreign = store.PartStore(parts.directory, stamp="0" * 64)  # a writer of other inputs
    foreign.write_part({k: v[6:] for k, v in whole.items()})
    with pytest.raises(store.StoreError, match="part-000000006.npz was computed from other"):
        parts.merge(study.n_cells)
    with pytest.raises(store.StoreError, match="1 part files of other inputs"):
        store.PartStore(parts.directory).prepare(study)
    (parts.directory / "part-000000006.npz").write_bytes(b"not a zip")  # a failing disk
    assert store.PartStore(parts.directory).prepare(study) == parts.stamp  # runs again
    np.testing.assert_array_equal(parts.done_cells(), np.arange(6))
