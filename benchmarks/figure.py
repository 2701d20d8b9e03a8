"""The work-precision plot: error against CPU time, one panel per reference scene."""
import math

from matplotlib.figure import Figure

STYLE = {"adaptive": dict(color="tab:blue", marker="o", label="kernel, adaptive (rtol)"),
         "fixed": dict(color="tab:orange", marker="s", label="kernel, fixed-step RK4 (dt)"),
         "floor": dict(color="tab:purple", marker="v",
                       label="floor: the kernel's tableau, rocking only (rtol)"),
         "scipy": dict(color="tab:green", marker="^",
                       label="scipy solve_ivp DOP853, rocking only (rtol)")}


def _annotate(ax, points, method):
    """Label the first and last rung with its setting."""
    for p in (points[0], points[-1]):
        text = f"{p.setting:.0e}"
        ax.annotate(text, (1e3 * p.cpu, p.error), textcoords="offset points", xytext=(4, 3),
                    fontsize=7, color=STYLE[method]["color"])


def work_precision_figure(all_curves, target_error, target_cpu):
    """A Figure with one log-log panel per scene: error against median CPU time [ms].

    Runs whose error is not finite (wrong impact count, missed overturning) are left out and
    counted in the panel.  The steady-rocking panel shows docs/design.md 10's target corner.
    """
    n = len(all_curves)
    cols = min(3, n)
    rows = math.ceil(n / cols)
    fig = Figure(figsize=(4.2 * cols, 3.6 * rows), layout="constrained")
    axes = fig.subplots(rows, cols, squeeze=False).ravel()
    for ax, curves in zip(axes, all_curves):
        missing = 0
        for method, style in STYLE.items():
            points = [p for p in curves.of(method) if math.isfinite(p.error)]
            missing += len(curves.of(method)) - len(points)
            if not points:
                continue
            floor = 1e-16
            ax.loglog([1e3 * p.cpu for p in points], [max(p.error, floor) for p in points],
                      ms=4, lw=1, **style)
            _annotate(ax, points, method)
        if curves.scene.key == "steady_rocking":
            ax.axhline(target_error, color="grey", ls=":", lw=1)
            ax.axvline(1e3 * target_cpu, color="grey", ls=":", lw=1)
            ax.text(1e3 * target_cpu, target_error, " target", fontsize=7, color="grey",
                    va="bottom")
        unit = "m" if curves.scene.measure == "slip" else "s"
        what = "largest slip" if curves.scene.measure == "slip" else \
            "t_overturn" if curves.scene.key == "overturning" else "impact times"
        ax.set_title(curves.scene.title
                     + (f"  ({missing} runs not comparable: see the table)" if missing else ""),
                     fontsize=10)
        ax.set_xlabel("CPU time per run [ms]")
        ax.set_ylabel(f"error of {what} [{unit}]")
        ax.grid(True, which="major", alpha=0.3)
    for ax in axes[n:]:
        ax.set_visible(False)
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncols=2, fontsize=9)
    fig.suptitle("Work-precision: error against CPU time (median of repeated runs)")
    return fig
