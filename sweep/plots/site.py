"""What the bodies of a site tell, drawn: ``sweep.probability.site`` beside the paper's limits.

One figure per site, in the units of the command's text (gal for accelerations, cm/s for
velocities), so that every number on it can be found there.  Left, against the PGA of the
motions (log axis, gal): the overturning fragility of every body with its 95 % Wilson
interval (drawn above the body's own a_o = (B/H) g only: below it the body cannot rock,
P = 0 exactly), (a) the bodies seen overturned (solid lines) and (b) those seen standing
(dashed), then (c) the posterior density of the site's PGA with its quantiles at the stated
probabilities.  Right: (d) the probability that a motion of (PGA, PGV) reproduces every
observation, filled contours, the region at each stated probability as a line, and the
simulated points (filled: consistent).  Ishiyama's deterministic lower limits
a_o (Eq. 14) and v_o (Eq. 16) are drawn as black dotted lines for comparison.  The heading
takes two lines at most; each legend sits in a corner free of data, else outside its panel
(``style.place_legend``).
"""
import matplotlib.pyplot as plt
import numpy as np

from ..probability.fragility import counted
from .style import GAL, fit_suptitle, fit_texts, place_legends, plain_log_axis

CM = 100.0  # cm/s per m/s
OVERTURNED_COLOURS = plt.cm.Reds(np.linspace(0.45, 0.95, 6))
STANDING_COLOURS = plt.cm.Blues(np.linspace(0.45, 0.95, 6))
DETERMINISTIC = {"color": "black", "ls": ":", "lw": 1.6}
QUANTILE_COLOUR = "#6a3d9a"


def _gal(a):
    """An acceleration [m/s^2] in gal, written with the arithmetic of the text
    (``sweep.probability.site_report.format_text``): '331'."""
    return f"{a * 100:.0f}"


def _deterministic(ax, lower_limits, vertical_label=True):
    """The deterministic lower limit a_o as a vertical line on an axis in gal (None: no
    limit)."""
    if lower_limits is None:
        return
    a_o = lower_limits["pga"]["value"]
    ax.axvline(a_o / GAL, **DETERMINISTIC,
               label=f"a_o = {_gal(a_o)} gal (Eq. 14, {lower_limits['pga']['body']})"
               if vertical_label else None)


def _fragility_panel(ax, estimate, lower_limits, overturned):
    """The fragility of the bodies seen overturned (solid) or standing (dashed)."""
    levels = np.asarray(estimate.ensemble.levels) / GAL
    bodies = [b for b in estimate.bodies if b.overturned == overturned]
    colours = OVERTURNED_COLOURS if overturned else STANDING_COLOURS
    style = "-" if overturned else "--"
    for k, body in enumerate(bodies):
        colour = colours[k % len(colours)]
        ax.fill_between(levels, body.lower, body.upper, where=levels >= body.west / GAL,
                        color=colour, alpha=0.1, lw=0)
        flag = ", slid near its bound" if body.slid_near_bound else ""
        ax.plot(levels, body.fragility, style, color=colour, lw=1.8, marker="o", ms=3,
                label=f"{body.name}{flag}")
    _deterministic(ax, lower_limits)
    ax.set_xscale("log")
    plain_log_axis(ax.xaxis)
    ax.set_ylim(-0.03, 1.03)
    ax.set_ylabel("P(overturn | PGA)")
    state = ("(a) bodies seen overturned (lower bounds)" if overturned else
             "(b) bodies seen standing (upper bounds)")
    ax.set_title(f"{state}: fragility, 95 % Wilson band above a_o", loc="left", fontsize=10)
    if not bodies:
        ax.text(0.5, 0.5, "none", transform=ax.transAxes, ha="center", va="center")
    ax.grid(alpha=0.25, which="both")
    ax.tick_params(labelbottom=False)
    return bool(bodies)


def _posterior_panel(ax, estimate, lower_limits):
    ax.set_xscale("log")
    plain_log_axis(ax.xaxis)
    post = estimate.posterior
    if post is None:
        ax.text(0.5, 0.5, "no posterior:\n" + estimate.reason, transform=ax.transAxes,
                ha="center", va="center", fontsize=9, wrap=True)
    else:
        knots = np.asarray(post.knots) / GAL
        ax.fill_between(knots, post.density, color=QUANTILE_COLOUR, alpha=0.25, lw=0)
        ax.plot(knots, post.density, color=QUANTILE_COLOUR, lw=1.5,
                label="posterior (prior uniform in ln PGA)")
        top = float(np.max(post.density))
        quantiles = estimate.quantiles
        for q, x in zip(estimate.ensemble.probabilities, () if quantiles is None else
                        quantiles[0]):
            ax.axvline(x / GAL, color=QUANTILE_COLOUR, lw=1.0, ls="--")
            ax.text(x / GAL, 1.08 * top, f"{q:.0%}\n{_gal(x)}", ha="center", va="bottom",
                    fontsize=8, color=QUANTILE_COLOUR,
                    bbox={"fc": "white", "ec": "none", "pad": 1.0})
        if quantiles is None:
            ax.text(0.02, 0.97, f"percentiles withheld: carried by only\n"
                    f"{estimate.support.text()}", transform=ax.transAxes, ha="left",
                    va="top", fontsize=8, color=QUANTILE_COLOUR)
        ax.set_ylim(0, 1.4 * top)
    _deterministic(ax, lower_limits)
    ax.set_xlim(estimate.ensemble.levels[0] / GAL, estimate.ensemble.levels[-1] / GAL)
    ax.set_xlabel("PGA of the motion [gal]")
    ax.set_ylabel("posterior density per ln PGA")
    ax.set_title("(c) the site's PGA given every body (quantiles in gal)", loc="left",
                 fontsize=10)
    ax.grid(alpha=0.25, which="both")


def _map_panel(fig, ax, estimate, lower_limits):
    m = estimate.map
    pga, pgv = np.asarray(m.pga) / GAL, np.asarray(m.pgv) * CM  # gal, cm/s
    shade = ax.contourf(pga, pgv, m.probability, levels=np.linspace(0, 1, 11),
                        cmap="Greens", vmin=0, vmax=1.15)
    fig.colorbar(shade, ax=ax, label="P(consistent with every body)", shrink=0.85)
    reached = [(q, region) for q, region in zip(estimate.ensemble.probabilities, m.regions)
               if region is not None]
    if reached:
        lines = ax.contour(pga, pgv, m.probability, levels=[q for q, _ in reached],
                           colors=QUANTILE_COLOUR, linewidths=1.4)
        ax.clabel(lines, fmt=lambda q: f"{q:.0%}", fontsize=8)
    never = [f"{q:.0%}" for q, region in zip(estimate.ensemble.probabilities, m.regions)
             if region is None]
    consistent = m.consistent == 1
    points_pga, points_pgv = np.asarray(m.points_pga) / GAL, np.asarray(m.points_pgv) * CM
    ax.scatter(points_pga[consistent], points_pgv[consistent], s=16, color="black",
               zorder=3, label="simulated, consistent")
    ax.scatter(points_pga[~consistent], points_pgv[~consistent], s=10,
               facecolor="none", edgecolor="#777777", lw=0.7, zorder=3,
               label="simulated, not consistent")
    if lower_limits is not None:
        ax.axvline(lower_limits["pga"]["value"] / GAL, **DETERMINISTIC)
        v_o = lower_limits["pgv"]["value"]
        ax.axhline(v_o * CM, **DETERMINISTIC, label="a_o, v_o: deterministic lower limits "
                                                   "(Eqs. 14, 16)")
        ax.text(pga[-1], v_o * CM, f"v_o = {v_o * CM:.3g} cm/s ", ha="right", va="bottom",
                fontsize=8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    plain_log_axis(ax.xaxis)
    plain_log_axis(ax.yaxis)
    ax.set_xlabel("PGA of the motion [gal]")
    ax.set_ylabel("PGV of the motion [cm/s]")
    title = "(d) motions consistent with every body"
    if never:
        title += f"\n(no motion reaches {', '.join(never)})"
    ax.set_title(title, loc="left", fontsize=10)
    return shade


def _heading(estimate, lower_limits):
    site = estimate.site
    where = "" if site.latitude is None else \
        f" ({site.latitude:g}° N, {site.longitude:g}° E)" if site.longitude is not None \
        else f" ({site.latitude:g}° N)"
    first = (f"{site.name or 'site'}{where}: {len(estimate.bodies)} bod{'y' if len(estimate.bodies) == 1 else 'ies'} under "
             f"{counted(len(estimate.members), 'motion')} ({', '.join(estimate.members[:4])}"
             f"{', ...' if len(estimate.members) > 4 else ''}) x "
             f"{len(estimate.ensemble.levels)} PGA levels")
    second = []
    if estimate.quantiles is not None:
        qs = " / ".join(_gal(x) for x in estimate.quantiles[0])
        probabilities = " / ".join(f"{q:.0%}" for q in estimate.ensemble.probabilities)
        second.append(f"PGA at {probabilities}: {qs} gal")
    elif estimate.posterior is not None:
        second.append(f"percentiles withheld ({estimate.support.text()})")
    if lower_limits is not None:
        second.append(f"deterministic a_o ≥ {_gal(lower_limits['pga']['value'])} gal")
    if estimate.excluded:
        second.append("kept out (they slide, mu < B/H): "
                      + ", ".join(name for name, _ in estimate.excluded))
    return [first, "; ".join(second)]


def figure_site(estimate, lower_limits=None):
    """The figure of one site.

    Parameters
    ----------
    estimate : sweep.probability.site.SiteEstimate
    lower_limits : dict, optional
        ``lower_limits`` of ``sweep.paper.estimate.estimate`` (None: no overturned body gives
        one).

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig = plt.figure(figsize=(14.0, 9.5), layout="constrained")
    grid = fig.add_gridspec(3, 2, width_ratios=(1.0, 1.05), height_ratios=(1.0, 1.0, 0.9))
    fallen = fig.add_subplot(grid[0, 0])
    standing = fig.add_subplot(grid[1, 0], sharex=fallen)
    density = fig.add_subplot(grid[2, 0], sharex=fallen)
    legends = [(ax, {"fontsize": 7.5}) for ax, overturned in ((fallen, True),
                                                             (standing, False))
               if _fragility_panel(ax, estimate, lower_limits, overturned)]
    _posterior_panel(density, estimate, lower_limits)
    if density.get_legend_handles_labels()[0]:
        legends.append((density, {"fontsize": 8}))
    if estimate.map is not None:
        consistency = fig.add_subplot(grid[:, 1])
        shade = _map_panel(fig, consistency, estimate, lower_limits)
        legends.append((consistency, {"fontsize": 8, "background": [shade],
                                      "outside": "below"}))
    fit_suptitle(fig, _heading(estimate, lower_limits), fontsize=10.5, x=0.01, ha="left")
    fit_texts(fig)
    place_legends(fig, [(ax, {"framealpha": 0.9, **options}) for ax, options in legends])
    return fig
