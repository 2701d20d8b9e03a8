"""Figs 12-16 of Ishiyama (1982): the rocking before an overturning, from our own sweeps.

A panel asks for a kind of rocking (``sweep.classify``) and the sweeps it may come from.  Among
the overturnings of the given datasets it takes the one of that kind nearest to point P
(v = 0.4, a = 1) in the normalized plane (log distance), simulates it again with its history
and draws θ/α and the floor acceleration against time: over the whole sweep, and over its last
cycles with the classifier's window shaded.  θ > 0 is rotation about the left corner, which a
floor acceleration to the right (a_x > 0) drives.
"""
from collections import namedtuple

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

from ..paper import classify, criteria  # noqa: E402
from ..runner import grid  # noqa: E402
from .scene import GAL  # noqa: E402
from .sweeps import POINT_P, _datasets, value_text  # noqa: E402

Panel = namedtuple("Panel", "kind holds steady title")
Panel.__doc__ = """A history to draw: the rocking ``kind``, the sweeps (``holds``) it may come
from, whether it must come from steady rocking (a finite period ratio, not a few cycles), and
the panel's title."""

INVERSE = Panel("inverse_phase", ("acceleration",), True,
                "overturning from inverse phase rocking (constant acceleration)")
SUBHARMONIC = Panel("subharmonic", ("acceleration", "velocity", "displacement"), True,
                    "overturning from subharmonic rocking")
FIGURE_PANELS = {  # figure: (title, panels); a one-panel title is completed by the sweep
    "fig12": ("Fig. 12: three kinds of rocking motion before overturning",
              (INVERSE, SUBHARMONIC,
               Panel("in_phase", ("velocity", "displacement"), False,
                     "overturning from in phase rocking (constant velocity or displacement)"))),
    "fig13": ("Fig. 13", (INVERSE,)),
    "fig14": ("Fig. 14", (SUBHARMONIC,)),
    "fig15": ("Fig. 15", (Panel("in_phase", ("velocity",), False, ""),)),
    "fig16": ("Fig. 16", (Panel("in_phase", ("displacement",), False, ""),)),
}
LAST_CYCLES = 5  # floor cycles shown before the final excursion at least

Found = namedtuple("Found", "ds study index result rocking")
Found.__doc__ = """An overturning of the wanted kind: its dataset, study, cell id, the scene
result with its history, and the classification."""


def _distance_to_p(ds, cells):
    """Log distance of the cells' overturning points from P in the normalized plane."""
    v = ds["v_norm_at_overturn"].values.ravel()[cells]
    a = ds["a_norm_at_overturn"].values.ravel()[cells]
    return np.hypot(np.log(v / POINT_P[0]), np.log(a / POINT_P[1]))


def find_overturning(datasets, panel):
    """The overturning of ``panel.kind`` nearest to P among the sweeps holding one of
    ``panel.holds`` (a ``Found``, or None), and the number of overturnings examined."""
    candidates = []
    for k, ds in enumerate(datasets):
        study = classify.study_of(ds)
        if study.excitation.get("hold", "acceleration") not in panel.holds:
            continue
        cells = classify.overturned_cells(ds)
        candidates += [(d, k, int(i), study) for d, i in zip(_distance_to_p(ds, cells), cells)]
    for examined, (_, k, index, study) in enumerate(sorted(candidates, key=lambda c: c[:3])):
        result = classify.simulate_cell(study, index)
        rocking = classify.classify_result(result)
        steady = rocking is not None and not np.isnan(rocking.period_ratio)
        if rocking is not None and rocking.kind == panel.kind and (steady or not panel.steady):
            return Found(datasets[k], study, index, result, rocking), examined + 1
    return None, len(candidates)


def _cell_text(found):
    """'amplitude = 1.1 west; B x H = 5 x 15 cm' and the point of overturning."""
    parts = [value_text(name, value)
             for name, value in grid.cell_values(found.study, found.index).items()]
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
    alpha = float(criteria.body_constants(h.attrs["B"], h.attrs["H"]).alpha)
    ax_theta.plot(t[pick], h["theta"].values[pick] / alpha, color="tab:blue", lw=0.8)
    for level in (-1.0, 1.0):
        ax_theta.axhline(level, color="0.5", ls=":", lw=0.8)
    ax_theta.set_ylim(-2.0, 2.0)
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


def figure_history(data, figure):
    """Figs 12-16 from sweep datasets: the history before an overturning of each kind.

    Parameters
    ----------
    data : xarray.Dataset or sequence of them
        Datasets of sweep studies (``sweep.run``).
    figure : str
        A key of ``FIGURE_PANELS``: one panel (Figs 13-16: the whole sweep and its last
        cycles) or three (Fig. 12: the last cycles of each kind).
    """
    title, panels = FIGURE_PANELS[figure]
    datasets = _datasets(data)
    found = [find_overturning(datasets, panel) for panel in panels]
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
