"""What the figures share: colours, cell edges, log axes, saving, and staying readable.

Outcome colours, cell edges, log axes with plain numbers, the gal, the datasets a figure takes,
saving a figure whole, and what keeps a figure readable: titles of at most two lines
(:func:`fit_suptitle`), labels wrapped to their axes (:func:`fit_texts`) and legends in a
corner free of data, else outside the axes (:func:`place_legend`).

Only matplotlib's object interface is used here and in the figure modules; the backend is the
caller's (``python -m sweep.plot`` and ``python -m sweep.scene`` choose ``Agg``).  Lengths of
text are measured in points with matplotlib's default font (``TextToPath``), so wrapping does
not depend on the backend.
"""
import re

import numpy as np
from matplotlib.collections import Collection, PathCollection
from matplotlib.colors import BoundaryNorm, ListedColormap
from matplotlib.font_manager import FontProperties
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.path import Path
from matplotlib.text import Text
from matplotlib.textpath import TextToPath
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


FEW_DECADES = 3.0  # a log axis over more decades is labelled at powers of 10 only
MOST_DECADES = 7  # powers of 10 labelled at most: every other (third, ...) over more


class SparseLogLocator(LogLocator):
    """Major ticks of a log axis at 1, 2, 5 x 10^k over at most ``FEW_DECADES`` decades;
    over more, at powers of 10, every other (third, ...) one beyond ``MOST_DECADES``, so that
    no labels collide over nine decades."""

    def tick_values(self, vmin, vmax):
        low, high = sorted((vmin, vmax))
        few = not low > 0 or np.log10(high / low) <= FEW_DECADES
        self.set_params(subs=(1.0, 2.0, 5.0) if few else (1.0,),
                        numticks="auto" if few else MOST_DECADES)
        return super().tick_values(vmin, vmax)


def plain_log_axis(axis):
    """Log-scale ticks written as plain numbers (0.2, 50, 100): at 1, 2, 5 x 10^k, at
    powers of 10 over many decades (:class:`SparseLogLocator`)."""
    axis.set_major_locator(SparseLogLocator())
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


# --- text that fits -----------------------------------------------------------------------

TITLE_LINES = 2  # a figure's or a panel's title: at most this many lines
LABEL_LINES = 3  # an axis label wrapped to the length of its axes: at most this many lines
SMALLEST_TITLE_SIZE = 8.0  # points: a long figure title is set smaller down to this size
POINTS_PER_INCH = 72.0
UNBROKEN = re.compile(r"\S*\[[^\]]*\]\S*|\S+")  # the words of a text: '[m s-2]' is one
_MEASURE = TextToPath()


def text_width(text, fontsize):
    """Width [points] of one line of ``text`` at ``fontsize`` [points], default font."""
    return _MEASURE.get_text_width_height_descent(text, FontProperties(size=fontsize),
                                                  ismath=False)[0]


def shorten(line, width, fontsize):
    """``line`` whole if it fits ``width`` [points], else cut after a word (or a character,
    for one long word) and ended with '…'."""
    if text_width(line, fontsize) <= width:
        return line
    words = line.split(" ")
    while len(words) > 1 and text_width(" ".join(words) + " …", fontsize) > width:
        words.pop()
    text = " ".join(words)
    while len(text) > 1 and text_width(text + "…", fontsize) > width:
        text = text[:-1]
    return text.rstrip(" ,;:") + "…"


def wrap_text(text, width, fontsize, max_lines=None):
    """``text`` broken at spaces into lines of at most ``width`` points (its own line breaks
    kept, units in brackets whole, a word too long for a line shortened); beyond
    ``max_lines`` the last line kept ends in '…'."""
    lines = []
    for paragraph in text.split("\n"):
        if text_width(paragraph, fontsize) <= width:  # kept as written
            lines.append(paragraph)
            continue
        line = ""
        for word in UNBROKEN.findall(paragraph):
            trial = f"{line} {word}" if line else word
            if line and text_width(trial, fontsize) > width:
                lines.append(line)
                line = word
            else:
                line = trial
        lines.append(line)
    lines = [shorten(line, width, fontsize) for line in lines]
    if max_lines is not None and len(lines) > max_lines:
        lines[max_lines - 1:] = [shorten(" ".join(lines[max_lines - 1:]) + " …", width,
                                         fontsize)]
    return "\n".join(lines)


def _two_lines(text, width, fontsize):
    """``text`` in at most ``TITLE_LINES`` lines of ``width`` points: wrapped if that is
    enough, else its first line and the rest (joined by '; ') shortened to one line each."""
    wrapped = wrap_text(text, width, fontsize)
    if wrapped.count("\n") < TITLE_LINES:
        return wrapped
    first, *rest = text.split("\n")
    if not rest:
        return wrap_text(text, width, fontsize, max_lines=TITLE_LINES)
    return "\n".join((shorten(first, width, fontsize),
                      shorten("; ".join(rest), width, fontsize)))


def fit_suptitle(fig, lines, fontsize=10.0, **kwargs):
    """The figure's title in at most two lines across its width: ``lines`` (what is drawn;
    the details) wrapped, set smaller down to ``SMALLEST_TITLE_SIZE`` while that takes more
    lines, then each line shortened with '…'.  ``kwargs`` go to ``fig.suptitle``."""
    text = "\n".join(line for line in ([lines] if isinstance(lines, str) else lines) if line)
    width = 0.97 * fig.get_figwidth() * POINTS_PER_INCH
    size = fontsize
    while (size > SMALLEST_TITLE_SIZE
           and wrap_text(text, width, size).count("\n") >= TITLE_LINES):
        size -= 0.5
    return fig.suptitle(_two_lines(text, width, size), fontsize=size, **kwargs)


def _titles(ax):
    """The three title texts of ``ax`` (left, centre, right)."""
    return [t for t in (getattr(ax, "_left_title", None), ax.title,
                        getattr(ax, "_right_title", None)) if t is not None]


def fit_texts(fig):
    """Once the layout has placed the axes: every axis label wrapped to the length of its
    axes (at most ``LABEL_LINES`` lines) and every panel title to the width of its panel (at
    most ``TITLE_LINES``), so that nothing runs into a neighbour or off the figure."""
    fig.draw_without_rendering()  # the constrained layout: the axes' final size
    size = fig.get_size_inches() * POINTS_PER_INCH
    for ax in fig.axes:
        if not ax.get_visible():
            continue
        box = ax.get_position()
        width, height = 0.95 * box.width * size[0], 0.95 * box.height * size[1]
        for label, length in ((ax.xaxis.label, width), (ax.yaxis.label, height)):
            if label.get_text():
                label.set_text(wrap_text(label.get_text(), length, label.get_fontsize(),
                                         max_lines=LABEL_LINES))
        for title in _titles(ax):
            if title.get_text():
                title.set_text(_two_lines(title.get_text(), width, title.get_fontsize()))


# --- legends off the data --------------------------------------------------------------------

# where a legend may go inside its axes, in this order: the corners, then the middles of the edges
LEGEND_CORNERS = ("upper left", "upper right", "lower right", "lower left", "upper center",
                  "lower center", "center left", "center right")
LEGEND_CLEARANCE = 3.0  # points kept between a legend and the nearest datum


def _line_hits(line, box, dpi):
    """Whether a Line2D's markers or segments reach into the display box ``box``."""
    xy = line.get_transform().transform(np.asarray(line.get_xydata(), dtype=float))
    finite = np.all(np.isfinite(xy), axis=1)
    if line.get_marker() not in (None, "None", "", " ") and np.any(finite):
        radius = 0.5 * line.get_markersize() * dpi / POINTS_PER_INCH
        if np.any(_inside(xy[finite], box.padded(radius))):
            return True
    if line.get_linestyle() in ("None", "", " "):
        return False
    for piece in np.split(xy, np.flatnonzero(~finite)):  # the pieces between missing values
        piece = piece[np.all(np.isfinite(piece), axis=1)]
        if len(piece) > 1 and Path(piece).intersects_bbox(box, filled=False):
            return True
    return False


def _inside(points, box):
    return ((points[:, 0] >= box.x0) & (points[:, 0] <= box.x1)
            & (points[:, 1] >= box.y0) & (points[:, 1] <= box.y1))


def _collection_hits(collection, box, dpi):
    """Whether a collection's markers (scatter) or paths (bars, bands, contours) reach into
    ``box``; filled paths also when the box lies inside them."""
    if isinstance(collection, PathCollection) and len(collection.get_offsets()):
        points = collection.get_offset_transform().transform(collection.get_offsets())
        sizes = collection.get_sizes()
        radius = 0.5 * np.sqrt(sizes.max() if len(sizes) else 36.0) * dpi / POINTS_PER_INCH
        return bool(np.any(_inside(points, box.padded(radius))))
    faces = collection.get_facecolor()
    filled = len(faces) > 0 and bool(np.any(np.asarray(faces)[:, 3] > 0))
    transform = collection.get_transform()
    return any(transform.transform_path(path).intersects_bbox(box, filled=filled)
               for path in collection.get_paths())


def covers_data(box, ax, renderer, background=()):
    """Whether the display box ``box`` covers anything ``ax`` draws from data: its lines,
    markers, collections, patches and texts, except the ``background`` artists."""
    box = box.padded(LEGEND_CLEARANCE * ax.figure.dpi / POINTS_PER_INCH)
    dpi = ax.figure.dpi
    for artist in [*ax.lines, *ax.collections, *ax.patches, *ax.texts]:
        if artist in background or not artist.get_visible():
            continue
        if isinstance(artist, Line2D):
            hit = _line_hits(artist, box, dpi)
        elif isinstance(artist, Collection):
            hit = _collection_hits(artist, box, dpi)
        elif isinstance(artist, Patch):
            hit = artist.get_transform().transform_path(artist.get_path()).intersects_bbox(
                box, filled=artist.get_fill())
        elif isinstance(artist, Text):
            hit = bool(artist.get_text()) and artist.get_window_extent(renderer).overlaps(box)
        else:
            hit = False
        if hit:
            return True
    return False


def place_legend(ax, handles=None, corners=LEGEND_CORNERS, background=(), layout=True,
                 outside="right", **kwargs):
    """A legend of ``ax`` in the first of ``corners`` where it covers no data (see
    :func:`covers_data`), else outside the axes, ``outside`` ('right' or 'below') them.

    ``layout=False`` when the figure's layout is already final (a caller placing the legends
    of several panels lays the figure out once); ``kwargs`` go to ``ax.legend``.
    """
    fig = ax.figure
    if layout:
        fig.draw_without_rendering()
    renderer = fig.canvas.get_renderer()
    given = {} if handles is None else {"handles": handles}
    for corner in corners:
        legend = ax.legend(loc=corner, **given, **kwargs)
        if not covers_data(legend.get_window_extent(renderer), ax, renderer, background):
            return legend
    if outside == "below":  # under the x axis's ticks and label
        bottom = ax.transAxes.inverted().transform(
            (0.0, ax.xaxis.get_tightbbox(renderer).y0))[1]
        return ax.legend(loc="upper center", bbox_to_anchor=(0.5, bottom - 0.01),
                         borderaxespad=0.0, **given, **kwargs)
    return ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0,
                     **given, **kwargs)


def place_legends(fig, placements, rounds=3):
    """:func:`place_legend` for every ``(ax, options)`` of ``placements``, the figure laid out
    once; placed again while a legend put outside its axes has changed the layout so that
    one inside now covers data (at most ``rounds`` times)."""
    placed = {}
    again = placements
    for _ in range(rounds):
        fig.draw_without_rendering()
        renderer = fig.canvas.get_renderer()
        again = [(ax, options) for ax, options in again if ax not in placed
                 or _covering(placed[ax], ax, renderer, options.get("background", ()))]
        for ax, options in again:
            placed[ax] = place_legend(ax, layout=False, **options)
        if not any(_outside(placed[ax], ax, renderer) for ax, _ in again):
            break  # the layout is as it was: every legend placed stays right
        again = [(ax, options) for ax, options in placements
                 if not _outside(placed[ax], ax, renderer)]
    return [placed[ax] for ax, _ in placements]


def _outside(legend, ax, renderer):
    """Whether a legend lies (partly) outside its axes, where the layout makes room for it."""
    box = legend.get_window_extent(renderer)
    inside = ax.bbox.padded(1.0)
    return not (inside.contains(box.x0, box.y0) and inside.contains(box.x1, box.y1))


def _covering(legend, ax, renderer, background):
    """Whether a legend inside its axes covers data there (one outside never does)."""
    if _outside(legend, ax, renderer):
        return False
    return covers_data(legend.get_window_extent(renderer), ax, renderer, background)


def legend_columns(fig, labels, fontsize):
    """Columns of a legend under the panels: every entry side by side if that fits the
    figure's width, else one column."""
    width = sum(text_width(label, fontsize) + 4.0 * fontsize for label in labels)
    return len(labels) if width <= 0.95 * fig.get_figwidth() * POINTS_PER_INCH else 1


def save_figure(fig, output, dpi=150):
    """Write ``fig`` to ``output`` whole (a temporary file renamed onto it); format from the
    suffix (png without one)."""
    with replacing(output) as tmp:
        fig.savefig(tmp, dpi=dpi, format=output.suffix.lstrip(".") or "png")
