"""Values that are valid but likely not what was meant: the warnings of a scene.

A bare number is in SI units, so ``B: 30`` is a body 30 m wide, ``phase: 90`` is 90 rad and
``pga: 0.4`` is 0.4 m/s^2 (0.04 g, under which most bodies stand); a file in m/s^2 read with
``units: g`` shakes the floor ten times too hard.  :func:`scene_doubts` finds such values in a
checked scene and its resolved SI form, each as a
:class:`~sweep.io.problems.Problem` whose message starts with the value as written
(``30 (a bare number is in m): a body 30 m wide; did you mean 30 cm?``);
:func:`~sweep.io.problems.warn` issues them as ``InputWarning`` s, which never stop the work.
A study reports each once per axis (``sweep.runner.cell_checks.cell_problems``); a list of
accelerations (a study's axis, the levels of a bodies file) is doubted as a whole
(:func:`levels_read_in_si`).
"""
import math
from pathlib import Path

from pydantic import BaseModel

from ..bodies import G
from . import units
from .files import named
from .problems import Problem

# Bodies that rock are furniture, equipment, tombstones and statues, 0.1 to a few metres; a
# bare number (metres) above this was more likely meant in cm or mm.
MAX_BARE_SIZE = 10.0  # m
# A bare angle (radians) beyond a full turn was more likely meant in degrees.
MAX_BARE_ANGLE = 2.0 * math.pi  # rad
# Strong-motion records reach about 1-2 g horizontally, exceptionally 3 g; a scaled PGA above
# this is more likely a record read in the wrong units or scaled twice.
MAX_PGA = 3.0 * G  # m/s^2
# A file read in g whose numbers exceed this (5 g) more likely holds m/s^2 or gal.
MAX_PEAK_IN_G = 5.0
# Peak floor accelerations that rock or overturn bodies are 1-10 m/s^2 and rarely below
# 0.2 m/s^2 (West's (B/H) g is 1 m/s^2 even for a body ten times taller than wide), while a
# fraction of g is almost always below 2: a bare acceleration (m/s^2) below this, other than 0,
# reads like g.
MAX_BARE_G = 2.0  # m/s^2
# Floors rock bodies at 0.1-20 Hz; above this a frequency is more likely an angular
# frequency in rad/s or a sampling rate.
MAX_FREQUENCY = 100.0  # Hz
# Dry stone, wood, concrete and steel give friction coefficients of 0.2-1; above this a
# coefficient is more likely a typo, a percentage or an angle of friction, unless it is a power
# of ten (10, 100, ...): the usual way to keep a body from sliding at all.
MAX_FRICTION = 2.0

_SIZES = {"B": "a body {:g} m wide", "H": "a body {:g} m tall",
          "i_g": "a radius of gyration of {:g} m", "R_1": "G {:g} m from its left corner",
          "R_2": "G {:g} m from its right corner", "h": "G {:g} m above its base"}
_FRICTION = ("mu", "mu_s", "mu_k", "mu_edge_s", "mu_edge_k")
_SCALING = ("scale_with", "scale", "pga", "pgv", "sa")


class ReadsAsG(Problem):
    """The doubt of a bare acceleration that reads like g (a :class:`Problem`): a study weighs
    it against the other values of its axis (:func:`levels_read_in_si`)."""

    __slots__ = ()


def reads_as_g(q):
    """True for a bare acceleration whose size reads like a fraction of g:
    0 < abs(value) < ``MAX_BARE_G``."""
    return not q.unit and q.dimension == "acceleration" and 0.0 < abs(q.value) < MAX_BARE_G


def levels_read_in_si(values):
    """True when a list of accelerations as written (numbers, unit strings or
    :class:`~sweep.io.units.Quantity`) holds a bare number of ``MAX_BARE_G`` or more: its bare
    numbers are then meant in m/s^2 (``[0.5, 1, 2, 4]``), none of them is doubted."""
    def bare(value):
        try:
            q = units.parse_quantity(value, "acceleration")
        except ValueError:
            return None
        return None if q.unit else q.value

    return any(abs(v) >= MAX_BARE_G for v in map(bare, values) if v is not None)


def _g_doubt(path, q):
    """The doubt of a bare acceleration that reads like g."""
    v = q.value
    return ReadsAsG(path, v, f"{_written(q)}: {v / G:.3g} g; did you mean {v:g} g "
                             f"({v * G:.3g} m/s^2)? write '{v:g} g' or '{v:g} m/s^2' to "
                             "silence this")


def _quantities(model, path=""):
    """``[(dotted path, Quantity)]`` of every quantity of a checked scene, sections included,
    in the order of the fields."""
    found = []
    for key, value in model.__dict__.items():  # the field values, in field order
        where = f"{path}.{key}" if path else key
        if isinstance(value, units.Quantity):
            found.append((where, value))
        elif isinstance(value, BaseModel):
            found += _quantities(value, where)
    return found


def _written(q):
    """A quantity as written, with what a bare number means: ``30 (a bare number is in m)``."""
    if q.unit:
        return str(q)
    return f"{q.value:g} (a bare number is in {units.units_of(q.dimension)[0]})"


def _quantity_doubt(path, q):
    """The doubt of one quantity, or None."""
    if not q.unit and path.startswith("body.") and q.value > MAX_BARE_SIZE:
        return Problem(path, q.value, f"{_written(q)}: {_SIZES[path[5:]].format(q.value)}; "
                                      f"did you mean {q.value:g} cm?")
    if not q.unit and q.dimension == "angle" and abs(q.value) > MAX_BARE_ANGLE:
        return Problem(path, q.value, f"{_written(q)}: {q.value / (2 * math.pi):.3g} turns; "
                                      f"did you mean {q.value:g} deg?")
    if reads_as_g(q):
        return _g_doubt(path, q)
    if q.dimension == "frequency" and q.to_si() > MAX_FREQUENCY:
        return Problem(path, str(q), f"{_written(q)}: above {MAX_FREQUENCY:g} Hz; if it is an "
                                     f"angular frequency in rad/s, write "
                                     f"{q.to_si() / (2 * math.pi):.4g} Hz")
    return None


def body_doubts(entry, path):
    """Doubts of a body's bare sizes (``B``, ``H``, ``i_g`` of a bodies file's entry), at
    ``path`` (``sites[0].bodies[2]``)."""
    doubts = []
    for key in _SIZES:
        q = getattr(entry, key, None)
        doubt = None if q is None else _quantity_doubt(f"body.{key}", q)
        if doubt is not None:
            doubts.append(doubt._replace(path=f"{path}.{key}"))
    return doubts


def levels_doubt(levels, path):
    """The doubt of a list of acceleration levels (``[(dotted path, Quantity)]``, e.g. the
    ``levels: {pga: ...}`` of a bodies file at ``path``), or None: once, at the first bare
    level that reads like g, unless the list is written in m/s^2 (:func:`levels_read_in_si`)."""
    doubted = [(where, q) for where, q in levels if reads_as_g(q)]
    if not doubted or levels_read_in_si([q for _, q in levels]):
        return None
    doubt = _g_doubt(*doubted[0])
    more = len(doubted) - 1
    return doubt if not more else doubt._replace(
        message=f"{doubt.message} (and {more} more value{'s' * (more > 1)} of {path})")


def glob_notes(path, pattern, found, skipped):
    """What a record glob (``pattern`` at ``path``) leaves out of the folders of the files it
    ``found``: the files ``skipped`` (``sweep.io.files.find_files``), named; [] or one
    :class:`Problem`."""
    if not skipped:
        return []
    folders = "the same folder" if len({Path(p).parent for p in found}) < 2 else "their folders"
    return [Problem(path, pattern, f"takes {len(found)} file{'s' * (len(found) != 1)} and "
                                   f"leaves out {len(skipped)} "
                                   f"other{'s' * (len(skipped) != 1)} of {folders}: "
                                   f"{named(skipped)}")]


def _no_sliding(mu):
    """True for 10, 100, 1000, ...: a coefficient meant to keep the body from sliding."""
    return mu >= 10.0 and mu == 10.0 ** round(math.log10(mu))


def _friction_doubts(contact):
    return [Problem(f"contact.{key}", value, f"{value:g}: a friction coefficient above "
                                             f"{MAX_FRICTION:g}, where stone, wood and steel "
                                             "give 0.2-1 (a power of ten such as 10 keeps "
                                             "the body from sliding)")
            for key in _FRICTION if (value := getattr(contact, key)) is not None
            and value > MAX_FRICTION and not _no_sliding(value)]


def _record_doubt(component, g, ground):
    """The doubt of a record or synthetic ``component`` (``g`` as checked, ``ground`` resolved):
    numbers read in g that look like m/s^2, else a PGA after scaling above ``MAX_PGA``; or
    None."""
    rec = ground["source"]
    factor = units.fixed_factor(rec.units, "acceleration")
    peak = rec.pga / factor  # the largest of the file's numbers
    if factor == G and peak > MAX_PEAK_IN_G:
        key, said = (("units", g.units) if g.units is not None else
                     ("path", f"{Path(g.path).name} (in g, as its comments state)"))
        return Problem(f"excitation.{component}.{key}", getattr(g, key),
                       f"{said}: the file's numbers peak at {peak:.3g}, a PGA of {peak:.3g} g; "
                       "are they in m/s^2 or gal?")
    pga = abs(ground["scale"]) * rec.pga
    if not pga > MAX_PGA:
        return None
    key = next((name for name in _SCALING if getattr(g, name) is not None),
               "model" if g.kind == "synthetic" else "name" if g.name is not None else "path")
    value = g.sa.value if key == "sa" else getattr(g, key)
    key = "sa.value" if key == "sa" else key
    said = Path(g.path).name if key == "path" else value
    return Problem(f"excitation.{component}.{key}", str(value),
                   f"{said}: the motion's PGA after scaling is {pga / G:.3g} g, above "
                   f"{MAX_PGA / G:g} g; are the record's units and the scale meant?")


def scene_doubts(scene, resolved):
    """The values of a checked scene that are likely not what was meant.

    Parameters
    ----------
    scene : sweep.io.scene_schema.Scene
        As ``load_scene`` returns it: it tells which numbers were written bare.
    resolved : dict
        Its ``resolve_scene``: the records read and scaled.

    Returns
    -------
    list of Problem
        Paths below the scene (``body.B``, ``excitation.horizontal.pga``), the value given,
        and a message that starts with it; at most one per record component.
    """
    found = [doubt for path, q in _quantities(scene)
             if (doubt := _quantity_doubt(path, q)) is not None]
    found += _friction_doubts(scene.contact)
    for key, ground in resolved["excitation"].items():
        g = getattr(scene.excitation, key)
        if g.kind == "floor":  # the ground under the building was read and scaled
            key, g, ground = f"{key}.ground", g.ground, ground.get("ground", ground)
        if ground["kind"] == "record":
            doubt = _record_doubt(key, g, ground)
            found += [doubt] if doubt is not None else []
    return found
