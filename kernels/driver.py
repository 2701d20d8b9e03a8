"""The event loop of one scene, and ``run_cells`` over a chunk of scenes.

What a mode provides to the loop:

1. ``motion.n_dof`` and ``motion.rhs``: its compact state and equations of motion;
2. ``motion.to_full``/``from_full``: its kinematic constraints;
3. ``events.event_values``: the functions g > 0 that hold while the mode does;
4. its rows of the mode table, ``transitions.on_event``: each event's law and next mode.

Rest integrates nothing: the scan of ``rest_skipping`` skips to the next instant at which the
floor can move the body.  A step never crosses a break of the floor motion; after one, the
mode's guards are tested again with the new floor values.  The loop ends at t_end, at
overturning, at final rest once the floor is still for good, or with a failure status
(step/event budget, non-finite state, Painleve, or a stop request of a watchdog thread
read from the control array ``ctl`` once per pass of the loop: compiled code cannot be
interrupted by a signal, so a thread that wants it to stop writes a flag that it reads).

Every pass of the loop takes at most one Runge-Kutta step or one interval of a rest's scan,
so that the lanes of a GPU warp, one scene each, do alike work in a pass (docs/gpu.md, "One
step per pass").  A step in which an event is found ends its pass; the next pass steps again
from the same state exactly to the event (the event ``k_to`` and the step ``dt_to`` carried
from one pass to the next), polishes it and applies the event's law.  A rest's scan carries
its position ``ta``, ``phi_a`` and end ``t_scan`` from pass to pass; the rest's time is
added once, when the scan ends.
"""
import math

import numpy as np

from ._jit import jit
from .codes import (ADAPTIVE, BUDGET_EXHAUSTED, CLAMPED, CTL_CELL, CTL_STOP, CTX_S,
                    CTX_SIGMA, IOMEGA, ITHETA, LOG_FLAGS, LOG_OMEGA, LOG_T, N_HIST, N_LOG,
                    N_MODES, N_STATE, NON_FINITE, OK, OVERTURNED, PAINLEVE, REST,
                    RESTRAINT_ANCHOR, TIME_BUDGET)
from .event_search import first_event, polish
from .events import event_values, n_events
from .extremes import (BASE_REF, MAX_LIFT, MAX_SLIP, MAX_THETA, MAX_TRAVEL, observe,
                       observe_turns)
from .ground import G, amplitudes, ground, ground_end, next_break
from .history import hold, sample_step
from .integrate import FIRST_STEP, fit_dense, next_step_size, step
from .motion import from_full, n_dof, rhs, to_full
from .rest_skipping import (anchored_threshold, rest_begin, rest_interval, rest_scanning,
                            rest_threshold)
from .state import Step, new_work, scene_of
from .tableaus import tableau
from .tolerances import (BREAK_GUARD, ERR_FLOOR, MIN_DT, MIN_RETRY_DT, RETRY_SHRINK,
                         THRESHOLD_NUDGE)
from .transitions import (NOT_AN_IMPACT, initial_mode, leave_rest, on_event,
                          painleve_at_entry)


@jit
def _enter(mode, s, sigma, t, scene, rec, q, z, K, ctx, g_old):
    """Make mode current at time t from the full state q: its compact state z, contact ctx,
    slope K[0] and event values g_old; False if it has D <= 0 (Painleve)."""
    ctx[CTX_S] = s
    ctx[CTX_SIGMA] = sigma
    from_full(mode, q, ctx, scene.body, z)
    if mode == REST:
        return True
    if painleve_at_entry(mode, s, sigma, t, q, scene, rec):
        return False
    rhs(mode, t, z, ctx, scene, rec, K[0])
    event_values(mode, t, q, ctx, scene, rec, g_old)
    return True


@jit
def _finite(z, n):
    for k in range(n):
        if not math.isfinite(z[k]):        # np.isfinite has no CUDA form
            return False
    return True


@jit
def _report(res, status, t, t_rest, t_broken, mode, counts, scene, work):
    """Fill the result record ``res`` (``codes.RESULT_DTYPE``); counts = (impacts, steps,
    events, clamps)."""
    q = work.q
    overturned = status == OVERTURNED
    res.status = status
    res.t_end = t
    res.t_rest = t_rest if (status == OK and mode == REST) else math.nan
    res.t_overturn = t if overturned else math.nan
    res.direction = int(math.copysign(1.0, q[ITHETA])) if overturned else 0
    f, A, V = amplitudes(t, scene.floor.x)
    res.f_at_overturn = f if overturned else math.nan
    res.a_at_overturn = A if overturned else math.nan
    res.v_at_overturn = V if overturned else math.nan
    res.max_abs_theta = work.extremes[MAX_THETA]
    res.max_slip = work.extremes[MAX_SLIP]
    res.max_travel = work.extremes[MAX_TRAVEL]
    res.max_lift = work.extremes[MAX_LIFT]
    res.impacts, res.steps, res.events, res.energy_clamps = counts
    res.t_broken = t_broken
    for m in range(N_MODES):
        res.mode_time[m] = work.mode_time[m]


@jit
def run_scene(row, rec, res, log, hist, ctl, work):
    """Simulate one scene (a device function of the CUDA target as it is: ``cuda_batch``).

    Parameters
    ----------
    row : record of ``codes.SCENE_DTYPE``
        The scene, read by field name, SI units.
    rec : ndarray, shape (n,)
        Shared buffer of record samples [m/s^2] that the ground rows point into.
    res : record of ``codes.RESULT_DTYPE``
        Filled with the scalar results, by field name.
    log : ndarray, shape (m, N_LOG)
        Filled with (t, omega after, impact flags) of the first m impacts (``LOG_*``).
    hist : ndarray, shape (k, N_HIST)
        Filled with the state every ``solver.dt_out`` seconds (first k samples).
    ctl : ndarray of int64, shape (N_CTL,)
        The control array (``codes.CTL_*``): the scene ends with status ``TIME_BUDGET`` once
        ``ctl[CTL_STOP]`` equals ``ctl[CTL_CELL]`` as it was at the start.
    work : record of ``state.WORK_DTYPE``
        The scene's buffers, zeroed (``state.new_work``): the caller allocates them, as
        device code cannot.

    Returns
    -------
    (n_log, n_hist) : number of rows written to log and hist.

    References
    ----------
    docs/physics.md sections 1-3; docs/design.md section 3.
    """
    scene = scene_of(row)
    body, contact, floor, solver, _, restraint = scene
    method = int(solver.method)
    adaptive = method == ADAPTIVE     # the step size is controlled
    tab = tableau(method)
    q, z, z_new, z_stage, q_end = work.q, work.z, work.z_new, work.z_stage, work.q_end
    K, D, ctx, values, scratch = work.K, work.D, work.ctx, work.values, work.scratch
    extremes, mode_time = work.extremes, work.mode_time
    g_old, g_new, g_last = values.old, values.new, values.last
    end = tab.stages
    t_end = solver.t_end
    t_still = ground_end(floor)
    held = restraint.kind == RESTRAINT_ANCHOR        # an anchor holds the body at rest
    kappa = anchored_threshold(body, restraint.tie) if held else rest_threshold(body, contact)
    t_broken = math.nan

    status = OK
    err_old = ERR_FLOOR
    t = 0.0
    t_entry = 0.0                     # when the current mode was entered
    nlog = 0
    nh = 0
    impacts = 0
    events = 0
    steps = 0
    clamps = 0
    cell = ctl[CTL_CELL]              # a stop request names the cell, never a later one
    dt_next = solver.dt if not adaptive else min(solver.max_step, FIRST_STEP)
    t_brk = t_lim = math.inf          # the next break of the floor motion, and its guard
    k_to, dt_to = -1, 0.0             # an event found in the last pass's step, the step to it
    scanning = False                  # a rest's scan is under way: at ta, phi_a, up to t_scan
    t_e, ta, phi_a, t_scan = math.inf, 0.0, 0.0, 0.0
    mode, s, sigma = initial_mode(q, scene, rec)
    if held:                                          # (it starts flat at rest: api)
        mode, s, sigma = REST, 0.0, 0.0
    if not _enter(mode, s, sigma, t, scene, rec, q, z, K, ctx, g_old):
        status = PAINLEVE
    t_rest = 0.0 if mode == REST else math.nan
    extremes[BASE_REF] = math.nan                     # set where the body first touches
    observe(mode, q, body, extremes)

    while status == OK and t < t_end:
        if ctl[CTL_STOP] == cell:
            status = TIME_BUDGET
            break
        n = n_dof(mode)
        if mode == REST:
            if not scanning:
                if t >= t_still:
                    break                               # final rest: nothing can move it
                t_e, phi_a, t_scan = rest_begin(t, t_end, kappa, floor, rec)
                ta = t
            if rest_scanning(t_e, ta, t_scan):          # one interval a pass
                t_e, ta, phi_a = rest_interval(ta, phi_a, t_scan, kappa, floor, rec)
            scanning = rest_scanning(t_e, ta, t_scan)
            if scanning:
                continue
            t1 = min(t_e, t_end)
            nh = hold(hist, nh, t1, q, REST, floor, rec, solver.dt_out)
            mode_time[REST] += t1 - t
            t = t1
            if t_e >= t_end:
                break
            a_x, a_y = ground(t, floor, rec)
            if held:                                    # a tie gives way, for good
                held = False
                t_broken = t
                kappa = rest_threshold(body, contact)
            mode, s, sigma = leave_rest(a_x, G + a_y, body, contact)
            if mode == REST:                            # exactly at the threshold
                t += THRESHOLD_NUDGE * max(1.0, t)
                continue
            events += 1
            t_entry = t
            if not _enter(mode, s, sigma, t, scene, rec, q, z, K, ctx, g_old):
                status = PAINLEVE
            continue

        k_e = k_to
        if k_e < 0:
            if steps >= solver.max_steps or events >= solver.max_events:
                status = BUDGET_EXHAUSTED
                break
            t_brk = next_break(t, floor)
            t_lim = t_brk - BREAK_GUARD if t_brk < math.inf else math.inf
            if not adaptive:
                dt_next = solver.dt
            dt = min(dt_next, solver.max_step, t_end - t, t_brk - t)
            err = step(method, mode, n, t, z, dt, t_lim, ctx, scene, rec, K, z_stage, z_new)
            steps += 1
            if not _finite(z_new, n):
                if adaptive and dt > MIN_RETRY_DT:
                    dt_next = RETRY_SHRINK * dt
                    continue
                status = NON_FINITE
                break
            if adaptive:
                dt_next = next_step_size(dt, err, err_old, tab.order)
                if err > 1.0:
                    if dt_next < MIN_DT * max(1.0, t):
                        status = BUDGET_EXHAUSTED
                    continue
                err_old = max(err, ERR_FLOOR)
            taken = Step(mode, n, t, dt, z, z_new, K, end, D)
            fit_dense(method, taken)
            k_e, x_e = first_event(taken, ctx, scene, rec, values, scratch)
            if k_e >= 0:
                k_to, dt_to = k_e, x_e * dt     # the next pass steps again, exactly to it
                continue
        else:                           # the last pass found an event: the step to it
            k_to = -1
            dt = dt_to
            if dt > 0.0:
                step(method, mode, n, t, z, dt, t_lim, ctx, scene, rec, K, z_stage, z_new)
                dt += polish(k_e, Step(mode, n, t, dt, z, z_new, K, end, D), ctx, scene,
                             rec, scratch)
            else:
                for k in range(n):
                    z_new[k] = z[k]
            taken = Step(mode, n, t, dt, z, z_new, K, end, D)
            fit_dense(method, taken)
        nh = sample_step(hist, nh, taken, ctx, scene, rec, scratch)
        to_full(mode, z_new, ctx, body, q_end)
        if dt > 0.0:
            observe_turns(taken, q, q_end, ctx, body, scratch, extremes)
        observe(mode, q_end, body, extremes)
        mode_time[mode] += dt
        t += dt
        for k in range(n):
            z[k] = z_new[k]
        for k in range(N_STATE):
            q[k] = q_end[k]

        if k_e < 0 and t >= t_lim and t < t_end:
            # a break of the floor motion: test the mode's guards with the new values
            t = t_brk
            event_values(mode, t, q, ctx, scene, rec, g_new)
            for k in range(n_events(mode)):
                if g_new[k] <= 0.0 and g_old[k] > 0.0:
                    k_e = k
                    break
        if k_e < 0:
            for k in range(N_STATE):
                K[0, k] = K[end, k]
            if t >= t_lim:
                rhs(mode, t, z, ctx, scene, rec, K[0])
                event_values(mode, t, q, ctx, scene, rec, g_old)
            else:                                       # the last sample was the step's end
                for k in range(n_events(mode)):
                    g_old[k] = g_last[k]
            continue

        # --- the event: its law and the next mode (the mode table) -----------------------
        events += 1
        mode_old = mode
        mode, s, sigma, status, flags = on_event(k_e, mode, t, q, ctx, scene, rec,
                                                 t > t_entry)
        t_entry = t
        if flags != NOT_AN_IMPACT:
            impacts += 1
            if flags & CLAMPED:
                clamps += 1
            if nlog < log.shape[0]:
                log[nlog, LOG_T] = t
                log[nlog, LOG_OMEGA] = q[IOMEGA]
                log[nlog, LOG_FLAGS] = flags
                nlog += 1
        if status != OK:
            mode = mode_old
            break
        if mode == REST:
            t_rest = t
        observe(mode, q, body, extremes)                # a landing: the base's first footprint
        if not _enter(mode, s, sigma, t, scene, rec, q, z, K, ctx, g_old):
            status = PAINLEVE

    if not _finite(q, N_STATE):
        status = NON_FINITE
    if status == OK and mode == REST and t < t_end:
        mode_time[REST] += t_end - t                    # final rest lasts to the end
        nh = hold(hist, nh, t_end, q, REST, floor, rec, solver.dt_out)
    _report(res, status, t, t_rest, t_broken, mode, (impacts, steps, events, clamps), scene,
            work)
    return nlog, nh


@jit(runtime=True)
def run_cells(rows, rec, results, ctl):
    """Run every scene row of ``rows`` (n records of ``codes.SCENE_DTYPE``) into
    ``results`` (n records of ``codes.RESULT_DTYPE``), writing the index of the running
    cell to ``ctl[CTL_CELL]`` (n once done) for a watchdog thread, which may stop it (see
    ``run_scene``).  One set of buffers serves every scene, zeroed before each; ``buffers``
    is used in every pass, so that it outlives each scene (its record holds no reference)."""
    log = np.zeros((0, N_LOG))
    hist = np.zeros((0, N_HIST))
    buffers = new_work()
    work = buffers[0]
    for i in range(rows.shape[0]):
        ctl[CTL_CELL] = i
        buffers.view(np.uint8)[:] = 0
        run_scene(rows[i], rec, results[i], log, hist, ctl, work)
    ctl[CTL_CELL] = rows.shape[0]
