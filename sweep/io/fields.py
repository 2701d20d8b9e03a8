"""Fields shared by the input files' pydantic models, and their base :class:`StrictModel`.

Quantities with units and bounds, plain numbers, counts and seeds; :class:`StrictModel` is the
base of every section of a file."""
import sys
from dataclasses import dataclass
from typing import Annotated

from pydantic import (AfterValidator, BaseModel, BeforeValidator, ConfigDict, Field,
                      PlainValidator, model_validator)

from . import units
from .units import Quantity

MAX_COUNT = 2 ** 53  # largest count (max_steps, max_events) a float64 scene field holds exactly


@dataclass(frozen=True)
class QuantityOf:
    """Annotation of a quantity field: its dimensions and bound, for its JSON Schema (a number
    in SI units or a string ``"<number> <unit>"``) and the reference (``sweep.io.reference``)."""

    dimensions: tuple
    gt: float = None
    ge: float = None

    def __get_pydantic_json_schema__(self, core_schema, handler):
        bounds = {key: value for key, value in (("exclusiveMinimum", self.gt),
                                                ("minimum", self.ge)) if value is not None}
        return {"anyOf": [{"type": "number", **bounds},
                          {"type": "string", "pattern": units.QUANTITY_PATTERN}],
                "x-dimensions": list(self.dimensions)}


def quantity(*dimensions, gt=None, ge=None):
    """Annotated type: a :class:`Quantity` of ``dimensions`` with an optional sign check."""
    def check(q):
        # every unit factor is positive, so the sign of the value is the sign in SI
        if gt is not None and not q.value > gt:
            raise ValueError(f"must be greater than {gt}")
        if ge is not None and not q.value >= ge:
            raise ValueError(f"must be greater than or equal to {ge}")
        return q
    return Annotated[Quantity, PlainValidator(lambda v: units.parse_quantity(v, dimensions)),
                     AfterValidator(check), QuantityOf(dimensions, gt, ge)]


def _plain_number(value):
    """Refuse true/false where a number is meant (YAML's booleans are ints to Python), and an
    integer beyond the float range."""
    if isinstance(value, bool):
        raise ValueError("must be a number, not true/false")
    if isinstance(value, int) and abs(value) > sys.float_info.max:
        raise ValueError("must be a finite number")
    return value


Real = Annotated[float, BeforeValidator(_plain_number)]
Count = Annotated[int, BeforeValidator(_plain_number), Field(gt=0, le=MAX_COUNT)]
Length = quantity("length", gt=0)
Instant = quantity("time", ge=0)
Duration = quantity("time", gt=0)
Frequency = quantity("frequency", gt=0)
Angle = quantity("angle")
Acceleration = quantity("acceleration")
Coefficient = Annotated[Real, Field(ge=0)]
Seed = Annotated[int, BeforeValidator(_plain_number), Field(ge=0, le=2 ** 63 - 1)]


class StrictModel(BaseModel):
    """A section of an input file: unknown keys and non-finite numbers refused."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)

    @model_validator(mode="before")
    @classmethod
    def _empty_section(cls, data):
        """A section written with nothing under it (``contact:``) is an empty mapping."""
        return {} if data is None else data

