"""Bodies files of ``python -m sweep.estimate``: bodies seen overturned and standing at a site.

A bodies file::

    site: village graveyard            # optional
    bodies:
      - {name: stone 1, B: 30 cm, H: 90 cm, overturned: true, direction: N}
      - {name: stone 2, B: 40 cm, H: 80 cm, overturned: false, mu: 0.6}

``B``, ``H`` (and the optional radius of gyration ``i_g``) are lengths with units
(``sweep.io.units``); ``mu`` is the friction coefficient, if known; ``direction`` any label of
the direction of fall.  ``load_bodies`` checks a file with the pydantic models below and reports
every problem at once, as scene and study files do.
"""
from dataclasses import dataclass
from typing import Annotated, Optional, Union

from pydantic import Field, StrictBool, StrictFloat, StrictInt, StrictStr, ValidationError

from .problems import FileProblems, validation_problems
from .scene_schema import Coefficient, Length, StrictModel
from .yamlio import read_yaml, top_level_problems


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


class BodyEntry(StrictModel):
    """An entry of ``bodies``: size, state and what else is known of the body."""

    name: Optional[Union[StrictStr, StrictInt, StrictFloat]] = None
    B: Length
    H: Length
    i_g: Optional[Length] = None
    overturned: StrictBool
    mu: Optional[Coefficient] = None
    direction: Optional[StrictStr] = None


class BodiesFile(StrictModel):
    """A bodies file: an optional ``site`` and a non-empty list of ``bodies``."""

    site: Optional[StrictStr] = None
    bodies: Annotated[list[BodyEntry], Field(min_length=1)]


_FIELD_NAMES = sorted(set(BodiesFile.model_fields) | set(BodyEntry.model_fields))


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
    top = top_level_problems(raw, [], "bodies file", "site, bodies")
    if top:
        raise FileProblems(top, name)
    try:
        checked = BodiesFile.model_validate(raw)
    except ValidationError as err:
        raise FileProblems(validation_problems(err, _FIELD_NAMES), name) from None
    bodies = [Body(name=f"body {i + 1}" if b.name is None else str(b.name), B=b.B.to_si(),
                   H=b.H.to_si(), overturned=b.overturned,
                   i_g=None if b.i_g is None else b.i_g.to_si(),
                   mu=None if b.mu is None else float(b.mu), direction=b.direction)
              for i, b in enumerate(checked.bodies)]
    return checked.site, bodies
