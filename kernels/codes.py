"""Integer codes shared by the kernel and its users, and standard gravity.

Modes (the paper's six motion types), end statuses, ground-motion kinds, the layout of the
flat float64 parameter row that describes one scene to the compiled code and the same row
as a named record (``SCENE_DTYPE``), the indices of the state vector, and the columns of
the impact log and the history.  The name tuples feed
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

# --- the full state q = (x, y, theta, u, v, omega) of G relative to the floor (PHYSICS 1.1)
IX, IY, ITHETA, IU, IV, IOMEGA = range(6)
N_STATE = 6
# the mode's contact: corner s (-1 left, +1 right), slip direction sigma, pivot or rest x
CTX_S, CTX_SIGMA, CTX_X = range(3)
N_CTX = 3

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

# Ground component parameters (12 floats per component).  SI units.
#   G_AMP: sine/pulse: acceleration amplitude [m/s^2]; sweep: the held amplitude
#          (m/s^2, m/s or m after G_HOLD); record: scale factor on the samples [-]
#   G_FREQ: sine frequency [Hz]; sweep: its rate, d(ln f)/dt [1/s] (log law) or df/dt
#          [Hz/s] (linear law); G_F0/G_F1: sweep start/stop frequency [Hz]
#   G_START, G_DUR: the window [s] (G_DUR = inf: no end; sweep: the sweep length)
#   G_REC_OFF, G_REC_N, G_REC_DT: slice of the shared record buffer and its sample step
(G_KIND, G_AMP, G_FREQ, G_PHASE, G_START, G_DUR, G_F0, G_F1, G_LAW, G_HOLD,
 G_REC_OFF, G_REC_N, G_REC_DT) = range(13)
G_SIZE = 13

# --- landing laws after a translation jump (scene key ``contact.landing``) -----------------
# flat: the two-contact impulse (PHYSICS 2.3); face_friction: one contact at the middle of
# the base whose friction impulse turns the body; corner: the leading corner strikes first
# (PHYSICS 2.2).  docs/landing.md derives them.
LANDING_FLAT, LANDING_FACE_FRICTION, LANDING_CORNER = range(3)
LANDING_NAMES = ("flat", "face_friction", "corner")

# Scene parameter row.  Body [m, m, m^2], contact [-] (P_LANDING: a LANDING_* code), initial
# state, solver options, then the horizontal ground (P_GX ...) and the vertical ground (P_GY ...).
(P_B, P_H, P_I2,
 P_MU_S, P_MU_K, P_MU_EDGE_S, P_MU_EDGE_K, P_E_X, P_E_Y, P_LANDING,
 P_THETA0, P_OMEGA0, P_U0, P_V0, P_LIFT0,
 P_METHOD, P_RTOL, P_ATOL, P_DT, P_MAX_STEP, P_T_END, P_MAX_STEPS, P_MAX_EVENTS,
 P_THETA_OVER, P_ZENO_DT, P_DT_OUT) = range(26)
P_GX = 26
P_GY = P_GX + G_SIZE
N_PAR = P_GY + G_SIZE

# The same row as a numpy structured record (``SCENE_DTYPE``): compiled code reads the scene
# by name (``row.body.B``, ``row.floor.x.amp``, ``row.solver.rtol``) through one pointer.
# ``kernels.api`` views a float64 row (n, N_PAR) as records without copying.
GROUND_FIELDS = ("kind", "amp", "freq", "phase", "start", "dur", "f0", "f1", "law", "hold",
                 "rec_off", "rec_n", "rec_dt")                       # G_KIND ... G_REC_DT
SCENE_FIELDS = (("body", ("B", "H", "i2")),
                ("contact", ("mu_s", "mu_k", "mu_edge_s", "mu_edge_k", "e_x", "e_y",
                             "landing")),
                ("initial", ("theta", "omega", "u", "v", "lift")),
                ("solver", ("method", "rtol", "atol", "dt", "max_step", "t_end", "max_steps",
                            "max_events", "theta_over", "zeno_dt", "dt_out")),
                ("floor", ("x", "y")))                               # P_B ... P_GY + G_DT


def _record(names, formats):
    return [(name, fmt) for name, fmt in zip(names, formats)]


GROUND_DTYPE = np.dtype(_record(GROUND_FIELDS, ["f8"] * G_SIZE))
SCENE_DTYPE = np.dtype([(group, _record(names, [GROUND_DTYPE if group == "floor" else "f8"]
                                        * len(names))) for group, names in SCENE_FIELDS])
assert SCENE_DTYPE.itemsize == 8 * N_PAR


# Per-cell scalar results (float64 row).  R_MAX_SLIP: how far the base moved along the floor
# (``extremes.footprint``); R_MAX_TRAVEL: the largest |x - x0| of G, rotation included.
(R_STATUS, R_T_END, R_T_OVERTURN, R_DIRECTION, R_MAX_ABS_THETA, R_IMPACTS, R_T_REST,
 R_MAX_SLIP, R_MAX_LIFT, R_STEPS, R_EVENTS, R_ENERGY_CLAMPS,
 R_F_AT_OVERTURN, R_A_AT_OVERTURN, R_V_AT_OVERTURN, R_MAX_TRAVEL) = range(16)
R_MODE_TIME = 16                      # six entries, seconds in each mode
N_RES = R_MODE_TIME + N_MODES

# Impact flag bits (what an impact law did)
SLIPPED = 1              # the impulse left the friction cone: the contact slipped
CLAMPED = 2              # the law would have gained energy: a plastic law replaced it
IMPACT_PAINLEVE = 4      # the impact problem has no solution (Painleve case)

# Impact log columns: time, omega after, flag bits
LOG_T, LOG_OMEGA, LOG_FLAGS = range(3)
N_LOG = 3

# History columns (when asked for): sampled every P_DT_OUT seconds.
(H_T, H_X, H_Y, H_THETA, H_U, H_V, H_OMEGA, H_MODE, H_AX, H_AY) = range(10)
N_HIST = 10
HISTORY_NAMES = ("t", "x", "y", "theta", "u", "v", "omega", "mode", "a_x", "a_y")
