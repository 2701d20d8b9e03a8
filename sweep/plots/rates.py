"""The sweep rate against the overturning points of frequency sweeps (rate studies).

One panel per rate study (``studies/rate_study_*.yaml``): the quantity a sweep runs through
at overturning (v/v_H for constant acceleration, the paper's curve a; a/((B/H) g) for
constant velocity or displacement, line c) against the octave duration T [s per octave], log
x, one colour per level: the ensemble median with its range (bar), the fit
y = y_inf + c (T/T_0)^-k to the ensemble means (``sweep.paper.rates.fit_slow_limit``, dashed)
and its limit y_inf with its 95 % interval (band at the right, beyond the slowest sweep).
P's v = 0.4 (or West's a = 1) is the grey line.  A second series of a study (e.g. the paper's
fixed 1 ms step beside the adaptive integrator) is drawn with open markers, without its fit.
"""
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.ticker import FixedLocator, FuncFormatter, NullFormatter

from ..paper.criteria import POINT_P
from ..paper.rates import level_fits, rate_cells, summarize, swept_quantity
from .style import as_list, plain_log_axis

REFERENCE = {"v": (POINT_P[0], "P: v = 0.4 v_H"), "a": (POINT_P[1], "West: a = (B/H) g")}
AXIS_LABEL = {"v": "velocity amplitude at overturning / v_H",
              "a": "acceleration amplitude at overturning / ((B/H) g)"}
LIMIT_SPAN = (2.0, 8.0)  # the limit band spans these multiples of the slowest T
SERIES_MARKERS = ("o", "s", "^", "D")
V_TICKS = (0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0)


def _draw_level(ax, summary, s, i, colour, marker, filled, offset):
    """Median and range of level ``i`` of series ``s`` against T (shifted by ``offset`` so
    that series do not hide each other)."""
    T = summary.octave_times * offset
    median = summary.median[s, i]
    bar = np.array([median - summary.low[s, i], summary.high[s, i] - median])
    ax.errorbar(T, median, yerr=bar, color=colour, marker=marker, ms=5, lw=0.9, capsize=2,
                mfc=colour if filled else "white", mec=colour, ls="none")


def _draw_fit(ax, fit, T, colour):
    """The fitted curve from the fastest T to the band, and the limit with its interval."""
    grid = np.geomspace(T.min(), T.max() * LIMIT_SPAN[1], 200)
    ax.plot(grid, fit.value + fit.c * (grid / T.min()) ** -fit.k, color=colour, ls="--", lw=1.0)
    band = T.max() * np.array(LIMIT_SPAN)
    ax.fill_between(band, fit.low, fit.high, color=colour, alpha=0.35, lw=0)
    ax.plot(band, [fit.value] * 2, color=colour, lw=1.8)


def draw_rates(ax, ds):
    """One rate study on ``ax``; returns the legend handles."""
    cells = rate_cells(ds)
    summary = summarize(cells)
    q = swept_quantity(cells.hold)
    colours = plt.cm.viridis(np.linspace(0.0, 0.9, summary.levels.size))
    handles = []
    first_fits = level_fits(summary, 0)  # the first series only: the others are compared
    for s, label in enumerate(cells.labels):
        offset = 1.0 + 0.08 * s
        fits = first_fits if s == 0 else {}
        for i, level in enumerate(summary.levels):
            if not np.any(summary.overturned[s, i]):
                continue
            _draw_level(ax, summary, s, i, colours[i], SERIES_MARKERS[s % 4], s == 0, offset)
            if float(level) in fits:
                _draw_fit(ax, fits[float(level)], summary.octave_times, colours[i])
        if label:
            handles.append(Line2D([], [], color="0.3", marker=SERIES_MARKERS[s % 4], ls="none",
                                  mfc="0.3" if s == 0 else "white", label=label))
    for i, level in enumerate(summary.levels):
        over = summary.overturned[:, i].sum()
        handles.append(Line2D([], [], color=colours[i], marker="o", ls="none",
                              label=f"{level:g} {cells.unit}"
                                    + ("" if over else ": never overturned")))
    value, text = REFERENCE[q]
    ax.axhline(value, color="goldenrod", lw=1.5)
    ax.annotate(text, (0.01, value), xytext=(0, 3), textcoords="offset points", fontsize=8,
                color="darkgoldenrod", xycoords=("axes fraction", "data"))
    if first_fits:
        level, fit = min(first_fits.items(), key=lambda item: item[1].value)
        ax.annotate(f"limit {fit.value:.3f} ({fit.low:.3f}–{fit.high:.3f})\nat {level:g} "
                    f"{cells.unit}", (summary.octave_times.max() * LIMIT_SPAN[0], fit.low),
                    xytext=(0, -4), textcoords="offset points", va="top", fontsize=8)
    ax.set_xscale("log")
    plain_log_axis(ax.xaxis)
    low, high = min(np.nanmin(summary.low), value), np.nanmax(summary.high)
    if q == "v":  # from P's 0.4 to where curve a runs, 0.8-2.5: log, plain ticks
        ax.set_yscale("log")
        ax.yaxis.set_major_locator(FixedLocator(V_TICKS))
        ax.yaxis.set_major_formatter(FuncFormatter(lambda y, _: f"{y:g}"))
        ax.yaxis.set_minor_formatter(NullFormatter())
        ax.set_ylim(0.9 * low, 1.08 * high)
    else:  # a few per cent above West's line
        ax.set_ylim(low - 0.02, high + 0.02)
    ax.set_xlim(summary.octave_times.min() / 1.4, summary.octave_times.max() * LIMIT_SPAN[1])
    ax.set_xlabel("octave duration T of the sweep [s per octave] (slower →)")
    ax.set_ylabel(AXIS_LABEL[q])
    ax.grid(True, which="both", color="0.92", lw=0.5)
    direction = "down" if q == "v" else "up"
    ax.set_title(f"constant {cells.hold}, swept {direction}: {cells.body}", fontsize=9)
    handles += [Line2D([], [], color="0.3", ls="--", label="fit y_inf + c (T/T_0)^-k"),
                Patch(color="0.3", alpha=0.35, label="its limit T → ∞, 95 % interval")]
    return handles


def figure_rates(datasets):
    """Overturning against the sweep rate, one panel per rate study.

    Parameters
    ----------
    datasets : xarray.Dataset or sequence of them
        Datasets of rate studies (``studies/rate_study_*.yaml``): frequency sweeps with an
        ``amplitude`` axis, a duration axis and an ensemble (``phase`` or ``seed``).
    """
    datasets = as_list(datasets)
    columns = min(2, len(datasets))
    rows = -(-len(datasets) // columns)
    fig, axes = plt.subplots(rows, columns, figsize=(7.4 * columns, 6.6 * rows),
                             layout="constrained", squeeze=False)
    for ax, ds in zip(axes.flat, datasets):
        handles = draw_rates(ax, ds)
        ax.legend(handles=handles, fontsize=7, loc="upper center", ncols=4,
                  bbox_to_anchor=(0.5, -0.12), frameon=False)
    for ax in axes.flat[len(datasets):]:
        ax.set_axis_off()
    fig.suptitle("Overturning against the sweep rate: median over the starting phases "
                 "(bar: their range), fitted and extrapolated to infinitely slow sweeps",
                 fontsize=10)
    return fig
