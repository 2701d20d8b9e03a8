"""Integer codes shared by the kernel and its users, and standard gravity.

Modes (the paper's six motion types), end statuses, ground-motion kinds, the record that
describes one scene to the compiled code (``SCENE_DTYPE``) and the record it fills with the
scene's results (``RESULT_DTYPE``), the indices of the state vector, and the columns of the
impact log and the history.  The name tuples feed
error messages and the CF ``flag_meanings`` of the output datasets.  ``G`` is defined here,
once for the kernel (``ground``) and ``sweep`` (``sweep.bodies``): this module imports numpy
alone, so ``sweep``'s input checks read it without loading numba.
"""
import numpy as np

G = 9.80665  # standard gravity [m/s^2]

# --- modes (Ishiyama's Fig. 1) -------------------------------------------------------------
REST, SLIDE, ROTATION, SLIDE_ROTATION, TRANSLATION_JUMP, ROTATION_JUMP = range(6)
MODE_NAMES = ("rest", "slide", "rotation", "slide_rotation", "translation_jump", "rotation_jump")
N_MODES = 6

# --- the full state q = (x, y, theta, u, v, omega) of G relative to the floor ------------
# (docs/physics.md 1.1)
IX, IY, ITHETA, IU, IV, IOMEGA = range(6)
N_STATE = 6
# the mode's contact: corner s (-1 left, +1 right), slip direction sigma, pivot or rest x;
# and the floor acceleration last computed: its time, a_x, a_y and 1 once there is one
CTX_S, CTX_SIGMA, CTX_X, CTX_FLOOR_T, CTX_FLOOR_X, CTX_FLOOR_Y, CTX_FLOOR_HELD = range(7)
N_CTX = 7

# --- end status of a scene ------------------------------------------------------------------
# TIME_BUDGET: a watchdog stopped the scene (``api.run_cells(..., budget=)``); INVALID_SCENE:
# the cell's scene could not be built, so it never ran (set in Python, not by the kernel).
OK, OVERTURNED, BUDGET_EXHAUSTED, NON_FINITE, PAINLEVE, TIME_BUDGET, INVALID_SCENE = range(7)
STATUS_NAMES = ("ok", "overturned", "budget_exhausted", "non_finite", "painleve",
                "time_budget", "invalid_scene")
STATUS_MESSAGES = (
    "the scene ran to its end time or to final rest",
    "the body overturned (|theta| reached the overturning angle)",
    "the step or event budget was used up before the end time",
    "a non-finite state was met",
    "Painleve paradox: the contact problem has no consistent solution (D <= 0)",
    "stopped after the per-cell wall-time budget",
    "the cell's scene could not be built (its problem is reported as a warning)",
)
FAILED_STATUSES = (BUDGET_EXHAUSTED, NON_FINITE, PAINLEVE, TIME_BUDGET, INVALID_SCENE)

# --- the control array shared by ``driver.run_cells`` and a watchdog thread (int64) --------
# CTL_CELL: index of the cell now running (written by the kernel; the chunk's length once
# done); CTL_STOP: index of a cell to stop (written by the watchdog; -1 stops none).
CTL_CELL, CTL_STOP = range(2)
N_CTL = 2

# --- outcome of a cell in a study -----------------------------------------------------------
FAILED, NO_ROCKING, ROCKED, OVERTURN = -1, 0, 1, 2
OUTCOME_NAMES = ("failed", "no_rocking", "rocked", "overturned")  # for codes -1, 0, 1, 2

# --- integrators ----------------------------------------------------------------------------
ADAPTIVE, FIXED = 0, 1
METHOD_NAMES = ("adaptive", "fixed")

# --- ground-motion kinds --------------------------------------------------------------------
G_NONE, G_SINE, G_SWEEP, G_RECORD, G_PULSE_RECT, G_PULSE_TRI = range(6)
LAW_LOG, LAW_LINEAR = 0, 1
HOLD_ACCELERATION, HOLD_VELOCITY, HOLD_DISPLACEMENT = 0, 1, 2

# --- landing laws after a translation jump (scene key ``contact.landing``) -----------------
# flat: the two-contact impulse (docs/physics.md 2.3); face_friction: one contact at the middle of
# the base whose friction impulse turns the body; corner: the leading corner strikes first
# (docs/physics.md 2.2).  docs/landing.md derives them.
LANDING_FLAT, LANDING_FACE_FRICTION, LANDING_CORNER = range(3)
LANDING_NAMES = ("flat", "face_friction", "corner")

# --- restraints (scene section ``restraint``): none, or an anchor, a tension-only tie at
# each corner of the base that breaks for good above its strength (docs/anchors.md)
RESTRAINT_NONE, RESTRAINT_ANCHOR = 0, 1
RESTRAINT_NAMES = ("none", "anchor")

# --- the scene record: what compiled code reads of one scene, by name -----------------------
# The records here and in ``state`` are built with align=True: numba-cuda loads the float64
# fields of a packed record a byte at a time.  Every field is 8 bytes: the layout is the same.
# ``row.body.B``, ``row.floor.x.amp``, ``row.solver.rtol``: one pointer, float64 fields, SI.
# A ground component (``floor.x`` horizontal, ``floor.y`` vertical):
#   kind: a G_* code; amp: sine/pulse: acceleration amplitude [m/s^2]; sweep: the held
#         amplitude (m/s^2, m/s or m after ``hold``); record: scale factor on the samples [-]
#   freq: sine frequency [Hz]; sweep: its rate, d(ln f)/dt [1/s] (log law) or df/dt [Hz/s]
#         (linear law); f0/f1: sweep start/stop frequency [Hz]; law: LAW_*; hold: HOLD_*
#   start, dur: the window [s] (dur = inf: no end; sweep: the sweep length); phase [rad]
#   rec_off, rec_n, rec_dt: slice of the shared record buffer and its sample step [s]
GROUND_DTYPE = np.dtype([(name, "f8") for name in (
    "kind", "amp", "freq", "phase", "start", "dur", "f0", "f1", "law", "hold",
    "rec_off", "rec_n", "rec_dt")], align=True)
# body: breadth, height [m], squared radius of gyration about G [m^2], G from the middle of the
# base (x_g, y_g) [m] (symmetric: 0, H/2; docs/bodies.md); contact: friction,
# restitution and the landing law (a LANDING_* code); initial: theta [rad], omega [rad/s],
# u, v [m/s] and lift [m]; solver: method (ADAPTIVE/FIXED) and the options of
# ``kernels.api.DEFAULTS`` (theta_over: the overturning angle [rad]); restraint: a
# RESTRAINT_* code and the strength of one tie per unit mass of the body, T/m [m/s^2].
SCENE_DTYPE = np.dtype([
    ("body", [(name, "f8") for name in ("B", "H", "i2", "x_g", "y_g")]),
    ("contact", [(name, "f8") for name in ("mu_s", "mu_k", "mu_edge_s", "mu_edge_k", "e_x",
                                           "e_y", "landing")]),
    ("initial", [(name, "f8") for name in ("theta", "omega", "u", "v", "lift")]),
    ("solver", [(name, "f8") for name in ("method", "rtol", "atol", "dt", "max_step", "t_end",
                                          "max_steps", "max_events", "theta_over",
                                          "zeno_dt", "dt_out")]),
    ("floor", [("x", GROUND_DTYPE), ("y", GROUND_DTYPE)]),
    ("restraint", [("kind", "f8"), ("tie", "f8")]),
], align=True)

# --- the result record of one scene (``driver._report`` fills it) ---------------------------
# status: a status code; t_end: the time reached [s]; t_overturn, t_rest: NaN when it did not
# overturn or come to final rest; direction: sign of theta at overturning (0: none);
# max_slip: how far the base moved along the floor (``extremes.footprint``); max_travel: the
# largest |x - x0| of G, rotation included; *_at_overturn: the floor's frequency [Hz],
# acceleration and velocity amplitude (``ground.amplitudes``) at overturning, else NaN;
# energy_clamps: impacts whose restitution was clamped; mode_time: seconds in each mode;
# t_broken: when the restraint broke (NaN: it held, or there is none).
RESULT_DTYPE = np.dtype([
    ("status", "i8"), ("t_end", "f8"), ("t_overturn", "f8"), ("direction", "i8"),
    ("max_abs_theta", "f8"), ("impacts", "i8"), ("t_rest", "f8"), ("max_slip", "f8"),
    ("max_lift", "f8"), ("steps", "i8"), ("events", "i8"), ("energy_clamps", "i8"),
    ("f_at_overturn", "f8"), ("a_at_overturn", "f8"), ("v_at_overturn", "f8"),
    ("max_travel", "f8"), ("mode_time", "f8", (N_MODES,)), ("t_broken", "f8"),
], align=True)

# Impact flag bits (what an impact law did)
SLIPPED = 1              # the impulse left the friction cone: the contact slipped
CLAMPED = 2              # the law would have gained energy: a plastic law replaced it
IMPACT_PAINLEVE = 4      # the impact problem has no solution (Painleve case)

# Impact log columns: time, omega after, flag bits
LOG_T, LOG_OMEGA, LOG_FLAGS = range(3)
N_LOG = 3

# History columns (when asked for): sampled every ``solver.dt_out`` seconds.
(H_T, H_X, H_Y, H_THETA, H_U, H_V, H_OMEGA, H_MODE, H_AX, H_AY) = range(10)
N_HIST = 10
HISTORY_NAMES = ("t", "x", "y", "theta", "u", "v", "omega", "mode", "a_x", "a_y")
