"""Rate studies: the slow-limit fit, the figure, the similarity of sweeps, the fixed 1 ms step.

Independent values: data drawn from y_inf + c T^-k with known parameters and noise (the fit
must recover y_inf, its interval must cover it at about its nominal rate); the similarity of
docs/physics.md A1 (lengths x 4, times x 2: the same trajectory); the octave duration of a log
sweep (duration / log2(f_start/f_stop)).
"""
import numpy as np
import pytest

from sweep import run_study, simulate
from sweep.paper import rates
from sweep.plots.rates import figure_rates

T_RATES = 40.0 * 2.0 ** np.arange(6)  # s per octave: 40 ... 1280, as the rate studies
TRUE = (0.75, 0.15, 2.0 / 3.0)       # y_inf, c, k of the synthetic data
CONTACT = {"mu": 0.8, "e_x": -0.8, "e_y": 0.2}


def _synthetic(rng, sigma):
    T0 = T_RATES[0]
    y = TRUE[0] + TRUE[1] * (T_RATES / T0) ** -TRUE[2]
    return y + rng.normal(0.0, sigma, T_RATES.size)


def test_fit_recovers_the_limit_and_its_interval_covers_it_at_the_nominal_rate():
    rng = np.random.default_rng(1)
    sigma = np.full(T_RATES.size, 0.004)
    fits = [rates.fit_slow_limit(T_RATES, _synthetic(rng, sigma), sigma) for _ in range(60)]
    values = np.array([f.value for f in fits])
    covered = np.mean([f.low <= TRUE[0] <= f.high for f in fits])
    assert abs(np.median(values) - TRUE[0]) < 0.01
    assert 0.85 <= covered <= 1.0  # nominal 0.95; 60 draws: 3 standard deviations below
    assert abs(np.median([f.k for f in fits]) - TRUE[2]) < 0.15
    # chi2 of a good model has its dof (3) as mean
    assert 1.5 < np.mean([f.chi2 for f in fits]) < 5.0


def test_fit_without_sigma_scales_the_covariance_by_the_residuals():
    rng = np.random.default_rng(2)
    fits = [rates.fit_slow_limit(T_RATES, _synthetic(rng, 0.004)) for _ in range(60)]
    covered = np.mean([f.low <= TRUE[0] <= f.high for f in fits])
    assert 0.8 <= covered <= 1.0
    assert all(np.isnan(f.chi2) and f.scaled for f in fits)


def test_fit_needs_four_rates():
    with pytest.raises(ValueError, match="at least 4"):
        rates.fit_slow_limit(T_RATES[:3], [1.0, 0.9, 0.85])


# --- the figure from a small synthetic rate study --------------------------------------------

DURATIONS = [4.0, 8.0, 16.0, 32.0]  # s of a 2-octave sweep: 2 ... 16 s per octave


@pytest.fixture(scope="module")
def synthetic_rate_study():
    """A tiny rate study run for its layout, its results replaced by known values: level L
    overturns at v = L * (0.75 + 0.15 (T/T_0)^-2/3) + 0.003 * (phase index - 0.5)."""
    study = {"name": "tiny_rates", "title": "tiny rate study",
             "scene": {"body": {"B": 0.05, "H": 0.15}, "contact": CONTACT,
                       "excitation": {"horizontal": {
                           "kind": "sweep", "hold": "acceleration", "amplitude": "1.5 west",
                           "f_start": 8.0, "f_stop": 2.0, "duration": 4.0}},
                       "solver": {"t_end": 0.1}},
             "grid": {"amplitude": {"values": [1.2, 2.0], "unit": "west"},
                      "excitation.horizontal.duration": {"values": DURATIONS, "unit": "s"},
                      "phase": {"values": [0, 90], "unit": "deg"}}}
    ds = run_study(study)
    T = ds["duration"].values / 2.0
    level = ds["amplitude"].values[:, None, None]
    member = np.arange(2)[None, None, :]
    v = level * (TRUE[0] + TRUE[1] * (T[None, :, None] / T[0]) ** -TRUE[2]) \
        + 0.003 * (member - 0.5)
    ds["v_norm_at_overturn"].values[...] = v
    ds["a_norm_at_overturn"].values[...] = level
    ds["overturned"].values[...] = 1
    ds["outcome"].values[...] = 2
    ds["t_overturn"].values[...] = 0.5 * ds["duration"].values[None, :, None]
    ds["f_at_overturn"].values[...] = 4.0
    return ds


def test_rate_cells_read_the_octave_duration_and_the_swept_velocity(synthetic_rate_study):
    cells = rates.rate_cells(synthetic_rate_study)
    assert cells.hold == "acceleration"
    assert sorted(set(cells.octave_time)) == [d / 2.0 for d in DURATIONS]
    summary = rates.summarize(cells)
    T = summary.octave_times
    expected = summary.levels[:, None] * (TRUE[0] + TRUE[1] * (T / T[0]) ** -TRUE[2])
    np.testing.assert_allclose(summary.mean[0], expected, rtol=1e-12)
    np.testing.assert_allclose(summary.high[0] - summary.low[0], 0.003, rtol=1e-9)


def test_figure_draws_each_level_with_its_extrapolated_limit(synthetic_rate_study):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = figure_rates([synthetic_rate_study])
    ax = fig.axes[0]
    assert ax.get_xscale() == "log"
    bands = [c.get_paths()[0].vertices[:, 1] for c in ax.collections
             if c.get_paths() and len(c.get_paths()[0].vertices) > 3]
    limits = sorted(0.5 * (b.min() + b.max()) for b in bands)
    # the limit of level L is L * 0.75, within the fit's interval (sem 0.0015 per point)
    np.testing.assert_allclose(limits, [1.2 * TRUE[0], 2.0 * TRUE[0]], atol=0.02)
    texts = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "1.2 west" in texts and "2 west" in texts
    plt.close(fig)


# --- similarity and the fixed step ------------------------------------------------------------

def _sweep_scene(B, H, f_start, duration, solver, hold_amplitude="2 west"):
    return {"body": {"B": B, "H": H}, "contact": CONTACT,
            "excitation": {"horizontal": {"kind": "sweep", "hold": "acceleration",
                                          "amplitude": hold_amplitude, "f_start": f_start,
                                          "f_stop": f_start / 32.0, "duration": duration,
                                          "phase": 0.3}},
            "solver": {"max_events": 1_000_000, **solver}}


def test_a_body_four_times_larger_is_the_smaller_body_swept_twice_as_fast():
    """docs/physics.md A1: lengths x 4, times x 2.  The 20 x 60 cm body swept 6.4 -> 0.2 Hz in
    25 s (5 s per octave) is the 5 x 15 cm body swept 12.8 -> 0.4 Hz in 12.5 s.  Exact in the
    model; the solver's absolute settings (max_step, zeno_dt, atol) are scaled or made
    negligible, else they differ by ~1 % (chaotic growth of the integration error)."""
    solver = {"rtol": 1e-10, "atol": 1e-13}
    small = simulate(_sweep_scene(0.05, 0.15, 12.8, 12.5,
                                  {**solver, "max_step": 0.025, "zeno_dt": 1e-6}))
    large = simulate(_sweep_scene(0.20, 0.60, 6.4, 25.0,
                                  {**solver, "max_step": 0.05, "zeno_dt": 2e-6}))
    assert small.overturned and large.overturned
    assert large.impact_count == small.impact_count
    assert large.t_overturn / 2.0 == pytest.approx(small.t_overturn, rel=1e-6)
    assert large.f_at_overturn * 2.0 == pytest.approx(small.f_at_overturn, rel=1e-6)


def test_fixed_1ms_step_overturns_where_the_adaptive_run_does():
    """One cell of steady inverse-phase rocking (Fig. 9 body, 2 (B/H) g, 40 s per octave).
    docs/physics.md 3.5: the paper's 1 ms step errs by ~1e-3 rad per impact, good enough for sweep
    maps; over the ~8,000 impacts of this sweep it delays the overturning by 0.65 s, 0.016
    octave: the overturning frequency within 2 %."""
    adaptive = simulate(_sweep_scene(0.05, 0.15, 12.8, 200.0, {}))
    fixed = simulate(_sweep_scene(0.05, 0.15, 12.8, 200.0, {"method": "fixed", "dt": 1e-3}))
    assert adaptive.overturned and fixed.overturned
    assert fixed.f_at_overturn == pytest.approx(adaptive.f_at_overturn, rel=0.02)
    assert abs(fixed.t_overturn - adaptive.t_overturn) < 40.0 * np.log2(1.02)
