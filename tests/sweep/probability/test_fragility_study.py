"""Fragility of a real ensemble study: probabilities grow with the level, within their
intervals, and the fitted curve sits where the simulated fractions are."""
import numpy as np
import pytest
from scipy.stats import norm

import sweep
from sweep.probability.fragility import fragility

G = 9.80665


@pytest.fixture(scope="module")
def ensemble():
    """A 20 x 80 cm body under 24 synthetic M 7 motions at 20 km, scaled to 7 PGA levels."""
    west = G * 0.25
    study = {"name": "ensemble",
             "scene": {"body": {"B": 0.2, "H": 0.8},
                       "contact": {"mu": 0.8, "e_x": -0.8, "e_y": 0.2},
                       "excitation": {"horizontal": {
                           "kind": "synthetic", "model": "boore2003", "magnitude": 7.0,
                           "distance": "20 km", "vs30": "760 m/s"}},
                       "solver": {"t_end": 30.0}},
             "grid": {"seed": list(range(24)),
                      "pga": {"values": (west * np.geomspace(1.1, 4.0, 7)).tolist()}}}
    return sweep.run_study(study)


def test_probability_does_not_decrease_with_the_level_beyond_its_intervals(ensemble):
    frag = fragility(ensemble, ["seed"], "pga", replicates=200)
    p = frag["p_overturned"].values
    lower, upper = frag["p_overturned_lower"].values, frag["p_overturned_upper"].values
    # a later level's interval never lies wholly below an earlier level's
    for j in range(len(p)):
        assert np.all(upper[j:] >= lower[j] - 1e-12)
    assert p[0] < 0.5 < p[-1]  # from mostly standing to mostly overturned


def test_the_fit_passes_through_the_simulated_fractions(ensemble):
    frag = fragility(ensemble, ["seed"], "pga", replicates=200)
    assert int(frag["fit_status"]) == 0
    theta, beta = float(frag["theta"]), float(frag["beta"])
    x = frag["im_median"].values
    fitted = norm.cdf(np.log(x / theta) / beta)
    inside = (fitted >= frag["p_overturned_lower"].values - 0.05) & \
             (fitted <= frag["p_overturned_upper"].values + 0.05)
    assert inside.sum() >= len(x) - 1  # a lognormal is a convention: one level may miss
    # the median lies above West's acceleration: nothing overturns below it
    assert theta > G * 0.25
