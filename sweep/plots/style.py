"""What the figures share: outcome colours, cell edges, log axes with plain numbers, the gal,
the datasets a figure takes, and saving a figure whole.

Only matplotlib's object interface is used here and in the figure modules; the backend is the
caller's (``python -m sweep.plot`` and ``python -m sweep.scene`` choose ``Agg``).
"""
import numpy as np
from matplotlib.colors import BoundaryNorm, ListedColormap
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

from ..io.files import replacing

# outcome code -> colour: failed, no rocking, rocked, overturned
OUTCOME_COLOURS = {-1: "#9e9e9e", 0: "#deebf7", 1: "#fdae6b", 2: "#cb181d"}
GAL = 0.01  # 1 gal = 1 cm/s^2 in m/s^2


# short labels of axes in the paper's body-relative units
RELATIVE_LABELS = {"west": "{} / (B/H) g", "v_H": "{} / v_H", "alpha": "{} / α"}


def axis_label(da):
    """Axis label of a coordinate: ``long name [units]`` (no brackets for a dimensionless
    ratio), or the body-relative form (``amplitude / (B/H) g``) for a level of ``west``,
    ``v_H`` or ``alpha``."""
    unit = da.attrs.get("study_unit")
    if unit in RELATIVE_LABELS:
        return RELATIVE_LABELS[unit].format(da.name)
    name = da.attrs.get("long_name", da.name)
    units = da.attrs.get("units", "")
    return name if units in ("", "1") else f"{name} [{units}]"


def study_axis(coord):
    """The study's name of a coordinate (``study_axis``; its own name in older datasets)."""
    return coord.attrs.get("study_axis", coord.name)


def cell_edges(values, log):
    """Cell edges around centres (geometric midpoints on a log axis)."""
    v = np.asarray(values, dtype=float)
    if v.size == 1:
        return np.array([v[0] * 0.9, v[0] * 1.1]) if log else np.array([v[0] - 0.5, v[0] + 0.5])
    w = np.log(v) if log else v
    mid = 0.5 * (w[1:] + w[:-1])
    e = np.concatenate([[2 * w[0] - mid[0]], mid, [2 * w[-1] - mid[-1]]])
    return np.exp(e) if log else e


def plain_log_axis(axis):
    """Log-scale ticks at 1, 2, 5 x 10^k written as plain numbers (0.2, 50, 100)."""
    axis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
    axis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
    axis.set_minor_formatter(NullFormatter())


def log_axes(ax):
    """Both axes of ``ax`` logarithmic, ticks as plain numbers."""
    ax.set_xscale("log")
    ax.set_yscale("log")
    plain_log_axis(ax.xaxis)
    plain_log_axis(ax.yaxis)


def outcome_colours():
    """Colormap and norm that draw each outcome code in its colour (for ``pcolormesh``)."""
    codes = sorted(OUTCOME_COLOURS)
    cmap = ListedColormap([OUTCOME_COLOURS[c] for c in codes])
    return cmap, BoundaryNorm(np.arange(codes[0] - 0.5, codes[-1] + 1.0), cmap.N)


def as_list(data):
    """A list of datasets from one Dataset or a sequence of them."""
    return [data] if hasattr(data, "data_vars") else list(data)


def save_figure(fig, output, dpi=150):
    """Write ``fig`` to ``output`` whole (a temporary file renamed onto it); format from the
    suffix (png without one)."""
    with replacing(output) as tmp:
        fig.savefig(tmp, dpi=dpi, format=output.suffix.lstrip(".") or "png")
