"""The mode table: which mode a body is in, and what each event leads to.

Modes are the paper's six motion types (``codes``), events those of ``events`` (docs/physics.md
1.3, 2 and 3.1).

=================  ================  ===========================  ========================
mode               event             law                          next mode
=================  ================  ===========================  ========================
rest               floor exceeds     -                            ``leave_rest``
                   kappa g_e (``rest_skipping``)
slide              stop (u = 0)      -                            ``leave_rest``
slide              free fall         -                            translation jump
rotation,          impact (theta=0)  ``face_impact`` (2.1-2.3)    ``select_face``
slide_rotation     lift-off (N = 0)  -                            rotation jump
                   slip (|F| = mu N) -                            slide rotation
                   slip ends (V = 0) corner stops                 ``select_corner`` (or
                                                                  rotation: see below)
                   overturn, D <= 0  -                            end (overturned, Painleve)
translation jump   landing           ``landing_impact`` (2.3,     ``select_face``
                                     docs/landing.md)
rotation jump      corner gap = 0    ``corner_impact`` (2.2)      bounce (Zeno: ``zeno``)
                                                                  or ``select_corner``
                   overturn          -                            end (overturned)
=================  ================  ===========================  ========================

A slip that ends at the instant it began is not started again: the corner reached the edge
of its friction cone and turned back (a graze), where sticking and slipping differ by
round-off in |F| - mu N, so it sticks (where its normal force is positive).  Else the
two choices could hand the body to each other at one instant without end; a build with
floating-point contraction did so on 5 of the 10,000 cells of the GPU benchmark's map.

Every choice returns (mode, s, sigma): the contact corner (-1 left, +1 right) and the slip
direction sgn(V_cx), as the equations of motion need them.  Zeno closure (``zeno``) decides
whether a contact that would close again within zeno_dt is closed now.
"""
import math

from ._jit import jit
from .codes import (CTX_S, CTX_SIGMA, IMPACT_PAINLEVE, IOMEGA, ITHETA, IU, IV, IX, IY, OK,
                    OVERTURNED, PAINLEVE, REST, ROTATION, ROTATION_JUMP, SLIDE, SLIDE_ROTATION,
                    TRANSLATION_JUMP)
from .corner_impact import corner_impact
from .events import (EV_GAP_L, EV_JUMP_OVERTURN, EV_LIFTOFF, EV_OVERTURN, EV_PAINLEVE,
                     EV_SLIP, EV_STOP)
from .face_impact import face_impact, landing_impact
from .ground import G, ground
from .motion import (corner, corner_velocity, floor_at, half_base, rotation_dynamics,
                     slide_rotation_dynamics, sliding_friction)
from .tolerances import ROCKING_ROUNDOFF
from .zeno import closing_speed, leaves, rocking_closes, stop_corner

NOT_AN_IMPACT = -1       # impact flags of an event that was not an impact


@jit
def mu_required(A, b, h, i2):
    """Friction needed for pure rocking at onset, Shenton's mu_req(A) (docs/physics.md 1.3)."""
    return (A * (i2 + b * b) + b * h) / ((i2 + h * h) + A * b * h)


@jit
def leave_rest(a_x, g_e, body, contact):
    """The rest table of docs/physics.md 1.3 with A = |a_x|/g_e and beta = b_s/h, tan alpha of the
    corner s the floor drives the body towards (docs/bodies.md).

    Beyond A > beta rest has no consistent contact force (the other corner's normal force
    would be negative, docs/physics.md 1.2 (1)).  Rocking needs the pivot to stick both as the
    face's edge at onset (mu_s, as the table) and as the lone corner once the other lifts
    (mu_edge_s, rotation's own slip test); slide rotation needs mu_edge_k > beta to lift the
    other corner.  Failing both, the face slides backwards, even with A <= mu_s: the
    rotation would slip at once and slide back onto the face, a cycle without time
    (docs/conventions.md).
    """
    h, i2 = body.h, body.i2
    mu_s = contact.mu_s
    if g_e <= 0.0:
        return TRANSLATION_JUMP, 0.0, 0.0
    A = abs(a_x) / g_e
    drive = math.copysign(1.0, a_x)
    s = -drive                         # a_x > 0 tips the body about its left corner
    b = half_base(s, body)
    beta = b / h
    if A <= beta:
        if A <= mu_s:
            return REST, 0.0, 0.0
        return start_slide(-drive, body, contact)
    if min(mu_s, contact.mu_edge_s) >= mu_required(A, b, h, i2):
        return ROTATION, s, 0.0
    if contact.mu_edge_k > beta:       # the pivot slips backwards relative to the floor
        return SLIDE_ROTATION, s, -drive
    return start_slide(-drive, body, contact)


@jit
def start_slide(sigma, body, contact):
    """Flat sliding with sgn(u) = sigma; with mu_k > b_s/h (s = sigma, the leading corner)
    the body trips over that corner instead (one normal force would turn negative, docs/physics.md
    1.2 (2))."""
    if sliding_friction(sigma, body, contact) > half_base(sigma, body) / body.h:
        return SLIDE_ROTATION, sigma, sigma
    return SLIDE, 0.0, sigma


@jit
def select_corner(q, s, a_x, g_e, body, contact, v_tol):
    """Mode of a body whose corner s touches the floor (gap 0).

    A corner velocity below v_tol (a bounce or a slip that would end within zeno_dt) is
    closed by the plastic impulse that stops it, so the state satisfies the contact
    constraints of the mode it enters without gaining energy.
    """
    Vx, Vy = corner_velocity(q, s, body)
    if leaves(Vy, v_tol):
        return ROTATION_JUMP, s, 0.0
    stop_corner(q, s, body, not leaves(abs(Vx), v_tol))
    if leaves(abs(Vx), v_tol):
        sigma = math.copysign(1.0, Vx)
        N = slide_rotation_dynamics(q[ITHETA], q[IOMEGA], s, sigma, a_x, g_e, body,
                                    contact.mu_edge_k)[2]
        if N <= 0.0:
            return ROTATION_JUMP, s, 0.0
        return SLIDE_ROTATION, s, sigma
    thdd, F, N = rotation_dynamics(q[ITHETA], q[IOMEGA], s, a_x, g_e, body)
    if N > 0.0:
        if abs(F) <= contact.mu_edge_s * N:
            return ROTATION, s, 0.0
        return SLIDE_ROTATION, s, -math.copysign(1.0, F)
    return unstick(q, s, -math.copysign(1.0, F), a_x, g_e, body, contact.mu_edge_k)


@jit
def unstick(q, s, sigma_f, a_x, g_e, body, mu):
    """Mode of a resting corner (V_c = 0) that sticking would have to pull down (N <= 0).

    The corner flies if gravity alone lets it rise: its free acceleration
    -(g_e + omega^2 r_cy) >= 0.  Otherwise the floor pushes (N_slip = (g_e + omega^2 r_cy)/D
    > 0, docs/physics.md 1.2 (4)) and the corner slips in the direction sigma in which its own
    tangential acceleration u'' - theta'' r_cy - omega^2 r_cx points; sigma_f (against the
    sticking friction force) when neither direction is consistent.
    """
    theta, omega = q[ITHETA], q[IOMEGA]
    rcx, rcy = corner(s, theta, body)
    if g_e + omega * omega * rcy <= 0.0:
        return ROTATION_JUMP, s, 0.0
    for sigma in (sigma_f, -sigma_f):
        thdd, udd, N, D = slide_rotation_dynamics(theta, omega, s, sigma, a_x, g_e, body, mu)
        if N > 0.0 and D > 0.0 and sigma * (udd - thdd * rcy - omega * omega * rcx) > 0.0:
            return SLIDE_ROTATION, s, sigma
    return SLIDE_ROTATION, s, sigma_f


@jit
def select_face(q, a_x, g_e, body, contact, solver):
    """Mode after an impact or landing with theta = 0 (both corners at the floor).

    Zeno closure: a corner contact whose next impact would come within zeno_dt is closed
    to face contact, its return timed with the theta'' of the mode the corner enters
    (slide rotation where it slips: a slipping pivot can bring the body back where a
    sticking one would tip it, and the bounces then decay geometrically).  A face contact
    sets q to it in place (omega = v = 0, u = the base's slip velocity).
    """
    v_tol = closing_speed(solver.zeno_dt)
    if abs(q[IOMEGA]) * 0.5 * (body.b1 + body.b2) <= ROCKING_ROUNDOFF * (abs(q[IU])
                                                                      + abs(q[IV])):
        q[IOMEGA] = 0.0                 # round-off of a rotation-free impulse, not rocking
    omega = q[IOMEGA]
    VL = corner_velocity(q, -1.0, body)[1]
    VR = corner_velocity(q, 1.0, body)[1]
    if leaves(VL, v_tol) and leaves(VR, v_tol):
        if abs(omega) > 0.0:
            return ROTATION_JUMP, 0.0, 0.0
        return TRANSLATION_JUMP, 0.0, 0.0
    if omega != 0.0:
        s = -1.0 if omega > 0.0 else 1.0          # omega > 0 lifts the right corner
        q0, q1, q2, q3, q4, q5 = q[0], q[1], q[2], q[3], q[4], q[5]
        m, s2, sigma = select_corner(q, s, a_x, g_e, body, contact, v_tol)
        thdd = rotation_dynamics(0.0, omega, s, a_x, g_e, body)[0]
        if m == SLIDE_ROTATION:                   # rocking on a slipping corner
            slipping = slide_rotation_dynamics(0.0, omega, s, sigma, a_x, g_e, body,
                                               contact.mu_edge_k)
            if slipping[3] > 0.0:                 # (D <= 0: Painleve, said on entry)
                thdd = slipping[0]
        if rocking_closes(omega, thdd, solver.zeno_dt):
            q[0], q[1], q[2], q[3], q[4], q[5] = q0, q1, q2, q3, q4, q5
        elif s * q[IOMEGA] < 0.0:                 # the corner's closure left it rocking
            return m, s2, sigma
    # face contact: normal impulses under the base stop omega and v and leave u, which is
    # then the slip velocity of the base
    q[IOMEGA] = 0.0
    q[IV] = 0.0
    slip = q[IU]
    if leaves(abs(slip), v_tol):
        q[IU] = slip
        return start_slide(math.copysign(1.0, slip), body, contact)
    q[IU] = 0.0
    return leave_rest(a_x, g_e, body, contact)


@jit
def initial_mode(q, scene, rec):
    """Full initial state q (x = 0) and (mode, s, sigma) from the scene's initial values."""
    body = scene.body
    theta, omega, lift = scene.initial.theta, scene.initial.omega, scene.initial.lift
    q[IX] = 0.0
    q[ITHETA] = theta
    q[IU] = scene.initial.u
    q[IV] = scene.initial.v
    q[IOMEGA] = omega
    a_x, a_y = ground(0.0, scene.floor, rec)
    g_e = G + a_y
    if lift > 0.0:
        q[IY] = lift - min(corner(-1.0, theta, body)[1], corner(1.0, theta, body)[1])
        if theta != 0.0 or omega != 0.0:
            return ROTATION_JUMP, 0.0, 0.0
        return TRANSLATION_JUMP, 0.0, 0.0
    if theta != 0.0 or omega != 0.0:
        s = -math.copysign(1.0, theta if theta != 0.0 else omega)
        rcx, rcy = corner(s, theta, body)
        q[IY] = -rcy
        q[IV] = -omega * rcx          # the contact corner does not move vertically
        return select_corner(q, s, a_x, g_e, body, scene.contact,
                             closing_speed(scene.solver.zeno_dt))
    q[IY] = body.h
    if q[IV] > 0.0:
        return TRANSLATION_JUMP, 0.0, 0.0
    q[IV] = 0.0
    if q[IU] != 0.0:
        return start_slide(math.copysign(1.0, q[IU]), body, scene.contact)
    return leave_rest(a_x, g_e, body, scene.contact)


@jit
def _face_landing(mode, s, sigma, q, a_x, g_e, scene):
    """Impact with the face flat (theta = 0) and the mode after it: a landing after a
    translation jump by the scene's landing law, a rocking impact by ``face_impact``."""
    q[IY] = scene.body.h
    if mode == TRANSLATION_JUMP:
        flags = landing_impact(q, scene.body, scene.contact)
    else:
        flags = face_impact(q, scene.body, scene.contact)
    if flags & IMPACT_PAINLEVE:
        return mode, s, sigma, PAINLEVE, flags
    m, s2, sg2 = select_face(q, a_x, g_e, scene.body, scene.contact, scene.solver)
    return m, s2, sg2, OK, flags


@jit
def on_event(k, mode, t, q, ctx, scene, rec, lasted):
    """Apply event k of the mode at time t to q by the table above; ``lasted``: the mode
    held for some time since it was entered.

    Returns (mode, s, sigma, status, impact flags); the flags are ``NOT_AN_IMPACT`` when
    the event was not an impact.
    """
    body, contact = scene.body, scene.contact
    a_x, a_y = floor_at(t, ctx, scene, rec)
    g_e = G + a_y
    s = ctx[CTX_S]
    sigma = ctx[CTX_SIGMA]
    v_tol = closing_speed(scene.solver.zeno_dt)
    if mode == ROTATION or mode == SLIDE_ROTATION:
        if k == EV_OVERTURN:
            return mode, s, sigma, OVERTURNED, NOT_AN_IMPACT
        if k == EV_PAINLEVE:
            return mode, s, sigma, PAINLEVE, NOT_AN_IMPACT
        if k == EV_LIFTOFF:
            return ROTATION_JUMP, 0.0, 0.0, OK, NOT_AN_IMPACT
        if k == EV_SLIP and mode == ROTATION:
            F = rotation_dynamics(q[ITHETA], q[IOMEGA], s, a_x, g_e, body)[1]
            return SLIDE_ROTATION, s, -math.copysign(1.0, F), OK, NOT_AN_IMPACT
        if k == EV_SLIP:                                # the slipping corner stops
            q[IU] = q[IOMEGA] * corner(s, q[ITHETA], body)[1]
            m, s2, sg2 = select_corner(q, s, a_x, g_e, body, contact, v_tol)
            if m == SLIDE_ROTATION and not lasted and \
                    rotation_dynamics(q[ITHETA], q[IOMEGA], s, a_x, g_e, body)[2] > 0.0:
                m, s2, sg2 = ROTATION, s, 0.0           # a slip that ended as it began
            return m, s2, sg2, OK, NOT_AN_IMPACT
        q[ITHETA] = 0.0                                 # EV_IMPACT: the other corner strikes
        return _face_landing(mode, s, sigma, q, a_x, g_e, scene)
    if mode == SLIDE:
        if k == EV_STOP:
            q[IU] = 0.0
            m, s2, sg2 = leave_rest(a_x, g_e, body, contact)
            return m, s2, sg2, OK, NOT_AN_IMPACT
        q[IV] = 0.0                                     # EV_FREE_FALL: g_e reached 0
        return TRANSLATION_JUMP, 0.0, 0.0, OK, NOT_AN_IMPACT
    if mode == TRANSLATION_JUMP:                        # landing
        return _face_landing(mode, s, sigma, q, a_x, g_e, scene)
    # rotation jump
    if k == EV_JUMP_OVERTURN:
        return mode, s, sigma, OVERTURNED, NOT_AN_IMPACT
    sc = -1.0 if k == EV_GAP_L else 1.0
    q[IY] = -corner(sc, q[ITHETA], body)[1]
    flags = corner_impact(q, sc, body, contact)
    if flags & IMPACT_PAINLEVE:
        return mode, s, sigma, PAINLEVE, flags
    if leaves(corner_velocity(q, sc, body)[1], v_tol):   # still airborne
        return ROTATION_JUMP, 0.0, 0.0, OK, flags
    m, s2, sg2 = select_corner(q, sc, a_x, g_e, body, contact, v_tol)
    return m, s2, sg2, OK, flags


@jit
def painleve_at_entry(mode, s, sigma, t, q, scene, rec):
    """Whether slide rotation, entered now, has no consistent contact force (D <= 0,
    docs/physics.md 3.2)."""
    if mode != SLIDE_ROTATION:
        return False
    a_x, a_y = ground(t, scene.floor, rec)
    D = slide_rotation_dynamics(q[ITHETA], q[IOMEGA], s, sigma, a_x, G + a_y, scene.body,
                                scene.contact.mu_edge_k)[3]
    return D <= 0.0
