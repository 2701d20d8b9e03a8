"""What one scene did, in words: the line ``python -m sweep.scene`` prints first and the title
of its plot, e.g. "overturned at t = 3.41 s towards −θ after 12 impacts" or "stood: max |θ|/α
0.38, no slip, 79 impacts, modes: rotation 9.97 s".

θ > 0 is rotation about the left corner; α = atan(B/H) is the slenderness angle, so a body
overturns when |θ|/α passes 1 with too much speed to fall back.
"""
import math

from kernels.codes import MODE_NAMES

MOTION_MODES = MODE_NAMES[1:]  # every motion type but rest
# Motion types in which the base can move along the floor (in rest and rotation it cannot).
SLIP_MODES = tuple(mode for mode in MOTION_MODES if mode != "rotation")
SHOWN_LENGTH = 1e-3  # m: a slip or lift smaller than this is not worth a word


def slip_of_base(max_slip, max_abs_theta, B, H):
    """How far the base slipped at least [m]: the largest offset of G from its start beyond
    b (1 - cos theta) + h sin theta, the most that rotation about a corner by up to
    ``max_abs_theta`` carries it (as ``runner.cells.slid`` reckons)."""
    theta = min(max_abs_theta, 0.5 * math.pi)
    return max(0.0, max_slip - 0.5 * B * (1.0 - math.cos(theta)) - 0.5 * H * math.sin(theta))


def length_text(metres):
    """'1.27 cm', '4 mm', '2.7 m': a length to three digits in the unit that suits it."""
    for factor, unit in ((1.0, "m"), (100.0, "cm")):
        if abs(metres) * factor >= 1.0:
            return f"{metres * factor:.3g} {unit}"
    return f"{metres * 1000.0:.3g} mm"


def _impacts(n):
    return "no impact" if n == 0 else f"{n} impact{'' if n == 1 else 's'}"


def verdict(results):
    """One line on what the body did.

    Parameters
    ----------
    results : mapping
        ``status``, ``t_overturn`` [s], ``overturn_direction`` (+1, -1), ``impact_count``,
        ``max_abs_theta`` [rad], ``B`` and ``H`` [m], ``max_slip`` [m] (of G: the slip of
        the base is :func:`slip_of_base`), ``max_lift`` [m], ``mode_time`` ({mode name:
        s}), ``t_rest`` [s, or None or NaN] and ``t_final`` [s] (the ``Result`` of
        ``sweep.runner.simulate`` as a dict has them all).
    """
    impacts = _impacts(results["impact_count"])
    if results["status"] == "overturned":
        side = "+θ" if results["overturn_direction"] > 0 else "−θ"
        return (f"overturned at t = {results['t_overturn']:.2f} s towards {side} "
                f"{'after' if results['impact_count'] else 'with'} {impacts}")
    moved = sorted(((time, mode) for mode, time in results["mode_time"].items()
                    if mode in MOTION_MODES and time > 0), reverse=True)
    if results["status"] != "ok":
        head = f"failed ({results['status']}) at t = {results['t_final']:.2f} s"
    elif not moved:
        return "stood still: the body never left rest"
    else:
        head = "stood"
    alpha = math.atan2(results["B"], results["H"])
    slipped = any(mode in SLIP_MODES for _, mode in moved)
    slip = slip_of_base(results["max_slip"], results["max_abs_theta"], results["B"],
                        results["H"]) if slipped else 0.0
    parts = [f"max |θ|/α {results['max_abs_theta'] / alpha:.2g}",
             f"max slip {length_text(slip)}" if slip > SHOWN_LENGTH else "no slip"]
    if results["max_lift"] > SHOWN_LENGTH:
        parts.append(f"max lift {length_text(results['max_lift'])}")
    parts.append(impacts)
    if moved:
        parts.append("modes: " + ", ".join(f"{mode.replace('_', ' ')} {time:.2g} s"
                                           for time, mode in moved))
    t_rest = results["t_rest"]
    if t_rest is not None and math.isfinite(t_rest):
        parts.append(f"at rest from t = {t_rest:.2f} s")
    return f"{head}: {', '.join(parts)}"
