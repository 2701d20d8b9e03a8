"""Figures of a risk report (``sweep.probability.risk_report.RiskOutcome``): per body the
hazard curve, the fragility with its band and the stripes' fractions, the risk integrand over
the IM with the disaggregation of λ_O by segment, and the probability in ``years`` with its
interval; over a grid of bodies the risk map with the contour of the target probability."""
import numpy as np
from matplotlib.colors import LogNorm

from ..io.imt import display_scale
from ..probability import risk as risk_integral
from .style import fit_suptitle, log_axes, save_figure

MAP_CMAP = "viridis"
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
    """Four panels for one body (``index`` into the body shape)."""
    from matplotlib.figure import Figure

    curve, r, f = outcome.curve, outcome.risks[index], outcome.fits[index]
    factor, unit = display_scale(curve.units)
    fig = Figure(figsize=(10, 7.5), layout="constrained")
    (ax_h, ax_f), (ax_i, ax_p) = fig.subplots(2, 2)
    x = np.geomspace(curve.levels[0], curve.levels[-1], 400)
    ax_h.plot(curve.levels / factor, curve.rates, "o-", ms=3, color="k", lw=1,
              label="hazard curve")
    if outcome.stripes:
        for s in outcome.stripes:
            ax_h.axvline(s.level / factor, color="tab:blue", lw=0.6, alpha=0.5)
        ax_h.plot([], [], color="tab:blue", lw=0.6, label="stripes")
    log_axes(ax_h)
    ax_h.set(xlabel=f"{curve.im} [{unit}]", ylabel="annual rate of exceedance [1/yr]",
             title="hazard")
    ax_h.legend(fontsize=8)

    if r is not None:
        log_theta, beta = np.log(r.median), r.beta
        ax_f.plot(x / factor, risk_integral.fragility_at(x, log_theta, beta), color="tab:red",
                  label=f"θ = {r.median / factor:.3g} {unit}, β = {r.beta:.2f}")
        if f is not None:
            lo, hi = f.band(x)
            ax_f.fill_between(x / factor, lo, hi, color="tab:red", alpha=0.2,
                              label=f"{100 * outcome.confidence:g} % band")
    if f is not None and outcome.stripes:
        levels = np.array([s.level for s in outcome.stripes])
        k = outcome.k[(slice(None),) + index]
        n = outcome.n[(slice(None),) + index]
        ax_f.plot(levels / factor, k / np.maximum(n, 1), "ks", ms=4, label="stripes: k/n")
    ax_f.set_xscale("log")
    ax_f.set(xlabel=f"{curve.im} [{unit}]", ylabel="P(overturn | im)", ylim=(-0.02, 1.02),
             title="fragility")
    ax_f.legend(fontsize=8)

    if r is not None:
        density = risk_integral.integrand(curve, x, log_theta, beta)
        ax_i.plot(x / factor, density, color="tab:purple", label="F(x) |dλ/d ln x|")
        ax_i.set_xscale("log")
        twin = ax_i.twinx()
        lower, upper = r.lower[:-1], r.upper[:-1]
        twin.bar(np.sqrt(lower * upper) / factor, r.shares[:-1],
                 width=(upper - lower) / factor, color="tab:orange", alpha=0.35,
                 edgecolor="tab:orange", label="share of λ_O per segment")
        twin.set_ylabel("share of λ_O")
        twin.set_ylim(bottom=0)
        ax_i.set(xlabel=f"{curve.im} [{unit}]", ylabel="risk integrand [1/yr per ln x]",
                 title="which shaking causes it")
        ax_i.legend(fontsize=8, loc="upper left")

        lo, hi = r.probability_interval
        ax_p.bar([0], [r.probability], color="tab:red", width=0.5)
        if np.isfinite(lo):
            ax_p.errorbar([0], [r.probability], yerr=[[max(r.probability - lo, 0.0)],
                                                  [max(hi - r.probability, 0.0)]],
                          color="k", capsize=8)
        if outcome.target is not None:
            ax_p.axhline(outcome.target, color="k", ls="--", lw=1,
                         label=f"target {100 * outcome.target:g} %")
            ax_p.legend(fontsize=8)
        ax_p.set_xticks([0], [f"{outcome.years:g} years"])
        ax_p.set_xlim(-1, 1)
        ax_p.set(ylabel="P(overturn)", title=(
            f"λ_O = {r.annual_rate:.3g}/yr (return period {r.return_period:.3g} yr)\nP = "
            f"{100 * r.probability:.3g} %" + (f" [{100 * lo:.3g}, {100 * hi:.3g}] %"
                                              if np.isfinite(lo) else "")
            + f" in {outcome.years:g} years"))
    else:
        reason = f.reason if f is not None else "no fragility"
        for ax in (ax_i, ax_p):
            ax.text(0.5, 0.5, f"no risk: {reason}", ha="center", va="center", wrap=True,
                    transform=ax.transAxes)
    fit_suptitle(fig, [f"risk of overturning: {outcome.name} — {outcome.labels()[index]}",
                       curve.source])
    return fig


def figure_map(outcome):
    """Probability in ``years`` over the (one or two) body axes of the grid, the target
    contour drawn and the cells meeting it marked."""
    from matplotlib.figure import Figure

    p = outcome.probabilities()
    dims = outcome.body_dims
    fig = Figure(figsize=(7, 5.5), layout="constrained")
    ax = fig.subplots()
    if len(dims) == 1:
        values = outcome.body_coords[dims[0]][0]
        ax.plot(values, p, "o-")
        if outcome.target is not None:
            ax.axhline(outcome.target, color="k", ls="--", label=f"target {outcome.target:g}")
            ax.legend()
        ax.set(xlabel=_label(outcome, dims[0]), ylabel=f"P(overturn in {outcome.years:g} yr)")
    else:
        xs, ys = (outcome.body_coords[d][0] for d in dims[:2])
        grid = p if len(dims) == 2 else p.reshape(p.shape[0], p.shape[1], -1)[..., 0]
        positive = grid[np.isfinite(grid) & (grid > 0)]
        norm = LogNorm(positive.min(), positive.max()) if positive.size and \
            positive.max() > 10 * positive.min() else None
        mesh = ax.pcolormesh(xs, ys, grid.T, shading="nearest", cmap=MAP_CMAP, norm=norm)
        for i, x in enumerate(xs):
            for j, y in enumerate(ys):
                _cell_label(ax, mesh, x, y, grid[i, j])
        fig.colorbar(mesh, ax=ax, label=f"P(overturn in {outcome.years:g} yr)")
        if outcome.target is not None and np.isfinite(grid).sum() >= 4 and \
                np.nanmin(grid) < outcome.target < np.nanmax(grid):
            ax.contour(xs, ys, grid.T, levels=[outcome.target], colors=CONTOUR_COLOR,
                       linewidths=2, zorder=2)
            ax.plot([], [], color=CONTOUR_COLOR, lw=2,
                    label=f"P = {outcome.target:g} (target), interpolated")
        if outcome.target is not None:
            ok = np.argwhere(grid <= outcome.target)
            ax.plot(xs[ok[:, 0]], ys[ok[:, 1]], "w*", mec="k", mew=0.6, ms=10, ls="none",
                    zorder=4, label=f"P ≤ {outcome.target:g}: meets the target")
        if ax.get_legend_handles_labels()[0]:
            fig.legend(loc="outside lower center", ncols=2, fontsize=8)
        ax.set(xlabel=_label(outcome, dims[0]), ylabel=_label(outcome, dims[1]))
    fit_suptitle(fig, [f"risk map: {outcome.name}", outcome.curve.source])
    return fig


def _cell_label(ax, mesh, x, y, value):
    """The probability of a cell below its centre, on a box of the cell's colour above the
    contour, in black or white, whichever contrasts more with that colour."""
    if not np.isfinite(value):
        ax.annotate("n/a", (x, y), xytext=(0, -9), textcoords="offset points", ha="center",
                    va="top", fontsize=8, color="0.2")
        return
    colour = mesh.cmap(mesh.norm(value))
    ax.annotate(f"{100 * value:.2g} %", (x, y), xytext=(0, -9), textcoords="offset points",
                ha="center", va="top", fontsize=8, zorder=3,
                color="k" if relative_luminance(colour) > BLACK_OR_WHITE else "w",
                bbox={"boxstyle": "round,pad=0.2", "fc": colour, "ec": "none"})


def _label(outcome, dim):
    units = outcome.body_coords[dim][1].get("units")
    return dim + (f" [{units}]" if units not in (None, "1") else "")


def save(fig, path):
    save_figure(fig, path)
