"""Scene files (docs/design.md section 4): their checks, and their resolution into SI.

``load_scene`` reads a YAML file (or takes a dict), checks it against the models of
``sweep.io.scene_models`` and reports every problem at once as
:class:`~sweep.io.problems.FileProblems` with dotted paths; ``resolve_scene`` turns the checked
scene into the resolved SI dict of ``kernels/api.py`` (units and body-relative units resolved
with the scene's own body, records loaded, defaults of ``kernels.api.DEFAULTS`` filled in).
"""
import functools
import math

import numpy as np

from kernels.api import DEFAULTS, PackingError, scene_row

from ..groundmotion.oscillator import pseudo_acceleration
from . import floors, records, units
from .loader import load_file
from .problems import MISSING, FileProblems, Problem, dotted_path, warn
from .scene_models import (KINDS, _FILE_OPTIONS, Body, Building, BuildingMode, Contact,
                           Excitation, FloorMotion, FrictionPendulum, Initial,
                           IsolatedMotion, LinearIsolator, NoMotion, PulseMotion,
                           RecordMotion, Restraint, Scene, SineMotion, Solver,
                           SpectralTarget, SweepMotion, SyntheticMotion, _read_file)
from .units import Quantity

T_TAIL = 5.0  # s simulated after the last excitation ends, for the body to settle or fall
MAX_HISTORY = 2_000_000  # samples of a history (about 200 MB): t_end / dt_out at most this
SAMPLES_PER_PERIOD = 20  # history samples per sine or sweep period: its peaks within 1.3 %


# --- errors -----------------------------------------------------------------------------------

_MODELS = (Scene, Body, Contact, Excitation, NoMotion, SineMotion, SweepMotion, RecordMotion,
           SpectralTarget, PulseMotion, SyntheticMotion, FloorMotion, Building, BuildingMode,
           IsolatedMotion, LinearIsolator, FrictionPendulum, Initial, Solver, Restraint)
_FIELD_NAMES = sorted({name for model in _MODELS for name in model.model_fields})


def _union_tag(loc, i):
    """The tag pydantic inserts after a ground component (``excitation.horizontal.sine``), an
    isolator or a building's ``modes``."""
    if i >= 2 and loc[i - 1] in ("horizontal", "vertical", "ground", "under") and \
            loc[i] in KINDS:
        return True
    if loc[i - 1:i] == ("isolator",) and loc[i] in ("linear", "friction_pendulum"):
        return True
    return loc[i - 1:i] == ("modes",) and loc[i] in ("count", "list")


def _dotted(loc):
    """Dotted path of a pydantic location, without union tags
    (``excitation.horizontal.sine.amplitude`` -> ``...horizontal.amplitude``)."""
    return dotted_path(loc, _union_tag)


def load_scene(source, *, base_dir=None):
    """Read and check a scene; every problem is reported at once.

    Parameters
    ----------
    source : str, Path or dict
        A YAML file, or a dict of the same schema (e.g. after :func:`apply_overrides`).
    base_dir : str or Path, optional
        Folder that relative record paths start from; default the file's folder (or the
        working directory for a dict).

    Returns
    -------
    Scene

    Raises
    ------
    FileProblems
        Every syntax error, duplicate key, unknown key, missing value, wrong unit or value out
        of range, each with its dotted path and the value given.
    """
    return load_file(source, Scene, "scene", "body, contact", _FIELD_NAMES, base_dir=base_dir,
                     dotted=_dotted, tags=KINDS, despite_syntax=True)


# --- resolution into SI -----------------------------------------------------------------------

def _si(quantity, default, body=None):
    return default if quantity is None else quantity.to_si(body)


def _phase(g, body):
    """A sine's or sweep's phase [rad]: as given, drawn from its ``seed``, or the default."""
    if g.seed is not None:
        return 2.0 * math.pi * float(np.random.default_rng(g.seed).random())
    return _si(g.phase, DEFAULTS["ground"]["phase"], body)


@functools.lru_cache(maxsize=256)
def _synthetic(model, magnitude, distance, vs30, seed, dt):
    from ..groundmotion import stochastic
    options = {} if dt is None else {"dt": dt}
    return stochastic.generate(model, magnitude, distance, vs30, seed, **options)


def _accelerogram(g):
    """The :class:`~sweep.io.records.Record` of a record or synthetic component."""
    if g.kind == "synthetic":
        try:
            return _synthetic(g.model, g.magnitude, g.distance.to_si(), g.vs30.to_si(), g.seed,
                              None if g.dt is None else g.dt.to_si())
        except ValueError as err:
            raise FileProblems([Problem("model", g.model, str(err))]) from None
    return (records.load_record(g.name) if g.name is not None
            else _read_file(g.path, {key: getattr(g, key) for key in _FILE_OPTIONS}))


def _scale(g, rec, body, excitation):
    """Factor on a record's samples: that of the component ``scale_with`` names (resolved
    before, in ``excitation``), ``scale``, or the one that gives its ``pga``/``pgv``/``sa``."""
    if g.scale_with is not None:
        return excitation[g.scale_with]["scale"]
    if g.pga is not None or g.pgv is not None:
        key = "pga" if g.pga is not None else "pgv"
        target, measured = getattr(g, key), getattr(rec.intensity, key)
    elif g.sa is not None:
        key, target = "sa.value", g.sa.value
        measured = pseudo_acceleration(rec.samples, rec.dt, g.sa.period.to_si())
    else:
        return DEFAULTS["ground"]["scale"] if g.scale is None else g.scale
    if not measured > 0:
        raise FileProblems([Problem(key, str(target), "the motion is zero throughout: it "
                                                      "cannot be scaled to a peak")])
    return target.to_si(body) / measured


def _ground(g, body, excitation, t_end=None):
    """Resolved SI dict of one ground component (kernels/api.py docstring); a synthetic
    motion and a floor resolve into a record (its samples), keeping the :class:`Record` as
    ``source`` (a floor its resolved ``ground`` too).  ``excitation``: the components resolved
    before it; ``t_end``: how long a floor over an endless ground is computed."""
    if g.kind == "none":
        return {"kind": "none"}
    if g.kind == "floor":
        try:
            return floors.resolve_floor(g.building, _ground(g.ground, body, excitation), t_end)
        except FileProblems as err:
            raise err.with_prefix("ground") from None
    if g.kind == "isolated":
        try:
            under = _ground(g.under, body, excitation, t_end)
        except FileProblems as err:
            raise err.with_prefix("under") from None
        return floors.resolve_isolated(g.isolator, under, t_end)
    defaults = DEFAULTS["ground"]
    out = {"kind": g.kind, "start": _si(g.start, defaults["start"]),
           "duration": _si(g.duration, defaults["duration"])}
    if g.kind == "sine":
        frequency = g.frequency.to_si()
        out.update(amplitude=units.acceleration_amplitude(g.amplitude, frequency, body),
                   frequency=frequency, phase=_phase(g, body))
    elif g.kind == "sweep":
        out.update(hold=g.hold, amplitude=g.amplitude.to_si(body), f_start=g.f_start.to_si(),
                   f_stop=g.f_stop.to_si(), law=g.law or defaults["law"],
                   phase=_phase(g, body))
    elif g.kind == "pulse":
        out.update(shape=g.shape, amplitude=g.amplitude.to_si(body))
    else:
        rec = _accelerogram(g)
        out.update(kind="record", samples=rec.samples, dt=rec.dt,
                   scale=_scale(g, rec, body, excitation), source=rec)
    return out


def _capacity_caution(isolator, path):
    """Caution that an isolator's largest displacement is past its ``displacement_capacity``
    (the slide is computed without the stop: docs/isolation.md)."""
    if isolator is not None and isolator["exceeded"]:
        warn([Problem(f"{path}.displacement_capacity", f"{isolator['capacity']:g} m",
                      f"the isolator slides {isolator['max_displacement']:.3g} m, past its "
                      "capacity: the platform's motion is computed as if it had no stop")])


def _end(ground):
    """Time at which a resolved component stops moving the floor: inf never, None no motion."""
    if ground["kind"] == "none":
        return None
    if "ground" in ground:  # a floor ends with its ground's ring-down, or never
        end = _end(ground["ground"])
        if end is None or not math.isfinite(end):
            return end
    length = math.inf if ground["duration"] is None else ground["duration"]
    if ground["kind"] == "record":
        length = min(length, ground["dt"] * len(ground["samples"]))
    return ground["start"] + length


def _history_dt(grounds, t_end):
    """Default sampling of a history: ``DEFAULTS["solver"]["dt_out"]``, or finer to keep every
    peak of the floor motion (the finest record ``dt``; 1/``SAMPLES_PER_PERIOD`` of the period
    of a sine or of a sweep's highest frequency, of a pulse's length), yet coarse enough for
    ``t_end`` to take ``MAX_HISTORY`` samples at most."""
    dt = DEFAULTS["solver"]["dt_out"]
    for ground in grounds:
        if ground["kind"] == "record":
            dt = min(dt, ground["dt"])
        elif ground["kind"] == "sine":
            dt = min(dt, 1.0 / (SAMPLES_PER_PERIOD * ground["frequency"]))
        elif ground["kind"] == "sweep":
            dt = min(dt, 1.0 / (SAMPLES_PER_PERIOD * max(ground["f_start"], ground["f_stop"])))
        elif ground["kind"] == "pulse":
            dt = min(dt, ground["duration"] / SAMPLES_PER_PERIOD)
    return max(dt, t_end / (MAX_HISTORY - 1))  # one sample short of the limit: no rounding over


def resolve_scene(scene):
    """The resolved SI scene dict of ``kernels/api.py`` for a checked scene.

    Parameters
    ----------
    scene : Scene, or anything :func:`load_scene` takes

    Returns
    -------
    dict
        ``body`` (its ``mass`` [kg] when given), ``contact`` (all six coefficients),
        ``excitation`` (``horizontal``, ``vertical``), ``initial``, ``solver`` (all keys)
        and, when the scene has one, ``restraint`` (``kind``, ``strength`` [N]), in m, s,
        rad, Hz, kg, N.  Sine amplitudes are acceleration amplitudes; a sweep's amplitude is
        in the SI unit of its ``hold``;
        a record (or a synthetic motion, resolved into one) has ``samples`` [m/s^2,
        read-only], ``dt``, ``scale`` (from ``pga`` or ``pgv`` if given, or the horizontal's
        for a vertical ``scale_with: horizontal``) and ``source``, the
        :class:`~sweep.io.records.Record`.  A ``seed`` of a sine or sweep is resolved into
        its ``phase``.  Without ``solver.t_end``: the end of the excitation + 5 s when every component
        ends, else ``DEFAULTS["solver"]["t_end"]``.  Without ``solver.dt_out``: the finest record
        ``dt`` or 1/20 of the shortest sine or sweep period (or pulse), at most
        ``DEFAULTS["solver"]["dt_out"]`` (0.02 s), at least ``t_end / MAX_HISTORY``.

    Raises
    ------
    FileProblems
        A value that the kernel refuses once in SI (out of the float range), or ``pga`` asked
        of a record that is zero throughout.
    """
    return resolve_and_pack(scene, [])[0]


def resolve_and_pack(scene, records):
    """:func:`resolve_scene` and the kernel row of the resolved scene, packed once
    (``kernels.api.scene_row``: the scene's records placed in ``records``); raises as
    :func:`resolve_scene` does."""
    if not isinstance(scene, Scene):
        scene = load_scene(scene)
    b = scene.body
    body = {"B": b.B.to_si(), "H": b.H.to_si(), "i_g": _si(b.i_g, DEFAULTS["body"]["i_g"]),
            "G": None if b.G is None else [x.to_si() for x in b.G]}
    if b.mass is not None:
        body["mass"] = b.mass.to_si()

    contact = dict(DEFAULTS["contact"])
    for key in contact:
        if getattr(scene.contact, key) is not None:
            contact[key] = getattr(scene.contact, key)
        elif key.startswith("mu") and scene.contact.mu is not None:
            contact[key] = scene.contact.mu

    excitation = {}
    for key in ("horizontal", "vertical"):
        try:
            excitation[key] = _ground(getattr(scene.excitation, key), body, excitation,
                                      _si(scene.solver.t_end, DEFAULTS["solver"]["t_end"]))
        except FileProblems as err:
            raise err.with_prefix(f"excitation.{key}") from None
        _capacity_caution(excitation[key].get("isolator"), f"excitation.{key}.isolator")

    initial = {key: _si(getattr(scene.initial, key), default, body)
               for key, default in DEFAULTS["initial"].items()}

    solver = dict(DEFAULTS["solver"])
    for key in solver:
        value = getattr(scene.solver, key)
        if value is not None:
            solver[key] = value.to_si(body) if isinstance(value, Quantity) else value
    if scene.solver.t_end is None:
        ends = [e for e in map(_end, excitation.values()) if e is not None]
        if ends and all(math.isfinite(e) for e in ends):
            solver["t_end"] = max(ends) + T_TAIL
    if scene.solver.dt_out is None:
        solver["dt_out"] = _history_dt(excitation.values(), solver["t_end"])
    resolved = {"body": body, "contact": contact, "excitation": excitation,
                "initial": initial, "solver": solver}
    if scene.restraint is not None:
        resolved["restraint"] = {"kind": scene.restraint.kind,
                                 "strength": scene.restraint.strength.to_si()}
    return resolved, _row(resolved, scene, records)


def _row(resolved, scene, records):
    """The kernel row of a resolved scene (``kernels.api.scene_row``); :class:`FileProblems`
    if the kernel refuses a resolved value: values within range as written may leave the
    float range in SI (a displacement amplitude times omega^2)."""
    try:
        return scene_row(resolved, records)
    except PackingError as err:                  # the kernel names the value's dotted path
        path, message = err.path, err.reason
    except (ValueError, ArithmeticError) as err:
        path, message = "(scene)", str(err)
    node = scene
    for key in path.split("."):
        node = getattr(node, key, None)
    given = MISSING if node is None else str(node) if isinstance(node, Quantity) else \
        [str(x) for x in node] if isinstance(node, list) else node
    raise FileProblems([Problem(path, given, f"in SI units: {message.replace('`', '')}")])
