"""Pictures of one scene: successive positions of the body every 1/50 s (the paper's
Figs 3-5) beside theta(t), the floor acceleration and the motion type; and an animation."""
import matplotlib.pyplot as plt
import numpy as np

from kernels.codes import MODE_NAMES

from .style import GAL

MAX_OUTLINES = 150            # more outlines than this blur into a smear


def outline(x, y, theta, b, h):
    """Corners (5 points, closed) of the body with centroid (x, y) at angle theta."""
    c, s = np.cos(theta), np.sin(theta)
    local = np.array([[-b, -h], [b, -h], [b, h], [-b, h], [-b, -h]])
    return x + local[:, 0] * c - local[:, 1] * s, y + local[:, 0] * s + local[:, 1] * c


def draw_scene(ds, title=""):
    """Four panels from a history Dataset (``cf.history_dataset``): a matplotlib Figure."""
    b, h = 0.5 * float(ds.attrs["B"]), 0.5 * float(ds.attrs["H"])
    alpha = np.arctan(b / h)
    t = ds["time"].values
    fig = plt.figure(figsize=(12, 6.5), layout="constrained")
    grid = fig.add_gridspec(3, 2, width_ratios=[1.1, 1])
    ax_pos = fig.add_subplot(grid[:, 0])
    stride = max(1, int(np.ceil(t.size / MAX_OUTLINES)))
    colours = plt.cm.viridis(np.linspace(0, 1, t[::stride].size))
    for k, colour in zip(range(0, t.size, stride), colours):
        px, py = outline(ds.x.values[k], ds.y.values[k], ds.theta.values[k], b, h)
        ax_pos.plot(px * 100, py * 100, color=colour, lw=0.6)
    ax_pos.axhline(0, color="k", lw=1.5)
    ax_pos.set_aspect("equal")
    ax_pos.set_xlabel("x relative to the floor [cm]")
    ax_pos.set_ylabel("height [cm]")
    every = stride * (t[1] - t[0]) if t.size > 1 else 0.0
    ax_pos.set_title(f"positions every {every:.3g} s (colour: time 0 → {t[-1]:.2f} s)")

    ax_theta = fig.add_subplot(grid[0, 1])
    ax_theta.plot(t, ds.theta.values / alpha, lw=1)
    ax_theta.axhline(1, color="grey", ls=":", lw=0.8)
    ax_theta.axhline(-1, color="grey", ls=":", lw=0.8)
    ax_theta.set_ylabel("θ / α")
    ax_theta.set_title(f"α = {alpha:.4f} rad")
    ax_floor = fig.add_subplot(grid[1, 1], sharex=ax_theta)
    ax_floor.plot(t, ds.a_x.values / GAL, lw=1, label="horizontal")
    if np.any(ds.a_y.values != 0):
        ax_floor.plot(t, ds.a_y.values / GAL, lw=1, label="vertical")
        ax_floor.legend(loc="upper right", fontsize=8)
    ax_floor.set_ylabel("floor acc. [gal]")
    ax_mode = fig.add_subplot(grid[2, 1], sharex=ax_theta)
    ax_mode.step(t, ds["mode"].values, where="post", lw=1)
    ax_mode.set_yticks(range(len(MODE_NAMES)), [m.replace("_", " ") for m in MODE_NAMES],
                       fontsize=8)
    ax_mode.set_ylim(-0.5, len(MODE_NAMES) - 0.5)
    ax_mode.set_xlabel("time [s]")
    for ax in (ax_theta, ax_floor):
        ax.tick_params(labelbottom=False)
    fig.suptitle(title)
    return fig


def animate_scene(ds, path, title="", quiet=False):
    """GIF of the body on the moving floor, in real time (one frame per history sample).

    The axes are drawn once; each frame redraws only the body, the floor, the title and the
    spines above them (as a full drawing stacks them) over that background, and the frames go
    to the GIF as they are drawn (``gif.save_gif``), with a progress line on stderr unless
    ``quiet``.
    """
    from ..runner.progress import Progress
    from .gif import save_gif
    b, h = 0.5 * float(ds.attrs["B"]), 0.5 * float(ds.attrs["H"])
    t = ds["time"].values
    dt = float(t[1] - t[0]) if t.size > 1 else 0.02
    # floor displacement by integrating its acceleration twice (from rest at t = 0)
    v_floor = np.concatenate([[0.0], np.cumsum(0.5 * (ds.a_x.values[1:] + ds.a_x.values[:-1]) * dt)])
    d_floor = np.concatenate([[0.0], np.cumsum(0.5 * (v_floor[1:] + v_floor[:-1]) * dt)])
    x_abs = d_floor + ds.x.values
    y, theta, mode = ds.y.values, ds.theta.values, ds["mode"].values
    span = max(np.ptp(x_abs) + 4 * b, 3 * h)
    centre = 0.5 * (x_abs.max() + x_abs.min())
    fig, ax = plt.subplots(figsize=(5, 5))
    ax.set_xlim((centre - span / 2) * 100, (centre + span / 2) * 100)
    ax.set_ylim(-0.1 * h * 100, (2.4 * h + span * 0.2) * 100)
    ax.set_aspect("equal")
    ax.set_xlabel("x [cm]")
    (floor,) = ax.plot([], [], color="k", lw=3)
    (body,) = ax.plot([], [], color="tab:blue", lw=2)
    label = ax.set_title(title)
    moving = [floor, body, *ax.spines.values(), label]  # in the order a full drawing uses
    for artist in moving:
        artist.set_animated(True)
    canvas = fig.canvas
    canvas.draw()
    background = canvas.copy_from_bbox(fig.bbox)
    progress = Progress(t.size, quiet=quiet, prefix=f"animating {path}", unit="frame")

    def frame(k):
        px, py = outline(x_abs[k], y[k], theta[k], b, h)
        body.set_data(px * 100, py * 100)
        floor.set_data([(d_floor[k] - span) * 100, (d_floor[k] + span) * 100], [0, 0])
        label.set_text(f"{title}  t = {t[k]:.2f} s  {MODE_NAMES[int(mode[k])]}")
        canvas.restore_region(background)
        for artist in moving:
            fig.draw_artist(artist)
        progress.update(1)
        return np.asarray(canvas.buffer_rgba())

    save_gif(path, (frame(k) for k in range(t.size)), fps=max(1, round(1 / dt)))
    progress.close()
    plt.close(fig)
