"""The pydantic models of a scene's body, contact and restraint: shape, mass, friction, anchor.

A body is given as a rectangle (``B``, ``H``, ``G``, ``i_g``) or in the precarious-rock form
(``alpha_1, alpha_2`` with ``R_1, R_2`` or the height ``h`` of G), docs/bodies.md, with its
``mass`` where a restraint needs it; the contact as its friction and restitution coefficients
and its landing law (docs/physics.md §2); the restraint as an anchor's ties (docs/anchors.md).
"""
import math
from typing import Annotated, Literal, Optional

from pydantic import ConfigDict, Field, field_validator, model_validator

from kernels.api import DEFAULTS
from kernels.codes import LANDING_NAMES, RESTRAINT_NAMES

from .fields import Angle, Coefficient, Length, Real, StrictModel, quantity
from .problems import MISSING, FieldError
from .units import Quantity


class Body(StrictModel):
    """Full breadth ``B`` and height ``H``, centre of gravity ``G`` and ``i_g`` radius of
    gyration about G (default uniform); or, as the precarious-rock literature gives a body,
    ``alpha_1, alpha_2`` with ``R_1, R_2`` or with the height ``h`` of G (and optionally
    ``H``), converted into B and G (docs/bodies.md)."""

    model_config = ConfigDict(json_schema_extra={"if": {"not": {"required": ["alpha_1"]}},
                                                 "then": {"required": ["B", "H"]}})

    B: Optional[Length] = Field(None, description="full breadth (b = B/2); required unless "
                                                  "the rock form (alpha_1, alpha_2) is given")
    H: Optional[Length] = Field(None, description="full height (h = H/2); required unless "
                                                  "the rock form gives G (default 2 y_G)")
    G: Optional[Annotated[list[quantity("length")], Field(min_length=2, max_length=2)]] = Field(
        None, description="centre of gravity [x, y] from the middle of the base, x to the "
                          "right; default [0, H/2]")
    i_g: Optional[Length] = Field(None, description="radius of gyration about the centre of "
                                                    "gravity G; default a uniform block's, "
                                                    "sqrt((B^2 + H^2)/12)")
    alpha_1: Optional[Angle] = Field(None, description="angle at G between the vertical and "
                                                       "the left corner (-x), atan(b1/y_G)")
    alpha_2: Optional[Angle] = Field(None, description="angle at G between the vertical and "
                                                       "the right corner (+x), atan(b2/y_G)")
    R_1: Optional[Length] = Field(None, description="distance from G to the left corner")
    R_2: Optional[Length] = Field(None, description="distance from G to the right corner")
    h: Optional[Length] = Field(None, description="height of G above the base, with alpha_1 "
                                                  "and alpha_2 instead of R_1, R_2")
    mass: Optional[quantity("mass", gt=0)] = Field(
        None, description="mass of the body; required by a restraint")

    @field_validator("i_g")
    @classmethod
    def _square_finite(cls, i_g):
        """The kernel takes i_g squared."""
        if i_g is not None and not math.isfinite(i_g.to_si() * i_g.to_si()):
            raise ValueError("too large: its square leaves the float range")
        return i_g

    @property
    def form(self):
        """``"rock"`` for a body given by alpha_1, alpha_2 (its shape above the base unknown),
        else ``"rectangle"`` (B x H)."""
        return "rock" if self.alpha_1 is not None else "rectangle"

    @model_validator(mode="after")
    def _one_form(self):
        """B and H (and G), or the rock form turned into B and G (:meth:`_corners`)."""
        if all(getattr(self, key) is None for key in ROCK_KEYS):
            missing = [key for key in ("B", "H") if getattr(self, key) is None]
            if missing:
                raise FieldError.several([(key, MISSING, "is required (or give alpha_1, "
                                                         "alpha_2 and R_1, R_2 or h)")
                                          for key in missing])
            return self
        if self.B is not None or self.G is not None:
            raise FieldError("B" if self.B is not None else "G", MISSING,
                             "give B and G, or alpha_1, alpha_2 and R_1, R_2 or h, not both")
        b1, b2, h = self._corners()
        self.B = Quantity(b1 + b2, "m", "length")   # in metres: not a bare number written
        self.G = [Quantity(0.5 * (b1 - b2), "m", "length"), Quantity(h, "m", "length")]
        if self.H is None:
            self.H = Quantity(2.0 * h, "m", "length")
        return self

    def _corners(self):
        """(b1, b2, h) [m] of the rock form: b_i = h tan alpha_i with ``h``; with R_1, R_2
        the corners at (-R_1 sin alpha_1, -R_1 cos alpha_1) and (R_2 sin alpha_2,
        -R_2 cos alpha_2) from G, whose heights must agree (to 1e-9)."""
        missing = [key for key in ("alpha_1", "alpha_2") if getattr(self, key) is None]
        lengths = [key for key in ("R_1", "R_2", "h") if getattr(self, key) is not None]
        if missing or not lengths:
            raise FieldError(missing[0] if missing else "R_1", MISSING,
                             "the rock form needs alpha_1, alpha_2 and R_1, R_2 or h")
        if "h" in lengths and len(lengths) > 1:
            raise FieldError("h", str(self.h), "give R_1, R_2 or h, not both")
        if lengths in (["R_1"], ["R_2"]):
            raise FieldError("R_2" if lengths == ["R_1"] else "R_1", MISSING,
                             "the rock form needs R_1 and R_2 (or h)")
        a1, a2 = self.alpha_1.to_si(), self.alpha_2.to_si()
        for key, a in (("alpha_1", a1), ("alpha_2", a2)):
            if not 0.0 < a < math.pi / 2:
                raise FieldError(key, str(getattr(self, key)), "must lie between 0 and 90 deg")
        if self.h is not None:
            h = self.h.to_si()
            return h * math.tan(a1), h * math.tan(a2), h
        R1, R2 = self.R_1.to_si(), self.R_2.to_si()
        h1, h2 = R1 * math.cos(a1), R2 * math.cos(a2)
        if abs(h1 - h2) > 1e-9 * max(h1, h2):
            raise FieldError("R_2", str(self.R_2), _disagreeing_r2(self.R_2, h1 / math.cos(a2)))
        return R1 * math.sin(a1), R2 * math.sin(a2), 0.5 * (h1 + h2)


ROCK_KEYS = ("alpha_1", "alpha_2", "R_1", "R_2", "h")


def _disagreeing_r2(R_2, agreeing):
    """The message of an ``R_2`` whose corner is not at the height of R_1's: the value
    ``agreeing`` [m] that would be, in R_2's own unit."""
    unit = R_2.unit or "m"
    value = agreeing * R_2.value / R_2.to_si()
    return (f"R_2 = {R_2.value:.12g} {unit} does not agree with R_1 cos alpha_1 / cos alpha_2 "
            f"= {value:.6g} {unit}: give R_2: {value:.12g} {unit}, or use "
            "{alpha_1, alpha_2, h}")


class Contact(StrictModel):
    """Friction and restitution; ``mu`` sets all four friction coefficients, explicit ones win."""

    mu: Optional[Coefficient] = Field(None, description="the four friction coefficients "
                                                       "at once")
    mu_s: Optional[Coefficient] = Field(None, description="static friction, the base face on "
                                                         "the floor")
    mu_k: Optional[Coefficient] = Field(None, description="kinetic friction, the base face on "
                                                         "the floor")
    mu_edge_s: Optional[Coefficient] = Field(None, description="static friction, one corner "
                                                              "on the floor")
    mu_edge_k: Optional[Coefficient] = Field(None, description="kinetic friction, one corner "
                                                              "on the floor")
    e_x: Optional[Annotated[Real, Field(ge=-1, le=1)]] = Field(
        None, description="tangential restitution: -1 keeps, 0 stops the tangential velocity")
    e_y: Optional[Annotated[Real, Field(ge=0, le=1)]] = Field(
        None, description="normal restitution (0 with enough friction: Housner's impact)")
    landing: Literal[LANDING_NAMES] = Field(
        DEFAULTS["contact"]["landing"], description="law of a landing after a translation "
        "jump: face_friction (one contact at the middle of the base: its friction turns the "
        "body; the paper's Fig. 5), flat (two-contact impulse), corner (the leading corner "
        "first); docs/landing.md")


class Restraint(StrictModel):
    """An anchor: a tension-only vertical tie at each corner of the base, rigid until it must
    pull harder than its ``strength``, then broken for good (docs/anchors.md)."""

    kind: Literal[RESTRAINT_NAMES[1:]] = Field(description="the kind of restraint")
    strength: quantity("force", ge=0) = Field(description="the pull at which a tie breaks")
