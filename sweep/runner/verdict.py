"""What one scene did, in words: the first line of ``python -m sweep.scene``, its plot's title.

For example "overturned at t = 3.41 s: fell towards +x (right) after 12 impacts" or "stood: max
|θ|/α 0.38, no slip, 79 impacts, modes: rotation 9.97 s".

θ > 0 is rotation about the left corner, so a body that overturns with θ > 0 falls towards −x
(to the left); α = atan(B/H) is the slenderness angle, so a body overturns when |θ|/α passes
1 with too much speed to fall back.  The slip is the base's (``kernels.extremes``): how far
its footprint moved along the floor, which rocking about a corner leaves in place.
"""
import math

from kernels.codes import MODE_NAMES

MOTION_MODES = MODE_NAMES[1:]  # every motion type but rest
SHOWN_LENGTH = 1e-3  # m: a slip or lift smaller than this is not worth a word


# overturn_direction (the sign of theta at overturning) -> the way the body fell, in x
FALL_SIDES = {1: "-x", -1: "+x"}
FALL_WORDS = {"-x": "−x (left)", "+x": "+x (right)"}


def fall_side(direction):
    """'-x' or '+x': the way a body fell whose theta reached the overturning angle with the
    sign ``direction`` (+1: about the left corner, so to the left); None when it did not."""
    return FALL_SIDES.get(direction)


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
        ``max_abs_theta`` [rad], ``alpha`` [rad] (the smaller side's slenderness angle;
        default atan(B/H) from ``B`` and ``H`` [m]), ``max_slip`` [m] (of the base),
        ``max_lift`` [m], ``mode_time`` ({mode name:
        s}), ``t_rest`` [s, or None or NaN] and ``t_final`` [s] (the ``Result`` of
        ``sweep.runner.simulate`` as a dict has them all).
    """
    impacts = _impacts(results["impact_count"])
    if results["status"] == "overturned":
        side = FALL_WORDS[fall_side(results["overturn_direction"])]
        return (f"overturned at t = {results['t_overturn']:.2f} s: fell towards {side} "
                f"{'after' if results['impact_count'] else 'with'} {impacts}")
    moved = sorted(((time, mode) for mode, time in results["mode_time"].items()
                    if mode in MOTION_MODES and time > 0), reverse=True)
    if results["status"] != "ok":
        head = f"failed ({results['status']}) at t = {results['t_final']:.2f} s"
    elif not moved:
        return "stood still: the body never left rest"
    else:
        head = "stood"
    alpha = results.get("alpha") or math.atan2(results["B"], results["H"])
    slip = results["max_slip"]
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
