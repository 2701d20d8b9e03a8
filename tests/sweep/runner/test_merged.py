"""The streamed merge: variables in groups under a budget, read from the part files a group at a
time and written into the same netCDF file as from arrays in memory; memory that stays bounded
as a study grows (slow)."""
import netCDF4
import numpy as np
import pytest
import xarray as xr
from study_helpers import without_run_attrs

from sweep import cf, netcdf
from sweep.runner import grid, merged, store


def _parts(study, whole, folder, chunk_size=5):
    """The cells of ``whole`` as part files of ``chunk_size`` cells, in shuffled chunks."""
    parts = store.PartStore(folder)
    parts.prepare(study)
    for chunk in grid.plan(study.n_cells, [], chunk_size, seed=3):
        parts.write_part({key: value[chunk] for key, value in whole.items()})
    return parts


def _structure(path):
    """What ``ncdump -h`` shows of every variable, in the file's order, and the values."""
    with netCDF4.Dataset(path) as nc:
        return [(name, v.dimensions, v.dtype, v.filters(), v.chunking(),
                 [(a, repr(v.getncattr(a))) for a in v.ncattrs()])
                for name, v in nc.variables.items()]


@pytest.mark.parametrize("divisor, groups", [(1, 1), (3, 3), (10**9, len(cf.VARIABLES))])
def test_streamed_write_is_the_in_memory_write(study, whole, tmp_path, divisor, groups):
    n = study.n_cells
    budget = sum(merged.cell_bytes(name) for name in cf.VARIABLES) * n // divisor
    parts = _parts(study, whole, tmp_path / "parts")
    result = merged.MergedParts(parts.index(n), n, budget=budget)
    assert len(result.groups) >= groups
    streamed = store.write_merged(study, result, tmp_path / "streamed.nc", history="h",
                                  attrs={"extra": "x"})
    ds = cf.to_dataset(study, store.merge([whole], n), history="h")
    ds.attrs["extra"] = "x"
    memory = netcdf.write_netcdf(ds, tmp_path / "memory.nc")
    assert _structure(streamed) == _structure(memory)
    with xr.open_dataset(streamed) as a, xr.open_dataset(memory) as b:
        assert without_run_attrs(a.load()).identical(without_run_attrs(b.load()))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["memory.nc", "parts", "streamed.nc"]


def test_a_part_is_three_arrays_its_cells_packed_exactly(study, whole, tmp_path):
    """A part is read as three arrays (cell ids, fingerprint, one structured array of every
    variable), not one per variable; packing keeps every value, dtype and shape."""
    parts = _parts(study, whole, tmp_path / "parts", chunk_size=study.n_cells)
    (path,) = parts.parts()
    with np.load(path, allow_pickle=False) as npz:
        assert sorted(npz.files) == ["cell", "cells", "fingerprint"]
        cells = npz["cells"]
    assert cells.dtype.names == tuple(cf.VARIABLES)
    for name in cf.VARIABLES:
        assert cells[name].dtype == whole[name].dtype
        np.testing.assert_array_equal(cells[name], whole[name])


def test_merged_parts_hold_one_group_and_read_only_its_keys(study, whole, tmp_path):
    n = study.n_cells
    parts = _parts(study, whole, tmp_path / "parts")
    result = merged.MergedParts(parts.index(n), n, budget=merged.cell_bytes("t_rest") * n)
    assert result.groups[0] == ("outcome", "overturned", "status")  # int8: one byte each
    np.testing.assert_array_equal(result["status"], whole["status"])
    assert sorted(result._held) == ["outcome", "overturned", "status"]
    np.testing.assert_array_equal(result["t_rest"], whole["t_rest"])
    assert "status" not in result._held
    assert sorted(result.read(("outcome", "slid"))) == ["outcome", "slid"]
    assert list(result) == list(cf.VARIABLES)


@pytest.mark.parametrize("n_cells", [1, 1000, 10**6, 10**8])
@pytest.mark.parametrize("budget", [1, 4096, merged.BUDGET])
def test_groups_keep_the_order_and_stay_under_the_budget(n_cells, budget):
    groups = merged.groups(n_cells, budget)
    assert [name for group in groups for name in group] == list(cf.VARIABLES)
    for group in groups:
        size = sum(merged.cell_bytes(name) for name in group) * n_cells
        assert size <= budget or len(group) == 1
    assert len(merged.groups(10**6)) == 3  # 165 bytes a cell: 157 MiB in groups of 64 MiB


def test_a_missing_part_stops_the_merge(study, whole, tmp_path):
    parts = _parts(study, whole, tmp_path / "parts")
    lost = parts.parts()[1]
    with np.load(lost) as npz:
        cells = npz["cell"]
    lost.unlink()
    with pytest.raises(store.StoreError, match=f"{cells.size} cells have no results "
                                               rf"\(first: \[{cells[0]}, "):
        parts.merge(study.n_cells)


def test_placeholders_take_no_memory():
    a = merged.placeholder("mode_time", 10**6)
    assert a.shape == (10**6, 6) and a.dtype == np.float32 and np.isnan(a).all()
    assert a.strides == (0, 4) and merged.placeholder("outcome", 3).tolist() == [-1, -1, -1]


@pytest.mark.slow
def test_merge_memory_stays_bounded_as_cells_grow(tmp_path):
    """A merge and write of 4x the cells needs a few bytes more a cell (ids, outcome and
    status, one variable's copy), not the results of every cell (165 bytes a cell)."""
    from benchmarks.merge_memory import measure

    budget = 4 * 2**20
    (small, small_rss), (large, large_rss) = (measure(n, tmp_path, budget)
                                              for n in (200_000, 800_000))
    assert large_rss - small_rss < 0.25 * (large - small)
