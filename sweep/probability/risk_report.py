"""A risk file worked through: hazard → stripes → fragility → risk, for one body or every body
of a grid, and the results as JSON-ready dicts and a CF dataset (docs/risk.md).

:func:`compute` takes a checked risk file (``sweep.io.risk_schema.RiskSpec``) and returns a
:class:`RiskOutcome`; :func:`known` does the same for a hazard curve and a known lognormal
fragility, without simulating.  :func:`body_record` is the JSON of one body (the keys of
docs/design.md §12), :func:`to_dataset` the netCDF dataset.  SI units.
"""
from dataclasses import dataclass, field

import numpy as np

from .. import cf
from .._version import __version__
from . import fit as fitting
from . import risk as risk_integral
from . import risk_inputs
from . import stripes as stripe_analysis
from .hazard_curve import poe_from_rate

STATUS_KNOWN = "known"  # the fragility was given, not fitted


@dataclass
class RiskOutcome:
    """Everything a risk report says.

    ``fits`` and ``risks`` are object arrays of the body shape (``()`` for one body): a
    ``fit.LognormalFit`` (None for a known fragility) and a ``risk.Risk`` (None where the
    fit is not identifiable).  ``k``, ``n``: overturned and simulated motions per stripe and
    body.  ``body_coords``: {dim: (SI values, attrs)}.  ``warnings``: every caution said
    while it was computed (``path: message``), for the JSON and the dataset.
    """

    curve: object
    years: float
    target: float
    confidence: float
    fits: np.ndarray
    risks: np.ndarray
    body_dims: list = field(default_factory=list)
    body_coords: dict = field(default_factory=dict)
    stripes: list = None
    k: np.ndarray = None
    n: np.ndarray = None
    disaggregation: object = None
    name: str = "risk"
    site: str = None
    warnings: list = field(default_factory=list)

    @property
    def shape(self):
        return self.risks.shape

    def probabilities(self):
        """P in ``years`` per body (NaN where not identifiable), body shape."""
        return _field(self.risks, "probability")

    def labels(self):
        """A label per body: ``H = 0.8 m, b_over_h = 0.25`` (``body`` for one)."""
        out = np.empty(self.shape, dtype=object)
        for index in np.ndindex(*self.shape):
            parts = [f"{d} = {self.body_coords[d][0][i]:.4g}"
                     + (f" {self.body_coords[d][1].get('units')}"
                        if self.body_coords[d][1].get("units") not in (None, "1") else "")
                     for d, i in zip(self.body_dims, index)]
            out[index] = ", ".join(parts) or "body"
        return out


def _field(risks, name):
    out = np.full(risks.shape, np.nan)
    for index in np.ndindex(*risks.shape):
        if risks[index] is not None:
            out[index] = getattr(risks[index], name)
    return out


def known(curve, median, beta, years, target=None, confidence=0.95, name="risk"):
    """The :class:`RiskOutcome` of a known lognormal fragility (median [SI], beta)."""
    risks = np.empty((), dtype=object)
    risks[()] = risk_integral.risk(curve, median, beta, years, confidence=confidence)
    fits = np.empty((), dtype=object)
    return RiskOutcome(curve, years, target, confidence, fits, risks, name=name)


def compute(spec, folder, say=None, median=None, beta=None):
    """The :class:`RiskOutcome` of a checked risk file; stripe studies in ``folder``.

    ``spec`` is loaded with its hazard (``load_risk(..., hazard=risk_inputs.checked_hazard)``).
    ``median``, ``beta``: a known fragility instead of the stripes (the command's
    ``--median``, ``--beta``).  Raises what ``stripes.run`` raises.
    """
    checked = spec.checked
    curve = spec.curve
    common = dict(target=checked.target, confidence=checked.confidence, name=spec.name)
    if median is None and checked.fragility is not None:
        median, beta = checked.fragility.median.to_si(), float(checked.fragility.beta)
    if median is not None:
        outcome = known(curve, median, beta, checked.years, **common)
        outcome.site = checked.site
        return outcome
    entry = checked.stripes
    levels = risk_inputs.stripe_levels(entry)
    model = curve.source_model
    if entry.records is not None:
        plan = stripe_analysis.record_plan(levels, _record_sources(entry.records, spec.folder))
    elif entry.scenario is not None:
        plan = stripe_analysis.plan(levels, entry.motions, entry.seed, scenario=(
            float(entry.scenario.magnitude), entry.scenario.distance.to_si()))
    else:
        plan = stripe_analysis.plan(levels, entry.motions, entry.seed, model=model)
    vs30 = entry.vs30.to_si() if entry.vs30 is not None else \
        (model.vs30 if model is not None else None)
    paths = stripe_analysis.write_studies(plan, checked.scene, vs30, checked.grid, spec.name,
                                          folder, entry.model, curve.im)
    datasets = stripe_analysis.run(paths, say)
    k, n = stripe_analysis.counts(datasets)
    fits = stripe_analysis.fit(levels, stripe_analysis.outcomes(datasets),
                               shared_members=entry.records is not None,
                               confidence=checked.confidence, replicates=checked.replicates,
                               seed=entry.seed)
    risks = np.empty(fits.shape, dtype=object)
    for index in np.ndindex(*fits.shape):
        f = fits[index]
        if f.identifiable:
            risks[index] = risk_integral.risk(curve, f.theta, f.beta, checked.years,
                                              f.replicates, checked.confidence)
        elif f.status == fitting.SEPARATED:
            risks[index] = separated_risk(curve, levels, k[(slice(None),) + index],
                                          n[(slice(None),) + index], checked.years,
                                          checked.confidence)
    dims = stripe_analysis.body_dims(datasets[0])
    coords = {d: (np.asarray(datasets[0][d].values, dtype=float),
                  dict(datasets[0][d].attrs)) for d in dims}
    disaggregation = None
    if model is not None:
        disaggregation = model.disaggregate(levels, risk_inputs.distance_bins(
            checked.hazard.source))
    return RiskOutcome(curve, checked.years, checked.target, checked.confidence, fits, risks,
                       dims, coords, plan, k, n, disaggregation, spec.name, checked.site)


def _record_sources(names, folder):
    """Bundled record names as they are, files as absolute paths from the risk file's
    folder."""
    from pathlib import Path

    from ..io import records

    return [n if n in records.NAMES else str((Path(folder) / n).resolve()) for n in names]


def separated_risk(curve, levels, k, n, years, confidence):
    """The risk of stripes that separate (none overturned below a gap, all above it): the
    maximum-likelihood fragility is then a step (β → 0) somewhere in the gap between the
    highest level with a standing body x_s and the lowest with an overturned one x_o; the
    estimate takes the step at sqrt(x_s x_o), as the bootstrap does for such replicates
    (``fit._estimates``).  The interval is that of a step anywhere between the highest level
    at which no body overturned and the lowest at which all did, [λ(x_all), λ(x_none)]
    (a curve's end where there is no such level)."""
    import dataclasses

    levels = np.asarray(levels, dtype=float)
    standing = levels[(n - k) > 0].max()
    overturned = levels[k > 0].min()
    estimate = risk_integral.risk(curve, float(np.sqrt(standing * overturned)), 0.0, years,
                                  confidence=confidence)
    none = levels[(k == 0) & (n > 0)]
    every = levels[(k == n) & (n > 0)]
    x_none = none.max() if none.size else curve.levels[0]
    x_all = every.min() if every.size else curve.levels[-1]
    bounds = (float(curve.rate(x_all)), float(curve.rate(x_none)))
    return dataclasses.replace(estimate, rate_interval=bounds, probability_interval=tuple(
        float(p) for p in poe_from_rate(bounds, years)))


def _interval(pair):
    return [None if not np.isfinite(v) else float(v) for v in pair]


def body_record(outcome, index=()):
    """The JSON of one body: ``annual_rate``, ``probability``, ``years``, ``return_period``,
    ``interval``, ``fragility``, ``deaggregation`` (docs/design.md §12)."""
    r, f = outcome.risks[index], outcome.fits[index]
    record = {"body": outcome.labels()[index]}
    record.update({d: float(outcome.body_coords[d][0][i])
                   for d, i in zip(outcome.body_dims, index)})
    if f is None:
        fragility = {"median": r.median, "beta": r.beta, "status": STATUS_KNOWN}
    else:
        separated = f.status == fitting.SEPARATED and r is not None
        fragility = {"median": r.median if separated else f.theta,
                     "beta": r.beta if separated else f.beta,
                     "median_interval": list(f.theta_interval),
                     "beta_interval": list(f.beta_interval), "status": f.reason,
                     "stripes": {"levels": [s.level for s in outcome.stripes],
                                 **({"records": outcome.stripes[0].distances}
                                    if outcome.stripes[0].seeds is None else {}),
                                 "overturned": outcome.k[(slice(None),) + index].tolist(),
                                 "motions": outcome.n[(slice(None),) + index].tolist()}}
    fragility["units"] = outcome.curve.units
    record["fragility"] = fragility
    if r is None:
        record.update(annual_rate=None, probability=None, years=outcome.years,
                      return_period=None, interval=None, deaggregation=None)
        return record
    record.update(
        annual_rate=r.annual_rate, probability=r.probability, years=r.years,
        return_period=r.return_period,
        interval={"confidence": r.confidence, "annual_rate": _interval(r.rate_interval),
                  "probability": _interval(r.probability_interval),
                  "replicates": r.replicates},
        meets_target=None if outcome.target is None else bool(r.probability <= outcome.target),
        meets_target_upper=None if outcome.target is None or not np.isfinite(
            r.probability_interval[1]) else bool(r.probability_interval[1] <= outcome.target),
        deaggregation={"im_lower": r.lower.tolist(),
                       "im_upper": [None if not np.isfinite(u) else u for u in r.upper],
                       "share": r.shares.tolist(), "share_above_curve": r.share_above,
                       "share_below_curve_not_included": r.share_below})
    return record


def hazard_record(outcome):
    """The hazard used, for the JSON."""
    curve = outcome.curve
    record = {"im": curve.im, "units": curve.units, "source": curve.source,
              "levels": curve.levels.tolist(), "annual_rates": curve.rates.tolist()}
    d = outcome.disaggregation
    if d is not None:
        record["stripe_disaggregation"] = {
            "levels": d.levels.tolist(), "mean_magnitude": d.mean_magnitude.tolist(),
            "mean_distance": d.mean_distance.tolist()}
    return record


def report(outcome):
    """The JSON document of a risk report."""
    return {"name": outcome.name, "site": outcome.site, "im": outcome.curve.im,
            "years": outcome.years, "target": outcome.target,
            "bodies": [body_record(outcome, index) for index in np.ndindex(*outcome.shape)],
            "hazard": hazard_record(outcome), "warnings": list(outcome.warnings)}


SEGMENT, LEVEL, STRIPE = "segment", "hazard_level", "stripe"


def _variable(dims, data, units, long_name, **extra):
    return (dims, np.asarray(data), {"units": units, "long_name": long_name, **extra})


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
        if outcome.disaggregation is not None:
            d = outcome.disaggregation
            data["stripe_mean_magnitude"] = _variable(
                (STRIPE,), d.mean_magnitude, "1", "mean magnitude of the disaggregation")
            data["stripe_mean_distance"] = _variable(
                (STRIPE,), d.mean_distance, "m", "mean Rrup of the disaggregation")
    ds = xr.Dataset(data, coords={k: xr.Variable(*v) for k, v in coords.items()})
    ds.attrs.update({
        "Conventions": cf.CONVENTIONS, "title": f"risk of overturning: {outcome.name}",
        "source": f"{cf.PACKAGE} {__version__} (sweep.risk)",
        "hazard": curve.source, "intensity_measure": curve.im, "years": outcome.years,
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
    """Write ``ds`` to ``path`` atomically (``runner.store.write_netcdf``: a temporary name,
    then ``os.replace``)."""
    from ..runner.store import write_netcdf

    return write_netcdf(ds, path)
