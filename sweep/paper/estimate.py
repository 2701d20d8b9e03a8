"""Lower limits of the peak ground motion at a site from bodies seen overturned there.

Ishiyama (1982): a body overturns only if the peak horizontal floor acceleration exceeds
a_o = (B/H) g (Eq. 14) and the peak velocity exceeds v_o (Eqs. 15/16); then the peak
displacement exceeds d_o = v_o^2/a_o (Eq. 18; the paper finds this one too conservative).  Each
overturned body bounds PGA, PGV and PGD from below, and the most demanding one gives the bound.
Standing bodies bound nothing from above: the criteria are necessary, not sufficient, and for a
given record overturning is not monotonic in amplitude (Yim, Chopra & Penzien 1980).
A body whose friction coefficient is given and below B/H slides before it can rock (the
paper's conclusion 1): the criteria, which assume rocking, do not apply to it, so it bounds
nothing and is listed among the ``excluded`` bodies with the reason.  Bodies come from
``sweep.io.bodies_schema``; results are in SI, ``format_text`` writes them in the paper's
units.
"""
import math
import textwrap

import numpy as np

from . import criteria

# the peak quantity each limit bounds: (key, IshiyamaLimits field, equation, SI unit)
BOUNDS = (("pga", "a_o", "Eq. (14)", "m/s^2"), ("pgv", "v_o", "Eq. (16)", "m/s"),
          ("pgd", "d_o", "Eq. (18)", "m"))
PAPER_UNITS = {"pga": ("gal", 100.0), "pgv": ("cm/s", 100.0), "pgd": ("cm", 100.0)}
WIDTH = 92  # characters of a line of text output

STANDING_NOTE = (
    "Standing bodies do not give upper bounds of the peak ground motion. The criteria are "
    "necessary conditions for overturning, not sufficient ones: a body needs both the "
    "acceleration a_o and the velocity v_o, and above both it overturns only probably "
    "(region C of the paper's Fig. 21). For a given record, overturning is not monotonic in "
    "amplitude either (Yim, Chopra & Penzien 1980): a stronger shaking can leave a body "
    "standing that a weaker one overturns. A body left standing therefore does not prove "
    "that the peak acceleration was below its a_o, nor the peak velocity below its v_o.")


# --- estimating -------------------------------------------------------------------------------

def body_limits(body):
    """The lower limits of one body: ``criteria.IshiyamaLimits`` of floats [SI]; inf or NaN
    for sizes whose limits overflow double precision."""
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        limits = criteria.ishiyama_limits(body.B, body.H, body.i_g)
    return criteria.IshiyamaLimits(*(float(x) for x in limits))


def _finite(row):
    return all(math.isfinite(row[field]) for field in criteria.IshiyamaLimits._fields)


def slides(body):
    """True when the body's friction coefficient is known and below B/H: it slides before
    it rocks (Ishiyama 1982, conclusion 1)."""
    return body.mu is not None and body.mu < body.B / body.H


def sliding_reason(mu, B, H):
    """Why a body of friction ``mu`` < B/H is kept out of the rocking bounds."""
    return (f"mu = {mu:g} < B/H = {B / H:.3g}: the body slides rather than rocks (the "
            "paper's conclusion 1); the criteria assume rocking, so it bounds nothing")


def _notes(body, limits):
    """Why the criteria may not apply to ``body``, or give it no limits."""
    notes = []
    if not all(math.isfinite(x) for x in limits):
        notes.append("its limits overflow double precision (B/H or i_g out of range): it "
                     "bounds nothing")
    if slides(body):
        notes.append(sliding_reason(body.mu, body.B, body.H))
    if body.B > body.H:
        notes.append("B > H: squatter than the paper's bodies (its specimens have B/H from "
                     "1/5 to 1/3, Table 2)")
    return notes


def _bounds(rows):
    """{pga|pgv|pgd: {value, body}} from the overturned rows with finite limits that do not
    slide (None without any)."""
    fallen = [row for row in rows if row["overturned"] and _finite(row) and not row["slides"]]
    if not fallen:
        return None
    out = {}
    for key, field, equation, unit in BOUNDS:
        top = max(fallen, key=lambda row: row[field])
        out[key] = {"value": top[field], "units": unit, "body": top["name"],
                    "equation": equation}
    return out


def estimate(bodies):
    """Lower limits of PGA, PGV, PGD implied by the overturned bodies.

    Parameters
    ----------
    bodies : list of Body

    Returns
    -------
    dict
        ``bodies``: per body its name, B, H, state, a_o [m/s^2], v_o [m/s], d_o [m], T_c [s],
        ``slides`` and notes; ``lower_limits``: for ``pga``, ``pgv``, ``pgd`` the largest
        limit among the overturned bodies that do not slide and the body giving it (None if
        there is none); ``by_direction``: the same per direction of fall, for bodies that
        give one; ``excluded``: ``{name, reason}`` of the bodies that slide (mu < B/H);
        ``standing``: names of the standing bodies; ``standing_exceeded``: those that do not
        slide and whose a_o and v_o both lie below the lower limits (they stood although the
        criteria held); ``standing_note``: what standing bodies do not prove.

    References
    ----------
    Ishiyama (1982), Eqs. (14), (16), (18), (20).
    """
    rows = []
    for body in bodies:
        limits = body_limits(body)
        rows.append({"name": body.name, "B": body.B, "H": body.H, "i_g": body.i_g,
                     "mu": body.mu, "overturned": body.overturned,
                     "direction": body.direction, **limits._asdict(),
                     "slides": slides(body), "notes": _notes(body, limits)})
    directions = sorted({row["direction"] for row in rows if row["overturned"] and _finite(row)
                         and not row["slides"] and row["direction"] is not None})
    bounds = _bounds(rows)
    standing = [row for row in rows if not row["overturned"]]
    exceeded = [] if bounds is None else [
        row["name"] for row in standing if not row["slides"]
        and row["a_o"] < bounds["pga"]["value"] and row["v_o"] < bounds["pgv"]["value"]]
    return {"bodies": rows, "lower_limits": bounds,
            "by_direction": {d: _bounds([r for r in rows if r["direction"] == d])
                             for d in directions},
            "excluded": [{"name": row["name"], "reason": sliding_reason(row["mu"], row["B"],
                                                                        row["H"])}
                         for row in rows if row["slides"]],
            "standing": [row["name"] for row in standing],
            "standing_exceeded": exceeded, "standing_note": STANDING_NOTE}


# --- output -----------------------------------------------------------------------------------

def _paper(key, value):
    unit, factor = PAPER_UNITS[key]
    return f"{value * factor:.3g} {unit}"


def format_text(result, site=None):
    """The estimate as a table and sentences, in the paper's units (cm, gal, cm/s, s)."""
    lines = [f"site: {site}"] if site else []
    header = (f"{'body':<18} {'B [cm]':>7} {'H [cm]':>7} {'H/B':>5}  {'state':<10} "
              f"{'a_o [gal]':>9} {'v_o [cm/s]':>10} {'d_o [cm]':>8} {'T_c [s]':>7}")
    lines += [header, "-" * len(header)]
    for row in result["bodies"]:
        lines.append(f"{row['name'][:18]:<18} {row['B'] * 100:7.1f} {row['H'] * 100:7.1f} "
                     f"{row['H'] / row['B']:5.2f}  "
                     f"{'overturned' if row['overturned'] else 'standing':<10} "
                     f"{row['a_o'] * 100:9.1f} {row['v_o'] * 100:10.2f} "
                     f"{row['d_o'] * 100:8.2f} {row['T_c']:7.3f}")
        lines += [f"{'':<18} note: {note}" for note in row["notes"]]
    lines.append("")
    if result["excluded"]:
        lines.append(textwrap.fill(
            "Kept out of the limits (they slide rather than rock, mu < B/H): "
            + ", ".join(row["name"] for row in result["excluded"]) + ".", width=WIDTH))
    bounds = result["lower_limits"]
    if bounds is None:
        lines.append("No overturned body that rocks has finite limits: the bodies give no "
                     "lower limit of the peak ground motion.")
    else:
        lines.append("Lower limits of the peak horizontal ground motion implied by the "
                     "overturned bodies\n(the most demanding body gives each):")
        names = {"pga": "acceleration", "pgv": "velocity", "pgd": "displacement"}
        for key, _, _, _ in BOUNDS:
            b = bounds[key]
            lines.append(f"  peak {names[key]:<12} >= {_paper(key, b['value']):<11} "
                         f"({b['equation']}, from {b['body']})")
        lines.append("  The paper finds the displacement limit of Eq. (18) too conservative"
                     ", though a lower limit.")
        for direction, b in result["by_direction"].items():
            lines.append(f"  bodies fallen towards {direction}: "
                         + ", ".join(f"{key.upper()} >= {_paper(key, b[key]['value'])}"
                                     for key, _, _, _ in BOUNDS))
    if result["standing_exceeded"]:
        lines.append(textwrap.fill(
            "Standing although both limits above exceed their own a_o and v_o: "
            f"{', '.join(result['standing_exceeded'])} (the criteria are necessary, not "
            "sufficient).", width=WIDTH, initial_indent="  ", subsequent_indent="  "))
    lines.append("")
    lines.append(textwrap.fill(result["standing_note"], width=WIDTH))
    return "\n".join(lines)
