"""Figs. 17-21 render from closed forms and small results, with the numbers they must show.

Fig. 17 is checked against docs/physics.md A11; the criteria lines of Figs. 18-21 against Table 5
of the paper and closed forms; the outcomes of a small record study against West's criterion (a
body whose (B/H) g exceeds the record's peak acceleration cannot rock, docs/physics.md A2).
"""
import math

import matplotlib
import numpy as np
import pytest

from sweep import plot, run_study
from sweep.io import records
from sweep.paper import criteria
from sweep.plots import limits as plot_limits
from sweep.plots import records as plot_records

G = 9.80665
SCENE = {"body": {"B": 0.1, "H": 0.3}, "contact": {"mu": 0.8, "e_x": -0.8, "e_y": 0.2},
         "excitation": {"horizontal": {"kind": "record", "name": "elcentro1940_ns"},
                        "vertical": {"kind": "record", "name": "elcentro1940_ud"}},
         "solver": {"max_events": 100000}}
# H/B = 2 (a_o = 490 gal > PGA: no rocking), 4 and 10; B = 3, 12 and 50 cm
GRID = {"B": {"values": [3, 12, 50], "unit": "cm"}, "b_over_h": [0.5, 0.25, 0.1]}


@pytest.fixture(scope="module")
def record_result():
    return run_study({"name": "fig18_small", "title": "small", "scene": SCENE,
                      "grid": {**GRID, "excitation.vertical.scale": [0.0, 1.0]}})


@pytest.fixture(scope="module")
def summary_result():
    scene = {**SCENE, "excitation": {"horizontal": SCENE["excitation"]["horizontal"]}}
    return run_study({"name": "fig21_small", "title": "small", "scene": scene,
                      "grid": {"record": ["elcentro1940_ns", "taft1952_ew_s69e"], **GRID}})


# --- Fig. 17 ----------------------------------------------------------------------------------

def test_fig17_curves_pass_through_a11():
    # B = 10 cm, H = 30 cm (docs/physics.md A11): 326.888 gal, 19.4222 cm/s, 1.1540 cm, 0.37332 s
    H_cm, exact, approx = plot_limits.limit_curves(10, H_max_cm=30, num=2)
    assert H_cm[-1] == pytest.approx(30)
    assert exact["a"][-1] == pytest.approx(326.888, abs=1e-3)
    assert exact["v"][-1] == pytest.approx(19.4222, abs=1e-4)
    assert exact["d"][-1] == pytest.approx(1.1540, abs=1e-3)
    assert exact["T"][-1] == pytest.approx(0.37332, abs=1e-5)
    # the slender-body rules: 10 B/sqrt(H) [cm/s], B/10 [cm], sqrt(H)/16 [s]
    assert approx["v"][-1] == pytest.approx(100 / math.sqrt(30))
    assert approx["d"][-1] == pytest.approx(1.0)
    assert approx["T"][-1] == pytest.approx(math.sqrt(30) / 16)


def test_fig17_cli_needs_no_dataset(tmp_path):
    out = tmp_path / "fig17.png"
    assert plot.main(["--figure", "fig17", "-o", str(out)]) == 0
    assert out.read_bytes().startswith(b"\x89PNG")
    fig = plot_limits.figure_limits()
    labels = [ax.get_ylabel() for ax in fig.axes]
    assert [label.split("[")[-1] for label in labels] == ["gal]", "cm/s]", "cm]", "s]"]
    assert all(ax.get_xscale() == "log" for ax in fig.axes)
    # 5 breadths: a solid curve in each panel, a dashed rule in the last three
    assert sum(len(ax.get_lines()) for ax in fig.axes) == 5 * 4 + 5 * 3


def test_plot_cli_refuses_dataset_mismatch(tmp_path):
    with pytest.raises(SystemExit) as err:
        plot.main(["--figure", "fig18", "-o", str(tmp_path / "x.png")])
    assert err.value.code == 2
    with pytest.raises(SystemExit) as err:
        plot.main([str(tmp_path / "r.nc"), "--figure", "fig17", "-o", str(tmp_path / "x.png")])
    assert err.value.code == 2


# --- Figs. 18-20 ------------------------------------------------------------------------------

def test_peaks_of_bundled_records_are_table5():
    pga, pgv, source = plot_records.record_peaks({"kind": "record", "name": "taft1952_ew"})
    assert (pga, pgv, source) == (1.759, 0.1771, "Table 5")
    pga, pgv, source = plot_records.record_peaks({"name": "elcentro1940_ns", "scale": 0.5})
    assert (pga, pgv) == pytest.approx((0.5 * 3.417, 0.5 * 0.3232))
    # the bundled accelerations agree with Table 5 to 0.6 % (sweep/data/records/README.md)
    for name, (table_pga, _, _) in plot_records.TABLE5.items():
        assert records.load_record(name).pga == pytest.approx(table_pga, rel=6e-3)


def test_peaks_of_a_users_record(tmp_path):
    # a = A cos(2 pi f t) over whole cycles: PGA = A, PGV = A/(2 pi f)
    A, f, dt = 2.0, 1.5, 1e-3
    t = np.arange(0, 4 / f + dt / 2, dt)
    path = tmp_path / "cosine.txt"
    np.savetxt(path, np.column_stack([t, A * np.cos(2 * np.pi * f * t)]))
    pga, pgv, source = plot_records.record_peaks({"path": "cosine.txt", "scale": -2.0},
                                                 base_dir=tmp_path)
    assert source == "record"
    assert pga == pytest.approx(2 * A)
    assert pgv == pytest.approx(2 * A / (2 * np.pi * f), rel=1e-5)


def test_region_a_never_rocks_under_horizontal_shaking(record_result):
    outcome = record_result["outcome"].sel(excitation_vertical_scale=0.0)
    H, HB = plot_records.body_coords(outcome)
    np.testing.assert_allclose(H / HB, np.broadcast_to([[0.03], [0.12], [0.5]], H.shape))
    west = G / HB  # (B/H) g
    peak = records.load_record("elcentro1940_ns").pga
    assert np.any(west > peak) and np.any(west < peak)
    assert np.all(outcome.values[west > peak] == 0)
    # the record exceeds (B/H) g: rocking starts (A2; mu = 0.8 > b/h, so no sliding first)
    assert np.all(outcome.values[west < peak] >= 1)


def test_tally_counts_cells_by_the_criteria(record_result):
    outcome = record_result["outcome"].sel(excitation_vertical_scale=0.0)
    pga, pgv = 3.417, 0.3232
    counts = plot_records.tally(outcome, pga, pgv)
    # B = 3, 12, 50 cm and H/B = 2, 4, 10; H = 6 and 500 cm lie outside the 10-400 cm window;
    # H/B = 2 is region A (West), otherwise region B iff v_o > PGV
    expected = {"A": 0, "B": 0, "C": 0}
    for B in (0.03, 0.12, 0.5):
        for HB in (2, 4, 10):
            H = B * HB
            if not 0.1 <= H <= 4.0:
                continue
            v_o = float(criteria.ishiyama_velocity(B, H))
            region = "A" if G / HB > pga else ("B" if v_o > pgv else "C")
            expected[region] += 1
    assert {r: sum(c.values()) for r, c in counts.items()} == expected
    assert expected == {"A": 2, "B": 1, "C": 4}  # (B = 50 cm, H = 2 m) is in B


def test_record_maps_render(record_result, tmp_path):
    # Figs. 18-20 are one drawing of three studies
    assert plot.FIGURES["fig18"] is plot.FIGURES["fig19"] is plot.FIGURES["fig20"]
    path = tmp_path / "small.nc"
    record_result.to_netcdf(path)
    out = tmp_path / "fig18.png"
    assert plot.main([str(path), "--figure", "fig18", "-o", str(out)]) == 0
    assert out.read_bytes().startswith(b"\x89PNG")
    fig = plot.FIGURES["fig18"](record_result)
    maps = [ax for ax in fig.axes if ax.get_xlabel()]
    assert len(maps) == 2  # without and with the vertical component
    assert [ax.get_title().splitlines()[0] for ax in maps] == [
        "horizontal only", "with vertical elcentro1940_ud"]
    assert maps[0].get_xlabel() == "height of the body H [cm]"
    legend = [t.get_text() for t in fig.legends[0].get_texts()]
    assert "Eq. (14): (B/H) g = 341.7 gal (Table 5)" in legend
    assert "Eq. (16): v_o = 32.32 cm/s (Table 5)" in legend
    assert "Miyagi-ken-oki" in fig.legends[0].get_title().get_text()
    matplotlib.pyplot.close("all")


def test_record_map_refuses_a_sine_study(summary_result):
    ds = summary_result.copy()
    ds.attrs["study"] = "scene: {excitation: {horizontal: {kind: sine}}}"
    with pytest.raises(ValueError, match="not a record"):
        plot_records.figure_record_map(ds.isel(record=0, drop=True))


# --- Fig. 21 ----------------------------------------------------------------------------------

def test_summary_coordinates_are_the_criteria_ratios(summary_result):
    x, y, outcome = plot_records.normalized_cells(summary_result, "taft1952_ew_s69e", 1.759,
                                                  0.1771)
    # shown cells (H in 10..400 cm): B = 3 cm at H/B = 4, 10; 12 cm at 2, 4, 10; 50 cm at 2, 4
    B = np.array([0.03, 0.03, 0.12, 0.12, 0.12, 0.5, 0.5])
    HB = np.array([4, 10, 2, 4, 10, 2, 4])
    order = np.lexsort((y, x))
    expected_x = 1.759 * HB / G
    expected_y = 0.1771 / criteria.ishiyama_velocity(B, B * HB)
    expected = np.lexsort((expected_y, expected_x))
    np.testing.assert_allclose(x[order], expected_x[expected], rtol=1e-12)
    np.testing.assert_allclose(y[order], expected_y[expected], rtol=1e-12)
    assert np.all(outcome[x < 1] == 0)  # below West's acceleration nothing rocks


def test_summary_renders(summary_result, tmp_path):
    path = tmp_path / "small.nc"
    summary_result.to_netcdf(path)
    out = tmp_path / "fig21.png"
    assert plot.main([str(path), "--figure", "fig21", "-o", str(out)]) == 0
    assert out.read_bytes().startswith(b"\x89PNG")
    fig = plot_records.figure_summary(summary_result)
    plane, bars = fig.axes
    assert plane.get_xscale() == plane.get_yscale() == "log"
    assert [t.get_text() for t in bars.get_yticklabels()] == [
        f"{name} {r}" for name in ("elcentro1940_ns", "taft1952_ew_s69e") for r in "ABC"]
    matplotlib.pyplot.close("all")
