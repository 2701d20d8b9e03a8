"""Outcome maps over an axis of names (``sweep.plots.map``): the record x PGA map of a user who
brings records, any other axis of strings, and the command that used to fail on them.

Every cell's colour is checked against the dataset's outcome at the record named by the tick
label under the cell, and at the PGA the cell is centred on."""
import numpy as np
import pytest
import xarray as xr
import yaml
from matplotlib.colors import to_rgba
from study_helpers import SCENE

import sweep
from sweep import plot
from sweep.plots.map import figure_map
from sweep.plots.style import OUTCOME_COLOURS
from sweep.netcdf import write_netcdf

RECORDS = ["elcentro1940_ns", "taft1952_ew_s69e"]
RECORD_SCENE = {"body": {"B": 0.2, "H": 0.8}, "contact": {"mu": 0.8, "e_x": -0.8, "e_y": 0.2},
                "excitation": {"horizontal": {"kind": "record", "name": RECORDS[0]}},
                "solver": {"t_end": 6.0}}
PGA = {"start": 1.5, "stop": 12.0, "num": 4, "spacing": "log", "unit": "m/s^2"}


@pytest.fixture(scope="module")
def records_by_pga():
    """2 records x 4 PGA levels x 2 heights, the first 6 s of each record."""
    return sweep.run_study({"name": "records_by_pga", "title": "Two records scaled in PGA",
                            "scene": RECORD_SCENE,
                            "grid": {"record": RECORDS, "pga": PGA, "H": [0.6, 0.8]}})


def _cells(ax):
    """(name along y or x, value along the other axis, RGBA) of every drawn cell of a map,
    the name read from the tick label at the cell's centre."""
    mesh = ax.collections[0]
    ax.figure.canvas.draw()
    corners = mesh.get_coordinates()  # (rows + 1, columns + 1, 2)
    colours = np.asarray(mesh.get_facecolors()).reshape(corners.shape[0] - 1,
                                                        corners.shape[1] - 1, 4)
    x_names = {round(t.get_position()[0], 9): t.get_text() for t in ax.get_xticklabels()}
    y_names = {round(t.get_position()[1], 9): t.get_text() for t in ax.get_yticklabels()}
    for row in range(colours.shape[0]):
        for column in range(colours.shape[1]):
            x0, x1 = corners[row, column, 0], corners[row, column + 1, 0]
            y0, y1 = corners[row, column, 1], corners[row + 1, column, 1]
            yield x0, x1, y0, y1, x_names, y_names, colours[row, column]


def test_record_map_draws_one_row_per_record_named_and_coloured_by_outcome(records_by_pga):
    ds = records_by_pga
    fig = figure_map(ds)
    axes = [ax for ax in fig.axes if ax.get_visible()]
    assert len(axes) == 2  # a panel per height
    for ax, height in zip(axes, ds["H"].values):
        assert [t.get_text() for t in ax.get_yticklabels()] == RECORDS
        assert ax.get_ylim()[0] > ax.get_ylim()[1]  # the first record on top
        assert ax.get_xscale() == "log" and ax.get_ylabel() == "record"
        seen = set()
        for x0, x1, y0, y1, _, names, rgba in _cells(ax):
            record = names[round(0.5 * (y0 + y1), 9)]
            pga = float(np.sqrt(x0 * x1))  # the cell's centre on a log axis
            level = ds["pga"].values[np.argmin(abs(np.log(ds["pga"].values / pga)))]
            assert pga == pytest.approx(level, rel=1e-9)
            outcome = int(ds["outcome"].sel(record=record, pga=level, H=height))
            np.testing.assert_allclose(rgba, to_rgba(OUTCOME_COLOURS[outcome]), atol=1e-6)
            seen.add((record, level))
        assert len(seen) == len(RECORDS) * ds.sizes["pga"]


def test_records_as_columns_when_asked(records_by_pga):
    ax = figure_map(records_by_pga, x="record", y="pga").axes[0]
    assert [t.get_text() for t in ax.get_xticklabels()] == RECORDS
    for x0, x1, y0, y1, names, _, rgba in _cells(ax):
        record = names[round(0.5 * (x0 + x1), 9)]
        level = float(np.sqrt(y0 * y1))
        outcome = int(records_by_pga["outcome"].sel(record=record, H=0.6)
                      .sel(pga=level, method="nearest"))
        np.testing.assert_allclose(rgba, to_rgba(OUTCOME_COLOURS[outcome]), atol=1e-6)


def test_the_command_draws_a_record_map(records_by_pga, tmp_path, capsys):
    """`python -m sweep.plot RESULT.nc --figure map` on a record axis: once 'could not convert
    string to float', now a figure."""
    result = tmp_path / "records.nc"
    write_netcdf(records_by_pga, result)
    png = tmp_path / "map.png"
    assert plot.main([str(result), "--figure", "map", "-o", str(png)]) == 0
    assert png.read_bytes().startswith(b"\x89PNG")
    assert capsys.readouterr().err == ""
    with xr.open_dataset(result) as ds:  # read back from netCDF, strings as written
        assert [t.get_text() for t in figure_map(ds).axes[0].get_yticklabels()] == RECORDS


def test_a_glob_of_record_files_is_named_by_file(tmp_path):
    folder = tmp_path / "motions"
    folder.mkdir()
    t = np.arange(0.0, 4.0, 0.01)
    for name, frequency in (("north_N.txt", 2.0), ("south_E.txt", 1.2)):
        np.savetxt(folder / name, np.c_[t, 3.0 * np.sin(2 * np.pi * frequency * t)],
                   header="units: m/s^2", fmt="%.6f")
    study = tmp_path / "glob.yaml"
    study.write_text(yaml.safe_dump({
        "name": "glob", "scene": {**RECORD_SCENE, "solver": {"t_end": 4.0}},
        "grid": {"record": {"glob": "motions/*.txt"},
                 "pga": {"start": 2.0, "stop": 8.0, "num": 3, "spacing": "log",
                         "unit": "m/s^2"}}}))
    ds = sweep.run_study(study)
    assert list(ds["record"].values) == ["motions/north_N.txt", "motions/south_E.txt"]
    ax = figure_map(ds).axes[0]
    assert [t.get_text() for t in ax.get_yticklabels()] == ["north_N.txt", "south_E.txt"]


def test_any_axis_of_strings_is_categorical():
    """contact.landing, a dotted path whose values are names, maps like records."""
    ds = sweep.run_study({"name": "landing", "scene": {**SCENE, "solver": {"t_end": 1.0}},
                          "grid": {"contact.landing": ["flat", "corner"],
                                   "amplitude": {"values": [0.5, 2.5], "unit": "west"}}})
    ax = figure_map(ds).axes[0]
    assert [t.get_text() for t in ax.get_yticklabels()] == ["flat", "corner"]
    for x0, x1, y0, y1, _, names, rgba in _cells(ax):
        landing = names[round(0.5 * (y0 + y1), 9)]
        outcome = int(ds["outcome"].sel(landing=landing, amplitude=0.5 * (x0 + x1)))
        np.testing.assert_allclose(rgba, to_rgba(OUTCOME_COLOURS[outcome]), atol=1e-6)


def test_levels_are_drawn_in_the_unit_the_study_was_written_in(records_by_pga):
    """A pga axis written in g (stored in m/s^2) is drawn in g: cells centred at the levels
    as written, the axis labelled [g]; an axis written in m/s^2 stays as stored."""
    ds = records_by_pga.isel(pga=[0, 1]).sel(H=0.8)
    written = np.array([0.25, 0.5])  # g
    in_g = ds.assign_coords(pga=("pga", written * 9.80665, {**ds["pga"].attrs,
                                                            "study_unit": "g"}))
    ax = [a for a in figure_map(in_g).axes if a.get_visible()][0]
    assert ax.get_xlabel().endswith("[g]")
    edges = ax.collections[0].get_coordinates()[0, :, 0]
    centres = (np.sqrt(edges[:-1] * edges[1:]) if ax.get_xscale() == "log"
               else (edges[:-1] + edges[1:]) / 2)
    np.testing.assert_allclose(centres, written, rtol=1e-12)
    ax = [a for a in figure_map(ds).axes if a.get_visible()][0]
    assert ax.get_xlabel().endswith("[m s-2]")
