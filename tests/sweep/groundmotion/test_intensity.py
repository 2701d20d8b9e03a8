"""Intensity measures against closed forms and the tabulated peaks of El Centro 1940."""
import math

import numpy as np
import pytest

from sweep.groundmotion import applied
from sweep.groundmotion.intensity import G, measures
from sweep.io.records import load_record


def _tapered_sine(A, f, seconds, dt=0.005):
    """A sine of acceleration amplitude A at f Hz, faded in and out over 2 s (cosine tapers),
    so that it starts and ends at rest like a recorded motion."""
    t = np.arange(0.0, seconds, dt)
    taper = np.clip(np.minimum(t, seconds - t) / 2.0, 0.0, 1.0)
    envelope = 0.5 - 0.5 * np.cos(np.pi * taper)
    return A * envelope * np.sin(2 * np.pi * f * t), dt


def test_sine_peaks_and_arias_against_closed_forms():
    A, f, seconds = 2.0, 2.0, 40.0
    samples, dt = _tapered_sine(A, f, seconds)
    m = measures(samples, dt)
    omega = 2 * np.pi * f
    assert m.pga == pytest.approx(A, rel=1e-3)
    assert m.pgv == pytest.approx(A / omega, rel=0.01)
    # the displacement keeps a slow residual of the tapers' velocity offset, which the
    # 0.1 Hz high-pass leaves partly in place (measured: +5 %)
    assert m.pgd == pytest.approx(A / omega ** 2, rel=0.08)
    # Arias: pi/(2g) * integral of a^2: A^2/2 per second at full amplitude; a taper of 2 s
    # has a mean squared envelope of 3/8, so each adds 2 s * 3/8 * A^2/2
    expected = math.pi / (2 * G) * A ** 2 * (0.5 * (seconds - 4.0) + 2 * 2.0 * 3.0 / 8.0 / 2)
    assert m.arias == pytest.approx(expected, rel=0.01)
    # energy per second (in A^2) 1/2 at full amplitude, 3/8 in all over each taper: 5 % of
    # it is reached 2 s + (0.05 * total - 3/8) / (1/2) after the start, 95 % as long before
    # the end
    total = 0.5 * (seconds - 4.0) + 0.75
    t5 = 2.0 + (0.05 * total - 0.375) / 0.5
    assert m.d5_95 == pytest.approx(seconds - 2 * t5, abs=2 * dt)


def test_baseline_correction_removes_the_drift_of_an_offset():
    """A constant offset of 1 gal over 40 s integrates to 0.4 m/s and 8 m without a correction;
    the high-pass leaves the sine's own velocity."""
    samples, dt = _tapered_sine(2.0, 2.0, 40.0)
    shifted = measures(samples + 0.01, dt)
    assert shifted.pgv == pytest.approx(2.0 / (4 * np.pi), rel=0.05)
    assert shifted.pgd < 0.05


@pytest.mark.parametrize("name, pgv, pgd", [
    ("elcentro1940_ns", 0.3232, 0.1086),   # Table 5 of the paper: 32.32 cm/s, 10.86 cm
    ("elcentro1940_ew", 0.3647, 0.1978),   # 36.47 cm/s, 19.78 cm
])
def test_el_centro_against_the_tabulated_peaks(name, pgv, pgd):
    """The corrected peaks lie near the tabulated ones (other processing: within 10 % for
    PGV, 20 % for PGD), where the raw integration is off by 18 % and a factor 23."""
    rec = load_record(name)
    m = rec.intensity
    assert m.pga == pytest.approx(np.max(np.abs(rec.samples)))
    assert m.pgv == pytest.approx(pgv, rel=0.10)
    assert m.pgd == pytest.approx(pgd, rel=0.20)
    assert rec.intensity is m  # computed once per record


def test_zero_motion():
    m = measures(np.zeros(100), 0.01)
    assert (m.pga, m.pgv, m.pgd, m.arias) == (0.0, 0.0, 0.0, 0.0)


@pytest.mark.parametrize("hold, amplitude, expect", [
    # 1 to 4 Hz: omega from 2 pi to 8 pi
    ("acceleration", 2.0, (2.0, 2.0 / (2 * np.pi), 2.0 / (2 * np.pi) ** 2)),
    ("velocity", 0.1, (0.1 * 8 * np.pi, 0.1, 0.1 / (2 * np.pi))),
    ("displacement", 0.01, (0.01 * (8 * np.pi) ** 2, 0.01 * 8 * np.pi, 0.01)),
])
def test_sweep_peaks_are_the_largest_over_its_frequencies(hold, amplitude, expect):
    ground = {"kind": "sweep", "hold": hold, "amplitude": amplitude, "f_start": 4.0,
              "f_stop": 1.0}
    np.testing.assert_allclose(applied.peaks(ground)[:3], expect, rtol=1e-12)


def test_pulse_velocity_is_its_area():
    rect = applied.peaks({"kind": "pulse", "shape": "rectangular", "amplitude": -3.0,
                          "duration": 0.2})
    tri = applied.peaks({"kind": "pulse", "shape": "triangular", "amplitude": 3.0,
                         "duration": 0.2})
    assert rect.pga == 3.0 and rect.pgv == pytest.approx(0.6) and math.isnan(rect.pgd)
    assert tri.pgv == pytest.approx(0.3)
