"""Stochastic point-source motions (sweep.groundmotion.stochastic): published formulas, the
normalization of Boore (2003), seeds, argument checks and the check against BSSA14."""
import json
import math

import numpy as np
import pytest

from sweep.groundmotion import crustal, gmpe_check, stochastic
from sweep.groundmotion.intensity import measures

MODEL = "boore2003"


def test_seismic_moment_and_brune_corner_frequency_of_m65():
    # Hanks & Kanamori (1979): M = 2/3 log10 M0 - 10.7, M0 in dyne-cm; M 6.5 -> 10^25.8 dyne-cm
    moment = stochastic.seismic_moment(6.5)
    assert moment == pytest.approx(6.309573e25 * 1e-7, rel=1e-6)
    # Boore (2003): f0 = 4.906e6 * 3.5 km/s * (100 bar / 6.309573e25 dyne-cm)^(1/3)
    #             = 1.7171e7 * (1.584893e-24)^(1/3) = 1.7171e7 * 1.165914e-8 = 0.200198 Hz
    f0 = stochastic.corner_frequency(moment, 100.0e5, 3500.0)
    assert f0 == pytest.approx(0.200198, rel=1e-5)
    # Brune (1970) itself: source radius r = (7 M0 / (16 stress))^(1/3), f0 = 2.34 beta / (2 pi r)
    radius = (7.0 * moment / (16.0 * 100.0e5)) ** (1.0 / 3.0)
    assert f0 == pytest.approx(2.34 * 3500.0 / (2.0 * math.pi * radius), rel=1e-3)


def test_target_spectrum_at_1_hz_against_boores_formula_in_cgs_units():
    # M 6.5, Rrup 20 km, generic rock (Vs30 620 m/s: no site term), f = 1 Hz
    h = 10 ** (-0.405 + 0.235 * 6.5)                         # 13.2587 km (Yenier & Atkinson)
    r = math.sqrt(20.0 ** 2 + h ** 2)                        # 23.9957 km
    c = 0.55 * 2.0 / math.sqrt(2.0) / (4 * math.pi * 2.8 * 3.5 ** 3) * 1e-20  # cm s / dyne-cm
    source = c * 6.309573e25 / (1.0 + (1.0 / 0.200198) ** 2)  # cm s at 1 km
    path = (1.0 / r) * math.exp(-math.pi * 1.0 * r / (180.0 * 3.5))
    # Boore & Joyner (1997) generic rock, log-log between 1.58 at 0.84 Hz and 1.74 at 1.25 Hz
    amplification = math.exp(math.log(1.58) + math.log(1.0 / 0.84) / math.log(1.25 / 0.84)
                             * math.log(1.74 / 1.58))        # 1.64828
    site = amplification * math.exp(-math.pi * 0.04 * 1.0)
    expected = (2 * math.pi) ** 2 * source * path * site * 0.01  # cm/s -> m/s
    got = stochastic.fourier_amplitude(np.array([1.0]), 6.5, 20.0e3, 620.0)[0]
    assert got == pytest.approx(expected, rel=1e-4)  # f0 above has six digits


def test_site_term_follows_bssa14_linear_term():
    f = np.array([0.5, 1.0, 10.0])
    ratio = (stochastic.site_amplification(f, 360.0)
             / stochastic.site_amplification(f, 760.0))
    # BSSA14: c(2 s) = -1.0392, c(1 s) = -1.05, c(0.1 s) = -0.48724; ratio = (360/760)^c
    assert ratio == pytest.approx((360.0 / 760.0) ** np.array([-1.0392, -1.05, -0.48724]),
                                  rel=1e-6)
    # above V_c the term stops growing: V_c(0.1 s) = 1479.12 m/s
    assert stochastic.site_amplification(f, 2000.0)[2] == pytest.approx(
        stochastic.site_amplification(f, 1479.12)[2])


def test_mean_square_fourier_amplitude_of_50_motions_is_the_target():
    """Boore's normalization makes E|FAS|^2 equal to the target squared.  With 50 seeds a
    single bin scatters by 1/sqrt(50) = 14 %; over the ~20 to ~300 partly independent bins of
    each band below the expected scatter is 2-5 %, hence the 15 % per band and 5 % overall."""
    magnitude, distance, vs30 = 6.5, 20.0e3, 760.0
    spectra = []
    for seed in range(50):
        record = stochastic.generate(MODEL, magnitude, distance, vs30, seed)
        spectra.append(np.abs(np.fft.rfft(record.samples) * record.dt) ** 2)
    f = np.fft.rfftfreq(len(record.samples), record.dt)
    band = (f >= 0.2) & (f <= 20.0)
    ratio = (np.mean(spectra, axis=0)[band]
             / stochastic.fourier_amplitude(f[band], magnitude, distance, vs30) ** 2)
    assert ratio.mean() == pytest.approx(1.0, abs=0.05)
    for low, high in ((0.2, 0.8), (0.8, 3.2), (3.2, 12.8), (12.8, 20.0)):
        inside = (f[band] >= low) & (f[band] <= high)
        assert ratio[inside].mean() == pytest.approx(1.0, abs=0.15), (low, high)


def test_same_seed_same_samples_other_seed_other_samples():
    first = stochastic.generate(MODEL, 6.5, 20.0e3, 760.0, 7)
    again = stochastic.generate(MODEL, 6.5, 20.0e3, 760.0, 7)
    other = stochastic.generate(MODEL, 6.5, 20.0e3, 760.0, 8)
    assert first.samples.tobytes() == again.samples.tobytes()
    assert len(other.samples) == len(first.samples)
    assert not np.allclose(first.samples, other.samples)
    assert first.name == "boore2003 M6.5 R20km Vs30 760 seed 7"
    for text in ("Boore (2003)", "Campbell (2003)", "seed 7", "Vs30 760", "no vertical"):
        assert text in first.provenance
    samples = first.samples
    assert samples.dtype == np.float64 and samples.flags.c_contiguous
    assert not samples.flags.writeable


def test_motion_starts_and_ends_at_rest_and_duration_adds_quiet():
    record = stochastic.generate(MODEL, 7.5, 10.0e3, 760.0, 3)
    one_second = round(1.0 / record.dt)
    assert np.max(np.abs(record.samples[:one_second])) < 1e-3 * record.pga
    assert np.max(np.abs(record.samples[-one_second:])) < 1e-3 * record.pga
    longer = stochastic.generate(MODEL, 7.5, 10.0e3, 760.0, 3, duration=record.duration + 20.0)
    assert longer.duration == pytest.approx(record.duration + 20.0)
    assert longer.pga == pytest.approx(record.pga, rel=0.05)
    fine = stochastic.generate(MODEL, 7.5, 10.0e3, 760.0, 3, dt=0.005)
    assert fine.dt == 0.005 and fine.duration == pytest.approx(record.duration, abs=0.01)


@pytest.mark.parametrize("change, argument", [
    ({"model": "atkinson"}, "model"),
    ({"magnitude": 3.9}, "magnitude"), ({"magnitude": 8.6}, "magnitude"),
    ({"magnitude": float("nan")}, "magnitude"), ({"magnitude": "6"}, "magnitude"),
    ({"distance": 0.0}, "distance"), ({"distance": -5.0}, "distance"),
    ({"distance": 300.001e3}, "distance"),
    ({"vs30": 149.0}, "vs30"), ({"vs30": 2001.0}, "vs30"),
    ({"seed": -1}, "seed"), ({"seed": 1.5}, "seed"), ({"seed": True}, "seed"),
    ({"seed": "3"}, "seed"),
    ({"dt": 0.0}, "dt"), ({"dt": 0.05}, "dt"),
    ({"duration": 5.0}, "duration"),
])
def test_invalid_arguments_raise_value_error_naming_them(change, argument):
    arguments = {"model": MODEL, "magnitude": 6.5, "distance": 20.0e3, "vs30": 760.0,
                 "seed": 1} | change
    options = {key: arguments.pop(key) for key in ("dt", "duration") if key in arguments}
    with pytest.raises(ValueError, match=f"`{argument}`"):
        stochastic.generate(*arguments.values(), **options)


def test_largest_and_smallest_scenarios_are_accepted():
    for magnitude, distance, vs30 in ((4.0, 1.0, 150.0), (8.5, 300.0e3, 2000.0)):
        record = stochastic.generate(MODEL, magnitude, distance, vs30, 0)
        assert np.all(np.isfinite(record.samples)) and record.pga > 0.0


@pytest.mark.parametrize("magnitude, distance, vs30", [
    (5.5, 10.0e3, 760.0), (6.5, 20.0e3, 760.0), (7.5, 50.0e3, 760.0), (7.0, 20.0e3, 360.0)])
def test_median_pga_and_pgv_of_30_motions_within_one_sigma_of_bssa14(magnitude, distance, vs30):
    comparison = gmpe_check.compare(magnitude, distance, vs30, seeds=30)
    assert abs(comparison.z_pga) <= 1.0, comparison
    assert abs(comparison.z_pgv) <= 1.0, comparison


def test_softer_site_shakes_more_as_bssa14_says():
    rock = gmpe_check.compare(6.5, 20.0e3, 760.0, seeds=20)
    soil = gmpe_check.compare(6.5, 20.0e3, 360.0, seeds=20)
    assert soil.pga > rock.pga and soil.pgv > rock.pgv
    assert soil.pga_bssa14 > rock.pga_bssa14 and soil.pgv_bssa14 > rock.pgv_bssa14


def _median_peaks(magnitude, distance, seeds=20):
    peaks = [measures(r.samples, r.dt) for r in (
        stochastic.generate(MODEL, magnitude, distance, 760.0, seed) for seed in range(seeds))]
    return (np.exp(np.mean(np.log([p.pga for p in peaks]))),
            np.exp(np.mean(np.log([p.pgv for p in peaks]))))


def test_median_peaks_grow_with_magnitude_and_decay_with_distance():
    by_magnitude = np.array([_median_peaks(m, 20.0e3) for m in gmpe_check.MAGNITUDES])
    by_distance = np.array([_median_peaks(6.5, r) for r in gmpe_check.DISTANCES])
    assert np.all(np.diff(by_magnitude, axis=0) > 0)
    assert np.all(np.diff(by_distance, axis=0) < 0)


def test_bssa14_site_coefficients_match_pygmms_table():
    import pygmm

    table = pygmm.BooreStewartSeyhanAtkinson2014.COEFF
    rows = [int(np.flatnonzero(np.isclose(table.period, t))[0]) for t in crustal.BSSA14_PERIOD]
    assert np.array_equal(table.c[rows], crustal.BSSA14_C)
    assert np.array_equal(table.V_c[rows], crustal.BSSA14_VC)


def test_command_line_json(capsys):
    gmpe_check.main(["--seeds", "1", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert out["seeds"] == 1 and out["generation_s"] > 0.0
    assert len(out["scenarios"]) == (len(gmpe_check.MAGNITUDES) * len(gmpe_check.DISTANCES)
                                     * len(gmpe_check.VS30))


@pytest.mark.slow
def test_every_scenario_of_the_100_seed_table_within_one_sigma_of_bssa14():
    for vs30 in gmpe_check.VS30:
        for magnitude in gmpe_check.MAGNITUDES:
            for distance in gmpe_check.DISTANCES:
                c = gmpe_check.compare(magnitude, distance, vs30, seeds=100)
                assert max(abs(c.z_pga), abs(c.z_pgv)) <= 1.0, c
