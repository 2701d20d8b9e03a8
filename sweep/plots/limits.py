"""Fig. 17 of Ishiyama (1982): lower limits to overturn a homogeneous rectangular body.

Closed forms only (``sweep.paper.criteria``), no simulation: a_o of Eq. (14), v_o of Eq. (16),
d_o of Eq. (18) and the period T_c of Eq. (20) (corrected to 2 pi v_o/a_o, docs/physics.md A11)
against the height H, one curve per breadth B, in the paper's units (cm, gal, cm/s, s); the
slender-body rules of Eqs. (17), (19), (21) dashed.  Each panel's legend (its equations; the
breadths on the first) sits in a corner its curves leave free (``style.place_legends``).
"""
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.lines import Line2D

from ..paper import criteria
from .style import fit_suptitle, fit_texts, log_axes, place_legends

BREADTHS_CM = (5, 10, 20, 50, 100)  # one curve per breadth B [cm]
H_MAX_CM = 1000.0  # heights drawn from H = B (a cube's face) to this [cm]
SAMPLES = 200  # points per curve


def limit_curves(B_cm, H_max_cm=H_MAX_CM, num=SAMPLES):
    """Heights [cm] from B to ``H_max_cm`` and the exact and slender-body limits in paper units.

    Returns
    -------
    H_cm : ndarray, shape (num,)
    exact, approx : dict of str to ndarray
        ``a`` [gal], ``v`` [cm/s], ``d`` [cm], ``T`` [s] of Eqs. (14), (16), (18), (20); the
        slender-body rules (17), (19), (21) for ``v``, ``d``, ``T``.
    """
    H_cm = np.geomspace(B_cm, H_max_cm, num)
    B, H = B_cm / 100.0, H_cm / 100.0
    limits = criteria.ishiyama_limits(B, H)
    exact = {"a": 100 * limits.a_o, "v": 100 * limits.v_o, "d": 100 * limits.d_o,
             "T": limits.T_c}
    approx = {"v": 100 * criteria.ishiyama_velocity_approx(B, H),
              "d": np.full_like(H, 100 * criteria.ishiyama_displacement_approx(B)),
              "T": criteria.critical_period_approx(H)}
    return H_cm, exact, approx


PANELS = (  # key, y label, equation of the exact curve, of the dashed rule
    ("a", "lower limit of peak acceleration a_o [gal]", "(14)", None),
    ("v", "lower limit of peak velocity v_o [cm/s]", "(16)", "(17): 10 B/√H"),
    ("d", "lower limit of peak displacement d_o [cm]", "(18)", "(19): B/10"),
    ("T", "critical period T_c [s]", "(20)", "(21): √H/16"),
)


def figure_limits():
    """Fig. 17: a_o, v_o, d_o and T_c against H [cm], one curve per B; needs no dataset."""
    fig, axes = plt.subplots(2, 2, figsize=(10.5, 8.0), layout="constrained")
    colours = plt.cm.viridis(np.linspace(0.0, 0.85, len(BREADTHS_CM)))
    for B_cm, colour in zip(BREADTHS_CM, colours):
        H_cm, exact, approx = limit_curves(B_cm)
        for ax, (key, _, _, rule) in zip(axes.flat, PANELS):
            ax.plot(H_cm, exact[key], color=colour, lw=1.6, label=f"B = {B_cm} cm")
            if rule:
                ax.plot(H_cm, approx[key], color=colour, lw=1.0, ls="--")
    placements = []
    for ax, (key, label, eq, rule) in zip(axes.flat, PANELS):
        log_axes(ax)
        ax.set_xlabel("height of the body H [cm]")
        ax.set_ylabel(label)
        ax.grid(True, which="both", lw=0.3, alpha=0.5)
        handles = ax.get_legend_handles_labels()[0] if key == "a" else []
        handles.append(Line2D([], [], color="k", lw=1.6, label=f"solid: Eq. {eq}"))
        if rule:
            handles.append(Line2D([], [], color="k", lw=1.0, ls="--",
                                  label=f"dashed: Eq. {rule}"))
        placements.append((ax, {"handles": handles, "fontsize": 8, "framealpha": 0.9}))
    fit_suptitle(fig, ["Lower limits of acceleration, velocity and displacement to overturn a "
                       "homogeneous rectangular body (Ishiyama 1982, Fig. 17)",
                       "each curve starts at H = B; a_o = (B/H) g, v_o = 0.4 v_H, "
                       "d_o = v_o²/a_o, T_c = 2π v_o/a_o"])
    fit_texts(fig)
    place_legends(fig, placements)
    return fig
