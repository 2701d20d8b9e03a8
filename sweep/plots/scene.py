"""Pictures of one scene: successive positions of the body while it moves (the paper's
Figs 3-5) beside theta/alpha, the floor acceleration of each moving component and the motion
type, under a title that says what the body did (``runner.verdict``); and an animation.

Every panel is scaled to its data: a floor component that is zero throughout gets no panel
(a note says so), and the lines theta/alpha = ±1 are drawn only when the rocking comes within
a factor of two of them (else a note names them).
"""
import math

import matplotlib.pyplot as plt
import numpy as np

from kernels.codes import MODE_NAMES, REST

from ..runner.verdict import verdict
from .style import GAL

MAX_OUTLINES = 150            # more outlines than this blur into a smear
TITLE_WIDTH = 100             # characters of a scene plot's title line (13 pt over 12 inches)
CAPTION_WIDTH = 200           # ... of its caption's lines (7 pt)
ANIMATION_TITLE_WIDTH = 70    # ... of an animation's (8 pt over 5 inches)
FRAME_DT = 0.02               # s between frames of an animation: 50 frames a second, real time
ALPHA_LINE_REACH = 0.5        # theta/alpha = ±1 drawn when max |theta|/alpha is at least this
FLOOR_MARKS = 12              # hatch marks under the floor across the animation's view
FLOOR = {"a_x": ("horizontal", "tab:red"), "a_y": ("vertical", "tab:green")}


def outline(x, y, theta, b, h):
    """Corners (5 points, closed) of the body with centroid (x, y) at angle theta."""
    c, s = np.cos(theta), np.sin(theta)
    local = np.array([[-b, -h], [b, -h], [b, h], [-b, h], [-b, -h]])
    return x + local[:, 0] * c - local[:, 1] * s, y + local[:, 0] * s + local[:, 1] * c


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
        "mode_time": dict(zip(modes, np.atleast_1d(attrs["mode_time"]).tolist())),
        "t_final": float(ds["time"].values[-1])})


def quiet_components(ds):
    """The floor components (``a_x``, ``a_y``) that are zero throughout."""
    return [name for name in FLOOR if not np.any(ds[name].values)]


def _outlines(ds, b, h):
    """Outlines of the body while it moves (from the sample before it leaves rest to the one
    after it comes back for good; the whole history if it never moves), at most
    ``MAX_OUTLINES``: (xs, ys) in cm of shape (n, 5), the time between two, first and last."""
    t = ds["time"].values
    moving = np.flatnonzero(ds["mode"].values != REST)
    first, last = (max(moving[0] - 1, 0), min(moving[-1] + 1, t.size - 1)) if moving.size \
        else (0, t.size - 1)
    stride = max(1, int(np.ceil((last - first + 1) / MAX_OUTLINES)))
    pick = slice(first, last + 1, stride)
    xs, ys = outline(ds.x.values[pick, None], ds.y.values[pick, None],
                     ds.theta.values[pick, None], b, h)
    every = stride * (t[1] - t[0]) if t.size > 1 else 0.0
    return xs * 100, ys * 100, every, t[first], t[pick][-1]


def _draw_positions(ax, xs, ys, every, t_first, t_last):
    for px, py, colour in zip(xs, ys, plt.cm.viridis(np.linspace(0, 1, len(xs)))):
        ax.plot(px, py, color=colour, lw=0.6)
    ax.axhline(0, color="k", lw=1.5)
    ax.set_aspect("equal")
    ax.set_xlabel("x relative to the floor [cm]")
    ax.set_ylabel("height [cm]")
    ax.set_title(f"positions every {every:.3g} s\n(colour: time {t_first:.2f} → {t_last:.2f} s)",
                 fontsize=9)


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


def _draw_theta(ax, ds, alpha):
    """θ/α on an axis scaled to it; ±1 (where the body tips past its corner) drawn faintly
    when within reach, else named."""
    ratio = ds.theta.values / alpha
    peak = float(np.max(np.abs(ratio)))
    ax.plot(ds["time"].values, ratio, lw=1, color="tab:blue")
    ax.axhline(0, color="0.8", lw=0.6, zorder=0)
    limit = 1.15 * peak if peak > 0 else 1.0
    if peak >= ALPHA_LINE_REACH:
        for level in (-1, 1):
            ax.axhline(level, color="0.6", ls=":", lw=0.8)
        limit = max(limit, 1.15)
    else:
        _note(ax, "overturning at θ/α = ±1, off this scale")
    ax.set_ylim(-limit, limit)
    ax.set_ylabel(f"θ / α\n(α = {alpha:.3g} rad)")


def draw_scene(ds, name="", caption=()):
    """Positions, θ/α, the moving floor components and the motion type from a history
    Dataset (``cf.history_dataset``): a matplotlib Figure titled with what the body did
    (:func:`scene_verdict`) over ``name`` (the scene's file or name), smaller, and captioned
    with the lines of ``caption`` (how each record was read, ``records.provenance_line``)."""
    b, h = 0.5 * float(ds.attrs["B"]), 0.5 * float(ds.attrs["H"])
    alpha = math.atan2(b, h)
    quiet = quiet_components(ds)
    moving = [component for component in FLOOR if component not in quiet]
    xs, ys, *times = _outlines(ds, b, h)
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
    _draw_positions(body.add_subplot(grid[:, 0]), xs, ys, *times)
    ax_theta = body.add_subplot(grid[0, 1])
    _draw_theta(ax_theta, ds, alpha)
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


def animate_scene(ds, path, name="", quiet=False):
    """GIF of the body on the moving floor, in real time: one frame every ``FRAME_DT`` (the
    history sample nearest to it) or every sample of a coarser history.

    The floor moves by its baseline-corrected displacement (:func:`floor_displacement`), so
    the view, fixed, stays on the body.  The axes are drawn once; each frame redraws only the
    body, the floor, the title and the spines above them (as a full drawing stacks them) over
    that background, and the frames go to the GIF as they are drawn (``gif.save_gif``), with
    a progress line on stderr unless ``quiet``.
    """
    from ..runner.progress import Progress
    from .gif import save_gif
    b, h = 0.5 * float(ds.attrs["B"]), 0.5 * float(ds.attrs["H"])
    t = ds["time"].values
    dt = float(t[1] - t[0]) if t.size > 1 else FRAME_DT
    frame_dt = max(dt, FRAME_DT)
    frames = np.unique(np.rint(np.arange(0.0, t[-1] + 0.5 * dt, frame_dt) / dt).astype(int))
    frames = frames[frames < t.size]
    d_floor = floor_displacement(ds.a_x.values, dt)
    x_abs = d_floor + ds.x.values
    y, theta, mode = ds.y.values, ds.theta.values, ds["mode"].values
    corners_x, corners_y = outline(x_abs[:, None], y[:, None], theta[:, None], b, h)
    span = max(np.ptp(corners_x) + 2 * b, 3 * h)  # the whole body in view at every frame
    centre = 0.5 * (corners_x.max() + corners_x.min())
    # the floor: a line with hatch marks below it that move with it
    marks = centre + np.arange(-span, span, span / FLOOR_MARKS)
    hatch_x = np.stack([marks, marks - 0.1 * h, np.full_like(marks, np.nan)], axis=1).ravel()
    hatch_y = np.tile([0.0, -0.1 * h, np.nan], marks.size)
    bottom, top = -0.15 * h, corners_y.max() + 0.4 * h
    # 5 inches wide; as high as the view's aspect asks, plus an inch for the titles and label
    fig, ax = plt.subplots(figsize=(5, float(np.clip(4 * (top - bottom) / span, 2, 6)) + 1))
    ax.set_xlim((centre - span / 2) * 100, (centre + span / 2) * 100)
    ax.set_ylim(bottom * 100, top * 100)
    ax.set_aspect("equal")
    ax.set_xlabel("x [cm]")
    title = scene_verdict(ds)
    if title:
        fig.suptitle(_wrap(title, ANIMATION_TITLE_WIDTH), fontsize=8)
    (floor,) = ax.plot([], [], color="k", lw=1.5)
    (body,) = ax.plot([], [], color="tab:blue", lw=2)
    label = ax.set_title(name, fontsize=9)
    moving = [floor, body, *ax.spines.values(), label]  # in the order a full drawing uses
    for artist in moving:
        artist.set_animated(True)
    canvas = fig.canvas
    canvas.draw()
    background = canvas.copy_from_bbox(fig.bbox)
    progress = Progress(frames.size, quiet=quiet, prefix=f"animating {path}", unit="frame")

    def frame(k):
        px, py = outline(x_abs[k], y[k], theta[k], b, h)
        body.set_data(px * 100, py * 100)
        floor.set_data(np.r_[centre - span, centre + span, np.nan, hatch_x + d_floor[k]] * 100,
                       np.r_[0.0, 0.0, np.nan, hatch_y] * 100)
        label.set_text(f"{name}  t = {t[k]:.2f} s  {MODE_NAMES[int(mode[k])].replace('_', ' ')}")
        canvas.restore_region(background)
        for artist in moving:
            fig.draw_artist(artist)
        progress.update(1)
        return np.asarray(canvas.buffer_rgba())

    save_gif(path, (frame(k) for k in frames), fps=1.0 / frame_dt)
    progress.close()
    plt.close(fig)
