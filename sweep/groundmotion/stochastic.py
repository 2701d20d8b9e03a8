"""Synthetic horizontal accelerograms for an earthquake scenario: Boore's stochastic method.

The point-source method of Boore (2003, Pure Appl. Geophys. 160, 635-676; program SMSIM):
Gaussian white noise, shaped in time by a Saragoni-Hart window whose length is the source
duration 1/f0 plus a path duration, is transformed to the frequency domain, normalized so that
its mean square amplitude spectrum is unity, multiplied by the target Fourier amplitude spectrum
of acceleration (Brune omega-squared source x geometric spreading x anelastic attenuation x
crustal amplification x kappa0 decay) and transformed back.  The parameters are the western
North America set of :mod:`sweep.groundmotion.crustal` (Campbell 2003).

One horizontal component in a random direction (radiation pattern 0.55, partition 1/sqrt(2)).
The method has no vertical component and none is produced.  SI units inside: distance in m
(the closest distance to the rupture, Rrup), Vs30 in m/s, acceleration in m/s^2.

Validity.  The effective point-source distance R = sqrt(Rrup^2 + h(M)^2) (Yenier & Atkinson
2015) stands for the finite fault: it saturates the motion near large ruptures but carries no
directivity pulse, hanging-wall effect or fling, so within about one fault length of an
M >= 7 rupture the motions are averages, not near-fault motions.  Checked against BSSA14
(``python -m sweep.groundmotion.gmpe_check``) for M 5.5-7.5 and Rrup 10-50 km; the inputs
accepted (M 4-8.5, Rrup up to 300 km, Vs30 150-2000 m/s) extend beyond that check.  The site
term is linear: on soft sites (Vs30 < 300 m/s) under strong shaking it overestimates the high
frequencies, as soil nonlinearity is left out.

References
----------
Boore, D. M. (2003). Simulation of ground motion using the stochastic method. Pure Appl.
Geophys. 160, 635-676.
Brune, J. N. (1970). Tectonic stress and the spectra of seismic shear waves from earthquakes.
J. Geophys. Res. 75, 4997-5009.
Hanks, T. C. & Kanamori, H. (1979). A moment magnitude scale. J. Geophys. Res. 84, 2348-2350.
Campbell, K. W. (2003). Prediction of strong ground motion using the hybrid empirical method
and its use in the development of ground-motion (attenuation) relations in eastern North
America. Bull. Seismol. Soc. Am. 93, 1012-1033.
Yenier, E. & Atkinson, G. M. (2015). Regionally adjustable generic ground-motion prediction
equation based on equivalent point-source simulations. Bull. Seismol. Soc. Am. 105, 1989-2009.
Boore, D. M., Stewart, J. P., Seyhan, E. & Atkinson, G. M. (2014). NGA-West2 equations for
predicting PGA, PGV, and 5% damped PSA for shallow crustal earthquakes. Earthq. Spectra 30,
1057-1085.
"""
import math
from collections import namedtuple
from numbers import Integral, Real

import numpy as np

from . import crustal
from .record import Record

MODELS = ("boore2003",)
"""Names accepted by :func:`generate`."""
_PARAMETERS = {"boore2003": crustal.WNA}

MAGNITUDE_RANGE = (4.0, 8.5)
MAX_DISTANCE = 300.0e3  # m
VS30_RANGE = (150.0, 2000.0)  # m/s
# Largest sample step: a Nyquist frequency of 25 Hz, where kappa0 = 0.04 s has already cut the
# spectrum to exp(-pi 0.04 25) = 4 %.
MAX_DT = 0.02

# Saragoni-Hart window (Boore 2003): peak 1 at WINDOW_EPS t_eta, WINDOW_ETA at
# t_eta = WINDOW_F_TGM T_gm, with T_gm the excitation duration.
WINDOW_EPS = 0.2
WINDOW_ETA = 0.05
WINDOW_F_TGM = 2.0
# The window is cut at WINDOW_EXTENT t_eta, where it has fallen to 2e-4 of its peak.
WINDOW_EXTENT = 2.0
# Quiet before and after the window: the Brune pulse exp(-2 pi f0 |t|) spreads the noise over
# about 1/(2 pi f0) either side of it; 1/f0 leaves 0.2 % at the ends.  At least MIN_QUIET.
MIN_QUIET = 2.0  # s

Scenario = namedtuple("Scenario", "moment corner_frequency pseudo_depth effective_distance "
                                  "duration")
Scenario.__doc__ = """Derived quantities of an earthquake scenario, SI units: seismic moment
[N m], Brune corner frequency [Hz], finite-fault pseudo-depth h and effective point-source
distance [m], excitation duration T_gm = 1/f0 + path duration [s]."""


def seismic_moment(magnitude):
    """Seismic moment [N m] of a moment magnitude (Hanks & Kanamori 1979, as in Boore 2003:
    M0 = 10^(1.5 M + 16.05) dyne-cm)."""
    return 10.0 ** (1.5 * magnitude + 16.05) * 1.0e-7


def corner_frequency(moment, stress, beta):
    """Brune corner frequency [Hz] of a moment [N m], stress parameter [Pa] and shear-wave
    speed [m/s]: f0 = 4.906e6 beta (stress/M0)^(1/3) with beta in km/s, stress in bar and M0 in
    dyne-cm (Boore 2003, from Brune 1970)."""
    return 4.906e6 * (beta * 1.0e-3) * ((stress * 1.0e-5) / (moment * 1.0e7)) ** (1.0 / 3.0)


def pseudo_depth(magnitude, parameters=crustal.WNA):
    """Finite-fault factor h [m]: log10(h / 1 km) = a + b M (Yenier & Atkinson 2015, eq. 6)."""
    return 1.0e3 * 10.0 ** (parameters.finite_fault_a + parameters.finite_fault_b * magnitude)


def scenario(magnitude, distance, parameters=crustal.WNA):
    """:class:`Scenario` of a moment magnitude at a rupture distance ``distance`` [m].

    The effective distance sqrt(Rrup^2 + h^2) (Yenier & Atkinson 2015, eq. 5) enters the
    geometric spreading, the anelastic attenuation and the path duration.
    """
    moment = seismic_moment(magnitude)
    f0 = corner_frequency(moment, parameters.stress, parameters.beta)
    h = pseudo_depth(magnitude, parameters)
    r = math.hypot(distance, h)
    return Scenario(moment, f0, h, r, 1.0 / f0 + parameters.duration_slope * r)


def geometric_spreading(r, parameters=crustal.WNA):
    """Z(R): (R0/R)^n1 up to the hinge R1, Z(R1) (R1/R)^n2 beyond (Boore 2003)."""
    p = parameters
    r1 = p.spreading_hinge
    if r <= r1:
        return (p.reference_distance / r) ** p.spreading_near
    return (p.reference_distance / r1) ** p.spreading_near * (r1 / r) ** p.spreading_far


def site_amplification(f, vs30, parameters=crustal.WNA):
    """Crustal amplification of the reference site, times the BSSA14 linear site term from the
    reference Vs30 to ``vs30``.

    The reference amplification is interpolated linearly in log-log and held constant outside
    its table.  The site term exp(c(T) [ln min(Vs30, V_c(T)) - ln Vs30_ref]) is the ratio of
    BSSA14's linear terms, a response-spectral term applied here to the Fourier amplitude at
    f = 1/T (c and V_c interpolated in ln T, held at 0.01 s above 100 Hz and at 10 s below
    0.1 Hz).

    Parameters
    ----------
    f : ndarray
        Frequencies [Hz], non-negative.
    vs30 : float
        Time-averaged shear-wave speed of the upper 30 m [m/s].
    """
    p = parameters
    table_f = np.log(p.amplification_frequency)
    f_table = np.clip(f, p.amplification_frequency[0], p.amplification_frequency[-1])
    amplification = np.exp(np.interp(np.log(f_table), table_f, np.log(p.amplification)))
    period = np.log(crustal.BSSA14_PERIOD)
    ln_t = -np.log(np.clip(f, 1.0 / crustal.BSSA14_PERIOD[-1], 1.0 / crustal.BSSA14_PERIOD[0]))
    c = np.interp(ln_t, period, crustal.BSSA14_C)
    v_c = np.interp(ln_t, period, crustal.BSSA14_VC)
    return amplification * np.exp(c * (np.log(np.minimum(vs30, v_c)) - math.log(p.reference_vs30)))


def fourier_amplitude(f, magnitude, distance, vs30, parameters=crustal.WNA):
    """Target Fourier amplitude spectrum of one horizontal acceleration component [m/s].

    A(f) = (2 pi f)^2 C M0 / (1 + (f/f0)^2) Z(R) exp(-pi f R / (Q(f) beta)) Amp(f) exp(-pi
    kappa0 f), with C = radiation partition free_surface / (4 pi rho beta^3 R0) (Boore 2003),
    R the effective distance and Amp the site amplification (:func:`site_amplification`).

    Parameters
    ----------
    f : ndarray
        Frequencies [Hz], non-negative.
    magnitude : float
        Moment magnitude.
    distance : float
        Closest distance to the rupture [m].
    vs30 : float
        [m/s].
    """
    p = parameters
    s = scenario(magnitude, distance, p)
    f = np.asarray(f, dtype=np.float64)
    constant = (p.radiation * p.partition * p.free_surface
                / (4.0 * math.pi * p.rho * p.beta ** 3 * p.reference_distance))
    displacement = constant * s.moment / (1.0 + (f / s.corner_frequency) ** 2)
    # f / Q(f) = f^(1 - q_exponent) / q0, finite at f = 0
    anelastic = np.exp(-math.pi * f ** (1.0 - p.q_exponent) * s.effective_distance
                       / (p.q0 * p.beta))
    site = site_amplification(f, vs30, p) * np.exp(-math.pi * p.kappa0 * f)
    return ((2.0 * math.pi * f) ** 2 * displacement
            * geometric_spreading(s.effective_distance, p) * anelastic * site)


def saragoni_hart(t, t_eta):
    """Saragoni-Hart window w(t) = a (t/t_eta)^b exp(-c t/t_eta), peak 1 at WINDOW_EPS t_eta
    and WINDOW_ETA at t_eta: b = -eps ln(eta) / (1 + eps (ln eps - 1)), c = b/eps,
    a = (e/eps)^b (Boore 2003)."""
    eps, eta = WINDOW_EPS, WINDOW_ETA
    b = -eps * math.log(eta) / (1.0 + eps * (math.log(eps) - 1.0))
    c = b / eps
    x = np.asarray(t, dtype=np.float64) / t_eta
    return (math.e / eps) ** b * x ** b * np.exp(-c * x)


def _real(name, value):
    if isinstance(value, bool) or not isinstance(value, Real) or not math.isfinite(value):
        raise ValueError(f"`{name}` must be a finite number, got {value!r}")
    return float(value)


def _validated(model, magnitude, distance, vs30, seed, dt, duration):
    """The parameter set of ``model`` and the arguments as floats, or a ValueError."""
    if model not in _PARAMETERS:
        raise ValueError(f"unknown `model` {model!r}; models: {', '.join(MODELS)}")
    magnitude, distance, vs30, dt = (_real(name, value) for name, value in
                                     (("magnitude", magnitude), ("distance", distance),
                                      ("vs30", vs30), ("dt", dt)))
    if not MAGNITUDE_RANGE[0] <= magnitude <= MAGNITUDE_RANGE[1]:
        raise ValueError(f"`magnitude` {magnitude:g} is outside [{MAGNITUDE_RANGE[0]:g}, "
                         f"{MAGNITUDE_RANGE[1]:g}]")
    if not 0.0 < distance <= MAX_DISTANCE:
        raise ValueError(f"`distance` {distance:g} m is outside (0, {MAX_DISTANCE:g}] m "
                         f"(the closest distance to the rupture, in metres)")
    if not VS30_RANGE[0] <= vs30 <= VS30_RANGE[1]:
        raise ValueError(f"`vs30` {vs30:g} m/s is outside [{VS30_RANGE[0]:g}, "
                         f"{VS30_RANGE[1]:g}] m/s")
    if isinstance(seed, bool) or not isinstance(seed, Integral) or seed < 0:
        raise ValueError(f"`seed` must be a non-negative integer, got {seed!r}")
    if not 0.0 < dt <= MAX_DT:
        raise ValueError(f"`dt` {dt:g} s is outside (0, {MAX_DT:g}] s")
    if duration is not None:
        duration = _real("duration", duration)
    return _PARAMETERS[model], magnitude, distance, vs30, dt, duration


def generate(model, magnitude, distance, vs30, seed, *, dt=0.01, duration=None):
    """One horizontal accelerogram of Boore's (2003) stochastic method for a scenario.

    Parameters
    ----------
    model : str
        One of :data:`MODELS`.
    magnitude : float
        Moment magnitude, 4 to 8.5.
    distance : float
        Closest distance to the rupture Rrup [m], up to 300 km.
    vs30 : float
        Time-averaged shear-wave speed of the upper 30 m [m/s], 150 to 2000.
    seed : int
        Seed of the noise (``numpy.random.default_rng``): the same arguments give the same
        samples bit for bit.
    dt : float
        Sample step [s], at most :data:`MAX_DT`.
    duration : float, optional
        Length of the record [s], at least the window plus the quiet before and after it; the
        extra time is quiet at the end.  By default: max(MIN_QUIET, 1/f0) of quiet, the window
        of WINDOW_EXTENT WINDOW_F_TGM T_gm seconds and the same quiet again, lengthened by at
        most a few samples per hundred to a sample count whose FFT is fast.

    Returns
    -------
    Record
        Acceleration [m/s^2], read-only; the provenance states the model, its parameters,
        the scenario and the seed.

    Raises
    ------
    ValueError
        An unknown model, an argument outside its range, a seed that is not a non-negative
        integer, or a duration shorter than the motion.
    """
    p, magnitude, distance, vs30, dt, duration = _validated(model, magnitude, distance, vs30,
                                                            seed, dt, duration)
    s = scenario(magnitude, distance, p)
    t_eta = WINDOW_F_TGM * s.duration
    quiet = max(MIN_QUIET, 1.0 / s.corner_frequency)
    needed = 2.0 * quiet + WINDOW_EXTENT * t_eta
    explicit_duration = duration is not None
    if not explicit_duration:
        duration = needed
    elif duration < needed:
        raise ValueError(f"`duration` {duration:g} s is shorter than this motion: {needed:.1f} s "
                         f"(window {WINDOW_EXTENT * t_eta:.1f} s and {quiet:.1f} s of quiet "
                         f"on each side)")
    n = math.ceil(duration / dt) + 1
    if not explicit_duration:  # a 5-smooth length: the FFTs of a prime length are 10x slower
        from scipy.fft import next_fast_len
        n = next_fast_len(n, real=True)
    start = round(quiet / dt)
    window = saragoni_hart(dt * np.arange(math.ceil(WINDOW_EXTENT * t_eta / dt)), t_eta)

    noise = np.zeros(n)
    noise[start:start + len(window)] = np.random.default_rng(seed).standard_normal(len(window))
    noise[start:start + len(window)] *= window
    # Boore (2003): divide the noise spectrum by the square root of its mean square amplitude
    # spectrum.  By Parseval, the mean over the n DFT bins of |dt DFT|^2 is
    # dt^2 sum(noise^2).
    spectrum = np.fft.rfft(noise) / math.sqrt(np.dot(noise, noise))
    f = np.fft.rfftfreq(n, dt)
    samples = np.fft.irfft(spectrum * fourier_amplitude(f, magnitude, distance, vs30, p), n) / dt
    samples = np.ascontiguousarray(samples, dtype=np.float64)
    samples.flags.writeable = False

    name = f"{model} M{magnitude:g} R{distance / 1e3:g}km Vs30 {vs30:g} seed {seed}"
    provenance = (
        f"synthetic: stochastic point-source method of Boore (2003), parameters of {p.name} "
        f"(beta {p.beta / 1e3:g} km/s, rho {p.rho / 1e3:g} g/cm^3, stress {p.stress / 1e5:g} "
        f"bar, Q = {p.q0:g} f^{p.q_exponent:g}, spreading 1/R^{p.spreading_near:g} to "
        f"{p.spreading_hinge / 1e3:g} km then 1/R^{p.spreading_far:g}, kappa0 {p.kappa0:g} s, "
        f"Boore & Joyner (1997) generic rock, BSSA14 linear site term from Vs30 "
        f"{p.reference_vs30:g} m/s, "
        f"path duration {p.duration_slope * 1e3:g} s/km); M {magnitude:g}, Rrup "
        f"{distance / 1e3:g} km, h {s.pseudo_depth / 1e3:.2f} km (Yenier & Atkinson 2015), "
        f"effective distance {s.effective_distance / 1e3:.2f} km, Vs30 {vs30:g} m/s, "
        f"f0 {s.corner_frequency:.4g} Hz, T_gm {s.duration:.2f} s, Saragoni-Hart window "
        f"(eps {WINDOW_EPS:g}, eta {WINDOW_ETA:g}, t_eta {t_eta:.2f} s) starting at "
        f"{start * dt:.2f} s, seed {seed} (numpy default_rng), dt {dt:g} s; one horizontal "
        f"component, no vertical")
    return Record(name, dt, samples, provenance)
