"""What the stripes of one scene give: overturnings, fits, risks, sides, isolator displacements.

The stripes' datasets (``stripes.run``) of one scene, a body or a grid of bodies, fitted
(``fit``) and integrated over the hazard (``risk``) per body: the fragility where it is
identifiable, the step of stripes that separate, the bound of a body never overturned; each
side's overturnings (docs/bodies.md) and the isolator's largest displacements fitted per
stripe (``isolator_demand``).  ``risk_report`` and ``risk_options`` build on it.
"""
from collections import namedtuple

import numpy as np

from . import fit as fitting
from . import risk as risk_integral
from . import risk_inputs
from . import stripes as stripe_analysis
from .hazard_curve import poe_from_rate
from .isolator_demand import fit_stripes

SIDE_VARIABLES = ("overturn_direction", "alpha_1", "alpha_2")  # of a stripe's dataset


StripeResults = namedtuple("StripeResults", "datasets k n fits risks sides displacements")
StripeResults.__doc__ = """What the stripes of one scene give, per stripe and body: the
datasets, overturned and simulated motions ``k``, ``n``, the fits and risks, each side's
overturnings (:class:`StripeSides`) and the isolator's displacements per stripe
(``isolator_demand.StripeDisplacements``, None without an isolator), body shape."""


def stripe_results(datasets, spec):
    """The :class:`StripeResults` of the stripes' ``datasets`` of a checked risk file."""
    checked, curve = spec.checked, spec.curve
    entry = checked.stripes
    levels = risk_inputs.stripe_levels(entry)
    k, n = stripe_analysis.counts(datasets)
    fits = stripe_analysis.fit(levels, stripe_analysis.outcomes(datasets),
                               shared_members=entry.records is not None,
                               confidence=checked.confidence, replicates=checked.replicates,
                               seed=entry.seed)
    risks = np.empty(fits.shape, dtype=object)
    for index in np.ndindex(*fits.shape):
        f, along = fits[index], (slice(None),) + index
        if f.identifiable:
            risks[index] = risk_integral.risk(curve, f.theta, f.beta, checked.years,
                                              f.replicates, checked.confidence)
        elif f.status == fitting.SEPARATED:
            risks[index] = separated_risk(curve, levels, k[along], n[along], checked.years,
                                          checked.confidence)
        elif not k[along].any() and n[along].any():
            risks[index] = risk_integral.none_overturned(
                curve, levels, n[along], checked.years, checked.confidence,
                independent=entry.records is None)
    return StripeResults(datasets, k, n, fits, risks, stripe_sides(datasets),
                         stripe_displacements(datasets, levels))


def stripe_displacements(datasets, levels):
    """Per body, the isolator's largest displacements fitted per stripe
    (``isolator_demand.fit_stripes``), an object array of body shape; None where the stripes
    have no isolator (no finite ``isolator_max_displacement``)."""
    if any("isolator_max_displacement" not in ds for ds in datasets):
        return None
    values = np.array([ds["isolator_max_displacement"].transpose(
        stripe_analysis.member_dim(ds), ...).values for ds in datasets])
    if not np.isfinite(values).any():
        return None
    out = np.empty(values.shape[2:], dtype=object)
    for index in np.ndindex(*out.shape):
        out[index] = fit_stripes(levels, values[(slice(None), slice(None)) + index])
    return out


StripeSides = namedtuple("StripeSides", "left right alpha_1 alpha_2")
StripeSides.__doc__ = """Each side of the bodies of the stripes (docs/bodies.md): ``left`` and
``right``, the motions that overturned the body to the left (−x, about corner 1:
``overturn_direction`` +1) and to the right, per stripe and body (the shape of
``RiskOutcome.k``); ``alpha_1``, ``alpha_2`` [rad] per body (equal: G in the middle)."""


def stripe_sides(datasets):
    """The :class:`StripeSides` of the stripes' datasets (``stripes.run``); None for datasets
    reused from a version that did not write each side."""
    def motions_first(ds, name):
        return ds[name].transpose(stripe_analysis.member_dim(ds), ...).values

    if any(name not in ds for ds in datasets for name in SIDE_VARIABLES):
        return None
    overturned = stripe_analysis.outcomes(datasets) == 1
    direction = np.array([motions_first(ds, "overturn_direction") for ds in datasets])
    angles = (motions_first(datasets[0], name)[0] for name in ("alpha_1", "alpha_2"))
    return StripeSides((overturned & (direction == 1)).sum(axis=1),
                       (overturned & (direction == -1)).sum(axis=1), *angles)


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
