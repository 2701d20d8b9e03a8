"""Lower limits of the peak ground motion at a site from bodies seen overturned there.

    python -m sweep.estimate BODIES.yaml [--json]

Ishiyama (1982): a body overturns only if the peak horizontal floor acceleration exceeds
a_o = (B/H) g (Eq. 14) and the peak velocity exceeds v_o (Eqs. 15/16); then the peak
displacement exceeds d_o = v_o^2/a_o (Eq. 18; the paper finds this one too conservative).  Each
overturned body bounds PGA, PGV and PGD from below, and the most demanding one gives the bound.
Standing bodies bound nothing from above: the criteria are necessary, not sufficient, and for a
given record overturning is not monotonic in amplitude (Yim, Chopra & Penzien 1980).

A bodies file::

    site: village graveyard            # optional
    bodies:
      - {name: stone 1, B: 30 cm, H: 90 cm, overturned: true, direction: N}
      - {name: stone 2, B: 40 cm, H: 80 cm, overturned: false, mu: 0.6}

``B``, ``H`` (and the optional radius of gyration ``i_g``) are lengths with units
(``sweep.units``); ``mu`` is the friction coefficient, if known; ``direction`` any label of the
direction of fall.  Output in SI with ``--json``, else a table in the paper's units.
"""
import argparse
import difflib
import json
import sys
import textwrap
from dataclasses import dataclass

from . import criteria, units
from .cli import reported_problems
from .yamlio import MISSING, FileProblems, Problem, join_path, read_yaml

KEYS = ("site", "bodies")
BODY_KEYS = ("name", "B", "H", "i_g", "mu", "overturned", "direction")
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


@dataclass(frozen=True)
class Body:
    """One body of a bodies file, in SI units."""

    name: str
    B: float
    H: float
    overturned: bool
    i_g: float = None
    mu: float = None
    direction: str = None


# --- reading ----------------------------------------------------------------------------------

def _unknown_keys(mapping, allowed, path, problems):
    for key in mapping:
        if key not in allowed:
            close = difflib.get_close_matches(str(key), allowed, n=1)
            hint = f"; did you mean '{close[0]}'?" if close else ""
            problems.append(Problem(join_path(path, key), mapping[key], f"unknown key{hint}"))


def _length(raw, path, problems, required=True):
    """A positive length in m from a number (m) or a string with a unit; None if absent/bad."""
    if raw is None:
        if required:
            problems.append(Problem(path, MISSING, "required: a length such as '30 cm'"))
        return None
    try:
        quantity = units.parse_quantity(raw, "length")
        if quantity.body_relative:
            raise ValueError("must be a length in m, cm or mm")
    except ValueError as err:
        problems.append(Problem(path, raw, str(err)))
        return None
    if not quantity.value > 0:
        problems.append(Problem(path, raw, "must be greater than 0"))
        return None
    return quantity.to_si()


def _body(raw, index, problems):
    """A :class:`Body` from entry ``index`` of ``bodies``, or None (problems appended)."""
    path = f"bodies[{index}]"
    if not isinstance(raw, dict):
        problems.append(Problem(path, raw, "must be a mapping {name, B, H, overturned, ...}"))
        return None
    before = len(problems)
    _unknown_keys(raw, BODY_KEYS, path, problems)
    name = raw.get("name", f"body {index + 1}")
    if not isinstance(name, (str, int, float)) or isinstance(name, bool):
        problems.append(Problem(join_path(path, "name"), name, "must be a string"))
    B = _length(raw.get("B"), join_path(path, "B"), problems)
    H = _length(raw.get("H"), join_path(path, "H"), problems)
    i_g = _length(raw.get("i_g"), join_path(path, "i_g"), problems, required=False)
    overturned = raw.get("overturned", MISSING)
    if overturned is MISSING:
        problems.append(Problem(join_path(path, "overturned"), MISSING,
                                "required: true (overturned) or false (standing)"))
    elif not isinstance(overturned, bool):
        problems.append(Problem(join_path(path, "overturned"), overturned,
                                "must be true or false"))
    mu = raw.get("mu")
    if mu is not None and (isinstance(mu, bool) or not isinstance(mu, (int, float))
                           or not mu >= 0):
        problems.append(Problem(join_path(path, "mu"), mu, "must be a number >= 0"))
    direction = raw.get("direction")
    if direction is not None and not isinstance(direction, str):
        problems.append(Problem(join_path(path, "direction"), direction,
                                "must be a label such as 'N' or 'EW'"))
    if len(problems) > before:
        return None
    return Body(name=str(name), B=B, H=H, overturned=overturned, i_g=i_g,
                mu=None if mu is None else float(mu), direction=direction)


def load_bodies(source):
    """Read and check a bodies file (or a dict of the same schema); every problem at once.

    Returns
    -------
    site : str or None
    bodies : list of Body

    Raises
    ------
    FileProblems
        Unknown keys, missing or bad lengths, ``overturned`` not a boolean, ..., each with its
        dotted path (``bodies[2].B``) and the value given.
    """
    raw = source if isinstance(source, dict) else read_yaml(source)
    name = None if isinstance(source, dict) else str(source)
    problems = []
    if not isinstance(raw, dict):
        raise FileProblems([Problem("(file)", MISSING if raw is None else raw,
                                    "must be a mapping with a list 'bodies'")], name)
    _unknown_keys(raw, KEYS, "", problems)
    site = raw.get("site")
    if site is not None and not isinstance(site, str):
        problems.append(Problem("site", site, "must be a string"))
    entries = raw.get("bodies")
    bodies = []
    if not isinstance(entries, list) or not entries:
        problems.append(Problem("bodies", MISSING if entries is None else entries,
                                "required: a non-empty list of bodies"))
    else:
        bodies = [_body(entry, i, problems) for i, entry in enumerate(entries)]
    if problems:
        raise FileProblems(problems, name)
    return site, bodies


# --- estimating -------------------------------------------------------------------------------

def body_limits(body):
    """The lower limits of one body: ``criteria.IshiyamaLimits`` of floats [SI]."""
    limits = criteria.ishiyama_limits(body.B, body.H, body.i_g)
    return criteria.IshiyamaLimits(*(float(x) for x in limits))


def _notes(body):
    """Why the criteria may not apply to ``body``."""
    notes = []
    if body.mu is not None and body.mu < body.B / body.H:
        notes.append(f"mu = {body.mu:g} < B/H = {body.B / body.H:.3g}: the body slides "
                     "rather than rocks (the paper's conclusion 1); the criteria assume rocking")
    if body.B > body.H:
        notes.append("B > H: squatter than the paper's bodies (its specimens have B/H from "
                     "1/5 to 1/3, Table 2)")
    return notes


def _bounds(rows):
    """{pga|pgv|pgd: {value, body}} from the overturned rows (None without any)."""
    fallen = [row for row in rows if row["overturned"]]
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
        ``bodies``: per body its name, B, H, state, a_o [m/s^2], v_o [m/s], d_o [m], T_c [s]
        and notes; ``lower_limits``: for ``pga``, ``pgv``, ``pgd`` the largest limit among
        the overturned bodies and the body giving it (None if none overturned);
        ``by_direction``: the same per direction of fall, for bodies that give one;
        ``standing``: names of the standing bodies; ``standing_exceeded``: those whose a_o and
        v_o both lie below the lower limits (they stood although the criteria held);
        ``standing_note``: what standing bodies do not prove.

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
                     "notes": _notes(body)})
    directions = sorted({row["direction"] for row in rows
                         if row["overturned"] and row["direction"] is not None})
    bounds = _bounds(rows)
    standing = [row for row in rows if not row["overturned"]]
    exceeded = [] if bounds is None else [
        row["name"] for row in standing
        if row["a_o"] < bounds["pga"]["value"] and row["v_o"] < bounds["pgv"]["value"]]
    return {"bodies": rows, "lower_limits": bounds,
            "by_direction": {d: _bounds([r for r in rows if r["direction"] == d])
                             for d in directions},
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
    bounds = result["lower_limits"]
    if bounds is None:
        lines.append("No body overturned: the bodies give no lower limit of the peak ground "
                     "motion.")
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


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="python -m sweep.estimate",
        description="Lower limits of the peak ground acceleration, velocity and displacement "
                    "at a site from the sizes of bodies that overturned there (Ishiyama 1982, "
                    "Eqs. 14, 16, 18).")
    parser.add_argument("bodies", help="bodies file (YAML): site, bodies: [{name, B, H, "
                                       "overturned, mu, i_g, direction}]")
    parser.add_argument("--json", action="store_true", help="print the result as JSON (SI)")
    args = parser.parse_args(argv)
    with reported_problems(args.bodies):
        site, bodies = load_bodies(args.bodies)
    result = estimate(bodies)
    if args.json:
        json.dump({"site": site, **result}, sys.stdout, indent=1)
        print()
    else:
        print(format_text(result, site))
    return 0


if __name__ == "__main__":
    sys.exit(main())
