"""The event loop for one scene, and ``run_cells`` over a chunk of scenes.

What a mode provides to the loop (see ``motion``, ``events``, ``transitions``):

1. ``n_dof`` and ``rhs``: its compact state and equations of motion;
2. ``to_full``/``from_full``: its kinematic constraints;
3. ``event_values``: the functions g > 0 that hold while the mode does;
4. a branch of ``_handle`` that maps each event to impact laws and the next mode.

Rest integrates nothing: ``rest_exit`` skips to the next instant at which the floor can
move the body.  A step never crosses a break of the floor motion; after one, the mode's
guards are tested again with the new floor values.  The loop ends at t_end, at
overturning, at final rest once the floor is still for good, or with a failure status
(step/event budget, non-finite state, Painleve).
"""
import math

import numpy as np

from ._jit import jit
from .codes import (ADAPTIVE, BUDGET_EXHAUSTED, H_AX, H_AY, H_MODE, H_T, N_MODES, NON_FINITE,
                    OK, OVERTURNED, P_ATOL, P_B, P_DT, P_DT_OUT, P_E_X, P_E_Y, P_GX, P_H,
                    P_I2, P_LIFT0, P_MAX_EVENTS, P_MAX_STEP, P_MAX_STEPS, P_METHOD,
                    P_MU_EDGE_K, P_MU_EDGE_S, P_MU_K, P_MU_S, P_OMEGA0, P_RTOL, P_T_END,
                    P_THETA0, P_THETA_OVER, P_U0, P_V0, P_ZENO_DT, PAINLEVE,
                    R_A_AT_OVERTURN, R_DIRECTION, R_ENERGY_CLAMPS, R_EVENTS,
                    R_F_AT_OVERTURN, R_IMPACTS, R_MAX_ABS_THETA, R_MAX_LIFT, R_MAX_SLIP,
                    R_MODE_TIME, R_STATUS, R_STEPS, R_T_END, R_T_OVERTURN, R_T_REST,
                    R_V_AT_OVERTURN, REST, ROTATION, ROTATION_JUMP, SLIDE, SLIDE_ROTATION,
                    TRANSLATION_JUMP)
from .events import (EV_GAP_L, EV_JUMP_OVERTURN, EV_LIFTOFF,
                     EV_OVERTURN, EV_PAINLEVE, EV_SLIP, EV_STOP, MAX_EVENTS, event_value,
                     event_values, locate, n_events, peak)
from .ground import G, amplitudes, ground, ground_end, next_break
from .impact import CLAMPED, IMPACT_PAINLEVE, corner_impact, face_impact
from .integrate import dense, next_step_size, step
from .motion import (CTX_S, CTX_SIGMA, IOMEGA, ITHETA, IU, IV, IX, IY, N_CTX, corner,
                     corner_velocity, from_full, n_dof, rhs, rotation_dynamics,
                     slide_rotation_dynamics, to_full)
from .rest import rest_exit
from .transitions import leave_rest, select_corner, select_face, start_slide

# Fractions of a step at which the event functions are sampled when the step holds a turning
# point (omega or a vertical velocity changes sign): an event function that dips below zero
# and back inside one step is then still seen if the dip spans a third of it.  Without a
# turning point, theta and the gaps are monotone in the step and its end suffices.
SAMPLES = (1.0 / 3.0, 2.0 / 3.0, 1.0)
END_ONLY = (1.0, 1.0, 1.0)


@jit
def _initial(par, rec, body, contact, q, v_tol):
    """Full initial state (x = 0) and (mode, s, sigma) from the scene's initial values."""
    b, h, i2, mu_k, mu_edge_k = body
    mu_s, mu_edge_s = contact[0], contact[2]
    theta, omega, lift = par[P_THETA0], par[P_OMEGA0], par[P_LIFT0]
    q[IX] = 0.0
    q[ITHETA] = theta
    q[IU] = par[P_U0]
    q[IV] = par[P_V0]
    q[IOMEGA] = omega
    a_x, a_y = ground(0.0, par, rec)
    g_e = G + a_y
    if lift > 0.0:
        q[IY] = lift - min(corner(-1.0, theta, b, h)[1], corner(1.0, theta, b, h)[1])
        if theta != 0.0 or omega != 0.0:
            return ROTATION_JUMP, 0.0, 0.0
        return TRANSLATION_JUMP, 0.0, 0.0
    if theta != 0.0 or omega != 0.0:
        s = -math.copysign(1.0, theta if theta != 0.0 else omega)
        rcx, rcy = corner(s, theta, b, h)
        q[IY] = -rcy
        q[IV] = -omega * rcx          # the contact corner does not move vertically
        return select_corner(q, s, a_x, g_e, b, h, i2, mu_edge_s, mu_edge_k, v_tol)
    q[IY] = h
    if q[IV] > 0.0:
        return TRANSLATION_JUMP, 0.0, 0.0
    q[IV] = 0.0
    if q[IU] != 0.0:
        return start_slide(math.copysign(1.0, q[IU]), mu_k, b, h)
    return leave_rest(a_x, g_e, b, h, i2, mu_s, mu_k, mu_edge_k)


@jit
def _face_landing(mode, s, sigma, q, a_x, g_e, body, contact, v_tol, zeno_dt):
    """Impact with the face flat (theta = 0) and the mode after it (see ``_handle``)."""
    b, h, i2, mu_k, mu_edge_k = body
    mu_s, mu_edge_s, e_x, e_y = contact[0], contact[2], contact[4], contact[5]
    q[IY] = h
    flags = face_impact(q, e_x, e_y, mu_s, mu_k, mu_edge_s, mu_edge_k, b, h, i2)
    if flags & IMPACT_PAINLEVE:
        return mode, s, sigma, PAINLEVE, flags
    m, s2, sg2 = select_face(q, a_x, g_e, b, h, i2, mu_s, mu_k, mu_edge_s, mu_edge_k, v_tol,
                             zeno_dt)
    return m, s2, sg2, OK, flags


@jit
def _handle(k, mode, t, q, ctx, par, rec, body, contact, v_tol, zeno_dt):
    """Apply event k of the mode at time t to q: (mode, s, sigma, status, impact flags).

    impact flags is -1 when the event was not an impact.
    """
    b, h, i2, mu_k, mu_edge_k = body
    mu_s, mu_edge_s, e_x, e_y = contact[0], contact[2], contact[4], contact[5]
    a_x, a_y = ground(t, par, rec)
    g_e = G + a_y
    s = ctx[CTX_S]
    sigma = ctx[CTX_SIGMA]
    if mode == ROTATION or mode == SLIDE_ROTATION:
        if k == EV_OVERTURN:
            return mode, s, sigma, OVERTURNED, -1
        if k == EV_PAINLEVE:
            return mode, s, sigma, PAINLEVE, -1
        if k == EV_LIFTOFF:
            return ROTATION_JUMP, 0.0, 0.0, OK, -1
        if k == EV_SLIP and mode == ROTATION:
            F = rotation_dynamics(q[ITHETA], q[IOMEGA], s, a_x, g_e, b, h, i2)[1]
            return SLIDE_ROTATION, s, -math.copysign(1.0, F), OK, -1
        if k == EV_SLIP:                                # the slipping corner stops
            q[IU] = q[IOMEGA] * corner(s, q[ITHETA], b, h)[1]
            m, s2, sg2 = select_corner(q, s, a_x, g_e, b, h, i2, mu_edge_s, mu_edge_k, v_tol)
            return m, s2, sg2, OK, -1
        q[ITHETA] = 0.0               # EV_IMPACT: the other corner strikes (PHYSICS 2.1-2.3)
        return _face_landing(mode, s, sigma, q, a_x, g_e, body, contact, v_tol, zeno_dt)
    if mode == SLIDE:
        if k == EV_STOP:
            q[IU] = 0.0
            m, s2, sg2 = leave_rest(a_x, g_e, b, h, i2, mu_s, mu_k, mu_edge_k)
            return m, s2, sg2, OK, -1
        q[IV] = 0.0                                     # EV_FREE_FALL: g_e reached 0
        return TRANSLATION_JUMP, 0.0, 0.0, OK, -1
    if mode == TRANSLATION_JUMP:                        # flat landing
        return _face_landing(mode, s, sigma, q, a_x, g_e, body, contact, v_tol, zeno_dt)
    # rotation jump
    if k == EV_JUMP_OVERTURN:
        return mode, s, sigma, OVERTURNED, -1
    sc = -1.0 if k == EV_GAP_L else 1.0
    q[IY] = -corner(sc, q[ITHETA], b, h)[1]
    flags = corner_impact(q, sc, e_x, e_y, mu_edge_s, mu_edge_k, b, h, i2)
    if flags & IMPACT_PAINLEVE:
        return mode, s, sigma, PAINLEVE, flags
    if corner_velocity(q, sc, b, h)[1] > v_tol:         # it bounces: still airborne
        return ROTATION_JUMP, 0.0, 0.0, OK, flags
    m, s2, sg2 = select_corner(q, sc, a_x, g_e, b, h, i2, mu_edge_s, mu_edge_k, v_tol)
    return m, s2, sg2, OK, flags


@jit
def _polish(k, mode, n, t, z, f, dt, ctx, par, rec, body, mu_edge_s, theta_over, zbuf, q,
            gbuf):
    """Newton's step on event k from the stepped state z at t (f = dz/dt there): move z to
    z + d f and return d.  The event was found on the dense output, one order less exact
    than the step; this puts it on the root with the step's own accuracy."""
    b, h = body[0], body[1]
    to_full(mode, z, ctx, b, h, q)
    g0 = event_value(k, mode, t, q, ctx, par, rec, body, mu_edge_s, theta_over, gbuf)
    delta = 1e-7 * dt
    for j in range(n):
        zbuf[j] = z[j] + delta * f[j]
    to_full(mode, zbuf, ctx, b, h, q)
    slope = (event_value(k, mode, t + delta, q, ctx, par, rec, body, mu_edge_s, theta_over,
                         gbuf) - g0) / delta
    d = -g0 / slope if slope != 0.0 else 0.0
    if not abs(d) < 0.01 * dt:
        return 0.0
    for j in range(n):
        z[j] += d * f[j]
    return d


@jit
def _enter(mode, s, sigma, t, q, ctx, z, K, gold, par, rec, body, mu_edge_s, theta_over):
    """Make mode current at time t from the full state q; False if it has D <= 0."""
    b, h, i2, mu_k, mu_edge_k = body
    ctx[CTX_S] = s
    ctx[CTX_SIGMA] = sigma
    from_full(mode, q, ctx, b, h, z)
    if mode == REST:
        return True
    if mode == SLIDE_ROTATION:
        a_x, a_y = ground(t, par, rec)
        D = slide_rotation_dynamics(q[ITHETA], q[IOMEGA], s, sigma, a_x, G + a_y, b, h, i2,
                                    mu_edge_k)[3]
        if D <= 0.0:
            return False
    rhs(mode, t, z, par, rec, ctx, b, h, i2, mu_k, mu_edge_k, K[0])
    event_values(mode, t, q, ctx, par, rec, body, mu_edge_s, theta_over, gold)
    return True


@jit
def _observe(mode, q, b, h, stats):
    """Update max |theta|, max |x - x0| and max lift (gap under the lowest corner)."""
    stats[0] = max(stats[0], abs(q[ITHETA]))
    stats[1] = max(stats[1], abs(q[IX]))
    if mode == TRANSLATION_JUMP or mode == ROTATION_JUMP:
        gap = q[IY] + min(corner(-1.0, q[ITHETA], b, h)[1], corner(1.0, q[ITHETA], b, h)[1])
        stats[2] = max(stats[2], gap)


@jit
def _rate(j, q, b, h):
    """Rate of observed quantity j: theta (omega), x (u), lift (V_y of the lowest corner)."""
    if j == 0:
        return q[IOMEGA]
    if j == 1:
        return q[IU]
    s = -1.0 if corner(-1.0, q[ITHETA], b, h)[1] < corner(1.0, q[ITHETA], b, h)[1] else 1.0
    return corner_velocity(q, s, b, h)[1]


@jit
def _observe_turns(method, mode, n, z, z_new, K, dt, q0, q1, ctx, b, h, stats, zbuf, qs):
    """Observe the extremes inside a step: where a rate changes sign between the step's
    ends q0 and q1, its root on the dense output (Illinois' regula falsi) is one."""
    for j in range(3 if mode == TRANSLATION_JUMP or mode == ROTATION_JUMP else 2):
        fa = _rate(j, q0, b, h)
        fb = _rate(j, q1, b, h)
        if fa * fb >= 0.0:
            continue
        xa, xb = 0.0, 1.0
        x_old = 2.0
        side = 0
        for _ in range(50):
            x = (xa * fb - xb * fa) / (fb - fa)
            dense(method, n, z, z_new, K, dt, x, zbuf)
            to_full(mode, zbuf, ctx, b, h, qs)
            fx = _rate(j, qs, b, h)
            if abs(x - x_old) < 1e-12 or fx == 0.0:
                break
            x_old = x
            if fx * fb > 0.0:
                xb, fb = x, fx
                if side == 1:
                    fa *= 0.5
                side = 1
            else:
                xa, fa = x, fx
                if side == -1:
                    fb *= 0.5
                side = -1
        _observe(mode, qs, b, h, stats)


@jit
def _record(hist, nh, t, q, mode, par, rec):
    a_x, a_y = ground(t, par, rec)
    hist[nh, H_T] = t
    for j in range(6):
        hist[nh, 1 + j] = q[j]
    hist[nh, H_MODE] = mode
    hist[nh, H_AX] = a_x
    hist[nh, H_AY] = a_y


@jit
def _finite(z, n):
    for k in range(n):
        if not np.isfinite(z[k]):
            return False
    return True


@jit
def run_scene(par, rec, res, log, hist):
    """Simulate one scene.

    Parameters
    ----------
    par : ndarray, shape (N_PAR,)
        The scene row (layout in ``codes``), SI units.
    rec : ndarray, shape (n,)
        Shared buffer of record samples [m/s^2] that the ground rows point into.
    res : ndarray, shape (N_RES,)
        Filled with the scalar results (layout ``R_*`` in ``codes``).
    log : ndarray, shape (m, 3)
        Filled with (t, omega after, impact flags) of the first m impacts.
    hist : ndarray, shape (k, N_HIST)
        Filled with the state every ``P_DT_OUT`` seconds (first k samples).

    Returns
    -------
    (n_log, n_hist) : number of rows written to log and hist.

    References
    ----------
    PHYSICS.md sections 1-3; DESIGN.md section 3.
    """
    b = 0.5 * par[P_B]
    h = 0.5 * par[P_H]
    i2 = par[P_I2]
    mu_s = par[P_MU_S]
    mu_edge_s, mu_edge_k = par[P_MU_EDGE_S], par[P_MU_EDGE_K]
    # mu_k > b/h >= mu_edge_k: flat sliding would tip the body onto its leading corner, where
    # the lower edge friction tips it straight back.  The body slides flat on the verge of
    # tipping instead, with the friction that holds theta'' = 0 there: b/h.
    mu_k = min(par[P_MU_K], max(b / h, mu_edge_k))
    body = (b, h, i2, mu_k, mu_edge_k)
    contact = (mu_s, mu_k, mu_edge_s, mu_edge_k, par[P_E_X], par[P_E_Y])
    method = int(par[P_METHOD])
    rtol, atol = par[P_RTOL], par[P_ATOL]
    dt_fixed, max_step, t_end = par[P_DT], par[P_MAX_STEP], par[P_T_END]
    max_steps, max_events = par[P_MAX_STEPS], par[P_MAX_EVENTS]
    theta_over, zeno_dt, dt_out = par[P_THETA_OVER], par[P_ZENO_DT], par[P_DT_OUT]
    v_tol = 0.5 * G * zeno_dt        # a bounce this slow lands again within zeno_dt
    t_still = ground_end(par)
    kappa = min(mu_s, b / h)         # rest ends when |a_x| > kappa g_e (PHYSICS 1.3)

    q = np.zeros(6)
    z = np.zeros(6)
    z_new = np.zeros(6)
    ztmp = np.zeros(6)
    zbuf = np.zeros(6)
    qs = np.zeros(6)
    q_end = np.zeros(6)
    K = np.zeros((7, 6))
    ctx = np.zeros(N_CTX)
    gold = np.zeros(MAX_EVENTS)
    gnew = np.zeros(MAX_EVENTS)
    gtmp = np.zeros(MAX_EVENTS)
    stats = np.zeros(3)
    mode_time = np.zeros(N_MODES)

    gwork = np.zeros(MAX_EVENTS)

    status = OK
    err_old = 1e-4
    t = 0.0
    nlog = 0
    nh = 0
    impacts = 0
    events = 0
    steps = 0
    clamps = 0
    dt_next = dt_fixed if method != ADAPTIVE else min(max_step, 1e-3)
    mode, s, sigma = _initial(par, rec, body, contact, q, v_tol)
    if not _enter(mode, s, sigma, t, q, ctx, z, K, gold, par, rec, body, mu_edge_s,
                  theta_over):
        status = PAINLEVE
    t_rest = 0.0 if mode == REST else math.nan
    _observe(mode, q, b, h, stats)

    while status == OK and t < t_end:
        n = n_dof(mode)
        if mode == REST:
            if t >= t_still:
                break                                   # final rest: nothing can move it
            te = rest_exit(t, t_end, kappa, par, rec)
            t1 = min(te, t_end)
            while nh < hist.shape[0] and nh * dt_out <= t1:
                _record(hist, nh, nh * dt_out, q, REST, par, rec)
                nh += 1
            mode_time[REST] += t1 - t
            t = t1
            if te >= t_end:
                break
            a_x, a_y = ground(t, par, rec)
            mode, s, sigma = leave_rest(a_x, G + a_y, b, h, i2, mu_s, mu_k, mu_edge_k)
            if mode == REST:                            # exactly at the threshold
                t += 1e-12 * max(1.0, t)
                continue
            events += 1
            if not _enter(mode, s, sigma, t, q, ctx, z, K, gold, par, rec, body, mu_edge_s,
                          theta_over):
                status = PAINLEVE
            continue

        if steps >= max_steps or events >= max_events:
            status = BUDGET_EXHAUSTED
            break
        t_brk = next_break(t, par)
        t_lim = t_brk - 1e-12 if t_brk < math.inf else math.inf
        if method != ADAPTIVE:
            dt_next = dt_fixed
        dt = min(dt_next, max_step, t_end - t, t_brk - t)
        err = step(method, mode, n, t, z, dt, t_lim, par, rec, ctx, body, K, ztmp, z_new,
                   rtol, atol)
        steps += 1
        if not _finite(z_new, n):
            if method == ADAPTIVE and dt > 1e-12:
                dt_next = 0.1 * dt
                continue
            status = NON_FINITE
            break
        if method == ADAPTIVE:
            dt_next = next_step_size(dt, err, err_old)
            if err > 1.0:
                if dt_next < 1e-14 * max(1.0, t):
                    status = BUDGET_EXHAUSTED
                continue
            err_old = max(err, 1e-4)

        # --- events: the earliest zero of any event function inside this step ----------
        ne = n_events(mode)
        for k in range(ne):
            gtmp[k] = gold[k]
        xa = 0.0
        x_e = 2.0
        k_e = -1
        turning = mode == TRANSLATION_JUMP or mode == ROTATION_JUMP or \
            (mode != SLIDE and z[1] * z_new[1] <= 0.0)
        for xs in SAMPLES if turning else END_ONLY:
            if xs == xa:
                break
            dense(method, n, z, z_new, K, dt, xs, zbuf)
            to_full(mode, zbuf, ctx, b, h, qs)
            event_values(mode, t + xs * dt, qs, ctx, par, rec, body, mu_edge_s, theta_over,
                         gnew)
            for k in range(ne):
                if gnew[k] > 0.0:
                    continue
                xl, gl = xa, gtmp[k]
                if gl <= 0.0:        # entered the step at zero: did it rise and come back?
                    xl, gl = peak(k, xa, xs, method, mode, n, t, z, z_new, K, dt, ctx, par,
                                  rec, body, mu_edge_s, theta_over, zbuf, qs, gwork)
                if gl > 0.0:
                    xr = locate(k, xl, xs, gl, gnew[k], method, mode, n, t, z, z_new, K,
                                dt, ctx, par, rec, body, mu_edge_s, theta_over, zbuf, qs,
                                gwork)
                else:
                    xr = xa          # it left zero the wrong way: the event is now
                if xr < x_e:
                    x_e = xr
                    k_e = k
            if k_e >= 0:
                break
            xa = xs
            for k in range(ne):
                gtmp[k] = gnew[k]

        if k_e >= 0:
            dt = x_e * dt            # step again, exactly to the event
            if dt > 0.0:
                step(method, mode, n, t, z, dt, t_lim, par, rec, ctx, body, K, ztmp, z_new,
                     rtol, atol)
                dt += _polish(k_e, mode, n, t + dt, z_new, K[6], dt, ctx, par, rec, body,
                              mu_edge_s, theta_over, zbuf, qs, gwork)
            else:
                for k in range(n):
                    z_new[k] = z[k]
        while nh < hist.shape[0] and nh * dt_out <= t + dt:
            x = (nh * dt_out - t) / dt if dt > 0.0 else 0.0
            dense(method, n, z, z_new, K, dt, x, zbuf)
            to_full(mode, zbuf, ctx, b, h, qs)
            _record(hist, nh, nh * dt_out, qs, mode, par, rec)
            nh += 1
        to_full(mode, z_new, ctx, b, h, q_end)
        if dt > 0.0:
            _observe_turns(method, mode, n, z, z_new, K, dt, q, q_end, ctx, b, h, stats, zbuf,
                           qs)
        _observe(mode, q_end, b, h, stats)
        mode_time[mode] += dt
        t += dt
        for k in range(n):
            z[k] = z_new[k]
        for k in range(6):
            q[k] = q_end[k]

        if k_e < 0 and t >= t_lim and t < t_end:
            # a break of the floor motion: test the mode's guards with the new values
            t = t_brk
            event_values(mode, t, q, ctx, par, rec, body, mu_edge_s, theta_over, gnew)
            for k in range(n_events(mode)):
                if gnew[k] <= 0.0 and gold[k] > 0.0:
                    k_e = k
                    break
        if k_e < 0:
            for k in range(6):
                K[0, k] = K[6, k]
            if t >= t_lim:
                rhs(mode, t, z, par, rec, ctx, b, h, i2, mu_k, mu_edge_k, K[0])
                event_values(mode, t, q, ctx, par, rec, body, mu_edge_s, theta_over, gold)
            else:                                       # the last sample was the step's end
                for k in range(ne):
                    gold[k] = gtmp[k]
            continue

        # --- the event: impact laws and the next mode ------------------------------------
        events += 1
        mode_old = mode
        mode, s, sigma, status, flags = _handle(k_e, mode, t, q, ctx, par, rec, body,
                                                contact, v_tol, zeno_dt)
        if flags >= 0:
            impacts += 1
            if flags & CLAMPED:
                clamps += 1
            if nlog < log.shape[0]:
                log[nlog, 0] = t
                log[nlog, 1] = q[IOMEGA]
                log[nlog, 2] = flags
                nlog += 1
        if status != OK:
            mode = mode_old
            break
        if mode == REST:
            t_rest = t
        if not _enter(mode, s, sigma, t, q, ctx, z, K, gold, par, rec, body, mu_edge_s,
                      theta_over):
            status = PAINLEVE

    if not _finite(q, 6):
        status = NON_FINITE
    if status == OK and mode == REST and t < t_end:
        mode_time[REST] += t_end - t                    # final rest lasts to the end
        while nh < hist.shape[0] and nh * dt_out <= t_end:
            _record(hist, nh, nh * dt_out, q, REST, par, rec)
            nh += 1
    res[R_STATUS] = status
    res[R_T_END] = t
    res[R_T_REST] = t_rest if (status == OK and mode == REST) else math.nan
    res[R_T_OVERTURN] = t if status == OVERTURNED else math.nan
    res[R_DIRECTION] = math.copysign(1.0, q[ITHETA]) if status == OVERTURNED else 0.0
    f, A, V = amplitudes(t, par, P_GX)
    res[R_F_AT_OVERTURN] = f if status == OVERTURNED else math.nan
    res[R_A_AT_OVERTURN] = A if status == OVERTURNED else math.nan
    res[R_V_AT_OVERTURN] = V if status == OVERTURNED else math.nan
    res[R_MAX_ABS_THETA] = stats[0]
    res[R_MAX_SLIP] = stats[1]
    res[R_MAX_LIFT] = stats[2]
    res[R_IMPACTS] = impacts
    res[R_STEPS] = steps
    res[R_EVENTS] = events
    res[R_ENERGY_CLAMPS] = clamps
    for m in range(N_MODES):
        res[R_MODE_TIME + m] = mode_time[m]
    return nlog, nh


@jit
def run_cells(pars, rec, results):
    """Run every scene row of ``pars`` (shape (n, N_PAR)) into ``results`` (n, N_RES)."""
    log = np.zeros((0, 3))
    hist = np.zeros((0, 10))
    for i in range(pars.shape[0]):
        run_scene(pars[i], rec, results[i], log, hist)
