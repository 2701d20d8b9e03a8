"""Intensity measures of a floor acceleration history (docs/probability.md section 2).

PGA is read from the acceleration as it is applied.  PGV and PGD are peaks of the velocity and
displacement integrated (trapezoidal rule) after a baseline correction: a zero-phase 4th-order
Butterworth high-pass at ``HIGHPASS_HZ`` (the gain of the filter run forward and backward),
applied to the record padded with zeros on both sides, the acausal filter of the PEER NGA
processing (Boore & Bommer 2005, Soil Dyn. Earthq. Eng. 25; Ancheta et al. 2014, Earthquake
Spectra 30).  Without it a
record that does not start at rest drifts: El Centro 1940 NS integrates to 38.1 cm/s and
2.5 m; with it, 34.4 cm/s and 8.9 cm (tabulated: 32.3 cm/s and 10.9 cm), EW 37.0 cm/s and
19.4 cm (36.5 cm/s, 19.8 cm).  The significant
duration is the 5-95 % Arias-intensity duration (Trifunac & Brady 1975, BSSA 65).
"""
from dataclasses import dataclass

import numpy as np

from ..bodies import G
HIGHPASS_HZ = 0.1  # corner of the baseline high-pass [Hz]
HIGHPASS_ORDER = 4
# Zeros padded on each side: half of Converse & Brady's (1992) 1.5 * order / corner.
PAD_S = 0.75 * HIGHPASS_ORDER / HIGHPASS_HZ


@dataclass(frozen=True)
class Intensity:
    """Intensity measures of one horizontal motion, SI units.

    Attributes
    ----------
    pga : float
        Peak ground acceleration [m/s^2].
    pgv, pgd : float
        Peak ground velocity [m/s] and displacement [m] after the baseline correction.
    arias : float
        Arias intensity pi/(2g) * integral of a^2 dt [m/s].
    d5_95 : float
        Significant duration: time between 5 % and 95 % of the Arias intensity [s].
    """

    pga: float
    pgv: float
    pgd: float
    arias: float
    d5_95: float


def baseline_corrected(samples, dt):
    """The acceleration padded with ``PAD_S`` of zeros on each side (and to a power of two)
    and high-passed with the gain 1/(1 + (f_c/f)^(2n)) of a Butterworth filter run forward
    and backward, zero phase, applied to its Fourier transform: the filter rings into the
    pads, which therefore stay.  numpy only, so that reading a record imports no scipy."""
    pad = np.zeros(int(round(PAD_S / dt)))
    a = np.concatenate([pad, np.asarray(samples, dtype=np.float64), pad])
    n = 1 << int(np.ceil(np.log2(a.size)))
    f = np.fft.rfftfreq(n, dt)
    gain = np.zeros_like(f)
    gain[1:] = 1.0 / (1.0 + (HIGHPASS_HZ / f[1:]) ** (2 * HIGHPASS_ORDER))
    return np.fft.irfft(np.fft.rfft(a, n) * gain, n)[:a.size]


def _cumulative_trapezoid(y, dt):
    return np.concatenate([[0.0], np.cumsum(0.5 * (y[1:] + y[:-1]) * dt)])


def integrated(samples, dt):
    """Velocity and displacement of the baseline-corrected acceleration (pads included),
    starting at rest at the start of the first pad."""
    velocity = _cumulative_trapezoid(baseline_corrected(samples, dt), dt)
    return velocity, _cumulative_trapezoid(velocity, dt)


def measures(samples, dt):
    """:class:`Intensity` of an acceleration history sampled every ``dt`` seconds [m/s^2]."""
    a = np.asarray(samples, dtype=np.float64)
    if a.size < 2 or not np.any(a):
        return Intensity(float(np.max(np.abs(a), initial=0.0)), 0.0, 0.0, 0.0, 0.0)
    velocity, displacement = integrated(a, dt)
    husid = np.cumsum(a * a) * dt
    t5, t95 = np.searchsorted(husid, [0.05 * husid[-1], 0.95 * husid[-1]])
    return Intensity(pga=float(np.max(np.abs(a))), pgv=float(np.max(np.abs(velocity))),
                     pgd=float(np.max(np.abs(displacement))),
                     arias=float(np.pi / (2.0 * G) * husid[-1]), d5_95=float((t95 - t5) * dt))
