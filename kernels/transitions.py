"""Which mode a body is in, given its state and the floor (PHYSICS.md section 1.3).

``leave_rest`` is the table for a body whose face is on the floor without relative motion;
``select_corner`` decides for a body touching the floor with one corner; ``select_face``
decides with theta = 0 after an impact or a landing, including the Zeno closure of
section 3.1.  Each returns (mode, s, sigma): the contact corner (-1 left, +1 right) and
the slip direction sgn(V_cx), as the equations of motion need them.
"""
import math

from ._jit import jit
from .codes import REST, ROTATION, ROTATION_JUMP, SLIDE, SLIDE_ROTATION, TRANSLATION_JUMP
from .motion import IOMEGA, ITHETA, IU, IV, corner, corner_velocity, rotation_dynamics, \
    slide_rotation_dynamics


@jit
def mu_required(A, b, h, i2):
    """Friction needed for pure rocking at onset, Shenton's mu_req(A) (PHYSICS 1.3)."""
    return (A * (i2 + b * b) + b * h) / ((i2 + h * h) + A * b * h)


@jit
def leave_rest(a_x, g_e, b, h, i2, mu_s, mu_k, mu_edge_k):
    """The rest table of PHYSICS 1.3 with A = |a_x|/g_e and beta = b/h."""
    if g_e <= 0.0:
        return TRANSLATION_JUMP, 0.0, 0.0
    A = abs(a_x) / g_e
    beta = b / h
    if A <= mu_s and A <= beta:
        return REST, 0.0, 0.0
    drive = math.copysign(1.0, a_x)
    s = -drive                         # a_x > 0 tips the body about its left corner
    if A > beta:
        if mu_s >= mu_required(A, b, h, i2):
            return ROTATION, s, 0.0
        if mu_edge_k > beta:           # the pivot slips backwards relative to the floor
            return SLIDE_ROTATION, s, -drive
    if A > mu_s:
        return start_slide(-drive, mu_k, b, h)
    return REST, 0.0, 0.0


@jit
def start_slide(sigma, mu_k, b, h):
    """Flat sliding with sgn(u) = sigma; with mu_k > b/h the body trips over its leading
    corner instead (one normal force would turn negative, PHYSICS 1.2 (2))."""
    if mu_k > b / h:
        return SLIDE_ROTATION, sigma, sigma
    return SLIDE, 0.0, sigma


@jit
def select_corner(q, s, a_x, g_e, b, h, i2, mu_edge_s, mu_edge_k, v_tol):
    """Mode of a body whose corner s touches the floor (gap 0).

    A corner velocity below v_tol (a bounce or a slip that would end within zeno_dt) is
    closed by the plastic impulse that stops it (``stop_corner``), so the state satisfies
    the contact constraints of the mode it enters without gaining energy.
    """
    Vx, Vy = corner_velocity(q, s, b, h)
    if Vy > v_tol:
        return ROTATION_JUMP, s, 0.0
    stop_corner(q, s, b, h, i2, abs(Vx) <= v_tol)
    if abs(Vx) > v_tol:
        sigma = math.copysign(1.0, Vx)
        N = slide_rotation_dynamics(q[ITHETA], q[IOMEGA], s, sigma, a_x, g_e, b, h, i2,
                                    mu_edge_k)[2]
        if N <= 0.0:
            return ROTATION_JUMP, s, 0.0
        return SLIDE_ROTATION, s, sigma
    thdd, F, N = rotation_dynamics(q[ITHETA], q[IOMEGA], s, a_x, g_e, b, h, i2)
    if N > 0.0:
        if abs(F) <= mu_edge_s * N:
            return ROTATION, s, 0.0
        return SLIDE_ROTATION, s, -math.copysign(1.0, F)
    return _unstick(q, s, -math.copysign(1.0, F), a_x, g_e, b, h, i2, mu_edge_k)


@jit
def stop_corner(q, s, b, h, i2, tangential):
    """Apply at corner s the impulse P that stops its normal velocity (and, if tangential,
    its tangential one too): V_c+ = V_c- + W P with the corner's inverse mass matrix W (per
    unit mass).  The change of energy, P.V_c-/2, is never positive."""
    rcx, rcy = corner(s, q[ITHETA], b, h)
    Vx, Vy = corner_velocity(q, s, b, h)
    wxx = 1.0 + rcy * rcy / i2
    wxy = -rcx * rcy / i2
    wyy = 1.0 + rcx * rcx / i2
    if tangential:
        det = wxx * wyy - wxy * wxy
        Px = -(wyy * Vx - wxy * Vy) / det
        Py = -(wxx * Vy - wxy * Vx) / det
    else:
        Px = 0.0
        Py = -Vy / wyy
    q[IU] += Px
    q[IV] += Py
    q[IOMEGA] += (rcx * Py - rcy * Px) / i2


@jit
def _unstick(q, s, sigma_f, a_x, g_e, b, h, i2, mu):
    """Mode of a resting corner (V_c = 0) that sticking would have to pull down (N <= 0).

    The corner flies if gravity alone lets it rise: its free acceleration
    -(g_e + omega^2 r_cy) >= 0.  Otherwise the floor pushes (N_slip = (g_e + omega^2 r_cy)/D
    > 0, PHYSICS 1.2 (4)) and the corner slips in the direction sigma in which its own
    tangential acceleration u'' - theta'' r_cy - omega^2 r_cx points; sigma_f (against the
    sticking friction force) when neither direction is consistent.
    """
    theta, omega = q[ITHETA], q[IOMEGA]
    rcx, rcy = corner(s, theta, b, h)
    if g_e + omega * omega * rcy <= 0.0:
        return ROTATION_JUMP, s, 0.0
    for sigma in (sigma_f, -sigma_f):
        thdd, udd, N, D = slide_rotation_dynamics(theta, omega, s, sigma, a_x, g_e, b, h, i2,
                                                  mu)
        if N > 0.0 and D > 0.0 and sigma * (udd - thdd * rcy - omega * omega * rcx) > 0.0:
            return SLIDE_ROTATION, s, sigma
    return SLIDE_ROTATION, s, sigma_f


@jit
def select_face(q, a_x, g_e, b, h, i2, mu_s, mu_k, mu_edge_s, mu_edge_k, v_tol, zeno_dt):
    """Mode after an impact or landing with theta = 0 (both corners at the floor).

    Zeno closure (PHYSICS 3.1): a corner contact whose next impact would come within
    zeno_dt (2|omega|/|theta''| with a restoring theta'') is closed to face contact.
    A face contact sets q to it in place (omega = v = 0, u = the base's slip velocity).
    """
    if abs(q[IOMEGA]) * b <= 1e-12 * (abs(q[IU]) + abs(q[IV])):
        q[IOMEGA] = 0.0                 # round-off of a rotation-free impulse, not rocking
    omega = q[IOMEGA]
    VL = corner_velocity(q, -1.0, b, h)[1]
    VR = corner_velocity(q, 1.0, b, h)[1]
    if VL > v_tol and VR > v_tol:
        if abs(omega) > 0.0:
            return ROTATION_JUMP, 0.0, 0.0
        return TRANSLATION_JUMP, 0.0, 0.0
    if omega != 0.0:
        s = -1.0 if omega > 0.0 else 1.0          # omega > 0 lifts the right corner
        thdd = rotation_dynamics(0.0, omega, s, a_x, g_e, b, h, i2)[0]
        restoring = thdd * omega < 0.0
        if not (restoring and 2.0 * abs(omega) < zeno_dt * abs(thdd)):
            m, s2, sigma = select_corner(q, s, a_x, g_e, b, h, i2, mu_edge_s, mu_edge_k,
                                         v_tol)
            if s * q[IOMEGA] < 0.0:               # the closure left it rocking about s
                return m, s2, sigma
    # face contact: normal impulses under the base stop omega and v and leave u, which is
    # then the slip velocity of the base
    q[IOMEGA] = 0.0
    q[IV] = 0.0
    slip = q[IU]
    if abs(slip) > v_tol:
        q[IU] = slip
        return start_slide(math.copysign(1.0, slip), mu_k, b, h)
    q[IU] = 0.0
    return leave_rest(a_x, g_e, b, h, i2, mu_s, mu_k, mu_edge_k)
