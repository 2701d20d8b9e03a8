"""Quantities of scene files: a number in SI units or a string ``"<number> <unit>"``.

A value is parsed first into a :class:`Quantity` (value, unit, dimension), which checks the unit
against the field's dimension; it is turned into SI later by :meth:`Quantity.to_si`, which needs
the body for the paper's body-relative units: ``west`` (x (B/H) g, Eq. (1)), ``v_H`` (x the
single-shock overturning velocity, Eq. (9)) and ``alpha`` (x the slenderness angle atan(B/H)).
Unit names are case-insensitive; ``sec`` may stand for ``s``.
"""
import functools
import math
import re
from dataclasses import dataclass

from ..paper import criteria

DIMENSIONS = ("acceleration", "velocity", "length", "angle", "angular_velocity", "frequency",
              "time", "dimensionless")

# unit -> (dimension, factor to SI); keys are lower case
_FIXED = {
    "m/s^2": ("acceleration", 1.0), "cm/s^2": ("acceleration", 0.01),
    "mm/s^2": ("acceleration", 0.001), "gal": ("acceleration", 0.01),
    "g": ("acceleration", criteria.G),
    "m/s": ("velocity", 1.0), "cm/s": ("velocity", 0.01), "mm/s": ("velocity", 0.001),
    "kine": ("velocity", 0.01),
    "m": ("length", 1.0), "cm": ("length", 0.01), "mm": ("length", 0.001),
    "km": ("length", 1000.0),
    "rad": ("angle", 1.0), "deg": ("angle", math.pi / 180.0),
    "rad/s": ("angular_velocity", 1.0), "deg/s": ("angular_velocity", math.pi / 180.0),
    "hz": ("frequency", 1.0),
    "s": ("time", 1.0), "ms": ("time", 0.001), "min": ("time", 60.0),
}
# body-relative unit -> dimension; the factor depends on the body (see Quantity.to_si)
_RELATIVE = {"west": "acceleration", "v_h": "velocity", "alpha": "angle"}
_SPELLING = {"west": "west", "v_h": "v_H", "alpha": "alpha", "hz": "Hz"}
_EXAMPLES = {"acceleration": "341.7 gal", "velocity": "100 cm/s", "length": "10 cm",
             "angle": "30 deg", "angular_velocity": "10 deg/s", "frequency": "2 Hz",
             "time": "500 ms", "dimensionless": "0.5"}

_NUMBER = r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?"
_PATTERN = re.compile(rf"^\s*({_NUMBER})\s*([^\s\d.+-][^\s]*)?\s*$")


@functools.lru_cache(maxsize=256)
def _normalize(unit):
    """Canonical lower-case spelling: ``cm/sec2`` -> ``cm/s^2``, ``m/s/s`` -> ``m/s^2``."""
    u = unit.strip().lower().replace("**", "^").replace("sec", "s")
    u = re.sub(r"/s/s$", "/s^2", u)
    return re.sub(r"/s2$", "/s^2", u)


def units_of(dimension):
    """Unit names accepted for ``dimension`` (SI first), for messages."""
    names = [_SPELLING.get(u, u) for u, (d, _) in _FIXED.items() if d == dimension]
    names += [_SPELLING[u] for u, d in _RELATIVE.items() if d == dimension]
    return tuple(names)


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
            ``{"B": m, "H": m, "i_g": m or None}``; required for body-relative units.
        """
        if not self.unit:
            return self.value
        if self.unit in _FIXED:
            return self.value * _FIXED[self.unit][1]
        if body is None:
            raise ValueError(f"'{self}' is relative to the body and needs its B and H")
        B, H, i_g = body["B"], body["H"], body.get("i_g")
        if self.unit == "west":
            factor = criteria.west_acceleration(B, H)
        elif self.unit == "v_h":
            factor = criteria.single_shock_velocity(B, H, i_g)
        else:
            factor = criteria.body_constants(B, H, i_g).alpha
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
        match = _PATTERN.match(raw)
        if match is None:
            raise ValueError("expected a number or a string '<number> <unit>', e.g. "
                             f"'{_EXAMPLES[allowed[0]]}'")
        value, unit = float(match.group(1)), _normalize(match.group(2) or "")
    else:
        value, unit = _float(raw), ""
    if not math.isfinite(value):
        raise ValueError("must be a finite number")
    if not unit:
        return Quantity(value, "", allowed[0])
    found = _FIXED[unit][0] if unit in _FIXED else _RELATIVE.get(unit)
    if found is None:
        names = ", ".join(n for d in allowed for n in units_of(d))
        raise ValueError(f"unknown unit '{match.group(2)}' for {_either(allowed)}; use one of: "
                         f"{names}")
    if found not in allowed:
        raise ValueError(f"'{match.group(2)}' is a unit of {found.replace('_', ' ')}, "
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
