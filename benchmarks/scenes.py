"""Reference scenes of the work-precision benchmark (docs/design.md section 10) and their errors.

Each scene is a scene-file dict (units as in scene files), what its error measures, where its
reference comes from (an exact anchor of docs/physics.md section 4, or a tight-tolerance run), and
whether the rocking-only scipy model (``scipy_rocking``) solves the same problem: that needs
Housner's impact (e_x = e_y = 0) and friction that never lets the pivot slip (mu = 10), and a
scene in which the pivot never slips or lifts before the end.
"""
import math
from dataclasses import dataclass, field

import numpy as np

from sweep.io.scene_schema import load_scene, resolve_scene

from tests.naive import floor_motion

from . import references, scipy_rocking

HOUSNER = {"mu": 10.0, "e_x": 0.0, "e_y": 0.0}
THETA0_FREE = 0.5      # free rocking from theta0 = 0.5 alpha (docs/physics.md A4)
N_FREE = 50            # impacts compared with the quadrature anchor (t_50 = 1.783179 s)
# Impacts of an accumulation (chatter before rest) whose post-impact |omega| is below this
# are not compared: how many there are depends on the Zeno closure rule, not on accuracy.
OMEGA_CHATTER = 1e-3   # rad/s


@dataclass(frozen=True)
class Outcome:
    """What the errors are measured on: impact times [s], omega after each impact [rad/s],
    overturning time [s or None], largest slip [m]."""

    impact_times: np.ndarray
    omega_after: np.ndarray
    t_overturn: float | None
    max_slip: float

    @classmethod
    def of_kernel(cls, result):
        return cls(np.asarray(result.impact_times), np.asarray(result.omega_after),
                   result.t_overturn, result.max_slip)

    @classmethod
    def of_scipy(cls, out):
        return cls(np.asarray(out["impact_times"]), np.asarray(out["omega_after"]),
                   out["t_overturn"], math.nan)


@dataclass(frozen=True)
class ReferenceScene:
    """One benchmark scene.

    ``measure`` is ``"impacts"`` (max |t - t_ref| over impacts matched one to one, and the
    overturning time) or ``"slip"`` (|max_slip - ref|, m).  ``anchor`` returns the exact
    reference ``Outcome`` or is None (reference: the kernel at ``REFERENCE_RTOL``).
    ``n_compare`` compares only the first n impacts (the anchor gives n + 1); without it, n is
    the number of reference impacts up to its last one with |omega+| >= ``OMEGA_CHATTER``.  A
    run without exactly n impacts before the midpoint of reference impacts n and n + 1 has a
    count mismatch (error inf).
    """

    key: str
    title: str
    scene: dict
    measure: str = "impacts"
    rocking_only: bool = True
    anchor: object = None
    n_compare: int | None = None
    note: str = ""
    resolved: dict = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        object.__setattr__(self, "resolved", resolve_scene(load_scene(self.scene)))


def _scene(body, contact, horizontal=None, vertical=None, initial=None, t_end=10.0):
    excitation = {"horizontal": horizontal or {"kind": "none"},
                  "vertical": vertical or {"kind": "none"}}
    return {"body": body, "contact": contact, "excitation": excitation,
            "initial": initial or {}, "solver": {"t_end": t_end}}


def _free_rocking_anchor():
    alpha = scipy_rocking.body_constants(0.1, 0.3)[3]
    times = references.free_rocking_impact_times(0.1, 0.3, THETA0_FREE * alpha, N_FREE + 1)
    return Outcome(times, np.full(times.size, math.nan), None, math.nan)


def _slide_anchor():
    a_x = scipy_rocking.sine(0.3 * scipy_rocking.G, 2.0)
    return Outcome(np.empty(0), np.empty(0), None,
                   references.rigid_plastic_slide(a_x, 0.2, 10.0)[2])


SCENES = (
    ReferenceScene(
        "steady_rocking", "Steady rocking",
        _scene({"B": 0.1, "H": 0.3}, HOUSNER,
               {"kind": "sine", "amplitude": "1.5 west", "frequency": 4.0}),
        note="B = 0.1 m, H = 0.3 m, 1.5 west (0.5 g) at 4 Hz, 10 s, Housner impact "
             "(studies/steady_rocking.yaml)"),
    ReferenceScene(
        "free_rocking", "Free rocking to rest",
        _scene({"B": 0.1, "H": 0.3}, HOUSNER, initial={"theta": f"{THETA0_FREE} alpha"},
               t_end=3.0),
        anchor=_free_rocking_anchor, n_compare=N_FREE,
        note=f"released at rest from {THETA0_FREE} alpha, 3 s; error over the first {N_FREE} "
             "impacts against the quadrature of docs/physics.md A4 (accumulation at 1.783685 s)"),
    ReferenceScene(
        "overturning", "Overturning",
        _scene({"B": 0.1, "H": 0.3}, HOUSNER,
               {"kind": "sine", "amplitude": "0.5 g", "frequency": 1.0}),
        note="0.5 g (1.5 west) at 1 Hz: tips over in its first rocking swing, pure rocking "
             "(at 1 g the pivot slips just before lift-off even with mu = 10); error of "
             "t_overturn"),
    ReferenceScene(
        "sweep", "60 s sweep",
        _scene({"B": 0.1, "H": 0.3}, HOUSNER,
               {"kind": "sweep", "hold": "acceleration", "amplitude": "1.2 west",
                "f_start": 10.0, "f_stop": 2.0, "duration": 60.0, "law": "log"},
               t_end=60.0),
        note="constant acceleration 1.2 west, log sweep 10 -> 2 Hz in 60 s: rocks "
             "throughout without overturning"),
    ReferenceScene(
        "el_centro", "El Centro NS + UD",
        _scene({"B": 0.2, "H": 0.8}, HOUSNER,
               {"kind": "record", "name": "elcentro1940_ns"},
               {"kind": "record", "name": "elcentro1940_ud"}, t_end=30.0),
        note="B = 0.2 m, H = 0.8 m, El Centro 1940 NS with UD, first 30 s; rocks without "
             "overturning and comes to rest at 13.78 s through an accumulation of impacts; "
             "impact times amplify early errors about 1e4-fold by then.  The records are "
             "piecewise linear: the kernel steps from sample to sample, scipy's DOP853 steps "
             "across the kinks (as a user's call of solve_ivp does)"),
    ReferenceScene(
        "sliding", "Stick-slip sliding",
        _scene({"B": 0.3, "H": 0.3}, {"mu": 0.2},
               {"kind": "sine", "amplitude": "0.3 g", "frequency": 2.0}),
        measure="slip", rocking_only=False, anchor=_slide_anchor,
        note="B = H = 0.3 m, mu = 0.2 < b/h, 0.3 g at 2 Hz, 10 s: slides only; error of the "
             "largest slip against Newmark's rigid-plastic block (docs/physics.md A6, scipy rtol "
             "1e-12)"),
)


def scipy_problem(resolved):
    """Keyword arguments of ``scipy_rocking.housner_rocking`` for a resolved rocking scene.

    The Zeno closure follows the kernel's rule (an impact is the last when the next would
    come within ``zeno_dt``) for a still floor: after omega+ from theta = 0 the block returns
    in 2 omega+/(p^2 sin alpha) (docs/physics.md 1.2 (3) at theta = 0), hence zeno_omega =
    p^2 sin(alpha) zeno_dt / 2.
    """
    body, solver = resolved["body"], resolved["solver"]
    b, h, r, alpha, i2, eta, p = scipy_rocking.body_constants(body["B"], body["H"])
    a_x, breaks_x = floor_motion(resolved["excitation"]["horizontal"])
    a_y, breaks_y = floor_motion(resolved["excitation"]["vertical"])
    initial = resolved["initial"]
    return dict(B=body["B"], H=body["H"], a_x=a_x, a_y=a_y, theta0=initial["theta"],
                omega0=initial["omega"], t_end=solver["t_end"],
                a_x_breaks=tuple(sorted(set(breaks_x) | set(breaks_y))),
                theta_over=solver["theta_overturn"],
                zeno_omega=0.5 * p * p * math.sin(alpha) * solver["zeno_dt"])


def error(outcome, reference, scene):
    """(error, note): the scene's error of ``outcome``; inf and a note when not comparable."""
    if scene.measure == "slip":
        return abs(outcome.max_slip - reference.max_slip), ""
    if (outcome.t_overturn is None) != (reference.t_overturn is None):
        said = "overturned" if outcome.t_overturn is not None else "did not overturn"
        return math.inf, f"{said}, unlike the reference"
    t, t_ref = outcome.impact_times, reference.impact_times
    n = scene.n_compare
    if n is None:
        strong = np.flatnonzero(np.abs(reference.omega_after) >= OMEGA_CHATTER)
        n = int(strong[-1]) + 1 if strong.size else 0
    # the run must have n impacts before the midpoint of reference impacts n and n + 1
    window = 0.5 * ((t_ref[n - 1] if n else 0.0) + t_ref[n]) if n < t_ref.size else math.inf
    count = int(np.sum(t < window))
    if count != n:
        return math.inf, f"{count} impacts, reference {n}" + \
            (f" (before {window:.4g} s)" if math.isfinite(window) else "")
    t, t_ref = t[:n], t_ref[:n]
    err = float(np.max(np.abs(t - t_ref))) if t.size else 0.0
    if outcome.t_overturn is not None:
        err = max(err, abs(outcome.t_overturn - reference.t_overturn))
    return err, ""
