"""Pictures of one scene: the body's positions while it moves, with its histories; an animation.

Successive positions (the paper's Figs 3-5) beside theta/alpha, the floor acceleration of each
moving component and the motion type, under a title that says what the body did
(``runner.verdict``).

Every panel is scaled to its data: a floor component that is zero throughout gets no panel
(a note says so), and the lines where the body tips over a corner, theta = alpha_1 and
theta = -alpha_2 (theta/alpha = ±1 for a symmetric body), are drawn only when the rocking comes
within a factor of two of alpha (else a note names them).  The body is drawn from G with its
own base corners and G marked (docs/bodies.md).
"""
import math
import sys

import matplotlib.pyplot as plt
import numpy as np

from kernels.codes import MODE_NAMES, REST

from ..runner.verdict import verdict
from .gif import FPS, MAX_FPS, estimated_size, frame_step, save_gif
from .style import GAL

MAX_OUTLINES = 150            # more outlines than this blur into a smear
TITLE_WIDTH = 100             # characters of a scene plot's title line (13 pt over 12 inches)
CAPTION_WIDTH = 200           # ... of its caption's lines (7 pt)
ANIMATION_TITLE_WIDTH = 80    # ... of an animation's (8 pt over 5 inches)
NAME_WIDTH = 72               # characters of the scene's name under it (a path's end if longer)
WINDOW_MARGIN = 0.5           # s an animation shows before the first motion and after the last
STILL_SPAN = 2.0              # s an animation shows of a body that never moves
HEADING_LINE = 8 * 1.3 / 72   # inches of a heading line of an animation (8 pt)
HEADING_PAD = 0.12            # inches above and below the heading
TIME_LINE = 0.3               # inches of the frame's time line above the view (9 pt, padded)
BELOW_VIEW = 0.5              # inches below the view: tick labels and the x label
SIZE_SAMPLES = 5              # runs of successive frames encoded to estimate a GIF's size
GOLDEN = (math.sqrt(5) - 1) / 2
ALPHA_LINE_REACH = 0.5        # theta/alpha = ±1 drawn when max |theta|/alpha is at least this
FLOOR_MARKS = 12              # hatch marks under the floor across the animation's view
FLOOR = {"a_x": ("horizontal", "tab:red"), "a_y": ("vertical", "tab:green")}
ROCK = "rock"  # body_form of a history whose body was given by alpha_1, alpha_2 (R_i or h)
G_STYLE = {"marker": "o", "color": "tab:red", "ms": 4, "ls": "none"}  # G marked


def outline(x, y, theta, shape):
    """The outline (closed) of the body with G at (x, y) at angle theta; ``shape``: its
    vertices from G in the body, corner 1 and corner 2 first (:func:`body_shape`)."""
    c, s = np.cos(theta), np.sin(theta)
    local = np.vstack([shape, shape[:1]])
    return x + local[:, 0] * c - local[:, 1] * s, y + local[:, 0] * s + local[:, 1] * c


def body_shape(ds):
    """The vertices of the body's outline from G [m], shape (n, 2): the base corners
    (-b1, -y_G) and (b2, -y_G) first, from the attributes ``B``, ``H``, G (``x_G``, ``y_G``;
    default the middle) and ``body_form`` of a history Dataset.  A body given by B and H is
    the B x H rectangle; a rock (``body_form`` ``rock``: alpha_1, alpha_2 with R_1, R_2 or
    h) is known by its base corners and G only, and drawn as the triangle of its base and
    the point at height H above the base over G."""
    B, H = float(ds.attrs["B"]), float(ds.attrs["H"])
    x_G, y_G = float(ds.attrs.get("x_G", 0.0)), float(ds.attrs.get("y_G", 0.5 * H))
    left, right, top = -0.5 * B - x_G, 0.5 * B - x_G, H - y_G
    if ds.attrs.get("body_form") == ROCK:
        return np.array([[left, -y_G], [right, -y_G], [0.0, top]])
    return np.array([[left, -y_G], [right, -y_G], [right, top], [left, top]])


def side_angles(shape):
    """(alpha_1, alpha_2) [rad]: atan(b_i / y_G) of the base corners of a body shape, the
    angles of theta at which the body tips over corner 1 (theta > 0) and corner 2."""
    (left, bottom), (right, _) = shape[:2]
    return math.atan2(-left, -bottom), math.atan2(right, -bottom)


def slenderness(shape):
    """The smaller side's slenderness angle atan(b_i / y_G) of a body shape [rad]."""
    return min(side_angles(shape))


def scene_verdict(ds):
    """What the body did (``verdict.verdict``) from a history Dataset whose attributes hold
    the scene's result (``cf.history_dataset``), or None when they do not."""
    if "status" not in ds.attrs:
        return None
    attrs = ds.attrs
    modes = ds["mode"].attrs["flag_meanings"].split()
    return verdict({**{key: attrs[key] for key in (
        "status", "t_overturn", "overturn_direction", "impact_count", "max_abs_theta",
        "max_slip", "max_lift", "t_rest", "B", "H")},
        "alpha": slenderness(body_shape(ds)),
        "mode_time": dict(zip(modes, np.atleast_1d(attrs["mode_time"]).tolist())),
        "t_final": float(ds["time"].values[-1])})


def quiet_components(ds):
    """The floor components (``a_x``, ``a_y``) that are zero throughout."""
    return [name for name in FLOOR if not np.any(ds[name].values)]


def _outlines(ds, shape):
    """Outlines of the body while it moves (from the sample before it leaves rest to the one
    after it comes back for good; the whole history if it never moves), at most
    ``MAX_OUTLINES``: (xs, ys) in cm of shape (n, vertices + 1), G's (x, y) in cm at each,
    the time between two, first and last."""
    t = ds["time"].values
    moving = np.flatnonzero(ds["mode"].values != REST)
    first, last = (max(moving[0] - 1, 0), min(moving[-1] + 1, t.size - 1)) if moving.size \
        else (0, t.size - 1)
    stride = max(1, int(np.ceil((last - first + 1) / MAX_OUTLINES)))
    pick = slice(first, last + 1, stride)
    x, y = ds.x.values[pick, None], ds.y.values[pick, None]
    xs, ys = outline(x, y, ds.theta.values[pick, None], shape)
    every = stride * (t[1] - t[0]) if t.size > 1 else 0.0
    return xs * 100, ys * 100, (x[:, 0] * 100, y[:, 0] * 100), every, t[first], t[pick][-1]


def _draw_positions(ax, xs, ys, centres, every, t_first, t_last, rock=False):
    """The outlines coloured by time, G marked at the first and the last (``gid`` "outline"
    and "G"); a rock's outline named as what it is."""
    for px, py, colour in zip(xs, ys, plt.cm.viridis(np.linspace(0, 1, len(xs)))):
        ax.plot(px, py, color=colour, lw=0.6, gid="outline")
    ax.plot(*(np.asarray(c)[[0, -1]] for c in centres), **G_STYLE, gid="G")
    ax.axhline(0, color="k", lw=1.5)
    ax.set_aspect("equal")
    ax.set_xlabel("x relative to the floor [cm]")
    ax.set_ylabel("height [cm]")
    drawn = "rock: base corners, G (red),\napex at H above the base" if rock else "G in red"
    ax.set_title(f"positions every {every:.3g} s\n(colour: time {t_first:.2f} → "
                 f"{t_last:.2f} s)\n{drawn}", fontsize=9)


def _wrap(text, width):
    """``text`` in lines of ``width`` characters or fewer, broken after commas only."""
    lines = [""]
    for part in text.split(", "):
        if lines[-1] and len(lines[-1]) + 2 + len(part) > width:
            lines[-1] += ","
            lines.append(part)
        else:
            lines[-1] += f", {part}" if lines[-1] else part
    return "\n".join(lines)


def _note(ax, text):
    """A small grey line above the right end of ``ax``, after what is there."""
    said = ax.get_title(loc="right")
    ax.set_title(f"{said}; {text}" if said else text, loc="right", fontsize=8, color="0.4")


def _draw_theta(ax, ds, sides):
    """θ/α (α the smaller of ``sides`` = (α_1, α_2)) on an axis scaled to it; the lines
    θ = α_1 and θ = −α_2 (where the body tips past corner 1 or 2: θ/α = ±1 for a symmetric
    body) drawn faintly when within reach, else named."""
    alpha = min(sides)
    ratio = ds.theta.values / alpha
    peak = float(np.max(np.abs(ratio)))
    levels = (sides[0] / alpha, -sides[1] / alpha)
    ax.plot(ds["time"].values, ratio, lw=1, color="tab:blue")
    ax.axhline(0, color="0.8", lw=0.6, zorder=0)
    limit = 1.15 * peak if peak > 0 else 1.0
    symmetric = sides[0] == sides[1]
    if peak >= ALPHA_LINE_REACH:
        for level, name in zip(levels, ("α_1", "−α_2")):
            ax.axhline(level, color="0.6", ls=":", lw=0.8, gid="alpha")
            if not symmetric:
                ax.annotate(f"θ = {name}", (1.0, level), xycoords=("axes fraction", "data"),
                            xytext=(-2, 2), textcoords="offset points", ha="right",
                            fontsize=7, color="0.4")
        limit = max(limit, 1.15 * max(abs(level) for level in levels))
    else:
        _note(ax, "overturning at θ/α = ±1, off this scale" if symmetric else
              f"overturning at θ/α = {levels[0]:.3g} (α_1) and {levels[1]:.3g} (−α_2), "
              "off this scale")
    ax.set_ylim(-limit, limit)
    governing = "" if symmetric else "α_1 = " if sides[0] < sides[1] else "α_2 = "
    ax.set_ylabel(f"θ / α\n(α = {governing}{alpha:.3g} rad)")


def draw_scene(ds, name="", caption=()):
    """Positions, θ/α, the moving floor components and the motion type from a history
    Dataset (``cf.history_dataset``): a matplotlib Figure titled with what the body did
    (:func:`scene_verdict`) over ``name`` (the scene's file or name), smaller, and captioned
    with the lines of ``caption`` (how each record was read, ``records.provenance_line``)."""
    shape = body_shape(ds)
    quiet = quiet_components(ds)
    moving = [component for component in FLOOR if component not in quiet]
    xs, ys, *positions = _outlines(ds, shape)
    # the positions panel as wide as the body's sweep needs beside the 5-inch-high panels
    aspect = np.ptp(xs) / max(np.max(ys) - min(np.min(ys), 0.0), 1e-9)
    fig = plt.figure(figsize=(12, 6.5), layout="constrained")
    title = scene_verdict(ds)
    if title:
        fig.suptitle(_wrap(title, TITLE_WIDTH), fontsize=13)
    body = fig.subfigures(1, 1)
    if name:
        body.suptitle(name, fontsize=9, color="0.35")
    heights = [1.5, *[1.0] * len(moving), 0.9]
    grid = body.add_gridspec(len(heights), 2, height_ratios=heights,
                             width_ratios=[float(np.clip(aspect * 0.8, 0.3, 1.2)), 1])
    _draw_positions(body.add_subplot(grid[:, 0]), xs, ys, *positions,
                    rock=ds.attrs.get("body_form") == ROCK)
    ax_theta = body.add_subplot(grid[0, 1])
    _draw_theta(ax_theta, ds, side_angles(shape))
    t = ds["time"].values
    for row, component in enumerate(moving, start=1):
        label, colour = FLOOR[component]
        ax = body.add_subplot(grid[row, 1], sharex=ax_theta)
        ax.plot(t, ds[component].values / GAL, lw=0.8, color=colour)
        ax.axhline(0, color="0.8", lw=0.6, zorder=0)
        ax.set_ylabel(f"{label} floor\nacc. [gal]")
    if moving and quiet:
        _note(body.axes[-1], f"no {FLOOR[quiet[0]][0]} floor motion")
    elif quiet:
        _note(ax_theta, "the floor does not move")
    ax_mode = body.add_subplot(grid[-1, 1], sharex=ax_theta)
    ax_mode.step(t, ds["mode"].values, where="post", lw=1)
    ax_mode.set_yticks(range(len(MODE_NAMES)), [m.replace("_", " ") for m in MODE_NAMES],
                       fontsize=7)
    ax_mode.set_ylim(-0.5, len(MODE_NAMES) - 0.5)
    ax_mode.set_xlabel("time [s]")
    for ax in body.axes[1:-1]:
        ax.tick_params(labelbottom=False)
    if caption:
        fig.supxlabel("\n".join(_wrap(line, CAPTION_WIDTH) for line in caption), fontsize=7,
                      color="0.35", ha="left", x=0.01)
    return fig


def floor_displacement(a_x, dt):
    """Displacement of the floor [m] from its acceleration sampled every ``dt``, after the
    baseline correction of ``sweep.groundmotion.intensity`` (PGV and PGD use the same): a
    record that does not end at rest, or a sine started from rest, would otherwise drift."""
    from ..groundmotion.intensity import PAD_S, integrated

    if not np.any(a_x):
        return np.zeros_like(a_x)
    pad = int(round(PAD_S / dt))
    return integrated(a_x, dt)[1][pad:pad + a_x.size]


def animation_window(ds, start=None, end=None):
    """``(t0, t1, how)``: the times [s] an animation shows, and how they were chosen (words).

    By default from ``WINDOW_MARGIN`` before the body first leaves rest to ``WINDOW_MARGIN``
    after it last moves (its final rest; an overturning or a motion that lasts to the end of
    the history ends there), within the history; a body that never moves: the first
    ``STILL_SPAN``.  ``start`` and ``end`` given replace either end; the other one stays the
    default's where that leaves a window, else it is the history's own end.

    Raises
    ------
    ValueError
        ``start`` at or after the history's end, or ``end`` at or before its start, or
        ``end`` not after ``start``.
    """
    t = ds["time"].values
    moving = np.flatnonzero(ds["mode"].values != REST)
    if moving.size:
        t0, t1 = t[moving[0]] - WINDOW_MARGIN, t[moving[-1]] + WINDOW_MARGIN
        since = "the start" if t0 <= t[0] else f"{WINDOW_MARGIN:g} s before the first motion"
        if moving[-1] == t.size - 1:
            until = ("the overturning" if ds.attrs.get("status") == "overturned"
                     else "the end of the history, still moving")
        else:
            until = f"{WINDOW_MARGIN:g} s after the last (final rest)"
        how = f"from {since} to {until}"
    else:
        t0, t1 = t[0], t[0] + STILL_SPAN
        how = f"the body never moves: the first {STILL_SPAN:g} s"
    t0, t1 = max(t0, t[0]), min(t1, t[-1])
    if start is None and end is None:
        return t0, t1, how
    if start is not None and start >= t[-1]:
        raise ValueError(f"the history ends at {t[-1]:g} s, not after {start:g} s")
    if end is not None and end <= t[0]:
        raise ValueError(f"the history starts at {t[0]:g} s, not before {end:g} s")
    if start is not None and end is not None and not end > start:
        raise ValueError(f"the end {end:g} s is not after the start {start:g} s")
    if start is None:
        start = t0 if t0 < end else t[0]
    if end is None:
        end = t1 if t1 > start else t[-1]
    return max(start, t[0]), min(end, t[-1]), "as asked"


def _size(count):
    """Bytes for people: ``350 kB``, ``3.5 MB``."""
    return f"{count / 1e6:.2g} MB" if count >= 1e6 else f"{max(count / 1e3, 1):.0f} kB"


def _short(name, width):
    """``name`` in ``width`` characters at most: its end, after an ellipsis."""
    return name if len(name) <= width else "…" + name[-(width - 1):]


def animate_scene(ds, path, name="", quiet=False, fps=FPS, start=None, end=None):
    """GIF of the body on the moving floor, in real time: one frame every
    ``gif.frame_step`` (the history sample nearest to it) over :func:`animation_window`
    (by default the motion and ``WINDOW_MARGIN`` either side).

    Before any frame is written, one line on stderr (unless ``quiet``) gives the window and
    how it was chosen, the frame count, the frame rate and the file's estimated size
    (``gif.estimated_size``).  The floor moves by its baseline-corrected displacement
    (:func:`floor_displacement`), so the view, fixed, stays on the body.  The verdict and
    ``name`` head the figure, above the time and motion type of each frame.  The axes are
    drawn once; each frame redraws only the body, the floor, the time and the spines above
    them (as a full drawing stacks them) over that background, and the frames go to the GIF as
    they are drawn (``gif.save_gif``), with a progress line on stderr unless ``quiet``.

    Returns
    -------
    int
        The number of frames written.

    Raises
    ------
    ValueError
        A window outside the history (:func:`animation_window`), or ``fps`` not in (0,
        ``MAX_FPS``].
    """
    from ..runner.progress import Progress, emit
    if not 0 < fps <= MAX_FPS:
        raise ValueError(f"fps must be above 0 and at most {MAX_FPS}, got {fps:g}")
    shape = body_shape(ds)
    b, h = 0.5 * np.ptp(shape, axis=0)
    t = ds["time"].values
    dt = float(t[1] - t[0]) if t.size > 1 else 1.0 / FPS
    t0, t1, how = animation_window(ds, start, end)
    step = frame_step(fps, dt)
    times = t0 + step * np.arange(int(np.floor((t1 - t0) / step + 1e-9)) + 1)
    frames = np.unique(np.rint((times - t[0]) / dt).astype(int))
    frames = frames[frames < t.size]
    d_floor = floor_displacement(ds.a_x.values, dt)
    x_abs = d_floor + ds.x.values
    y, theta, mode = ds.y.values, ds.theta.values, ds["mode"].values
    shown = slice(frames[0], frames[-1] + 1)
    corners_x, corners_y = outline(x_abs[shown, None], y[shown, None], theta[shown, None],
                                   shape)
    span = max(np.ptp(corners_x) + 2 * b, 3 * h)  # the whole body in view at every frame
    centre = 0.5 * (corners_x.max() + corners_x.min())
    # the floor: a line with hatch marks below it that move with it
    marks = centre + np.arange(-span, span, span / FLOOR_MARKS)
    hatch_x = np.stack([marks, marks - 0.1 * h, np.full_like(marks, np.nan)], axis=1).ravel()
    hatch_y = np.tile([0.0, -0.1 * h, np.nan], marks.size)
    bottom, top = -0.15 * h, corners_y.max() + 0.4 * h
    # 5 inches wide; the view as high as its aspect asks, with room above it for the verdict's
    # lines, the name and the frame's time, each on its own line, and below it for the x label
    verdict_text = scene_verdict(ds)
    heading = [_wrap(verdict_text, ANIMATION_TITLE_WIDTH)] if verdict_text else []
    lines = sum(part.count("\n") + 1 for part in heading) + (1 if name else 0)
    above = HEADING_PAD + lines * HEADING_LINE + TIME_LINE
    view = float(np.clip(4 * (top - bottom) / span, 2, 6))
    height = above + view + BELOW_VIEW
    fig, ax = plt.subplots(figsize=(5, height))
    fig.subplots_adjust(left=0.12, right=0.97, top=1 - above / height,
                        bottom=BELOW_VIEW / height)
    ax.set_xlim((centre - span / 2) * 100, (centre + span / 2) * 100)
    ax.set_ylim(bottom * 100, top * 100)
    ax.set_aspect("equal")
    ax.set_xlabel("x [cm]")
    y_text = 1 - HEADING_PAD / 2 / height
    if heading:
        fig.text(0.5, y_text, heading[0], ha="center", va="top", fontsize=8)
        y_text -= (heading[0].count("\n") + 1) * HEADING_LINE / height
    if name:
        fig.text(0.5, y_text, _short(name, NAME_WIDTH), ha="center", va="top",
                 fontsize=8, color="0.35")
    (floor,) = ax.plot([], [], color="k", lw=1.5)
    (body,) = ax.plot([], [], color="tab:blue", lw=2, gid="outline")
    (centre_of_gravity,) = ax.plot([], [], **G_STYLE, gid="G")
    label = ax.set_title(" ", fontsize=9)
    moving = [floor, body, centre_of_gravity, *ax.spines.values(), label]  # the drawing order
    for artist in moving:
        artist.set_animated(True)
    canvas = fig.canvas
    canvas.draw()
    background = canvas.copy_from_bbox(fig.bbox)

    def frame(k):
        px, py = outline(x_abs[k], y[k], theta[k], shape)
        body.set_data(px * 100, py * 100)
        centre_of_gravity.set_data([x_abs[k] * 100], [y[k] * 100])
        floor.set_data(np.r_[centre - span, centre + span, np.nan, hatch_x + d_floor[k]] * 100,
                       np.r_[0.0, 0.0, np.nan, hatch_y] * 100)
        label.set_text(f"t = {t[k]:.2f} s   {MODE_NAMES[int(mode[k])].replace('_', ' ')}")
        canvas.restore_region(background)
        for artist in moving:
            fig.draw_artist(artist)
        return np.array(canvas.buffer_rgba())

    if not quiet:
        # frames spread by the golden ratio, so as not to fall on one phase of a periodic motion
        picks = np.unique(((np.arange(SIZE_SAMPLES) + 0.5) * GOLDEN % 1 * (frames.size - 1))
                          .astype(int))
        size = estimated_size([[frame(frames[min(k + j, frames.size - 1)]) for j in range(3)]
                               for k in picks], frames.size)
        how += "" if start is not None or end is not None else "; --from/--to choose"
        emit(f"animating {path}: t = {t[frames[0]]:.2f} to {t[frames[-1]]:.2f} s ({how}), "
             f"{frames.size} frames at {1 / step:.3g} fps (one every {step:g} s, real time), "
             f"about {_size(size)}", sys.stderr)
    progress = Progress(frames.size, quiet=quiet, prefix=f"animating {path}", unit="frame")

    def counted(k):
        rgba = frame(k)
        progress.update(1)
        return rgba

    save_gif(path, (counted(k) for k in frames), fps=1.0 / step)
    progress.close()
    plt.close(fig)
    return frames.size
