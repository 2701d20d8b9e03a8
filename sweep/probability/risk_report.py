"""A risk file worked through: hazard → stripes → fragility → risk, and its JSON.

For one body, every body of a grid, or every named option (``risk_options``; docs/risk.md,
docs/options.md), with an isolator's displacement demand (``isolator_demand``).

:func:`compute` takes a checked risk file (``sweep.io.risk_schema.RiskSpec``) and returns a
:class:`RiskOutcome`; :func:`known` does the same for a hazard curve and a known lognormal
fragility, without simulating.  :func:`body_record` is the JSON of one body (the keys of
docs/design.md §12); ``risk_dataset.to_dataset`` makes the netCDF dataset of it.  SI units.
"""
from dataclasses import dataclass, field

import numpy as np

from . import fit as fitting
from . import risk as risk_integral
from . import risk_inputs
from . import stripes as stripe_analysis
from .isolator_demand import record as isolator_record
from .stripe_results import stripe_results

STATUS_KNOWN = "known"  # the fragility was given, not fitted
DESCRIBED = {"body.B": "B", "body.H": "H", "contact.mu": "mu"}  # axes that describe_body says
# other axes in a conservator's words (describe_body), the rest by their dotted path
_HORIZONTAL = "excitation.horizontal."
SAID = {"restraint.strength": "anchor", "body.mass": "mass",
        **{f"{_HORIZONTAL}{place}building.{key}": said
           for place in ("", "under.") for key, said in (
               ("period", "building period"), ("damping", "building damping"),
               ("height_ratio", "floor height ratio"))},
        **{f"{_HORIZONTAL}isolator.{key}": f"isolator {said}" for key, said in (
            ("mu", "μ"), ("radius", "R"), ("period", "period"), ("damping", "damping"),
            ("displacement_capacity", "capacity"))}}


@dataclass
class RiskOutcome:
    """Everything a risk report says.

    ``fits`` and ``risks`` are object arrays of the body shape (``()`` for one body): a
    ``fit.LognormalFit`` (None for a known fragility) and a ``risk.Risk`` (its bound for a
    body never overturned, None where the fit is otherwise not identifiable).  ``k``, ``n``:
    overturned and simulated motions per stripe and body.  ``body_coords``: {dim: (SI
    values, attrs)}.  ``warnings``: every caution said while it was computed (``path:
    message``), for the JSON and the dataset.
    ``description``: the scene's body, {name: SI value} (:func:`body_parameters`).
    ``sides``: each side's overturnings and angles per body (``stripe_results.StripeSides``), None
    without stripes.  ``placement``: where the stripes' motions act, in words
    (``stripes.placement``: the ground, or a building's floor), None without stripes.
    ``displacements``: per body the isolator's displacements fitted per stripe
    (``isolator_demand.StripeDisplacements``; None for a body without an isolator,
    or no array).  ``options``: the names of a risk file's options, its one body dimension.
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
    description: dict = field(default_factory=dict)
    sides: object = None
    placement: str = None
    displacements: np.ndarray = None
    options: list = field(default_factory=list)

    @property
    def shape(self):
        return self.risks.shape

    def probabilities(self):
        """P in ``years`` per body (NaN where not identifiable), body shape."""
        return _field(self.risks, "probability")

    def axes(self):
        """The grid's axis of each body dimension, as the risk file names it (``H``,
        ``contact.mu``, ``excitation.horizontal.building.period``)."""
        return [self.body_coords[d][1].get("study_axis", d) for d in self.body_dims]

    def units(self):
        """The units of each axis's SI values (``m``; ``1`` for a number)."""
        return [self.body_coords[d][1].get("units", "1") for d in self.body_dims]

    def option(self, index):
        """{axis: SI value} of the body at ``index`` of the grid; {"option": name} of a
        named option."""
        if self.options:
            return {"option": self.options[index[0]]}
        return {a: float(self.body_coords[d][0][i])
                for a, d, i in zip(self.axes(), self.body_dims, index)}

    def labels(self):
        """A label per body: ``H = 0.8 m, contact.mu = 0.3, anchor 800 N`` (:data:`SAID`'s
        words where it has them; ``body`` for one; a named option's name)."""
        out = np.empty(self.shape, dtype=object)
        if self.options:
            out[:] = self.options
            return out
        for index in np.ndindex(*self.shape):
            parts = [(f"{SAID[a]} " if a in SAID else f"{a} = ") + f"{v:.4g}"
                     + (f" {u}" if u != "1" else "")
                     for (a, v), u in zip(self.option(index).items(), self.units())]
            out[index] = ", ".join(parts) or "body"
        return out

    def names(self):
        """A name per body for people, from its parameters: ``B 15 cm × H 60 cm (b/h 0.25),
        μ 0.8`` (the scene's body with the grid's values, and the grid's other axes);
        :meth:`labels` without a scene or for named options."""
        if not self.description or self.options:
            return self.labels()
        out = np.empty(self.shape, dtype=object)
        for index in np.ndindex(*self.shape):
            values = {DESCRIBED.get(a, a): v for a, v in self.option(index).items()}
            scene = {k: v for k, v in self.description.items()
                     if not (k == "H" and "b_over_h" in values)}  # B/(b/h) sets H
            out[index] = describe_body({**scene, **values}, dict(zip(self.axes(),
                                                                     self.units())))
        return out

    def demand(self, index):
        """The isolator's displacement demand of body ``index`` at the target's probability
        in ``years`` (``isolator_demand.IsolatorDemand``); None for a body without a friction
        pendulum, or without a target."""
        from .isolator_demand import demand

        fitted = None if self.displacements is None else self.displacements[index]
        if fitted is None or self.target is None:
            return None
        return demand(self.curve, fitted, self.years, self.target)

    def demands(self):
        """:meth:`demand` per body, an object array of body shape; None when no body has
        one."""
        if self.displacements is None or self.target is None:
            return None
        out = np.empty(self.shape, dtype=object)
        for index in np.ndindex(*self.shape):
            out[index] = self.demand(index)
        return out

    def fixed(self):
        """The body's parameters that the grid does not vary, in words (``μ 0.8``)."""
        varied = {DESCRIBED.get(a, a) for a in self.axes()}
        varied |= {"H"} if "b_over_h" in varied else set()
        return describe_body({k: v for k, v in self.description.items() if k not in varied})


def describe_body(values, units=None):
    """A body in words from {name: SI value} of ``B``, ``H``, ``b_over_h``, ``mu`` (those
    given) and of other axes (their ``units``, {name: unit}), named as :data:`SAID` names them
    or by their path: ``B 15 cm × H 60 cm (b/h 0.25), μ 0.8, building period 0.6 s``."""
    breadth, height, ratio = (values.get(k) for k in ("B", "H", "b_over_h"))
    if height is None and breadth is not None and ratio is not None:
        height = breadth / ratio
    if breadth is not None and height is not None:
        parts = [f"B {100 * breadth:.3g} cm × H {100 * height:.3g} cm (b/h "
                 f"{breadth / height:.3g})"]
    else:
        parts = [f"{k} {100 * v:.3g} cm" for k, v in (("B", breadth), ("H", height))
                 if v is not None] + ([f"b/h {ratio:.3g}"] if ratio is not None else [])
    if values.get("mu") is not None:
        parts.append(f"μ {values['mu']:.3g}")
    parts += [f"{SAID.get(k, k)} {v:.4g}" + (f" {(units or {}).get(k)}"
                                              if (units or {}).get(k, "1") != "1" else "")
              for k, v in values.items() if k not in ("B", "H", "b_over_h", "mu")]
    return ", ".join(parts)


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
    outcome = RiskOutcome(curve, years, target, confidence, fits, risks, name=name)
    caution_ends(outcome)
    return outcome


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
        outcome.description = body_parameters(checked.scene)
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
    if checked.options:
        from .risk_options import run_options

        results, dims, coords, placement = run_options(spec, plan, vs30, folder, say)
    else:
        paths = stripe_analysis.write_studies(plan, checked.scene, vs30, checked.grid,
                                              spec.name, folder, entry.model, curve.im)
        results = stripe_results(stripe_analysis.run(paths, say), spec)
        datasets = results.datasets
        dims = stripe_analysis.body_dims(datasets[0])
        coords = {d: (np.asarray(datasets[0][d].values, dtype=float),
                      dict(datasets[0][d].attrs)) for d in dims}
        placement = stripe_analysis.placement(checked.scene)
    disaggregation = None
    if model is not None:
        disaggregation = model.disaggregate(levels, risk_inputs.distance_bins(
            checked.hazard.source))
    outcome = RiskOutcome(curve, checked.years, checked.target, checked.confidence,
                          results.fits, results.risks, dims, coords, plan, results.k,
                          results.n, disaggregation, spec.name, checked.site,
                          description=body_parameters(checked.scene), sides=results.sides,
                          placement=placement, displacements=results.displacements,
                          options=list(checked.options or ()))
    caution_ends(outcome)
    return outcome


def body_parameters(scene):
    """{name: SI value} of a risk file's ``scene``: its body's ``B`` and ``H`` and its
    contact's ``mu``, those it gives; empty without a scene."""
    from pydantic import ValidationError

    from ..io.scene_schema import Body, Contact

    out = {}
    try:
        body = Body.model_validate((scene or {}).get("body") or {})
        out.update(B=body.B.to_si(), H=body.H.to_si())
    except (ValidationError, ValueError):  # its problems are the scene's, said elsewhere
        pass
    try:
        mu = Contact.model_validate((scene or {}).get("contact") or {}).mu
    except (ValidationError, ValueError):
        mu = None
    if mu is not None:
        out["mu"] = float(mu)
    return out


def caution_ends(outcome):
    """Caution of each body whose fragility reaches past the hazard curve's ends
    (``Risk.beyond_above``, ``Risk.beyond_below``) and of each whose rate is only bounded
    (none overturned): what the numbers then mean, and what to give to do better."""
    from ..io.imt import display_scale
    from ..io.problems import caution

    curve = outcome.curve
    factor, unit = display_scale(curve.units)
    names = outcome.names()

    def level(x):
        return f"{x / factor:.3g} {unit}"

    for index in np.ndindex(*outcome.shape):
        r = outcome.risks[index]
        who = f"{names[index]}: " if outcome.shape else ""
        _caution_demand(outcome.demand(index), who)
        if r is None:
            continue
        if r.bound is not None:
            caution(f"{who}{_bound_said(outcome, index, level)}", "stripes")
            continue
        if r.beyond_above:
            caution(f"{who}{_above_said(r, curve, level)}", "hazard")
        if r.beyond_below:
            caution(f"{who}an estimated {100 * r.share_below:.3g} % more than the rate of "
                    f"overturning would come from shaking below the hazard curve's first "
                    f"level, {level(curve.levels[0])}, not included: give a hazard curve "
                    "from lower levels", "hazard")


def _caution_demand(found, who):
    """Caution of an isolator's demand that the stripes do not reach, or of which more than
    ``isolator_demand.OUTSIDE_SHARE`` comes from shaking outside the stripes' range (the
    displacements held at the end stripes')."""
    from ..io.problems import caution
    from .isolator_demand import OUTSIDE_SHARE, said

    if found is None:
        return
    if found.displacement is None:
        caution(f"{who}isolator displacement: {said(found)}", "stripes")
    elif found.share_outside > OUTSIDE_SHARE:
        caution(f"{who}isolator displacement {said(found)}: {100 * found.share_outside:.3g} % "
                "of its rate comes from shaking outside the stripes' levels, where the "
                "displacements are held at the nearest stripe's: give stripes over a wider "
                "range", "stripes")


def _above_said(r, curve, level):
    """The caution of a fragility reaching past the curve's last level: the share from
    above it, the rate between the one computed and the most it could be, what to give."""
    last = curve.levels[-1]
    at_last = float(risk_integral.fragility_at(last, np.log(r.median), r.beta))
    reach = r.median * np.exp(2.0 * r.beta)  # where the fragility is 0.98
    median = f", below the fragility's median {level(r.median)}" if r.median > last else ""
    said = (f"{100 * r.share_above:.3g} % of the rate of overturning comes from shaking above "
            f"the hazard curve's last level, {level(last)}{median}, counted with the "
            f"fragility there ({at_last:.2g})")
    if not r.open_above:
        return (f"{said}: nearly all that shaking overturns the body, so the rate "
                f"{r.annual_rate:.3g}/yr is within 1 % of the most it could be")
    return (f"{said}: the rate is between {r.annual_rate:.3g} and {r.rate_at_most:.3g}/yr, the "
            "most if all that shaking overturned the body; give a hazard curve to higher "
            "levels" + (f" (to {level(reach)}, where the fragility is 0.98)" if reach > last
                        else ""))


def _bound_said(outcome, index, level):
    """The caution of a body that never overturned: its bound, and the share of it from
    below the lowest stripe, where the stripes say nothing."""
    r, curve = outcome.risks[index], outcome.curve
    levels, q = r.staircase
    below = q[0] * (curve.rates[0] - float(curve.rate(levels[0]))) / r.annual_rate
    return (f"none overturned at any stripe: the rate of overturning is at most "
            f"{r.annual_rate:.3g}/yr ({r.bound.split(': ')[-1]}), from P(overturn) ≤ "
            f"{q[0]:.2g} at the lowest stripe to {q[-1]:.2g} at the highest; more motions "
            f"lower it, and so do stripes below {level(levels[0])}, the lowest, whence "
            f"{100 * below:.3g} % of it comes")


def asymmetric(outcome, index=()):
    """True when body ``index`` of ``outcome`` has G off the middle (its angles differ)."""
    sides = outcome.sides
    return sides is not None and sides.alpha_1[index] != sides.alpha_2[index]


def _record_sources(names, folder):
    """Bundled record names as they are, files as absolute paths from the risk file's
    folder."""
    from pathlib import Path

    from ..io import records

    return [n if n in records.NAMES else str((Path(folder) / n).resolve()) for n in names]


def _interval(pair):
    return [None if not np.isfinite(v) else float(v) for v in pair]


def _side_record(outcome, index):
    """``overturned_left``, ``overturned_right`` per stripe of body ``index``, for the JSON
    (nothing without ``stripe_results.StripeSides``)."""
    sides = outcome.sides
    along = (slice(None),) + index
    return {} if sides is None else {"overturned_left": sides.left[along].tolist(),
                                     "overturned_right": sides.right[along].tolist()}


def body_record(outcome, index=()):
    """The JSON of one body: ``annual_rate``, ``probability``, ``years``, ``return_period``,
    ``interval``, ``fragility``, ``deaggregation`` (docs/design.md §12); for a body that never
    overturned, ``annual_rate``, ``probability`` and ``return_period`` are null and
    ``annual_rate_upper_bound``, ``probability_upper_bound`` and ``bound`` say the bound,
    on which ``meets_target`` is judged."""
    r, f = outcome.risks[index], outcome.fits[index]
    record = {"body": outcome.labels()[index]}
    record.update(outcome.option(index))
    if outcome.sides is not None:  # each side's angle: G off the middle when they differ
        record.update(alpha_1=float(outcome.sides.alpha_1[index]),
                      alpha_2=float(outcome.sides.alpha_2[index]))
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
                                 **_side_record(outcome, index),
                                 "motions": outcome.n[(slice(None),) + index].tolist()}}
    fragility["units"] = outcome.curve.units
    record["fragility"] = fragility
    found = outcome.demand(index)
    if found is not None:
        record["isolator_demand"] = isolator_record(found)
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
                       "share_below_curve_not_included": r.share_below,
                       "rate_above_curve_at_most": r.last_rate})
    if r.bound is not None:
        record.update(annual_rate=None, probability=None, return_period=None,
                      annual_rate_upper_bound=r.annual_rate,
                      probability_upper_bound=r.probability, bound=r.bound)
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
            "grid": [] if outcome.options else [{"axis": a, "units": u} for a, u in zip(
                outcome.axes(), outcome.units())],
            "options": outcome.options or None,
            "hazard": hazard_record(outcome), "placement": outcome.placement,
            "warnings": list(outcome.warnings)}
