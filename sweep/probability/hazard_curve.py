"""Hazard curves: the mean annual rate λ(x) at which a site's intensity measure exceeds x.

A :class:`HazardCurve` holds an intensity measure (``pga``, ``pgv`` or ``sa(T)``), its levels
in SI units (m/s² for accelerations, m/s for PGV) and their annual rates of exceedance; it is
read from OpenQuake, USGS and two-column files by ``sweep.probability.hazard_files``, or
computed from a source model (``sweep.probability.source_hazard``).

Probabilities of exceedance become rates by the Poisson model, λ = −ln(1 − P)/T
(:func:`rate_from_poe`; docs/risk.md).  Between levels the curve is a power law (straight in
log–log), λ(x) = λ_i (x/x_i)^(−k_i) (:meth:`HazardCurve.rate`).  A curve that is not one (levels
not increasing, rates rising or not positive) raises :class:`HazardFileError`, one line.
"""
from dataclasses import dataclass, field

import numpy as np

from ..io.imt import SI_UNITS, im_dimension

class HazardFileError(ValueError):
    """A hazard curve that cannot be used: ``str`` says where and why, on one line.

    ``key`` names the setting the problem is about when a caller may give it (``im``,
    ``units``, ``kind``, ``investigation_time``: a given value that contradicts the file, or
    one that neither states; ``site``: a row the file has not); None for the file itself.
    """

    def __init__(self, message, key=None):
        super().__init__(message)
        self.key = key


def rate_from_poe(poe, investigation_time):
    """Annual rate λ = −ln(1 − P)/T of a probability of exceedance P in T years (Poisson)."""
    return -np.log1p(-np.asarray(poe, dtype=float)) / investigation_time


def poe_from_rate(rate, investigation_time):
    """Probability P = 1 − exp(−λ T) of at least one exceedance in T years (Poisson)."""
    return -np.expm1(-np.asarray(rate, dtype=float) * investigation_time)


@dataclass(frozen=True)
class HazardCurve:
    """λ(x) of one intensity measure at one site.

    Attributes
    ----------
    im : str
        ``pga``, ``pgv`` or ``sa(T)``.
    levels : ndarray, shape (n,)
        Increasing IM levels [m/s² or m/s].
    rates : ndarray, shape (n,)
        Annual rates of exceedance [1/yr], non-increasing, positive.
    source : str
        Where the curve came from (a file, or a source model).
    source_model : object, optional
        The ``source_hazard.SourceModel`` of a computed curve, which disaggregates it (None
        when read from a file).
    """

    im: str
    levels: np.ndarray
    rates: np.ndarray
    source: str = ""
    source_model: object = field(default=None, compare=False, repr=False)

    def __post_init__(self):
        levels = np.asarray(self.levels, dtype=float)
        rates = np.asarray(self.rates, dtype=float)
        object.__setattr__(self, "levels", levels)
        object.__setattr__(self, "rates", rates)
        problem = curve_problem(levels, rates)
        if problem:
            raise HazardFileError(f"{self.source or 'hazard curve'}: {problem}")

    @property
    def units(self):
        return SI_UNITS[im_dimension(self.im)]

    def slopes(self):
        """k_i = −Δ ln λ / Δ ln x of each segment between levels, shape (n − 1,)."""
        return -np.diff(np.log(self.rates)) / np.diff(np.log(self.levels))

    def rate(self, x):
        """λ(x) by log–log interpolation; NaN outside [levels[0], levels[-1]]."""
        x = np.asarray(x, dtype=float)
        with np.errstate(divide="ignore"):
            log_rate = np.interp(np.log(x), np.log(self.levels), np.log(self.rates),
                                 left=np.nan, right=np.nan)
        return np.exp(log_rate)

    def level_at_rate(self, rate):
        """The level x with λ(x) = ``rate`` (log–log interpolation); NaN outside the curve."""
        log_rate = np.log(np.asarray(rate, dtype=float))
        order = np.argsort(np.log(self.rates))  # np.interp wants increasing abscissae
        return np.exp(np.interp(log_rate, np.log(self.rates)[order], np.log(self.levels)[order],
                                left=np.nan, right=np.nan))


def curve_problem(levels, rates):
    """Why ``levels`` and ``rates`` are not a hazard curve, or None."""
    if levels.ndim != 1 or levels.shape != rates.shape:
        return "levels and rates must be two lists of equal length"
    if levels.size < 2:
        return "a hazard curve needs at least 2 levels"
    if not (np.all(np.isfinite(levels)) and np.all(np.isfinite(rates))):
        return "levels and rates must be finite numbers"
    if np.any(levels <= 0):
        return f"levels must be positive (got {levels[levels <= 0][0]:g})"
    if np.any(np.diff(levels) <= 0):
        return "levels must increase"
    if np.any(rates <= 0):
        return (f"rates of exceedance must be positive (got {rates[rates <= 0][0]:g} at level "
                f"{levels[rates <= 0][0]:g}); drop the levels never exceeded")
    rising = np.flatnonzero(np.diff(rates) > 0)
    if rising.size:
        i = rising[0]
        return (f"the rate of exceedance rises from {rates[i]:g} at {levels[i]:g} to "
                f"{rates[i + 1]:g} at {levels[i + 1]:g}: a hazard curve never increases")
    return None
