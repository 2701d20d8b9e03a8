"""The site estimate in words (gal, cm/s) and as JSON (SI).

The tables and sentences of ``python -m sweep.estimate`` and the dict of its ``--json``, from
``sweep.probability.site``.
"""
import math

import numpy as np

from .fragility import counted
from .site_posterior import MIN_LEVELS, MIN_MATCHES, support_advice

MAP_METHOD = ("Gaussian-kernel average of the consistency indicator in (ln PGA, ln PGV/PGA); "
              "the region at q is where it is at least q")
PRIOR = "uniform in ln PGA over the levels"


def _peak(consistency_map):
    """The largest probability of the map (NaN when it is blank)."""
    finite = consistency_map.probability[np.isfinite(consistency_map.probability)]
    return float(finite.max()) if finite.size else math.nan


def _bounds_json(bounds, probabilities):
    return [{"probability": q, "value": b.value, "beyond": b.beyond}
            for q, b in zip(probabilities, bounds)]


def summary(estimate):
    """The estimate of a site as a JSON-ready dict, SI units; lists of probabilities are in
    the order of ``probabilities``."""
    ens = estimate.ensemble
    post, m, sup = estimate.posterior, estimate.map, estimate.support
    quantiles = estimate.quantiles
    return {
        "members": estimate.members, "levels": list(ens.levels), "t_end": estimate.t_end,
        "probabilities": list(ens.probabilities), "mu_default": ens.mu,
        "failed_cells": estimate.failed_cells,
        "excluded": [{"name": name, "reason": reason} for name, reason in estimate.excluded],
        "bodies": [{"name": b.name, "overturned": b.overturned, "B": b.B, "H": b.H, "mu": b.mu,
                    "mu_given": b.mu_given, "a_o": b.west, "fragility": b.fragility,
                    "fragility_lower": b.lower, "fragility_upper": b.upper,
                    "members_counted": b.members,
                    "bound": "lower" if b.overturned else "upper",
                    "bounds": _bounds_json(b.bounds, ens.probabilities),
                    "slid_near_bound": b.slid, "slid_flag": b.slid_near_bound}
                   for b in estimate.bodies],
        "likelihood": estimate.likelihood, "members_counted": estimate.counted,
        "support": None if sup is None else {
            "simulations_reproducing": sup.matches, "simulations": sup.cells,
            "levels_with_likelihood": sup.levels, "levels": sup.of_levels,
            "sufficient": sup.sufficient, "minimum": {"simulations": MIN_MATCHES,
                                                      "levels": MIN_LEVELS},
            "add_levels_between": None if sup.between is None else list(sup.between)},
        "posterior": None if post is None else {
            "prior": PRIOR, "pga": None if quantiles is None else quantiles[0],
            "pgv": None if quantiles is None else quantiles[1], "cut_below": post.cut_below,
            "cut_above": post.cut_above, "west_floor": estimate.west_floor,
            "percentiles_withheld": support_advice(sup)},
        "posterior_note": estimate.reason,
        "region": None if m is None else {
            "method": MAP_METHOD, "bandwidth_ln_pga": m.bandwidth[0],
            "bandwidth_ln_pgv_over_pga": m.bandwidth[1],
            "peak": _peak(m),
            "levels": [{"probability": q, "pga": None if r is None else [r[0], r[1]],
                        "pgv": None if r is None else [r[2], r[3]]}
                       for q, r in zip(ens.probabilities, m.regions)]},
        "datasets": estimate.datasets,
    }


def _gal(a):
    return f"{a * 100:.0f}"


def _bound_text(bound, levels):
    if bound.beyond == "above":
        return f"> {_gal(levels[-1])}"
    if bound.beyond == "below":
        return f"<= {_gal(bound.value)}"
    return _gal(bound.value)


def format_text(estimate, lower_limits=None, width=92):
    """The estimate as tables and sentences, in the paper's units (gal, cm/s); with the
    deterministic ``lower_limits`` (``sweep.paper.estimate``) side by side."""
    import textwrap

    ens = estimate.ensemble
    levels = ens.levels
    qs = " / ".join(f"{q:.0%}" for q in ens.probabilities)
    lines = [textwrap.fill(
        f"Ensemble: {counted(len(estimate.members), 'motion')} "
        f"({', '.join(estimate.members[:6])}"
        f"{', ...' if len(estimate.members) > 6 else ''}) scaled to {len(levels)} PGA levels "
        f"from {_gal(levels[0])} to {_gal(levels[-1])} gal, simulated for "
        f"{estimate.t_end:.1f} s; mu = {ens.mu:g} for the bodies that give none.", width)]
    if estimate.failed_cells:
        lines.append(f"{counted(estimate.failed_cells, 'simulation')} failed; left out of the "
                     "counts.")
    for name, reason in estimate.excluded:
        lines.append(textwrap.fill(f"Kept out: {name}: {reason}.", width,
                                   subsequent_indent="  "))
    if estimate.bodies:
        header = (f"{'body':<18} {'state':<10} {'a_o [gal]':>9}  {'slid':>4}  "
                  f"bound at {qs} [gal]")
        lines += ["", header, "-" * len(header)]
        note = ("slid: share of the simulations at the two levels around the body's 50 % "
                "bound in which it slid")
    for b in estimate.bodies:
        kind = "lower" if b.overturned else "upper"
        bounds = " / ".join(_bound_text(x, levels) for x in b.bounds)
        slid = "most" if b.slid_near_bound else "" if np.isnan(b.slid) else f"{b.slid:.0%}"
        lines.append(f"{b.name[:18]:<18} {'overturned' if b.overturned else 'standing':<10} "
                     f"{_gal(b.west):>9}  {slid:>4}  {kind}: {bounds}")
    if estimate.bodies:
        lines.append(note)
    flagged = [b.name for b in estimate.bodies if b.slid_near_bound]
    if flagged:
        lines.append(textwrap.fill(
            f"Slid in most of the simulations near their bound: {', '.join(flagged)} (the "
            "bound mixes sliding with rocking; a known mu would help).", width))
    lines.append("")
    post = estimate.posterior
    if post is None:
        lines.append(textwrap.fill(f"No posterior: {estimate.reason}.", width))
        return "\n".join(lines)
    lines.append(textwrap.fill(
        f"The site's shaking given every body (posterior, prior {PRIOR}), carried by "
        f"{estimate.support.text()} that reproduce every body:", width))
    quantiles = estimate.quantiles
    head = f"{'':<12} {'deterministic':>16}  " + ("  ".join(
        f"{q:>7.0%}" for q in ens.probabilities) if quantiles else "")
    lines.append(head.rstrip())
    for k, (key, unit, shown) in enumerate((("pga", "gal", _gal),
                                            ("pgv", "cm/s", lambda v: f"{v * 100:.3g}"))):
        limit = "" if lower_limits is None else f">= {shown(lower_limits[key]['value'])}"
        values = "  ".join(f"{shown(v):>7}" for v in quantiles[k]) if quantiles else ""
        lines.append(f"{key.upper() + ' [' + unit + ']':<12} {limit:>16}  {values}".rstrip())
    if not quantiles:
        lines.append(textwrap.fill(f"  Percentiles withheld: {support_advice(estimate.support)}.",
                                   width, subsequent_indent="  "))
    if post.cut_below or post.cut_above:
        ends = [end for end, cut in (("lowest", post.cut_below), ("highest", post.cut_above))
                if cut]
        lines.append(textwrap.fill(
            f"  The likelihood is not 0 at the {' and '.join(ends)} level: the quantiles on "
            "that side are set by the range of levels, not by the bodies.", width,
            subsequent_indent="  "))
    m = estimate.map
    lines.append("Motions consistent with every body, in (PGA, PGV):")
    for q, region in zip(ens.probabilities, m.regions):
        if region is None:
            lines.append(f"  at >= {q:.0%}: nowhere (at most {_peak(m):.0%})")
        else:
            lines.append(f"  at >= {q:.0%}: PGA {_gal(region[0])}-{_gal(region[1])} gal, "
                         f"PGV {region[2] * 100:.3g}-{region[3] * 100:.3g} cm/s")
    return "\n".join(lines)
