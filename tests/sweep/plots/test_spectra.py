"""Rocking spectra (``sweep.plots.spectra``): the similarity law they rest on, the frequency
parameter read from a dataset, the size effect under El Centro and the figure itself.

Every dataset comes from ``sweep.run_study`` (in this process, nothing written).  Pure rocking
with Housner's impact throughout: mu = 1, e_x = e_y = 0.
"""
import math

import matplotlib
import numpy as np
import pytest

import sweep
from sweep.plots.spectra import cell_blocks, figure_spectrum, size_dim, standing_limit

matplotlib.use("Agg")
G = 9.80665
HOUSNER = {"mu": 1.0, "e_x": 0.0, "e_y": 0.0}
TAN_ALPHA = (0.100335, 0.255342)  # tan(0.10), tan(0.25)


def _uniform_p(B, H):
    """sqrt(3g/4R), R = half-diagonal (docs/physics.md 1.1), for a uniform block B x H [m]."""
    return np.sqrt(3.0 * G / (4.0 * 0.5 * np.hypot(B, H)))


@pytest.fixture(scope="module")
def elcentro():
    """Blocks of alpha = 0.10 and 0.25 rad under El Centro 1940 NS, three breadths:
    R = 0.10/0.04 m, 2.0/0.81 m and 20/8.1 m."""
    return sweep.run_study({
        "name": "spectrum_test", "title": "Rocking spectrum under El Centro 1940 NS",
        "scene": {"body": {"B": 1.0, "H": 5.0}, "contact": HOUSNER,
                  "excitation": {"horizontal": {"kind": "record", "name": "elcentro1940_ns"}},
                  "solver": {"t_end": 60.0, "max_events": 100000}},
        "grid": {"B": [0.02, 0.4, 4.0], "b_over_h": list(TAN_ALPHA)}})


def test_one_sine_pulse_similarity():
    """Anchor A1 (Dimitrakopoulos & DeJong 2012): blocks of one alpha scaled by lambda = 1, 4,
    9 under one-sine pulses of the same a_p/(g tan alpha) and omega_p/p (frequency / sqrt
    lambda, pulse and simulation times x sqrt lambda) rock alike: the same peak theta/alpha,
    the same overturnings, overturning times in proportion."""
    B, b_over_h, omega_ratio = 0.2, 0.2, 5.0
    f = float(omega_ratio * _uniform_p(B, B / b_over_h) / (2.0 * math.pi))
    scales = np.array([1.0, 4.0, 9.0])
    ds = sweep.run_study({
        "name": "similarity",
        "scene": {"body": {"B": B, "H": B / b_over_h}, "contact": HOUSNER,
                  "excitation": {"horizontal": {"kind": "sine", "amplitude": "3 west",
                                                "frequency": f, "duration": 1.0 / f}}},
        "grid": {"size": scales.tolist(),
                 "frequency": (f / np.sqrt(scales)).tolist(),
                 "excitation.horizontal.duration": (np.sqrt(scales) / f).tolist(),
                 "solver.t_end": (6.0 * np.sqrt(scales)).tolist(),
                 # a_p/(g tan alpha): 'west' is (B/H) g = g tan alpha
                 "amplitude": {"values": [2.0, 2.5, 3.0, 4.0], "unit": "west"}},
        "zip": {"similar": ["size", "frequency", "excitation.horizontal.duration",
                            "solver.t_end"]}})
    peak = (ds["max_abs_theta"] / math.atan(b_over_h)).values
    outcome = ds["outcome"].values
    assert set(outcome[0]) == {1, 2}, "the levels should straddle the overturning boundary"
    np.testing.assert_array_equal(outcome, np.broadcast_to(outcome[0], outcome.shape))
    np.testing.assert_allclose(peak, np.broadcast_to(peak[0], peak.shape), rtol=1e-6)
    t_scaled = ds["t_overturn"].values / np.sqrt(scales)[:, None]
    np.testing.assert_allclose(t_scaled, np.broadcast_to(t_scaled[0], t_scaled.shape),
                               rtol=1e-6)


def test_p_from_size_and_slenderness_axes():
    """p of every cell equals sqrt(3g/4R) of its B and H, here set by the size axis and
    b_over_h on a base body (B = 0.1 m x size, H = B/(b/h))."""
    sizes, ratios = [0.5, 1.0, 30.0], [0.1, 0.25]
    ds = sweep.run_study({"name": "p", "scene": {"body": {"B": 0.1, "H": 0.3},
                                                 "solver": {"t_end": 0.01}},
                          "grid": {"size": sizes, "b_over_h": ratios}})
    blocks = cell_blocks(ds)
    B = 0.1 * np.array(sizes)[:, None] * np.ones(len(ratios))
    H = B / np.array(ratios)
    np.testing.assert_allclose(blocks["p"].values, _uniform_p(B, H), rtol=1e-12)
    np.testing.assert_allclose(np.tan(blocks["alpha"].values), B / H, rtol=1e-12)
    assert size_dim(blocks) == "size_factor"  # the dataset name of the size axis


def test_p_from_breadth_axis(elcentro):
    """The same with a B axis: p = sqrt(3g/4R), R = B/(2 sin alpha), alpha = atan(b/h)."""
    blocks = cell_blocks(elcentro)
    alpha = np.arctan(np.array(TAN_ALPHA))
    R = np.array([0.02, 0.4, 4.0])[:, None] / (2.0 * np.sin(alpha))
    np.testing.assert_allclose(blocks["p"].values, np.sqrt(0.75 * G / R), rtol=1e-12)
    assert size_dim(blocks) == "B"


def test_no_size_dimension_is_refused():
    """B x H grids change alpha along both dimensions: no spectrum to read."""
    ds = sweep.run_study({"name": "bh", "scene": {"body": {"B": 0.1, "H": 0.3},
                                                  "solver": {"t_end": 0.01}},
                          "grid": {"B": [0.1, 0.2], "H": [0.5, 1.0]}})
    with pytest.raises(ValueError, match="only the size"):
        size_dim(cell_blocks(ds))


def test_larger_blocks_of_one_slenderness_stand(elcentro):
    """Housner's size effect under El Centro NS (Makris & Konstantinidis 2003): at these three
    sizes the overturned blocks of each alpha are the smaller ones, the smallest fall and the
    largest stand.  Not monotone at every size: the study's finer grid has blocks that stand
    between sizes that fall (alpha = 0.25 rad: R = 0.17-0.19 m stand, 0.20-0.32 m fall)."""
    overturned = elcentro["outcome"].transpose("B", "b_over_h").values == 2
    assert np.all(overturned[0]) and not np.any(overturned[-1])
    for column in overturned.T:  # along increasing B: True ... True False ... False
        assert np.all(np.diff(column.astype(int)) <= 0), column
    counts = overturned.sum(axis=1)
    assert np.all(np.diff(counts) <= 0)
    assert counts[1] == 1  # R = 2.0 m falls at alpha = 0.10; R = 0.81 m stands at 0.25


def test_standing_limit():
    """Largest p up to which every block of a line stands; inf and -inf at the ends."""
    p = np.array([4.0, 1.0, 3.0, 2.0])
    assert standing_limit(p, np.array([2, 1, 2, 0])) == 2.0
    assert standing_limit(p, np.array([1, 1, 1, 1])) == math.inf
    assert standing_limit(p, np.array([1, 2, 1, 1])) == -math.inf
    assert standing_limit(p, np.array([1, 1, -1, 1])) == 2.0  # a failed cell is not standing


@pytest.mark.parametrize("yscale", ["log", "linear"])
def test_figure_draws_one_line_per_slenderness(elcentro, yscale):
    fig = figure_spectrum(elcentro, yscale=yscale)
    ax = fig.axes[0]
    labels = [line.get_label() for line in ax.get_lines() if line.get_label().startswith("α")]
    # p of the largest standing block: sqrt(3g/4R), R = B/(2 sin alpha) = 20.0 m and 0.808 m
    assert labels == ["α = 0.10 rad (b/h = 0.100): stands for all p ≤ 0.606 rad/s, R ≥ 20 m",
                      "α = 0.25 rad (b/h = 0.255): stands for all p ≤ 3.02 rad/s, R ≥ 0.81 m"]
    crosses = sum(len(line.get_xdata()) for line in ax.get_lines() if line.get_marker() == "x")
    assert crosses == int((elcentro["outcome"] == 2).sum())
    assert "elcentro1940_ns" in fig._suptitle.get_text()
    assert "PGA 0.349 g" in fig._suptitle.get_text()
    matplotlib.pyplot.close(fig)
