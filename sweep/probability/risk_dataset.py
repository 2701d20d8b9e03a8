"""The CF dataset of a risk report, written atomically.

Of a ``risk_report.RiskOutcome``: per body λ_O and P with their intervals or bounds, the
fragility, the disaggregation of λ_O by IM segment, each side of a body with G off the middle;
the hazard curve; the stripes' counts (docs/risk.md, "Formats in and out").  SI units.
"""
import numpy as np

from .. import cf
from .._version import __version__

SEGMENT, LEVEL, STRIPE = "segment", "hazard_level", "stripe"


def _variable(dims, data, units, long_name, **extra):
    return (dims, np.asarray(data), {"units": units, "long_name": long_name, **extra})


def _side_variables(sides, dims):
    """The dataset's variables of :class:`StripeSides`: per stripe and body, the motions that
    overturned the body to each side; per body, each side's angle."""
    return {
        **{f"stripe_overturned_{side}": _variable(
            (STRIPE,) + dims, counts, "1", f"motions that overturned the body to the {side}",
            comment=f"{towards}: overturn_direction {sign}1") for side, counts, towards, sign
           in (("left", sides.left, "-x, about corner 1", "+"),
               ("right", sides.right, "+x, about corner 2", "-"))},
        **{name: _variable(dims, angle, "rad", f"angle at G between the vertical and corner "
                                               f"{corner} of the body",
                           comment="alpha_1 = alpha_2: G in the middle of the base")
           for name, angle, corner in (("alpha_1", sides.alpha_1, "1 (left, -x)"),
                                       ("alpha_2", sides.alpha_2, "2 (right, +x)"))}}


def to_dataset(outcome, history=""):
    """The CF dataset of a risk report: per body λ_O, P in ``years`` with their intervals,
    return period, fragility, the disaggregation of λ_O by IM segment; the hazard curve;
    the stripes' counts."""
    import xarray as xr

    curve, dims, shape = outcome.curve, tuple(outcome.body_dims), outcome.shape
    units = curve.units
    im_name = f"{curve.im} ({units})"
    segments = curve.levels.size
    rows = {name: np.full(shape, np.nan) for name in (
        "annual_rate", "annual_rate_lower", "annual_rate_upper", "probability",
        "probability_lower", "probability_upper", "return_period", "theta", "theta_lower",
        "theta_upper", "beta", "beta_lower", "beta_upper", "share_above", "share_below")}
    contribution = np.full(shape + (segments,), np.nan)
    bounded = np.zeros(shape, dtype=np.int8)
    for index in np.ndindex(*shape):
        r, f = outcome.risks[index], outcome.fits[index]
        if f is not None:
            rows["theta"][index], rows["beta"][index] = f.theta, f.beta
            (rows["theta_lower"][index], rows["theta_upper"][index]) = f.theta_interval
            (rows["beta_lower"][index], rows["beta_upper"][index]) = f.beta_interval
        if r is None:
            continue
        if f is None or not f.identifiable:
            rows["theta"][index], rows["beta"][index] = r.median, r.beta
        rows["annual_rate"][index] = r.annual_rate
        rows["annual_rate_lower"][index], rows["annual_rate_upper"][index] = r.rate_interval
        rows["probability"][index] = r.probability
        rows["probability_lower"][index], rows["probability_upper"][index] = \
            r.probability_interval
        rows["return_period"][index] = r.return_period
        rows["share_above"][index], rows["share_below"][index] = r.share_above, r.share_below
        contribution[index] = r.contributions
        if r.bound is not None:  # the one-sided bounds only, in *_upper
            bounded[index] = 1
            for name in ("annual_rate", "probability", "return_period"):
                rows[name][index] = np.nan
    years = f"{outcome.years:g} years"
    data = {
        "annual_rate": _variable(dims, rows["annual_rate"], "yr-1",
                                 "annual rate of overturning",
                                 comment="integral of P(overturn | im) |d lambda/d im| on the "
                                         "hazard curve (log-log interpolation)"),
        "annual_rate_lower": _variable(dims, rows["annual_rate_lower"], "yr-1",
                                       "lower confidence bound of annual_rate"),
        "annual_rate_upper": _variable(dims, rows["annual_rate_upper"], "yr-1",
                                       "upper confidence bound of annual_rate"),
        "probability": _variable(dims, rows["probability"], "1",
                                 f"probability of overturning in {years}",
                                 comment="1 - exp(-annual_rate years) (Poisson)"),
        "probability_lower": _variable(dims, rows["probability_lower"], "1",
                                       "lower confidence bound of probability"),
        "probability_upper": _variable(dims, rows["probability_upper"], "1",
                                       "upper confidence bound of probability"),
        "return_period": _variable(dims, rows["return_period"], "yr",
                                   "mean return period of overturning"),
        "theta": _variable(dims, rows["theta"], units, f"{im_name}: median of the fragility"),
        "theta_lower": _variable(dims, rows["theta_lower"], units, "lower bound of theta"),
        "theta_upper": _variable(dims, rows["theta_upper"], units, "upper bound of theta"),
        "beta": _variable(dims, rows["beta"], "1", "dispersion of the fragility"),
        "beta_lower": _variable(dims, rows["beta_lower"], "1", "lower bound of beta"),
        "beta_upper": _variable(dims, rows["beta_upper"], "1", "upper bound of beta"),
        "share_above": _variable(dims, rows["share_above"], "1",
                                 "share of annual_rate from shaking above the curve's last "
                                 "level", comment="included: fragility at the last level "
                                                  "times its rate"),
        "share_below": _variable(dims, rows["share_below"], "1",
                                 "estimated share from shaking below the curve's first level",
                                 comment="not included: the first segment's power law "
                                         "extended to 0"),
        "contribution": _variable(dims + (SEGMENT,), contribution, "yr-1",
                                  "annual rate of overturning by IM segment",
                                  comment="the disaggregation of annual_rate: segment i runs "
                                          "from segment_lower to segment_upper; the last is "
                                          "above the curve"),
        "hazard_rate": _variable((LEVEL,), curve.rates, "yr-1",
                                 f"annual rate of exceedance of {curve.im}"),
        "none_overturned": _variable(
            dims, bounded, "1", "no motion overturned the body at any stripe",
            flag_values=np.array([0, 1], dtype=np.int8), flag_meanings="estimated bounded",
            comment="bounded: annual_rate, probability and return_period are not estimated; "
                    f"annual_rate_upper and probability_upper are one-sided "
                    f"{100 * outcome.confidence:g} % bounds (0 of n at each stripe), "
                    "contribution that of the bound"),
    }
    coords = {d: (d, outcome.body_coords[d][0], outcome.body_coords[d][1]) for d in dims}
    coords[LEVEL] = (LEVEL, curve.levels, {"units": units, "long_name": f"{im_name} level"})
    coords["segment_lower"] = (SEGMENT, curve.levels,
                               {"units": units, "long_name": "lower IM of the segment"})
    coords["segment_upper"] = (SEGMENT, np.append(curve.levels[1:], np.inf),
                               {"units": units, "long_name": "upper IM of the segment"})
    if outcome.stripes is not None:
        coords[STRIPE] = (STRIPE, [s.level for s in outcome.stripes],
                          {"units": units, "long_name": f"{im_name} of the stripe"})
        data["stripe_overturned"] = _variable((STRIPE,) + dims, outcome.k, "1",
                                              "motions that overturned the body")
        data["stripe_motions"] = _variable((STRIPE,) + dims, outcome.n, "1",
                                           "motions simulated (failed left out)")
        if outcome.sides is not None:
            data.update(_side_variables(outcome.sides, dims))
        if outcome.disaggregation is not None:
            d = outcome.disaggregation
            data["stripe_mean_magnitude"] = _variable(
                (STRIPE,), d.mean_magnitude, "1", "mean magnitude of the disaggregation")
            data["stripe_mean_distance"] = _variable(
                (STRIPE,), d.mean_distance, "m", "mean Rrup of the disaggregation")
    demands = outcome.demands()
    if demands is not None:
        values = np.array([np.nan if d is None or d.displacement is None else d.displacement
                           for d in demands.flat]).reshape(demands.shape)
        data["isolator_demand"] = _variable(
            dims, values, "m",
            f"isolator displacement exceeded with probability target_probability in {years}",
            comment="lambda_D(d) = integral of P(D > d | im) |d lambda| (lognormal per stripe "
                    "of isolator_max_displacement, interpolated in ln im)")
    ds = xr.Dataset(data, coords={k: xr.Variable(*v) for k, v in coords.items()})
    ds.attrs.update({
        "Conventions": cf.CONVENTIONS, "title": f"risk of overturning: {outcome.name}",
        "source": f"{cf.PACKAGE} {__version__} (sweep.risk)",
        "hazard": curve.source, "intensity_measure": curve.im, "years": outcome.years,
        **({"placement": outcome.placement} if outcome.placement else {}),
        "confidence": outcome.confidence,
        "history": history,
        "references": "Cornell et al. (2002) J. Struct. Eng. 128; Jalayer & Cornell (2009) "
                      "EESD 38; Baker (2015) Earthquake Spectra 31; Bazzurro & Cornell (1999)"
                      " BSSA 89"})
    if outcome.target is not None:
        ds.attrs["target_probability"] = outcome.target
    if outcome.warnings:
        ds.attrs["warnings"] = "\n".join(outcome.warnings)
    return ds


def write_dataset(ds, path):
    """Write ``ds`` to ``path`` atomically (``netcdf.write_netcdf``: a temporary name,
    then ``os.replace``)."""
    from ..netcdf import write_netcdf

    return write_netcdf(ds, path)
