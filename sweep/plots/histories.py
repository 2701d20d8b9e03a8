"""Figs 12-16 of Ishiyama (1982): the rocking before an overturning, from our own sweeps.

A panel asks for a kind of rocking and the sweeps it may come from
(``sweep.paper.classify.FIGURE_PANELS``); ``sweep.paper.classify.figure_overturnings`` finds,
among the overturnings of the sweep datasets, the one of that kind nearest to point P
(v = 0.4, a = 1) with its history.  This module draws what it found: θ/α and the floor
acceleration against time, over the whole sweep and over its last cycles with the
classifier's window shaded.  θ > 0 is rotation about the left corner, which a
floor acceleration to the right (a_x > 0) drives.
"""
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.ticker import MaxNLocator

from ..paper.classify import FIGURE_PANELS
from ..paper.plane import value_text
from .scene import body_shape, side_angles
from .style import GAL

LAST_CYCLES = 5  # floor cycles shown before the final excursion at least

def _cell_text(found):
    """'amplitude = 1.1 west; B x H = 5 x 15 cm' and the point of overturning."""
    parts = [value_text(name, value)
             for name, value in found.values.items()]
    h = found.result.history
    ds, i = found.ds, found.index
    a, v = (float(ds[f"{q}_norm_at_overturn"].values.ravel()[i]) for q in "av")
    return (f"{', '.join(parts)}; B × H = {100 * h.attrs['B']:.3g} × {100 * h.attrs['H']:.3g}"
            f" cm\noverturned at t = {found.result.t_overturn:.2f} s, f = "
            f"{found.result.f_at_overturn:.3g} Hz: a = {a:.3g} (B/H) g, v = {v:.3g} v_H")


def _rocking_text(rocking):
    ratio = ("" if np.isnan(rocking.period_ratio)
             else f"T_body/T_floor = {rocking.period_ratio:.2f}, ")
    n = rocking.half_cycles
    return (f"{ratio}phase c = {rocking.phase:+.2f}, {n} rocking half-cycle{'s' * (n != 1)} "
            "before the final excursion")


def _draw_history(ax_theta, ax_floor, found, window):
    """θ/α and the floor acceleration over ``window`` = (t0, t1); the classifier's window
    shaded when it lies inside."""
    h, rocking = found.result.history, found.rocking
    t = h["time"].values
    pick = (t >= window[0]) & (t <= window[1])
    alpha_1, alpha_2 = side_angles(body_shape(h))  # θ = α_1, −α_2: tipping over a corner
    alpha = min(alpha_1, alpha_2)
    ax_theta.plot(t[pick], h["theta"].values[pick] / alpha, color="tab:blue", lw=0.8)
    for level in (alpha_1 / alpha, -alpha_2 / alpha):
        ax_theta.axhline(level, color="0.5", ls=":", lw=0.8, gid="alpha")
    limit = max(2.0, 1.15 * max(alpha_1, alpha_2) / alpha)
    ax_theta.set_ylim(-limit, limit)
    ax_theta.set_ylabel("θ / α")
    ax_floor.plot(t[pick], h["a_x"].values[pick] / GAL, color="tab:red", lw=0.8,
                  label="horizontal")
    if np.any(h["a_y"].values[pick] != 0.0):
        ax_floor.plot(t[pick], h["a_y"].values[pick] / GAL, color="tab:green", lw=0.8,
                      label="vertical")
        ax_floor.legend(loc="upper left", fontsize=7)
    ax_floor.set_ylabel("floor acceleration [gal]")
    ax_floor.set_xlabel("time [s]")
    ax_floor.xaxis.set_major_locator(MaxNLocator(6))
    if window[0] <= rocking.t_start:
        for ax in (ax_theta, ax_floor):
            ax.axvspan(rocking.t_start, rocking.t_final, color="0.85", zorder=0)
            ax.axvline(found.result.t_overturn, color="k", lw=0.8)
    ax_theta.set_xlim(*window)


def _zoom(found):
    """Time window of the last cycles: the classifier's window and at least LAST_CYCLES
    floor cycles before the final excursion, to the overturning."""
    period = 1.0 / found.result.f_at_overturn
    t0 = min(found.rocking.t_start, found.rocking.t_final - LAST_CYCLES * period) - period
    return max(t0, 0.0), found.result.t_overturn + 0.1 * period


def _missing(ax, panel, examined):
    ax.text(0.5, 0.5, f"no overturning from {panel.kind.replace('_', ' ')} rocking\namong the "
                      f"{examined} overturnings of these sweeps", ha="center", va="center",
            transform=ax.transAxes)
    ax.set_axis_off()


def figure_history(found, figure):
    """Figs 12-16: the history before an overturning of each kind.

    Parameters
    ----------
    found : list of (Found or None, int)
        Per panel of the figure, the overturning found (with its history) and how many
        overturnings were examined (``sweep.paper.classify.figure_overturnings``).
    figure : str
        A key of ``FIGURE_PANELS``: one panel (Figs 13-16: the whole sweep and its last
        cycles) or three (Fig. 12: the last cycles of each kind).
    """
    title, panels = FIGURE_PANELS[figure]
    if len(panels) == 1:
        (hit, examined), panel = found[0], panels[0]
        fig, axes = plt.subplots(2, 2, figsize=(13.0, 6.4), layout="constrained",
                                 sharex="col", gridspec_kw={"width_ratios": [1.0, 1.3]})
        if hit is None:
            _missing(axes[0, 0], panel, examined)
            for ax in axes.flat[1:]:
                ax.set_axis_off()
            title += f": overturning from {panel.kind.replace('_', ' ')} rocking"
        else:
            _draw_history(axes[0, 0], axes[1, 0], hit, (0.0, hit.result.t_overturn))
            axes[0, 0].set_title("the whole sweep", fontsize=9)
            _draw_history(axes[0, 1], axes[1, 1], hit, _zoom(hit))
            axes[0, 1].set_title("its last cycles (grey: the cycles classified)", fontsize=9)
            hold = hit.study.excitation.get("hold", "acceleration")
            title += (f": overturning by a constant-{hold} sweep, from "
                      f"{panel.kind.replace('_', ' ')} rocking\n{_cell_text(hit)}\n"
                      f"{_rocking_text(hit.rocking)}")
    else:
        fig, axes = plt.subplots(2, len(panels), figsize=(5.0 * len(panels), 6.4),
                                 layout="constrained", squeeze=False, sharex="col")
        for col, (panel, (hit, examined)) in enumerate(zip(panels, found)):
            if hit is None:
                _missing(axes[0, col], panel, examined)
                axes[1, col].set_axis_off()
                continue
            _draw_history(axes[0, col], axes[1, col], hit, _zoom(hit))
            axes[0, col].set_title(f"{panel.title}\n{_cell_text(hit)}\n"
                                   f"{_rocking_text(hit.rocking)}", fontsize=8)
    fig.suptitle(title, fontsize=10)
    return fig
