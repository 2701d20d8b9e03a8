"""What the bodies of a site tell, drawn: ``sweep.probability.site`` beside the paper's limits.

One figure per site.  Left, against the PGA of the motions (log axis, m/s^2 below and g on
top): the overturning fragility of every body with its 95 % Wilson interval (drawn above the
body's own a_o = (B/H) g only: below it the body cannot rock, P = 0 exactly), (a) the bodies
seen overturned (solid lines) and (b) those seen standing (dashed), then (c) the posterior
density of the site's PGA with its quantiles at the stated probabilities.  Right: (d) the
probability that a motion of (PGA, PGV)
reproduces every observation, filled contours, the region at each stated probability as a
line, and the simulated points (filled: consistent).  Ishiyama's deterministic lower limits
a_o (Eq. 14) and v_o (Eq. 16) are drawn as black dotted lines for comparison.
"""
import matplotlib.pyplot as plt
import numpy as np

from ..paper import criteria
from .style import plain_log_axis

G = criteria.G
OVERTURNED_COLOURS = plt.cm.Reds(np.linspace(0.45, 0.95, 6))
STANDING_COLOURS = plt.cm.Blues(np.linspace(0.45, 0.95, 6))
DETERMINISTIC = {"color": "black", "ls": ":", "lw": 1.6}
QUANTILE_COLOUR = "#6a3d9a"


def _g_axis(ax):
    """A top axis in g over an x axis in m/s^2."""
    top = ax.secondary_xaxis("top", functions=(lambda a: a / G, lambda g: g * G))
    top.set_xscale("log")
    plain_log_axis(top.xaxis)
    return top


def _deterministic(ax, lower_limits, vertical_label=True):
    """The deterministic lower limit a_o as a vertical line (None: no limit)."""
    if lower_limits is None:
        return
    a_o = lower_limits["pga"]["value"]
    ax.axvline(a_o, **DETERMINISTIC,
               label=f"a_o = {a_o:.2f} m/s² (Eq. 14, {lower_limits['pga']['body']})"
               if vertical_label else None)


def _fragility_panel(ax, estimate, lower_limits, overturned):
    """The fragility of the bodies seen overturned (solid) or standing (dashed)."""
    levels = np.asarray(estimate.ensemble.levels)
    bodies = [b for b in estimate.bodies if b.overturned == overturned]
    colours = OVERTURNED_COLOURS if overturned else STANDING_COLOURS
    style = "-" if overturned else "--"
    for k, body in enumerate(bodies):
        colour = colours[k % len(colours)]
        ax.fill_between(levels, body.lower, body.upper, where=levels >= body.west,
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
    if bodies:
        ax.legend(fontsize=7.5, loc="upper left", framealpha=0.9)
    else:
        ax.text(0.5, 0.5, "none", transform=ax.transAxes, ha="center", va="center")
    ax.grid(alpha=0.25, which="both")
    ax.tick_params(labelbottom=False)


def _posterior_panel(ax, estimate, lower_limits):
    ax.set_xscale("log")
    plain_log_axis(ax.xaxis)
    post = estimate.posterior
    if post is None:
        ax.text(0.5, 0.5, "no posterior:\n" + estimate.reason, transform=ax.transAxes,
                ha="center", va="center", fontsize=9, wrap=True)
    else:
        ax.fill_between(post.knots, post.density, color=QUANTILE_COLOUR, alpha=0.25, lw=0)
        ax.plot(post.knots, post.density, color=QUANTILE_COLOUR, lw=1.5,
                label="posterior (prior uniform in ln PGA)")
        top = float(np.max(post.density))
        for q, x in zip(estimate.ensemble.probabilities, post.pga):
            ax.axvline(x, color=QUANTILE_COLOUR, lw=1.0, ls="--")
            ax.text(x, 1.08 * top, f"{q:.0%}\n{x:.2f}", ha="center", va="bottom", fontsize=8,
                    color=QUANTILE_COLOUR, bbox={"fc": "white", "ec": "none", "pad": 1.0})
        ax.set_ylim(0, 1.4 * top)
    _deterministic(ax, lower_limits)
    ax.set_xlim(estimate.ensemble.levels[0], estimate.ensemble.levels[-1])
    ax.set_xlabel("PGA of the motion [m/s²]")
    ax.set_ylabel("posterior density per ln PGA")
    ax.set_title("(c) the site's PGA given every body", loc="left", fontsize=10)
    ax.legend(fontsize=8, loc="upper left")
    ax.grid(alpha=0.25, which="both")


def _map_panel(fig, ax, estimate, lower_limits):
    m = estimate.map
    shade = ax.contourf(m.pga, m.pgv, m.probability, levels=np.linspace(0, 1, 11),
                        cmap="Greens", vmin=0, vmax=1.15)
    fig.colorbar(shade, ax=ax, label="P(consistent with every body)", shrink=0.85)
    reached = [(q, region) for q, region in zip(estimate.ensemble.probabilities, m.regions)
               if region is not None]
    if reached:
        lines = ax.contour(m.pga, m.pgv, m.probability, levels=[q for q, _ in reached],
                           colors=QUANTILE_COLOUR, linewidths=1.4)
        ax.clabel(lines, fmt=lambda q: f"{q:.0%}", fontsize=8)
    never = [f"{q:.0%}" for q, region in zip(estimate.ensemble.probabilities, m.regions)
             if region is None]
    consistent = m.consistent == 1
    ax.scatter(m.points_pga[consistent], m.points_pgv[consistent], s=16, color="black",
               zorder=3, label="simulated, consistent")
    ax.scatter(m.points_pga[~consistent], m.points_pgv[~consistent], s=10,
               facecolor="none", edgecolor="#777777", lw=0.7, zorder=3,
               label="simulated, not consistent")
    if lower_limits is not None:
        ax.axvline(lower_limits["pga"]["value"], **DETERMINISTIC)
        v_o = lower_limits["pgv"]["value"]
        ax.axhline(v_o, **DETERMINISTIC, label="a_o, v_o: deterministic lower limits "
                                              "(Eqs. 14, 16)")
        ax.text(m.pga[-1], v_o, f"v_o = {v_o * 100:.1f} cm/s ", ha="right", va="bottom",
                fontsize=8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    plain_log_axis(ax.xaxis)
    plain_log_axis(ax.yaxis)
    ax.set_xlabel("PGA of the motion [m/s²]")
    ax.set_ylabel("PGV of the motion [m/s]")
    title = "(d) motions consistent with every body"
    if never:
        title += f"\n(no motion reaches {', '.join(never)})"
    ax.set_title(title, loc="left", fontsize=10)
    ax.legend(fontsize=8, loc="upper left", framealpha=0.9)


def _heading(estimate, lower_limits):
    site = estimate.site
    where = "" if site.latitude is None else \
        f" ({site.latitude:g}° N, {site.longitude:g}° E)" if site.longitude is not None \
        else f" ({site.latitude:g}° N)"
    lines = [f"{site.name or 'site'}{where}: {len(estimate.bodies)} bodies under "
             f"{len(estimate.members)} motions ({', '.join(estimate.members[:4])}"
             f"{', ...' if len(estimate.members) > 4 else ''}) x "
             f"{len(estimate.ensemble.levels)} PGA levels"]
    if estimate.posterior is not None and lower_limits is not None:
        qs = " / ".join(f"{x:.2f}" for x in estimate.posterior.pga)
        probabilities = " / ".join(f"{q:.0%}" for q in estimate.ensemble.probabilities)
        lines.append(f"PGA at {probabilities}: {qs} m/s²; deterministic a_o ≥ "
                     f"{lower_limits['pga']['value']:.2f} m/s²")
    if estimate.excluded:
        lines.append("kept out (they slide, mu < B/H): "
                     + ", ".join(name for name, _ in estimate.excluded))
    return "\n".join(lines)


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
    _fragility_panel(fallen, estimate, lower_limits, overturned=True)
    _g_axis(fallen).set_xlabel("PGA [g]")
    _fragility_panel(standing, estimate, lower_limits, overturned=False)
    _posterior_panel(density, estimate, lower_limits)
    if estimate.map is not None:
        _map_panel(fig, fig.add_subplot(grid[:, 1]), estimate, lower_limits)
    fig.suptitle(_heading(estimate, lower_limits), fontsize=10.5, x=0.01, ha="left")
    return fig
