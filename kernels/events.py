"""Event functions of each mode (docs/physics.md 1.3).

Every event is written g(t, q) > 0 while the mode holds and fires when g reaches 0 from
above: an impact (the body side -s theta, a corner gap), lift-off (N_c), the onset of slip
(mu_edge_s N_c - |F_c|), the end of slip (sigma V_cx), the Painleve condition (D),
overturning (theta_over - |theta|), flat sliding stopping (sigma u) and the floor falling
faster than gravity (g_e).  What each event leads to is the mode table of ``transitions``;
where it lies inside a step, ``event_search``.
"""
from ._jit import jit
from .codes import (CTX_S, CTX_SIGMA, IOMEGA, ITHETA, IU, IY, ROTATION, ROTATION_JUMP, SLIDE,
                    SLIDE_ROTATION, TRANSLATION_JUMP)
from .ground import G
from .motion import (corner, corner_velocity, floor_at, rotation_dynamics,
                     slide_rotation_dynamics)

# event indices per mode
EV_IMPACT, EV_LIFTOFF, EV_SLIP, EV_OVERTURN, EV_PAINLEVE = range(5)   # rotation modes
EV_STOP, EV_FREE_FALL = range(2)                                     # slide
EV_GAP_L, EV_GAP_R, EV_JUMP_OVERTURN = range(3)                      # jumps


@jit
def n_events(mode):
    """Number of event functions of a mode."""
    if mode == ROTATION:
        return 4
    if mode == SLIDE_ROTATION:
        return 5
    if mode == SLIDE:
        return 2
    if mode == TRANSLATION_JUMP:
        return 1
    if mode == ROTATION_JUMP:
        return 3
    return 0


@jit
def event_values(mode, t, q, ctx, scene, rec, out):
    """Write the mode's event functions at (t, q) into out."""
    body = scene.body
    theta_over = scene.solver.theta_over
    s = ctx[CTX_S]
    if mode == ROTATION or mode == SLIDE_ROTATION:
        a_x, a_y = floor_at(t, ctx, scene, rec)
        g_e = G + a_y
        out[EV_IMPACT] = -s * q[ITHETA]
        out[EV_OVERTURN] = theta_over - abs(q[ITHETA])
        if mode == ROTATION:
            thdd, F, N = rotation_dynamics(q[ITHETA], q[IOMEGA], s, a_x, g_e, body)
            out[EV_LIFTOFF] = N
            out[EV_SLIP] = scene.contact.mu_edge_s * N - abs(F)
        else:
            sigma = ctx[CTX_SIGMA]
            thdd, udd, N, D = slide_rotation_dynamics(q[ITHETA], q[IOMEGA], s, sigma, a_x,
                                                      g_e, body, scene.contact.mu_edge_k)
            out[EV_LIFTOFF] = N
            out[EV_SLIP] = sigma * corner_velocity(q, s, body)[0]
            out[EV_PAINLEVE] = D
    elif mode == SLIDE:
        out[EV_STOP] = ctx[CTX_SIGMA] * q[IU]
        out[EV_FREE_FALL] = G + floor_at(t, ctx, scene, rec)[1]
    elif mode == TRANSLATION_JUMP:
        out[EV_GAP_L] = q[IY] - body.h
    elif mode == ROTATION_JUMP:
        out[EV_GAP_L] = q[IY] + corner(-1.0, q[ITHETA], body)[1]
        out[EV_GAP_R] = q[IY] + corner(1.0, q[ITHETA], body)[1]
        out[EV_JUMP_OVERTURN] = theta_over - abs(q[ITHETA])


@jit(inline="always")
def angle_event(k, mode):
    """Whether event k of the mode is a function of theta alone: impact and overturning of
    the rocking modes, whose compact state starts with theta."""
    return (mode == ROTATION or mode == SLIDE_ROTATION) and (k == EV_IMPACT or k == EV_OVERTURN)


@jit(inline="always")
def angle_value(k, theta, ctx, scene):
    """Event function k of a rocking mode that ``angle_event`` names, at the angle theta."""
    if k == EV_IMPACT:
        return -ctx[CTX_S] * theta
    return scene.solver.theta_over - abs(theta)


@jit
def event_value(k, mode, t, q, ctx, scene, rec, scratch):
    """Event function k alone; only lift-off, the onset of slip, the Painleve condition and
    free fall need the floor motion and the forces."""
    body, theta_over = scene.body, scene.solver.theta_over
    if angle_event(k, mode):
        return angle_value(k, q[ITHETA], ctx, scene)
    if mode == ROTATION or mode == SLIDE_ROTATION:
        if k == EV_SLIP and mode == SLIDE_ROTATION:
            return ctx[CTX_SIGMA] * corner_velocity(q, ctx[CTX_S], body)[0]
    elif mode == ROTATION_JUMP:
        if k == EV_JUMP_OVERTURN:
            return theta_over - abs(q[ITHETA])
        return q[IY] + corner(-1.0 if k == EV_GAP_L else 1.0, q[ITHETA], body)[1]
    elif mode == TRANSLATION_JUMP:
        return q[IY] - body.h
    elif mode == SLIDE and k == EV_STOP:
        return ctx[CTX_SIGMA] * q[IU]
    event_values(mode, t, q, ctx, scene, rec, scratch)
    return scratch[k]
