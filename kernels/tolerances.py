"""The kernel's numerical tolerances, each named once with what it guards.

Step fractions lie in [0, 1]; times are in seconds and relative ones scale with max(1, t).
Impulses and velocities are per unit mass (m/s).
"""
# --- root finding (``roots``) -------------------------------------------------------------
EPS = 2.2e-16             # double precision round-off, as Brent's zero writes it
EVENT_XTOL = 1e-13        # an event's root: Brent's xtol on the step fraction
PEAK_XTOL = 1e-10         # golden-section search for a peak above zero (relative to max(1, x))
TURN_XTOL = 1e-12         # a turning point (rate = 0) by regula falsi: step fraction
REST_XTOL = 1e-13         # the instant rest ends, by bisection: relative to max(1, t)
MAX_BRENT_ITER = 100      # iteration caps of the scalar root finders
MAX_TURN_ITER = 50

# --- events on a step (``event_search``) ------------------------------------------------
POLISH_DELTA = 1e-7       # Newton polish of an event: difference step, fraction of the step
POLISH_MAX = 0.01         # ... whose correction is taken only when smaller than this fraction
RISE_X = 1e-6             # an event that entered a step at zero: fraction of the sample where
                          # its rise is first tested

# --- time and steps (``driver``, ``rest_skipping``) -----------------------------------------
BREAK_GUARD = 1e-12       # the floor is read this long [s] before a break (its left-hand value)
THRESHOLD_NUDGE = 1e-12   # relative step past a rest threshold met exactly
MIN_RETRY_DT = 1e-12      # smallest step [s] retried after a non-finite state ...
RETRY_SHRINK = 0.1        # ... with this fraction of its length
MIN_DT = 1e-14            # a rejected step below this (relative to max(1, t)) ends the scene
ERR_FLOOR = 1e-4          # the PI controller's memory of the last error norm: start and floor

# --- impacts and contacts (``corner_impact``, ``face_impact``, ``transitions``) -------------
V_ZERO = 1e-14            # a tangential corner velocity below this [m/s] has no direction
ENERGY_ROUNDOFF = 1e-12   # an impact may not gain more than this fraction of the energy
IMPULSE_ROUNDOFF = 1e-12  # a normal impulse above -this x the sum of both is not a pull
ROCKING_ROUNDOFF = 1e-12  # |omega| b below this x (|u| + |v|) is round-off, not rocking
APPROACH_ROUNDOFF = 1e-12  # a corner velocity above -this x (|v| + b|omega|) is not approaching
