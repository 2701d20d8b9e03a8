"""The pydantic models of a scene file: excitation, initial state, solver, the scene itself.

The excitation is any kind of ground motion (docs/design.md section 4); the validators do every
check of a scene, the cross-field ones included.  Fields left out take
``kernels.api.DEFAULTS``; ``sweep.io.scene_schema`` loads a file into them and resolves them
into SI.  The body, the contact and the restraint are in ``sweep.io.body_models``.
"""
from pathlib import Path
from typing import Annotated, Literal, Optional, Union

from pydantic import (BeforeValidator, Discriminator, Field, PlainValidator, Tag,
                      ValidationInfo, WithJsonSchema, field_validator, model_validator)

from kernels.api import DEFAULTS

from . import records, units
from .body_models import Body, Contact, Restraint
from .fields import (Acceleration, Angle, Count, Duration, Frequency, Instant, QuantityOf, Real,
                     Seed, StrictModel, _plain_number, quantity)
from .problems import MISSING, FieldError
from .units import Quantity

KINDS = ("none", "sine", "sweep", "record", "pulse", "synthetic", "floor", "isolated")
SCALE_KEYS = ("scale", "pga", "pgv", "sa")  # how a record or synthetic motion is scaled
HOLD_DIMENSIONS = {"acceleration": "acceleration", "velocity": "velocity",
                   "displacement": "length"}


class _Ground(StrictModel):
    """A floor-motion component; the floor is still outside [start, start + duration)."""

    start: Optional[Instant] = Field(None, description="when the component starts moving "
                                                       "the floor")
    duration: Optional[Duration] = Field(None, description="how long it moves the floor "
                                                           "(default: to its end)")


class NoMotion(StrictModel):
    """A floor still along this direction."""

    kind: Literal["none"] = Field(description="the kind of motion")


class _Phased(_Ground):
    """A periodic motion's ``phase``, or a ``seed`` that draws it uniformly in [0, 2 pi)."""

    phase: Optional[Angle] = Field(None, description="phase at the start")
    seed: Optional[Seed] = Field(None, description="draws the phase uniformly in [0, 2 pi) "
                                                   "instead")

    @model_validator(mode="after")
    def _phase_or_seed(self):
        if self.phase is not None and self.seed is not None:
            raise FieldError("seed", self.seed, "give either phase or seed, not both")
        return self


class SineMotion(_Phased):
    """Amplitude as acceleration, velocity or displacement (converted with omega = 2 pi f)."""

    kind: Literal["sine"] = Field(description="the kind of motion")
    amplitude: quantity("acceleration", "velocity", "length") = Field(
        description="acceleration, velocity or displacement amplitude")
    frequency: Frequency = Field(description="frequency f")


class SweepMotion(_Phased):
    """Frequency sweep keeping the amplitude named by ``hold`` constant; ``duration`` = length."""

    kind: Literal["sweep"] = Field(description="the kind of motion")
    hold: Literal["acceleration", "velocity", "displacement"] = Field(
        DEFAULTS["ground"]["hold"], description="the amplitude kept constant")
    amplitude: Annotated[Quantity, QuantityOf(tuple(HOLD_DIMENSIONS.values()))] = Field(
        description="the amplitude held, of the dimension that hold names")
    f_start: Frequency = Field(description="frequency at the start")
    f_stop: Frequency = Field(description="frequency at the end")
    duration: Duration = Field(description="length of the sweep")
    law: Optional[Literal["log", "linear"]] = Field(None, description="frequency against time")

    @field_validator("amplitude", mode="plain")
    @classmethod
    def _amplitude_of_hold(cls, value, info: ValidationInfo):
        hold = info.data.get("hold")
        if hold is None:  # hold itself is wrong and reported; still check the amplitude
            return units.parse_quantity(value, tuple(HOLD_DIMENSIONS.values()))
        try:
            return units.parse_quantity(value, HOLD_DIMENSIONS[hold])
        except ValueError as err:
            raise ValueError(f"{err} (hold: {hold})") from None


class SpectralTarget(StrictModel):
    """The 5 %-damped pseudo-spectral acceleration Sa(T) a motion is scaled to
    (``sweep.groundmotion.oscillator``); T = 0 is the PGA."""

    period: Instant = Field(description="period T of the oscillator")
    value: quantity("acceleration", gt=0) = Field(description="Sa(T, 5 %) after scaling")


class _Scaled(_Ground):
    """An accelerogram multiplied by ``scale``, or scaled so that its PGA, its PGV
    (``sweep.groundmotion.intensity``) or its Sa(T) is the one given; a vertical component may
    take the horizontal one's factor instead (``scale_with: horizontal``), which keeps their
    ratio."""

    scale: Optional[Real] = Field(None, description="factor on the samples (-1 flips the "
                                                    "polarity)")
    pga: Optional[quantity("acceleration", gt=0)] = Field(
        None, description="the PGA the motion is scaled to")
    pgv: Optional[quantity("velocity", gt=0)] = Field(
        None, description="the PGV (after a 0.1 Hz baseline correction) it is scaled to")
    sa: Optional[SpectralTarget] = Field(
        None, description="the 5 %-damped pseudo-spectral acceleration it is scaled to: "
                          "{period, value}")
    scale_with: Optional[Literal["horizontal"]] = Field(
        None, description="vertical only: the horizontal component's scale factor")

    @model_validator(mode="after")
    def _one_scale(self):
        given = [key for key in SCALE_KEYS if getattr(self, key) is not None]
        if self.scale_with is not None and given:
            raise FieldError("scale_with", self.scale_with,
                              f"takes the {self.scale_with} component's scale factor: give no "
                              f"{given[0]} with it")
        if len(given) > 1:
            raise FieldError(given[1], str(getattr(self, given[1])),
                              f"give one of scale, pga, pgv and sa, not "
                              f"{' and '.join(given)}")
        return self


def _component(value):
    """A component of a record file: its number (from 1) or its name."""
    if isinstance(value, bool) or not isinstance(value, (int, str)):
        raise ValueError("must be a component's number (1, 2, ...) or its name")
    if isinstance(value, int) and value < 1:
        raise ValueError("component numbers start at 1")
    if isinstance(value, str) and not value.strip():
        raise ValueError("must not be empty")
    return value


class RecordMotion(_Scaled):
    """A bundled record (``name``) or a user's file (``path``), scaled by ``scale`` or to ``pga``
    or ``pgv``.

    A file's format (``records.FORMATS``) is told by its extension or content unless ``format``
    names it (docs/record_formats.md).  ``units`` is the acceleration unit of a two- or
    one-column file (default: the unit its ``#`` comments state, else m/s^2); a file that
    states its units (every other format; comments) refuses another.  ``dt`` is the sample step
    of a one-column file, required there only; ``component`` picks one of the components of a
    COSMOS or CSMIP file, by number or name.  A relative ``path`` is taken from the scene
    file's folder.
    """

    kind: Literal["record"] = Field(description="the kind of motion")
    name: Optional[str] = Field(None, description="a bundled record: "
                                                  + ", ".join(records.NAMES))
    units: Optional[str] = Field(None, description="acceleration unit of a one- or two-column "
                                                   "file (default: the one its comments "
                                                   "state, else m/s^2)")
    format: Optional[Literal[records.FORMATS]] = Field(None, description="the file's format "
                                                                         "(default: told by "
                                                                         "its name or content)")
    dt: Optional[Duration] = Field(None, description="sample step of a one-column file")
    component: Optional[Annotated[Union[int, str], PlainValidator(_component), WithJsonSchema(
        {"anyOf": [{"type": "integer", "minimum": 1}, {"type": "string"}]})]] = Field(
        None, description="component of a COSMOS or CSMIP file: its number (from 1) or name")
    path: Optional[str] = Field(None, description="a record file, relative to the scene "
                                                  "file's folder")

    @field_validator("name")
    @classmethod
    def _known_name(cls, name):
        if name is not None and name not in records.NAMES:
            raise ValueError(f"unknown record; bundled records: {', '.join(records.NAMES)}")
        return name

    @field_validator("units")
    @classmethod
    def _acceleration_unit(cls, unit):
        if unit is not None:
            units.fixed_factor(unit, "acceleration")
        return unit

    @field_validator("path")
    @classmethod
    def _readable(cls, path, info: ValidationInfo):
        if path is None:
            return None
        base = Path((info.context or {}).get("base_dir") or ".")
        full = (base / Path(path).expanduser()).resolve()
        if all(key in info.data for key in _FILE_OPTIONS):  # else an option's own error says it
            try:
                _read_file(full, info.data)
            except records.RecordError as err:
                raise ValueError(str(err)) from None
        return str(full)

    @model_validator(mode="after")
    def _one_source_one_scale(self):
        if self.name is None and self.path is None:
            raise FieldError("name", MISSING,
                              "required: name (a bundled record) or path (a file)")
        if self.name is not None and self.path is not None:
            raise FieldError("path", self.path, "give either name or path, not both")
        for key in _FILE_OPTIONS:
            if getattr(self, key) is not None and self.path is None:
                raise FieldError(key, str(getattr(self, key)), "given for a path: file only")
        return self


_FILE_OPTIONS = ("units", "format", "dt", "component")


def _read_file(path, options):
    """The :class:`~sweep.io.records.Record` of a record file with the options of a
    :class:`RecordMotion` (``units``, ``format``, ``dt``, ``component`` in ``options``)."""
    dt = options["dt"]
    return records.read_record_file(path, options["units"], format=options["format"],
                                    dt=None if dt is None else dt.to_si(),
                                    component=options["component"])


class SyntheticMotion(_Scaled):
    """A motion of a published stochastic model for an earthquake scenario
    (``sweep.groundmotion.stochastic``): moment magnitude, distance to the rupture, Vs30 and
    the seed of the noise; sampled every ``dt``."""

    kind: Literal["synthetic"] = Field(description="the kind of motion")
    model: str = Field("boore2003", description="the stochastic ground-motion model")
    magnitude: Annotated[Real, Field(ge=4.0, le=8.5)] = Field(description="moment magnitude")
    distance: quantity("length", gt=0) = Field(description="distance to the rupture")
    vs30: quantity("velocity", gt=0) = Field(description="mean shear-wave velocity of the "
                                                         "site's top 30 m")
    seed: Seed = Field(0, description="seed of the noise")
    dt: Optional[Duration] = Field(None, description="sample step (default: the model's)")

    @field_validator("model")
    @classmethod
    def _known_model(cls, model):
        from ..groundmotion import stochastic
        if model not in stochastic.MODELS:
            raise ValueError(f"unknown model; models: {', '.join(stochastic.MODELS)}")
        return model


class PulseMotion(_Ground):
    """Rectangular or triangular acceleration pulse of length ``duration``."""

    kind: Literal["pulse"] = Field(description="the kind of motion")
    shape: Literal["rectangular", "triangular"] = Field(description="the pulse's shape")
    amplitude: Acceleration = Field(description="peak acceleration")
    duration: Duration = Field(description="length of the pulse")


GroundMotion = Annotated[Union[NoMotion, SineMotion, SweepMotion, RecordMotion, PulseMotion,
                               SyntheticMotion], Field(discriminator="kind")]


def _ratio(value):
    """A damping ratio: a number (0.05) or a percentage (``"5 %"``)."""
    if isinstance(value, str) and value.strip().endswith("%"):
        try:
            return float(value.strip()[:-1]) / 100.0
        except ValueError:
            raise ValueError("must be a number or a percentage such as '5 %'") from None
    return _plain_number(value)


Damping = Annotated[float, BeforeValidator(_ratio), Field(ge=0, lt=1), WithJsonSchema(
    {"anyOf": [{"type": "number", "minimum": 0, "exclusiveMaximum": 1},
               {"type": "string", "pattern": r"^\s*[0-9.]+\s*%\s*$"}]})]


class BuildingMode(StrictModel):
    """One mode of a building at the floor (docs/floors.md)."""

    period: quantity("time", gt=0) = Field(description="period of the mode")
    damping: Optional[Damping] = Field(None, description="damping ratio (default: the "
                                                         "building's)")
    participation: Real = Field(description="participation factor times the mode shape at "
                                            "the floor, Gamma phi")


class Building(StrictModel):
    """A linear building: its fundamental ``period`` and the floor's ``height_ratio`` z/H
    give the modes of a uniform shear beam, or ``modes`` lists them (docs/floors.md)."""

    period: Optional[quantity("time", ge=0)] = Field(
        None, description="fundamental period T1 (0: a rigid building)")
    damping: Damping = Field("5 %", validate_default=True,
                             description="damping ratio of every mode (5 % or 0.05)")
    height_ratio: Annotated[Real, Field(gt=0, le=1)] = Field(
        1.0, description="height of the floor over the building's, z/H (1: the top)")
    modes: Annotated[Union[Annotated[int, BeforeValidator(_plain_number), Field(ge=1, le=100),
                                     Tag("count")],
                           Annotated[list[BuildingMode], Tag("list")]],
                     Discriminator(lambda v: "list" if isinstance(v, list) else "count")] = Field(
        1, description="number of shear-beam modes, or the modes as a list of {period, "
                       "damping, participation}")

    @model_validator(mode="after")
    def _period_or_modes(self):
        if isinstance(self.modes, list):
            given = [k for k in ("period", "height_ratio") if k in self.model_fields_set]
            if given:
                raise FieldError(given[0], str(getattr(self, given[0])),
                                 "the modes are listed: give each one's period and "
                                 "participation there, or a period and a number of modes")
        elif self.period is None:
            raise FieldError("period", MISSING, "the fundamental period is required unless "
                                                "modes lists the modes")
        return self


class FloorMotion(StrictModel):
    """The absolute acceleration of a floor of a linear ``building`` over any ``ground``
    motion (``sweep.groundmotion.floor``); the ground's ``start`` and ``duration`` are the
    floor's."""

    kind: Literal["floor"] = Field(description="the kind of motion")
    ground: GroundMotion = Field(description="the ground motion under the building")
    building: Building = Field(description="the building")

    @field_validator("ground", mode="before")
    @classmethod
    def _none_shorthand(cls, value):
        return {"kind": "none"} if value is None or value == "none" else value

    @model_validator(mode="after")
    def _own_scale(self):
        if getattr(self.ground, "scale_with", None) is not None:
            raise FieldError(("ground", "scale_with"), self.ground.scale_with,
                             "a floor's ground has a scale of its own")
        return self


Under = Annotated[Union[NoMotion, SineMotion, SweepMotion, RecordMotion, PulseMotion,
                        SyntheticMotion, FloorMotion], Field(discriminator="kind")]


class LinearIsolator(StrictModel):
    """A linear isolator: one oscillator of participation 1 (docs/isolation.md)."""

    kind: Literal["linear"] = Field(description="the kind of isolator")
    period: quantity("time", gt=0) = Field(description="isolated period")
    damping: Damping = Field("5 %", validate_default=True,
                             description="damping ratio (5 % or 0.05)")


class FrictionPendulum(StrictModel):
    """A friction pendulum: a Coulomb slider on a sphere (docs/isolation.md)."""

    kind: Literal["friction_pendulum"] = Field(description="the kind of isolator")
    radius: quantity("length", gt=0) = Field(description="radius of the sliding sphere")
    mu: Annotated[Real, Field(ge=0)] = Field(description="friction coefficient of the slider")
    displacement_capacity: Optional[quantity("length", gt=0)] = Field(
        None, description="largest displacement before the stop: a larger one is flagged "
                          "exceeded and cautioned, the slide goes on")


class IsolatedMotion(StrictModel):
    """The absolute acceleration of a platform on an ``isolator`` over any motion ``under``
    it but an isolated one (docs/isolation.md); ``under``'s ``start`` and ``duration`` are the
    platform's."""

    kind: Literal["isolated"] = Field(description="the kind of motion")
    under: Under = Field(description="the motion under the isolator")
    isolator: Annotated[Union[LinearIsolator, FrictionPendulum],
                        Field(discriminator="kind")] = Field(description="the isolator")

    @field_validator("under", mode="before")
    @classmethod
    def _not_isolated(cls, value):
        if isinstance(value, dict) and value.get("kind") == "isolated":
            raise FieldError("kind", "isolated", "an isolator stands on a ground or a floor, "
                                                 "not on another isolator")
        return {"kind": "none"} if value is None or value == "none" else value

    @field_validator("isolator", mode="before")
    @classmethod
    def _known_isolator(cls, value):
        kinds = ("linear", "friction_pendulum")
        if isinstance(value, dict) and "kind" in value and value["kind"] not in kinds:
            raise FieldError("kind", value["kind"],
                             f"unknown kind; expected one of: {', '.join(kinds)}")
        return value

    @model_validator(mode="after")
    def _own_scale(self):
        if getattr(self.under, "scale_with", None) is not None:
            raise FieldError(("under", "scale_with"), self.under.scale_with,
                             "an isolator's ground has a scale of its own")
        return self


Ground = Annotated[Union[NoMotion, SineMotion, SweepMotion, RecordMotion, PulseMotion,
                         SyntheticMotion, FloorMotion, IsolatedMotion],
                   Field(discriminator="kind")]


class Excitation(StrictModel):
    """The floor's motion: one component along each direction, of any kind."""

    horizontal: Ground = Field(default_factory=lambda: NoMotion(kind="none"),
                               description="floor acceleration along x (to the right)")
    vertical: Ground = Field(default_factory=lambda: NoMotion(kind="none"),
                             description="floor acceleration along y (upward)")

    @field_validator("horizontal", "vertical", mode="before")
    @classmethod
    def _none_shorthand(cls, value):
        """``vertical: none`` or an empty entry means no motion."""
        return {"kind": "none"} if value is None or value == "none" else value

    @model_validator(mode="after")
    def _isolated_horizontal(self):
        """An isolator (``kind: isolated``) moves the body horizontally only."""
        if self.vertical.kind == "isolated":
            raise FieldError(("vertical", "kind"), "isolated", "an isolator is horizontal: "
                                                               "give it as the horizontal")
        return self

    @model_validator(mode="after")
    def _scale_with_a_scaled_horizontal(self):
        """``scale_with`` is the vertical's, and needs a horizontal record or synthetic
        motion, which has a scale factor."""
        if isinstance(self.horizontal, _Scaled) and self.horizontal.scale_with is not None:
            raise FieldError(("horizontal", "scale_with"), self.horizontal.scale_with,
                              "only the vertical component can take the horizontal's scale")
        kind = self.horizontal.kind
        if isinstance(self.vertical, _Scaled) and self.vertical.scale_with is not None and \
                kind not in ("record", "synthetic"):
            raise FieldError(("vertical", "scale_with"), self.vertical.scale_with,
                              f"the horizontal component is of kind {kind}: only a record or "
                              "a synthetic motion has a scale factor to share")
        return self


class Initial(StrictModel):
    """Initial state: tilt, angular velocity, velocities of G and lift of the base [SI]."""

    theta: Optional[Angle] = Field(None, description="tilt, > 0 about the left corner")
    omega: Optional[quantity("angular_velocity")] = Field(None,
                                                          description="angular velocity")
    x_dot: Optional[quantity("velocity")] = Field(None, description="horizontal velocity of G")
    y_dot: Optional[quantity("velocity")] = Field(None, description="vertical velocity of G")
    lift: Optional[quantity("length", ge=0)] = Field(None, description="lift of the base "
                                                                       "above the floor")


class Solver(StrictModel):
    """Integrator and guards (docs/physics.md 3); ``t_end`` and ``dt_out`` (the history's sampling)
    default from the excitation."""

    method: Optional[Literal["adaptive", "fixed"]] = Field(
        None, description="steps controlled by rtol and atol, or fixed steps of dt")
    rtol: Optional[Annotated[Real, Field(gt=0)]] = Field(None, description="relative "
                                                                           "tolerance")
    atol: Optional[Annotated[Real, Field(gt=0)]] = Field(None, description="absolute "
                                                                           "tolerance")
    dt: Optional[Duration] = Field(None, description="step of the fixed method")
    max_step: Optional[Duration] = Field(None, description="largest adaptive step")
    t_end: Optional[Duration] = Field(None, description="time simulated (default: the end of "
                                                        "the excitation + 5 s, if it ends)")
    max_steps: Optional[Count] = Field(None, description="steps at most (then status "
                                                         "budget_exhausted)")
    max_events: Optional[Count] = Field(None, description="events (impacts, mode changes) at "
                                                          "most (then budget_exhausted)")
    theta_overturn: Optional[quantity("angle", gt=0)] = Field(
        None, description="|theta| at which the body counts as overturned")
    zeno_dt: Optional[Duration] = Field(None, description="contacts closing again within this "
                                                          "time close at once (Zeno)")
    dt_out: Optional[Duration] = Field(None, description="sampling step of the history "
                                                         "(--history, --plot, --animate)")


class Scene(StrictModel):
    """A scene file (docs/design.md section 4); fields left out take ``kernels.api.DEFAULTS``."""

    body: Body = Field(description="the rigid block")
    contact: Contact = Field(default_factory=Contact, description="friction and restitution")
    excitation: Excitation = Field(default_factory=Excitation, description="the floor's motion")
    initial: Initial = Field(default_factory=Initial, description="the state at t = 0")
    solver: Solver = Field(default_factory=Solver, description="integrator, budgets, history")
    restraint: Optional[Restraint] = Field(None, description="what holds the body down "
                                                             "(default none: free-standing)")

    @model_validator(mode="after")
    def _anchored_at_rest(self):
        """A restraint needs the body's ``mass`` (its strength is a force) and a body that
        starts flat at rest (docs/anchors.md)."""
        if self.restraint is None:
            return self
        errors = [FieldError(("body", "mass"), MISSING, "is required by the restraint: its "
                                                        "strength is a force")
                  ] if self.body.mass is None else []
        errors += [FieldError(("initial", key), str(value), "must be 0: an anchored body "
                                                            "starts flat at rest")
                   for key, value in self.initial if value is not None and value.value != 0]
        if errors:
            raise FieldError.every(errors)
        return self
