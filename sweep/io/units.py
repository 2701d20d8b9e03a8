"""Quantities of scene files: a number in SI units or a string ``"<number> <unit>"``.

A value is parsed first into a :class:`Quantity` (value, unit, dimension), which checks the unit
against the field's dimension; it is turned into SI later by :meth:`Quantity.to_si`, which needs
the body for the paper's body-relative units: ``west`` (x (B/H) g, Eq. (1)), ``v_H`` (x the
single-shock overturning velocity, Eq. (9)) and ``alpha`` (x the slenderness angle atan(B/H)).
Imperial lengths, velocities and accelerations take the exact factors of the international
yard (1959): 1 in = 0.0254 m, 1 ft = 0.3048 m, 1 yd = 0.9144 m, 1 mi = 1609.344 m; the pound
is the international avoirdupois pound (1959), 0.45359237 kg, its force 1 lbf = 0.45359237 kg
x g = 4.4482216152605 N, and 1 kgf = 1 kg x g = 9.80665 N (g the standard gravity).
Unit names are case-insensitive; ``sec`` may stand for ``s``, ``inch``, ``foot`` and ``feet``
for ``in`` and ``ft``.
"""
import functools
import math
import re
from dataclasses import dataclass

from .. import bodies

DIMENSIONS = ("acceleration", "velocity", "length", "angle", "angular_velocity", "frequency",
              "time", "mass", "force", "dimensionless")

# The international inch, foot, yard and mile (1959), exact in metres
INCH = 0.0254
FOOT = 0.3048
YARD = 0.9144
MILE = 1609.344
POUND = 0.45359237        # kg, the international avoirdupois pound (1959)

# unit -> (dimension, factor to SI); keys are lower case
_FIXED = {
    "m/s^2": ("acceleration", 1.0), "cm/s^2": ("acceleration", 0.01),
    "mm/s^2": ("acceleration", 0.001), "gal": ("acceleration", 0.01),
    "g": ("acceleration", bodies.G), "mg": ("acceleration", bodies.G / 1000.0),
    "m/s": ("velocity", 1.0), "cm/s": ("velocity", 0.01), "mm/s": ("velocity", 0.001),
    "kine": ("velocity", 0.01),
    "m": ("length", 1.0), "cm": ("length", 0.01), "mm": ("length", 0.001),
    "km": ("length", 1000.0),
    "in": ("length", INCH), "ft": ("length", FOOT), "yd": ("length", YARD),
    "mi": ("length", MILE),
    "in/s": ("velocity", INCH), "ft/s": ("velocity", FOOT), "mph": ("velocity", MILE / 3600.0),
    "in/s^2": ("acceleration", INCH), "ft/s^2": ("acceleration", FOOT),
    "rad": ("angle", 1.0), "deg": ("angle", math.pi / 180.0),
    "rad/s": ("angular_velocity", 1.0), "deg/s": ("angular_velocity", math.pi / 180.0),
    "hz": ("frequency", 1.0),
    "s": ("time", 1.0), "ms": ("time", 0.001), "min": ("time", 60.0),
    "kg": ("mass", 1.0), "t": ("mass", 1000.0), "lb": ("mass", POUND),
    "n": ("force", 1.0), "kn": ("force", 1000.0), "lbf": ("force", POUND * bodies.G),
    "kgf": ("force", bodies.G),
}
# body-relative unit -> dimension; the factor depends on the body (see Quantity.to_si)
_RELATIVE = {"west": "acceleration", "v_h": "velocity", "alpha": "angle"}
_SPELLING = {"west": "west", "v_h": "v_H", "alpha": "alpha", "hz": "Hz", "n": "N", "kn": "kN"}
# other spellings of a length, alone or before a ``/`` (``feet/s`` -> ``ft/s``)
_ALIASES = {"inch": "in", "inches": "in", "foot": "ft", "feet": "ft"}
_EXAMPLES = {"acceleration": "341.7 gal", "velocity": "100 cm/s", "length": "10 cm",
             "angle": "30 deg", "angular_velocity": "10 deg/s", "frequency": "2 Hz",
             "time": "500 ms", "mass": "120 kg", "force": "0.8 kN", "dimensionless": "0.5"}

_NUMBER = r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?"
# a quantity written as a string: a number, then its unit if any (also a JSON Schema pattern)
QUANTITY_PATTERN = rf"^\s*({_NUMBER})\s*([^\s\d.+-][^\s]*)?\s*$"
_PATTERN = re.compile(QUANTITY_PATTERN)


@functools.lru_cache(maxsize=256)
def _normalize(unit):
    """Canonical lower-case spelling: ``cm/sec2`` -> ``cm/s^2``, ``m/s/s`` -> ``m/s^2``."""
    u = unit.strip().lower().replace("**", "^").replace("sec", "s")
    u = re.sub(r"/s/s$", "/s^2", u)
    u = re.sub(r"/s2$", "/s^2", u)
    head, slash, rate = u.partition("/")
    return _ALIASES.get(head, head) + slash + rate


def units_of(dimension):
    """Unit names accepted for ``dimension`` (SI first), for messages."""
    names = [_SPELLING.get(u, u) for u, (d, _) in _FIXED.items() if d == dimension]
    names += [_SPELLING[u] for u, d in _RELATIVE.items() if d == dimension]
    return tuple(names)


def listing():
    """Every dimension with its unit names, SI first, for help texts:
    ``length: m, cm, ... | acceleration: m/s^2, ... | ...``."""
    return " | ".join(f"{d.replace('_', ' ')}: {', '.join(units_of(d))}" for d in DIMENSIONS
                      if units_of(d))


def _article(dimension):
    return ("an " if dimension[0] in "aeiou" else "a ") + dimension.replace("_", " ")


def _either(dimensions):
    """'an acceleration, a velocity or a length'."""
    names = [_article(d) for d in dimensions]
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " or " + names[-1]


@dataclass(frozen=True)
class Quantity:
    """A parsed quantity: ``value`` in ``unit`` (``""``: SI) of ``dimension``."""

    value: float
    unit: str
    dimension: str

    def __str__(self):
        return f"{self.value:g} {_SPELLING.get(self.unit, self.unit)}".rstrip()

    @property
    def body_relative(self):
        """True for ``west``, ``v_H`` and ``alpha``, which need the body to become SI."""
        return self.unit in _RELATIVE

    def to_si(self, body=None):
        """The value in SI units (m, s, rad, Hz and their products).

        Parameters
        ----------
        body : mapping, optional
            ``{"B": m, "H": m, "i_g": m or None, "G": [m, m] or None}``; required for
            body-relative units (with G off the middle, the smaller side's scale:
            ``sweep.bodies``).
        """
        if not self.unit:
            return self.value
        if self.unit in _FIXED:
            return self.value * _FIXED[self.unit][1]
        if body is None:
            raise ValueError(f"'{self}' is relative to the body and needs its B and H")
        B, H, i_g, centre = body["B"], body["H"], body.get("i_g"), body.get("G")
        if self.unit == "west":
            factor = bodies.west_acceleration(B, H, centre=centre)
        elif self.unit == "v_h":
            factor = bodies.single_shock_velocity(B, H, i_g, centre=centre)
        else:
            factor = bodies.slenderness(B, H, centre)
        return self.value * float(factor)


def _float(number):
    """``float(number)``; inf for an integer beyond the float range (refused as not finite)."""
    try:
        return float(number)
    except OverflowError:
        return math.inf


def parse_quantity(raw, dimension):
    """Parse a number (SI) or ``"<number> <unit>"`` into a :class:`Quantity`.

    Parameters
    ----------
    raw : int, float, str or Quantity
        The value as written in the file.
    dimension : str or tuple of str
        Allowed dimension(s) of :data:`DIMENSIONS`; a bare number takes the first.

    Raises
    ------
    ValueError
        Not a number, an unknown unit, or a unit of another dimension.
    """
    allowed = (dimension,) if isinstance(dimension, str) else tuple(dimension)
    if isinstance(raw, Quantity):
        if raw.dimension not in allowed:
            raise ValueError(f"'{raw}' is {_article(raw.dimension)}, expected {_either(allowed)}")
        return raw
    if isinstance(raw, bool) or not isinstance(raw, (int, float, str)):
        raise ValueError("expected a number or a string '<number> <unit>'")
    if isinstance(raw, str):
        return _parse_text(raw, allowed)
    return _quantity(_float(raw), "", allowed)


@functools.lru_cache(maxsize=1024)
def _parse_text(raw, allowed):
    """:func:`parse_quantity` of a string (cached: the cells of a study and the scenes of a
    loop repeat theirs)."""
    match = _PATTERN.match(raw)
    if match is None:
        raise ValueError("expected a number or a string '<number> <unit>', e.g. "
                         f"'{_EXAMPLES[allowed[0]]}'")
    return _quantity(float(match.group(1)), match.group(2) or "", allowed)


def _quantity(value, written, allowed):
    """The :class:`Quantity` of ``value`` in the unit ``written`` ("": none, SI), checked
    against the ``allowed`` dimensions."""
    if not math.isfinite(value):
        raise ValueError("must be a finite number")
    unit = _normalize(written)
    if not unit:
        return Quantity(value, "", allowed[0])
    found = _FIXED[unit][0] if unit in _FIXED else _RELATIVE.get(unit)
    if found is None:
        names = ", ".join(n for d in allowed for n in units_of(d))
        raise ValueError(f"unknown unit '{written}' for {_either(allowed)}; use one of: "
                         f"{names}")
    if found not in allowed:
        raise ValueError(f"'{written}' is a unit of {found.replace('_', ' ')}, "
                         f"expected {_either(allowed)}")
    return Quantity(value, unit, found)


def fixed_factor(unit, dimension):
    """SI factor of a unit that does not depend on the body (e.g. for record files)."""
    quantity = parse_quantity(f"1 {unit}", dimension)
    if quantity.body_relative:
        raise ValueError(f"'{unit}' is relative to the body; use a fixed unit")
    return quantity.to_si()


def acceleration_amplitude(quantity, frequency, body=None):
    """Acceleration amplitude [m/s^2] of a sinusoid whose amplitude is given in any unit.

    A velocity amplitude V or displacement amplitude D of a sinusoid at ``frequency`` f [Hz]
    has the acceleration amplitude A = V omega = D omega^2, omega = 2 pi f.
    """
    value = quantity.to_si(body)
    omega = 2.0 * math.pi * frequency
    if quantity.dimension == "velocity":
        return value * omega
    if quantity.dimension == "length":
        return value * omega ** 2
    if quantity.dimension == "acceleration":
        return value
    raise ValueError(f"'{quantity}' is not an acceleration, velocity or displacement")
