"""Figures of a risk report: per body its hazard, fragility and risk; the risk map of a grid.

Per body (``sweep.probability.risk_report.RiskOutcome``) the hazard curve, the fragility with
its band and the stripes' fractions, the risk integrand over the IM with the disaggregation of
λ_O by segment, and the probability in ``years`` with its interval; over a grid of bodies the
risk map with the contour of the target probability, and its options side by side against the
target."""
import numpy as np
from matplotlib.colors import LogNorm

from ..io.imt import display_scale
from ..probability import risk as risk_integral
from ..probability.hazard_curve import poe_from_rate
from ..probability.risk_report import asymmetric
from .fragility import SIDE_SHIFT, SIDE_STYLES
from .style import fit_suptitle, fit_texts, log_axes, plain_log_axis, save_figure

MAP_CMAP = "viridis"
TITLE_SIZE = 10.0  # points: a panel's title, two lines of its width
CONTOUR_COLOR = "tab:red"  # seen on every colour of viridis
# Relative luminance above which black text contrasts more than white (WCAG 2.1 contrast
# ratio (L1 + 0.05)/(L2 + 0.05), equal for both at L = sqrt(1.05 * 0.05) - 0.05): at least
# 4.58 on any colour.
BLACK_OR_WHITE = np.sqrt(1.05 * 0.05) - 0.05


def relative_luminance(colour):
    """WCAG 2.1 relative luminance of an sRGB(A) colour with components in [0, 1]."""
    c = np.asarray(colour[:3], dtype=float)
    linear = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    return float(linear @ [0.2126, 0.7152, 0.0722])


def figure_body(outcome, index=()):
    """Four panels for one body (``index`` into the body shape): the hazard, the fragility,
    which shaking causes the risk, the probability; what lies beyond the curve's ends and a
    bound in place of an estimate said in each."""
    from matplotlib.figure import Figure

    curve, r, f = outcome.curve, outcome.risks[index], outcome.fits[index]
    factor, unit = display_scale(curve.units)
    fig = Figure(figsize=(10, 7.5), layout="constrained")
    (ax_h, ax_f), (ax_i, ax_p) = fig.subplots(2, 2)
    _hazard_panel(ax_h, outcome, factor, unit)
    _fragility_panel(ax_f, outcome, index, factor, unit)
    if r is not None:
        _integrand_panel(ax_i, outcome, index, factor, unit)
        _probability_panel(ax_p, outcome, r)
    else:
        reason = f.reason if f is not None else "no fragility"
        for ax in (ax_i, ax_p):
            ax.text(0.5, 0.5, f"no risk: {reason}", ha="center", va="center", wrap=True,
                    transform=ax.transAxes)
    fit_suptitle(fig, [f"risk of overturning: {outcome.name} — {outcome.names()[index]}"
                       + _placed(outcome), curve.source])
    fit_texts(fig)
    return fig


def _pct(p):
    return f"{100 * p:.3g} %"


def _hazard_panel(ax, outcome, factor, unit):
    """The hazard curve (log axes labelled sparsely over many decades) and the stripes."""
    curve = outcome.curve
    ax.plot(curve.levels / factor, curve.rates, "o-", ms=3, color="k", lw=1,
            label="hazard curve")
    for s in outcome.stripes or ():
        ax.axvline(s.level / factor, color="tab:blue", lw=0.6, alpha=0.5)
    if outcome.stripes:
        ax.plot([], [], color="tab:blue", lw=0.6, label="stripes")
    log_axes(ax)
    ax.set(xlabel=f"{curve.im} [{unit}]", ylabel="annual rate of exceedance [1/yr]")
    ax.set_title("hazard", fontsize=TITLE_SIZE)
    ax.legend(fontsize=8)


def _im_range(curve, r):
    """IMs to draw a fragility over: the curve's, widened to θ e^(±3β)."""
    low, high = curve.levels[0], curve.levels[-1]
    if r is not None and np.isfinite(r.median):
        spread = np.exp(3.0 * r.beta) if r.beta > 0 else 1.5
        low, high = min(low, r.median / spread), max(high, r.median * spread)
    return np.geomspace(low, high, 400)


def _stripes_of(outcome, index):
    """(levels, k, n) of the body's stripes."""
    levels = np.array([s.level for s in outcome.stripes])
    at = (slice(None),) + index
    return levels, outcome.k[at], outcome.n[at]


def _fragility_panel(ax, outcome, index, factor, unit):
    """The fragility with its pointwise band, or the bound of a body never overturned, the
    stripes' k/n, and the curve's last level where the fragility reaches past it."""
    curve, r, f = outcome.curve, outcome.risks[index], outcome.fits[index]
    x = _im_range(curve, r)
    confidence = f"{100 * outcome.confidence:g} %"
    if r is not None and r.bound is not None:
        edges = np.concatenate([[x[0]], r.staircase[0], [x[-1]]])
        values = risk_integral.bounding_fragility(edges[1:], r.staircase)
        ax.stairs(values, edges / factor, color="tab:red", baseline=None,
                  label=f"one-sided {confidence} bound (none overturned)")
    elif r is not None:
        shape = f"β = {r.beta:.2f}" if r.beta > 0 else "a step"
        ax.plot(x / factor, risk_integral.fragility_at(x, np.log(r.median), r.beta),
                color="tab:red", label=f"θ = {r.median / factor:.3g} {unit}, {shape}")
        if f is not None and f.identifiable:
            lo, hi = f.band(x)
            how = (f"pointwise, {len(f.replicates)} bootstrap fits"
                   if f.interval == "bootstrap" else "delta method")
            ax.fill_between(x / factor, lo, hi, color="tab:red", alpha=0.2, lw=0,
                            label=f"{confidence} band, {how}")
    if f is not None and outcome.stripes:
        levels, k, n = _stripes_of(outcome, index)
        ax.plot(levels / factor, k / np.maximum(n, 1), "ks", ms=4, label="stripes: k/n")
        if asymmetric(outcome, index):
            _draw_sides(ax, outcome, index, levels / factor, n, k > 0)
    if r is not None and r.beyond_above:
        ax.axvline(curve.levels[-1] / factor, color="0.4", ls="--", lw=1,
                   label="the hazard curve's last level")
    ax.set_xscale("log")
    plain_log_axis(ax.xaxis)
    ax.set(xlabel=f"{curve.im} [{unit}]", ylabel="P(overturn | im)", ylim=(-0.02, 1.02))
    ax.set_title("fragility", fontsize=TITLE_SIZE)
    ax.legend(fontsize=7, loc="upper left")  # where a fragility is 0


def _integrand_panel(ax, outcome, index, factor, unit):
    """F(x) |dλ/d ln x| over the curve and the share of λ_O per segment, with the share from
    above the curve's last level as a hatched bar beyond it."""
    curve, r = outcome.curve, outcome.risks[index]
    x = np.geomspace(curve.levels[0], curve.levels[-1], 400)
    if r.bound is not None:
        fragility = risk_integral.bounding_fragility(x, r.staircase)
    else:
        fragility = risk_integral.fragility_at(x, np.log(r.median), r.beta)
    ax.plot(x / factor, fragility * risk_integral.hazard_density(curve, x),
            color="tab:purple", label="F(x) |dλ/d ln x|" + (" of the bound" if r.bound
                                                              else ""))
    ax.set_xscale("log")
    plain_log_axis(ax.xaxis)
    twin = ax.twinx()
    lower, upper = r.lower[:-1], r.upper[:-1]
    of = "the bound" if r.bound else "λ_O"
    twin.bar(np.sqrt(lower * upper) / factor, r.shares[:-1], width=(upper - lower) / factor,
             color="tab:orange", alpha=0.35, edgecolor="tab:orange",
             label=f"share of {of} per segment")
    last = curve.levels[-1]
    beyond = last * (curve.levels[-1] / curve.levels[-2])  # one segment's width in ln x
    if r.share_above > 0.005:
        twin.bar(np.sqrt(last * beyond) / factor, r.share_above, width=(beyond - last) / factor,
                 color="none", edgecolor="tab:red", hatch="///",
                 label=f"above the curve's last level: {_pct(r.share_above)}")
    twin.set_ylabel(f"share of {of}")
    twin.set_ylim(0, 1.15 * max(r.shares.max(), 1e-12))
    title = "which shaking causes it"
    if r.open_above:
        title = (f"{_pct(r.share_above)} of λ_O from above {last / factor:.3g} {unit},\nthe "
                 "curve's end: give a curve to higher levels")
    elif r.beyond_below:
        title = (f"{_pct(r.share_below)} more from below {curve.levels[0] / factor:.3g} {unit},"
                 "\nnot included: give a curve from lower levels")
    ax.set(xlabel=f"{curve.im} [{unit}]", ylabel="risk integrand [1/yr per ln x]")
    ax.set_title(title, fontsize=TITLE_SIZE)
    handles = [h for a in (ax, twin) for h in a.get_legend_handles_labels()[0]]
    ax.legend(handles=handles, fontsize=8, loc="upper left")


def _probability_panel(ax, outcome, r):
    """P in ``years``: the estimate with its interval and, where the fragility reaches past
    the curve, up to what it could be; or the bound of a body never overturned."""
    lo, hi = r.probability_interval
    if r.bound is not None:
        ax.bar([0], [r.probability], color="none", edgecolor="tab:red", hatch="///", width=0.5,
               label=f"≤ this: one-sided {100 * r.confidence:g} % bound")
        title = (f"λ_O ≤ {r.annual_rate:.3g}/yr, return period ≥ {r.return_period:.3g} yr\n"
                 f"P ≤ {_pct(r.probability)} in {outcome.years:g} years: none overturned")
    else:
        ax.bar([0], [r.probability], color="tab:red", width=0.5)
        if np.isfinite(lo):
            ax.errorbar([0], [r.probability], yerr=[[max(r.probability - lo, 0.0)],
                                                    [max(hi - r.probability, 0.0)]],
                        color="k", capsize=8)
        interval = f" [{100 * lo:.3g}, {100 * hi:.3g}] %" if np.isfinite(lo) else ""
        title = (f"λ_O = {r.annual_rate:.3g}/yr, return period {r.return_period:.3g} yr\n"
                 f"P = {_pct(r.probability)}{interval} in {outcome.years:g} years")
        if r.open_above:
            most = float(poe_from_rate(r.rate_at_most, r.years))
            ax.bar([0], [most - r.probability], bottom=[r.probability], width=0.5,
                   color="none", edgecolor="tab:red", hatch="///",
                   label="up to this if all shaking above the curve overturned it")
            title = (f"λ_O = {r.annual_rate:.3g} to {r.rate_at_most:.3g}/yr\nP = "
                     f"{_pct(r.probability)} to {_pct(most)} in {outcome.years:g} years")
    if outcome.target is not None:
        ax.axhline(outcome.target, color="k", ls="--", lw=1,
                   label=f"target {100 * outcome.target:g} %")
    ax.set_xticks([0], [f"{outcome.years:g} years"])
    ax.set_xlim(-1, 1)
    ax.set_ylim(0, 1.35 * max(ax.get_ylim()[1], outcome.target or 0.0))
    ax.set_ylabel("P(overturn)")
    ax.set_title(title, fontsize=TITLE_SIZE)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8, loc="upper center")


def figure_map(outcome):
    """Probability in ``years`` over the (one or two) body axes of the grid, the target
    contour drawn and the cells meeting it marked; a body never overturned at its bound,
    written "≤", meeting the target when its bound does."""
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D

    p = outcome.probabilities()
    bounded = np.vectorize(lambda r: getattr(r, "bound", None) is not None,
                           otypes=[bool])(outcome.risks)
    bound_label = (f"≤ : a body never overturned, one-sided {100 * outcome.confidence:g} % "
                   "bound")
    dims = outcome.body_dims
    fig = Figure(figsize=(7, 5.5), layout="constrained")
    ax = fig.subplots()
    if len(dims) == 1:
        values = outcome.body_coords[dims[0]][0]
        ax.plot(values, p, "o-")
        if bounded.any():
            ax.plot(values[bounded], p[bounded], "v", color="tab:red", ls="none",
                    label=bound_label.replace("≤ :", "▼ ≤:"))
        if outcome.target is not None:
            ax.axhline(outcome.target, color="k", ls="--", label=f"target {outcome.target:g}")
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=8)
        ax.set(xlabel=_label(outcome, dims[0]), ylabel=f"P(overturn in {outcome.years:g} yr)")
    else:
        xs, ys = (outcome.body_coords[d][0] for d in dims[:2])
        grid = p if len(dims) == 2 else p.reshape(p.shape[0], p.shape[1], -1)[..., 0]
        bounded = bounded if len(dims) == 2 else \
            bounded.reshape(p.shape[0], p.shape[1], -1)[..., 0]
        positive = grid[np.isfinite(grid) & (grid > 0)]
        norm = LogNorm(positive.min(), positive.max()) if positive.size and \
            positive.max() > 10 * positive.min() else None
        mesh = ax.pcolormesh(xs, ys, grid.T, shading="nearest", cmap=MAP_CMAP, norm=norm)
        for i, x in enumerate(xs):
            for j, y in enumerate(ys):
                _cell_label(ax, mesh, x, y, grid[i, j], bounded[i, j])
        fig.colorbar(mesh, ax=ax, label=f"P(overturn in {outcome.years:g} yr)")
        estimated = np.where(bounded, np.nan, grid)  # the contour: between estimates only
        if outcome.target is not None and np.isfinite(estimated).sum() >= 4 and \
                np.nanmin(estimated) < outcome.target < np.nanmax(estimated):
            ax.contour(xs, ys, estimated.T, levels=[outcome.target], colors=CONTOUR_COLOR,
                       linewidths=2, zorder=2)
            ax.plot([], [], color=CONTOUR_COLOR, lw=2,
                    label=f"P = {outcome.target:g} (target), interpolated")
        if outcome.target is not None:
            ok = np.argwhere(grid <= outcome.target)
            ax.plot(xs[ok[:, 0]], ys[ok[:, 1]], "w*", mec="k", mew=0.6, ms=10, ls="none",
                    zorder=4, label=f"P ≤ {outcome.target:g}: meets the target")
        if bounded.any():
            ax.add_line(Line2D([], [], ls="none", label=bound_label))
        if ax.get_legend_handles_labels()[0]:
            fig.legend(loc="outside lower center", ncols=2, fontsize=8)
        ax.set(xlabel=_label(outcome, dims[0]), ylabel=_label(outcome, dims[1]))
    fixed = outcome.fixed()
    fit_suptitle(fig, [f"risk map: {outcome.name}" + (f", {fixed}" if fixed else "")
                       + _placed(outcome), outcome.curve.source])
    return fig


def figure_options(outcome):
    """The options of a grid side by side: a horizontal bar per body (labelled with its axes'
    values) of P in ``years`` with its interval, the target line, the options meeting it
    marked (by the estimate; ★ also by the upper bound); a body never overturned at its
    bound, hatched."""
    from matplotlib.figure import Figure

    indices = list(np.ndindex(*outcome.shape))
    labels = [outcome.labels()[i] for i in indices]
    p = np.array([outcome.probabilities()[i] for i in indices])
    lower, upper = (np.array([np.nan if outcome.risks[i] is None or outcome.risks[i].bound
                              else outcome.risks[i].probability_interval[side]
                              for i in indices]) for side in (0, 1))
    bounded = [getattr(outcome.risks[i], "bound", None) is not None for i in indices]
    target = outcome.target
    y = np.arange(len(indices))
    fig = Figure(figsize=(7, 1.2 + 0.45 * len(indices)), layout="constrained")
    ax = fig.subplots()
    meets = np.array([target is not None and v <= target for v in p])
    ax.barh(y, np.nan_to_num(p), color=np.where(meets, "tab:green", "tab:gray"),
            label="P, meeting the target (green) or not (grey)")
    if any(bounded):
        ax.barh(y[bounded], p[bounded], color="none", hatch="//", edgecolor="k",
                label=f"never overturned: one-sided {100 * outcome.confidence:g} % bound")
    ax.errorbar(p, y, xerr=[p - lower, upper - p], fmt="none", ecolor="k", capsize=3,
                label=f"{100 * outcome.confidence:g} % interval")
    if target is not None:
        ax.axvline(target, color=CONTOUR_COLOR, ls="--", label=f"target {target:g}")
        sure = meets & (np.where(np.isnan(upper), p, upper) <= target)
        if sure.any():
            ax.plot(p[sure], y[sure], "*", color="w", mec="k", ms=11, ls="none",
                    label="meets it with the upper bound too")
    _annotate_demands(ax, outcome, indices, np.fmax(p, np.nan_to_num(upper)))
    ax.set_yticks(y, labels, fontsize=8)
    ax.invert_yaxis()
    ax.set(xlabel=f"P(overturn in {outcome.years:g} yr)", xlim=(0, None))
    fig.legend(loc="outside lower center", ncols=2, fontsize=8)
    fixed = outcome.fixed()
    fit_suptitle(fig, [f"options: {outcome.name}" + (f", {fixed}" if fixed else "")
                       + _placed(outcome), outcome.curve.source])
    return fig


def _annotate_demands(ax, outcome, indices, right):
    """Beside each option's bar, its isolator's displacement demand at the target's
    probability (``gid`` "isolator_demand")."""
    demands = outcome.demands()
    if demands is None:
        return
    for y, (index, x) in enumerate(zip(indices, right)):
        d = demands[index]
        if d is not None:
            text = "n/a" if d.displacement is None else f"{100 * d.displacement:.3g} cm"
            ax.annotate(f"isolator d* {text} at {100 * d.probability:g} %", (x, y),
                        xytext=(6, 0), textcoords="offset points", va="center", fontsize=7,
                        gid="isolator_demand")
    ax.set_xlim(0, 1.4 * np.nanmax(right))  # room for the words


def _draw_sides(ax, outcome, index, x, n, shown):
    """k/n of the motions that overturned a body with G off the middle to each side, beside
    each stripe where any overturned (``gid`` "left", "right"; docs/bodies.md)."""
    import math

    along = (slice(None),) + index
    sides = outcome.sides
    angles = {"left": sides.alpha_1[index], "right": sides.alpha_2[index]}
    for side, style in SIDE_STYLES.items():
        k = getattr(sides, side)[along]
        ax.plot(x[shown] * SIDE_SHIFT[side], (k / np.maximum(n, 1))[shown], **style, gid=side,
                label=f"fell {'−' if side == 'left' else '+'}x, "
                      f"α_{1 if side == 'left' else 2} {math.degrees(angles[side]):.3g}°")


def _placed(outcome):
    """" on a building's floor" when the stripes' motions are a building's ground (the
    building's keys are in the text and the JSON)."""
    return " on a building's floor" if outcome.placement and \
        outcome.placement.startswith("the ground of a building") else ""


def _cell_label(ax, mesh, x, y, value, bound=False):
    """The probability of a cell below its centre ("≤" before a bound), on a box of the
    cell's colour above the contour, in black or white, whichever contrasts more with that
    colour."""
    if not np.isfinite(value):
        ax.annotate("n/a", (x, y), xytext=(0, -9), textcoords="offset points", ha="center",
                    va="top", fontsize=8, color="0.2")
        return
    colour = mesh.cmap(mesh.norm(value))
    ax.annotate(f"{'≤ ' if bound else ''}{100 * value:.2g} %", (x, y), xytext=(0, -9),
                textcoords="offset points",
                ha="center", va="top", fontsize=8, zorder=3,
                color="k" if relative_luminance(colour) > BLACK_OR_WHITE else "w",
                bbox={"boxstyle": "round,pad=0.2", "fc": colour, "ec": "none"})


def _label(outcome, dim):
    units = outcome.body_coords[dim][1].get("units")
    return outcome.body_coords[dim][1].get("study_axis", dim) + (
        f" [{units}]" if units not in (None, "1") else "")


def save(fig, path):
    save_figure(fig, path)
