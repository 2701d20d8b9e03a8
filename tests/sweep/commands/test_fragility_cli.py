"""``python -m sweep.fragility`` and ``sweep.probability.fragility`` on small synthetic study
datasets built here with xarray (the layout of docs/design.md section 6).

Member m of a body with median capacity θ overturns at every level above θ exp(β ε_m),
ε_m ~ N(0, 1) (members reused at every level, as when a study scales the same motions), so
P(overturning) = Φ(ln(x/θ)/β) with known θ and β; a body rocks above West's acceleration
g B/H; some cells fail.  Every check is against these generating arrays.
"""
import json
import subprocess

import numpy as np
import pytest
import xarray as xr
from study_helpers import PY, cli_env

from sweep.fragility import main
from sweep.probability.fit import FITTED, SEPARATED
from sweep.probability.fragility import FragilityError, fragility

G = 9.80665
BETA = 0.4
BREADTHS, HEIGHT = np.array([0.2, 0.3]), 0.6
LEVELS = np.geomspace(1.0, 12.0, 8)  # target PGA [m/s²]
MEMBERS = 40
FLAGS = {"flag_values": np.array([-1, 0, 1, 2], dtype=np.int8),
         "flag_meanings": "failed no_rocking rocked overturned"}


def _median_capacity(breadth):
    """θ [m/s²] of a body: twice West's acceleration g B/H."""
    return 2.0 * G * breadth / HEIGHT


def _outcomes(x, breadth, capacity_factor, failed):
    """Outcome codes of cells at PGA ``x`` for members of ``capacity_factor`` exp(β ε)."""
    capacity = _median_capacity(breadth) * capacity_factor
    outcome = np.where(x > capacity, 2, np.where(x > G * breadth / HEIGHT, 1, 0))
    return np.where(failed, -1, outcome).astype(np.int8)


def _variables(dims, outcome, pga, pgv, breadth, slid):
    tan_alpha = breadth / HEIGHT
    p = np.sqrt(3 * G / (4 * 0.5 * np.hypot(breadth, HEIGHT)))
    return {
        "outcome": (dims, outcome, {"units": "1", "long_name": "outcome of the cell", **FLAGS}),
        "overturned": (dims, np.where(outcome < 0, -1, outcome == 2).astype(np.int8),
                       {"units": "1", "long_name": "body overturned"}),
        "slid": (dims, slid.astype(np.int8), {"units": "1", "long_name": "body slid"}),
        "status": (dims, np.where(outcome < 0, 2, 0).astype(np.int8),
                   {"units": "1", "long_name": "end status of the simulation"}),
        "pgv": (dims, pgv, {"units": "m s-1", "long_name": "peak ground velocity"}),
        "pgd": (dims, pgv * 0.3, {"units": "m", "long_name": "peak ground displacement"}),
        "pga_norm": (dims, pga / (G * tan_alpha), {"units": "1",
                                                   "long_name": "PGA / (g tan alpha)"}),
        "pgv_norm": (dims, pgv * p / (G * tan_alpha), {"units": "1",
                                                       "long_name": "PGV p / (g tan alpha)"}),
    }


def striped_study(seed=0, failed_fraction=0.03, identical=False):
    """Dims (B, H, pga, seed): every seed scaled to every target PGA (an axis).

    Returns the dataset and the failed mask, shape (B, H, pga, seed)."""
    rng = np.random.default_rng(seed)
    factor = np.ones(MEMBERS) if identical else np.exp(BETA * rng.standard_normal(MEMBERS))
    shape = (BREADTHS.size, 1, LEVELS.size, MEMBERS)
    x = np.broadcast_to(LEVELS[None, None, :, None], shape)
    breadth = np.broadcast_to(BREADTHS[:, None, None, None], shape)
    failed = rng.random(shape) < failed_fraction
    outcome = _outcomes(x, breadth, factor[None, None, None, :], failed)
    pgv = x * np.exp(rng.normal(np.log(0.1), 0.3, MEMBERS))[None, None, None, :]
    slid = rng.random(shape) < 0.2
    dims = ("B", "H", "pga", "seed")
    coords = {"B": ("B", BREADTHS, {"units": "m", "long_name": "breadth"}),
              "H": ("H", [HEIGHT], {"units": "m", "long_name": "height"}),
              "pga": ("pga", LEVELS, {"units": "m s-2", "long_name": "target PGA"}),
              "seed": ("seed", np.arange(MEMBERS), {"units": "1", "long_name": "seed"})}
    ds = xr.Dataset(_variables(dims, outcome, x, pgv, breadth, slid), coords=coords,
                    attrs={"Conventions": "CF-1.11", "title": "synthetic ensemble"})
    return ds, failed


def cloud_study(seed=1, records=120):
    """Dims (B, record): every record at its own PGA (a variable), no levels dimension."""
    rng = np.random.default_rng(seed)
    names = np.array([f"rec{r:03d}" for r in range(records)])
    shape = (BREADTHS.size, records)
    breadth = np.broadcast_to(BREADTHS[:, None], shape)
    pga = np.broadcast_to(np.exp(rng.uniform(np.log(1.0), np.log(15.0), records)), shape)
    factor = np.exp(BETA * rng.standard_normal(records))
    outcome = _outcomes(pga, breadth, factor[None, :], np.zeros(shape, bool))
    pgv = pga * np.exp(rng.normal(np.log(0.1), 0.3, records))
    dims = ("B", "record")
    variables = _variables(dims, outcome, pga, pgv, breadth, np.zeros(shape, bool))
    variables["pga"] = (dims, pga.copy(), {"units": "m s-2",
                                           "long_name": "peak ground acceleration"})
    coords = {"B": ("B", BREADTHS, {"units": "m", "long_name": "breadth"}),
              "record": ("record", names, {"units": "1", "long_name": "record"})}
    return xr.Dataset(variables, coords=coords, attrs={"title": "records at their own PGA"})


@pytest.fixture
def striped(tmp_path):
    ds, failed = striped_study()
    path = tmp_path / "ensemble.nc"
    ds.to_netcdf(path)
    return path, ds, failed


def _run(argv, capsys):
    status = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return status, out, err


def test_writes_a_cf_dataset_beside_the_input(striped, capsys):
    path, ds, failed = striped
    status, out, err = _run([path, "--over", "seed", "--im", "pga", "--replicates", "300"],
                            capsys)
    assert (status, err) == (0, "")
    written = path.with_name("ensemble_fragility_pga.nc")
    assert f"wrote {written}" in out and "B 0.2 m × H 0.6 m (b/h 0.333)" in out
    with xr.open_dataset(written) as frag:
        for name, da in frag.variables.items():
            assert da.attrs.get("units") and da.attrs.get("long_name"), name
        assert set(frag["p_overturned"].dims) == {"B", "H", "pga"}
        assert frag.attrs["failed_cells"] == int(failed.sum())
        assert (frag["fit_status"] == FITTED).all()
        theta = _median_capacity(BREADTHS)
        np.testing.assert_allclose(frag["theta"].values[:, 0], theta, rtol=0.25)
        assert np.all(frag["theta_lower"] < frag["theta"])
        assert np.all(frag["theta"] < frag["theta_upper"])
        assert frag["theta"].attrs["units"] == "m s-2"


def test_failed_cells_are_left_out_and_counted(tmp_path):
    ds, failed = striped_study(failed_fraction=0.15)
    frag = fragility(ds, ["seed"], "pga", "pga", replicates=200)
    outcome = ds["outcome"].values
    counted = ~failed
    np.testing.assert_array_equal(frag["n_failed"].values, failed.sum(axis=-1))
    np.testing.assert_array_equal(frag["n_members"].values, counted.sum(axis=-1))
    np.testing.assert_array_equal(frag["k_overturned"].values,
                                  ((outcome == 2) & counted).sum(axis=-1))
    np.testing.assert_array_equal(frag["k_rocked"].values,
                                  ((outcome >= 1) & counted).sum(axis=-1))
    slid = ds["slid"].values == 1
    np.testing.assert_array_equal(frag["k_slid"].values, (slid & counted).sum(axis=-1))
    np.testing.assert_allclose(frag["p_overturned"].values,
                               ((outcome == 2) & counted).sum(-1) / counted.sum(-1))
    assert frag.attrs["failed_cells"] == failed.sum() > 0
    assert np.all(frag["fit_points"].values == counted.sum(axis=(-2, -1)))


def test_im_median_per_level_and_pgv_fit(striped):
    """IM = pgv with the members scaled in pga: the level's median PGV, and a cloud-like
    fit on the PGV of each cell."""
    _, ds, failed = striped
    frag = fragility(ds, ["seed"], "pgv", replicates=200)
    pgv = np.where(failed, np.nan, ds["pgv"].values)
    np.testing.assert_allclose(frag["im_median"].values, np.nanmedian(pgv, axis=-1))
    assert frag["theta"].attrs["units"] == "m s-1"
    assert (frag["fit_status"] == FITTED).all()


def test_identical_members_give_zero_or_one_and_no_fit():
    """A deterministic ensemble: every member alike, so p is 0 or 1 at every level and the
    levels separate: θ and β cannot be estimated."""
    ds, _ = striped_study(failed_fraction=0.0, identical=True)
    frag = fragility(ds, ["seed"], "pga", "pga", replicates=100)
    p = frag["p_overturned"].values
    assert set(np.unique(p)) <= {0.0, 1.0}
    np.testing.assert_array_equal(p[..., :], (LEVELS > _median_capacity(BREADTHS)[:, None])
                                  [:, None, :])
    assert (frag["fit_status"] == SEPARATED).all()
    assert np.isnan(frag["theta"]).all() and np.isnan(frag["beta_upper"]).all()


def test_cloud_of_records_is_binned(tmp_path, capsys):
    """No levels dimension and PGA a variable: bins in ln PGA and a fit on every cell."""
    path = tmp_path / "records.nc"
    cloud_study().to_netcdf(path)
    out = tmp_path / "records_fragility.nc"
    status, stdout, err = _run([path, "--over", "record", "--im", "pga", "--bins", "6",
                                "--dataset", out, "--json", "--replicates", "300"], capsys)
    assert (status, err) == (0, "")
    summary = json.loads(stdout)
    assert summary["levels"] is None and len(summary["groups"]) == BREADTHS.size
    with xr.open_dataset(out) as frag:
        assert frag.sizes["im_bin"] == 6
        assert np.all(frag["im_lower"].values[1:] == frag["im_upper"].values[:-1])
        assert (frag["n_members"].sum("im_bin") == 120).all()
        np.testing.assert_allclose(frag["theta"].values, _median_capacity(BREADTHS),
                                   rtol=0.2)
        assert np.all((frag["beta_lower"] < BETA) & (BETA < frag["beta_upper"]))


def test_json_from_the_command_line(striped, tmp_path):
    path, ds, failed = striped
    done = subprocess.run([PY, "-m", "sweep.fragility", str(path), "--over", "seed",
                           "--im", "pga_norm", "--json", "--dataset", str(tmp_path / "f.nc"),
                           "--replicates", "200"],
                          capture_output=True, text=True, env=cli_env(), timeout=300)
    assert (done.returncode, done.stderr) == (0, "")
    summary = json.loads(done.stdout)
    assert summary["intensity_measure"] == "pga_norm" and summary["levels"] == "pga"
    assert summary["failed_cells"] == int(failed.sum())
    for group, breadth in zip(summary["groups"], BREADTHS):
        assert group["coords"] == {"B": breadth, "H": HEIGHT}
        assert group["levels"] == pytest.approx(list(LEVELS))
        overturned = group["overturned"]
        assert all(lo <= p <= hi for lo, p, hi in zip(overturned["lower"], overturned["p"],
                                                      overturned["upper"]))
        assert all(k <= n for k, n in zip(overturned["k"], group["n"]))
        fit = group["fit"]
        assert fit["status"] == "fitted"
        # θ in PGA/(g tan α) = θ_PGA / (g B/H) = 2
        assert fit["theta_interval"][0] < fit["theta"] < fit["theta_interval"][1]
        assert fit["theta"] == pytest.approx(2.0, rel=0.25)


def test_figures(striped, tmp_path, capsys):
    path, _, _ = striped
    for kind in ("curves", "map"):
        figure = tmp_path / f"{kind}.png"
        status, _, err = _run([path, "--over", "seed", "--im", "pga", "--kind", kind, "-o",
                               figure, "--replicates", "100"], capsys)
        assert (status, err) == (0, "")
        assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def _bad_inputs(tmp_path, striped_path):
    text = tmp_path / "notes.nc"
    text.write_text("not a dataset")
    other = tmp_path / "other.nc"
    xr.Dataset({"a": ("x", [1, 2])}).to_netcdf(other)
    no_pgv = tmp_path / "no_pgv.nc"
    xr.open_dataset(striped_path).drop_vars(["pgv", "pgv_norm"]).to_netcdf(no_pgv)
    return [
        ([tmp_path / "missing.nc", "--over", "seed", "--im", "pga"], "cannot read"),
        ([text, "--over", "seed", "--im", "pga"], "cannot open as a netCDF dataset"),
        ([other, "--over", "seed", "--im", "pga"], "not a study dataset"),
        ([striped_path, "--over", "sed", "--im", "pga"],
         "'sed' is not a dimension of the dataset; its dimensions are B, H, pga, seed"),
        ([striped_path, "--over", "seed", "--im", "pga", "--levels", "amplitude"],
         "'amplitude' is not a dimension"),
        ([no_pgv, "--over", "seed", "--im", "pgv"], "no intensity measure 'pgv'"),
        ([no_pgv, "--over", "seed", "--im", "pga", "--kind", "map", "-o", tmp_path / "m.png"],
         "--kind map needs pga and pgv"),
        ([striped_path, "--over", "seed", "--im", "pga", "--dataset", text / "x.nc"],
         "is a file, not a folder"),
        ([striped_path, "--over", "seed", "--im", "pga", "-o", "/proc/fragility.png"],
         "not writable"),
        ([striped_path, "--over", "B", "--im", "pga"],
         "'B' is not an ensemble dimension: its cells are other bodies, each a group of its "
         "own; the ensemble dimensions of this dataset: seed"),
    ]


def test_bad_inputs_exit_2_with_one_line(striped, tmp_path, capsys):
    path, _, _ = striped
    for argv, message in _bad_inputs(tmp_path, path):
        before = sorted(p.name for p in tmp_path.iterdir())
        status, out, err = _run(argv, capsys)
        assert status == 2, argv
        assert message in err and len(err.strip().splitlines()) == 1, err
        assert "Traceback" not in err and out == ""
        assert sorted(p.name for p in tmp_path.iterdir()) == before  # nothing written


def test_bad_input_from_the_command_line_has_no_traceback(striped):
    path, _, _ = striped
    done = subprocess.run([PY, "-m", "sweep.fragility", str(path), "--over", "record",
                           "--im", "pga"], capture_output=True, text=True, env=cli_env(),
                          timeout=120)
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr.strip().splitlines() == [
        f"{path}: 'record' is not a dimension of the dataset; its dimensions are "
        "B, H, pga, seed"]


def test_api_refuses_what_the_dataset_cannot_answer():
    ds, _ = striped_study()
    with pytest.raises(FragilityError, match="both the levels and an ensemble"):
        fragility(ds, ["pga"], "pga", "pga")
    with pytest.raises(FragilityError, match="at least one ensemble dimension"):
        fragility(ds, [], "pga", "pga")


def _study_dataset():
    """Dims as ``sweep.run`` writes them for grid {b_over_h, excitation.horizontal.magnitude,
    size, pga, seed}: coordinates carry the study's axis names (``study_axis``)."""
    ds, _ = striped_study()
    ds = ds.isel(H=0, drop=True).rename({"B": "b_over_h"}).expand_dims(
        magnitude=[6.0, 7.0], size_factor=[1.0]).transpose("b_over_h", "magnitude",
                                                           "size_factor", "pga", "seed")
    for dim, axis in (("b_over_h", "b_over_h"), ("magnitude", "excitation.horizontal.magnitude"),
                      ("size_factor", "size"), ("pga", "pga"), ("seed", "seed")):
        ds[dim].attrs["study_axis"] = axis
    return ds


@pytest.mark.parametrize("over, refused", [
    (["b_over_h"], "b_over_h"), (["seed", "size_factor"], "size_factor"),
    (["seed", "magnitude"], None), (["seed"], None)])
def test_only_ensemble_dimensions_are_members(tmp_path, capsys, over, refused):
    path = tmp_path / "study.nc"
    _study_dataset().to_netcdf(path)
    argv = [path, *[a for name in over for a in ("--over", name)], "--im", "pga",
            "--replicates", "20"]
    status, out, err = _run(argv, capsys)
    if refused is None:
        assert (status, err) == (0, "")
        return
    assert status == 2 and out == ""
    assert err.splitlines() == [
        f"{path}: '{refused}' is not an ensemble dimension: its cells are other bodies, each "
        "a group of its own; the ensemble dimensions of this dataset: magnitude, seed"]


def test_a_dataset_without_ensemble_dimensions_says_so():
    ds = _study_dataset().isel(magnitude=0, seed=0, drop=True)
    with pytest.raises(FragilityError, match=r"'b_over_h' is not an ensemble dimension: .*; "
                                             r"this dataset has no ensemble dimension"):
        fragility(ds, ["b_over_h"], "pga", "pga")


def test_labels_and_counts_read_as_written():
    """Coordinates without float noise in the group labels (0.1 + 0.2 m is 0.3 m); one
    replicate, one bin, one cell: singular."""
    from sweep.fragility import format_table
    from sweep.probability.fragility import counted, describe_group
    assert describe_group({"B": (0.1 + 0.2, "m"), "H": (0.6, "m"),
                           "mu": (0.7000000000000001, "1")}) == \
        "B 0.3 m × H 0.6 m (b/h 0.5), mu 0.7"
    assert describe_group({"mu": (0.123456789, "1")}) == "mu 0.123457"  # 6 digits
    assert [counted(n, "motion") for n in (0, 1, 2)] == ["0 motions", "1 motion", "2 motions"]
    ds, _ = striped_study(failed_fraction=0.0)
    one = ds.isel(B=[0], pga=[0], seed=[0])
    frag = fragility(one, ["seed"], "pga", None, bins=1, replicates=1)
    assert "(1 replicate, seed 0)" in frag.attrs["fit_interval_method"]
    assert frag.attrs["im_bins"] == "1 bin of equal width in ln pga"
    assert "0 of 1 cell failed and left out" in format_table(frag)
