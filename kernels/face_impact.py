"""Impact with the face flat, theta = 0: the landing after a jump and the rocking impact.

The landing after a translation jump and the rocking impact of the other corner
(docs/physics.md 2.1-2.3, docs/landing.md).

Both corners get Newton's normal target -e_y V_n- (0 for a corner not approaching); the
total tangential impulse acts at the height -h below G.  The two-contact solution is taken
when both normal impulses are >= 0 (a flat landing, or a squat block whose old pivot cannot
lift); otherwise only the corner striking harder (on a flat landing, where both strike
alike, the leading one) takes the impulse with the edge friction (Housner's case,
``corner_impact``), and if that drives the other corner into the floor,
that one is struck in turn: a sequence of single-corner impacts, each dissipative.  A
landing after a translation jump takes the scene's law (``landing_impact``): this
two-contact impulse (flat), one contact at the middle of the base (face_friction), or the
leading corner first (corner).
"""
import math

from ._jit import jit
from .codes import (CLAMPED, IMPACT_PAINLEVE, IOMEGA, IU, IV, LANDING_CORNER,
                    LANDING_FACE_FRICTION, SLIPPED)
from .corner_impact import corner_impact, point_impact, restore_velocities
from .motion import corner_velocity, half_base, kinetic_energy, sliding_friction
from .tolerances import APPROACH_ROUNDOFF, ENERGY_ROUNDOFF, IMPULSE_ROUNDOFF, V_ZERO

SEQUENTIAL_IMPACTS = 50  # at most this many alternating corner impacts in one face impact


@jit
def face_impulses(q, body, contact):
    """Two-contact impulses (P_L, P_R, P_t, flags) with the face flat (docs/physics.md 2.3,
    generalised to omega != 0 as the velocity-level two-contact problem), with the surface
    friction: the tangential impulse is (1 + e_x) times the sticking one, capped by the
    friction cone |P_t| <= mu_s (P_L + P_R), beyond which it slips with mu_k.

    The corners lie at (-b1, -h) and (b2, -h) from G: an impulse (P_L, P_R, P_t) changes
    V_L, V_R and the base's V_x by the symmetric matrix
    [[a, d, -k_1], [d, c, k_2], [-k_1, k_2, 1 + k_3]] with a = 1 + k_11, c = 1 + k_22,
    d = 1 - k_12 (k_ij = b_i b_j / i^2, k_i = b_i h / i^2, k_3 = h^2 / i^2; docs/bodies.md).
    P_t is its third unknown by cofactors, written so that the mirror image of a state
    (b1 <-> b2, u, omega -> -u, -omega) gives the mirrored impulses bit for bit."""
    b1, b2, h, i2 = body.b1, body.b2, body.h, body.i2
    e_x, e_y, mu_s = contact.e_x, contact.e_y, contact.mu_s
    u, v, omega = q[IU], q[IV], q[IOMEGA]
    VL = v - omega * b1
    VR = v + omega * b2
    Vx = u + omega * h
    dL = -VL - e_y * min(VL, 0.0)
    dR = -VR - e_y * min(VR, 0.0)
    k1 = b1 * h / i2
    k2 = b2 * h / i2
    a = 1.0 + b1 * b1 / i2
    c = 1.0 + b2 * b2 / i2
    d = 1.0 - b1 * b2 / i2
    det = a * c - d * d                    # the normal block's determinant
    det3 = (1.0 + h * h / i2) * det - (a * k2 * k2 + c * k1 * k1) - 2.0 * d * (k1 * k2)
    Pt = (1.0 + e_x) * ((c * k1 + d * k2) * dL - (a * k2 + d * k1) * dR - det * Vx) / det3
    # normals with the tangential impulse fixed
    rL = dL + k1 * Pt
    rR = dR - k2 * Pt
    PL = (c * rL - d * rR) / det
    PR = (a * rR - d * rL) / det
    if omega != 0.0 and min(PL, PR) < -IMPULSE_ROUNDOFF * (abs(PL) + abs(PR)):
        # a rocking impact whose sticking two-contact solution pulls a corner down: the old
        # pivot lifts (Housner's case); a flat landing goes on to the friction cap (2.3)
        return PL, PR, Pt, 0
    if abs(Pt) <= mu_s * (PL + PR):
        return PL, PR, Pt, 0
    sigma = math.copysign(1.0, Vx) if abs(Vx) > V_ZERO else -math.copysign(1.0, Pt)
    f = -sigma * sliding_friction(sigma, body, contact)   # P_t = f (P_L + P_R)
    a11 = a - k1 * f
    a12 = d - k1 * f
    a21 = d + k2 * f
    a22 = c + k2 * f
    det = a11 * a22 - a12 * a21
    if det == 0.0:
        return 0.0, 0.0, 0.0, IMPACT_PAINLEVE
    PL = (a22 * dL - a12 * dR) / det
    PR = (a11 * dR - a21 * dL) / det
    return PL, PR, f * (PL + PR), SLIPPED


@jit
def face_impact(q, body, contact):
    """Impact with theta = 0, both corners at the floor; updates q, returns flag bits."""
    h, i2 = body.h, body.i2
    b = 0.5 * (body.b1 + body.b2)           # the normal impulses' moment about G is
    x_g = 0.5 * (body.b1 - body.b2)         # b2 P_R - b1 P_L = b (P_R - P_L) - x_G (P_L + P_R)
    u, v, omega = q[IU], q[IV], q[IOMEGA]
    ke = kinetic_energy(q, i2)
    PL, PR, Pt, flags = face_impulses(q, body, contact)
    tol = IMPULSE_ROUNDOFF * (abs(PL) + abs(PR))
    if not flags & IMPACT_PAINLEVE and PL >= -tol and PR >= -tol:
        q[IU] += Pt
        q[IV] += PL + PR
        q[IOMEGA] += (b * (PR - PL) - x_g * (PL + PR) + h * Pt) / i2
        if kinetic_energy(q, i2) <= ke * (1.0 + ENERGY_ROUNDOFF):
            return flags
        restore_velocities(q, u, v, omega)
    # Only the corner striking harder takes the impulse, then the other in turn.
    return corner_sequence(q, striking_corner(q, body), body, contact)


@jit
def striking_corner(q, body):
    """The corner moving faster into the floor with the face flat (-1 left, +1 right).  On
    a tie, omega = 0 (a landing), the leading corner, on the side u points to: the friction
    impulse against u loads it and unloads the trailing one, whose normal impulse is the
    one that turns negative (docs/physics.md 2.3, docs/landing.md).  With u = 0 too the two-contact
    impulse has P_t = 0 and both normal impulses > 0, so no single corner is asked for."""
    VL = corner_velocity(q, -1.0, body)[1]
    VR = corner_velocity(q, 1.0, body)[1]
    if VL == VR:
        return math.copysign(1.0, q[IU])
    return -1.0 if VL < VR else 1.0


@jit
def approaches(q, s, body):
    """Whether corner s moves into the floor (beyond round-off)."""
    return corner_velocity(q, s, body)[1] < -APPROACH_ROUNDOFF * (
        abs(q[IV]) + half_base(s, body) * abs(q[IOMEGA]))


@jit
def corner_sequence(q, s, body, contact):
    """Single-corner impacts (docs/physics.md 2.2) at theta = 0: corner s, then the other in turn
    while the last one drives it into the floor; updates q, returns the flag bits
    (``CLAMPED`` too if ``SEQUENTIAL_IMPACTS`` did not end it)."""
    flags = 0
    for _ in range(SEQUENTIAL_IMPACTS):
        flags |= corner_impact(q, s, body, contact)
        if flags & IMPACT_PAINLEVE:
            return flags
        s = -s
        if not approaches(q, s, body):
            return flags
    return flags | CLAMPED


@jit
def landing_impact(q, body, contact):
    """Landing after a translation jump (theta = omega = 0) by the contact's law
    (``codes.LANDING_*``); updates q, returns the flag bits.

    flat: ``face_impact``, the two-contact impulse (docs/physics.md 2.3).  face_friction: the
    two-coefficient impact (2.2) of the point of the base below G (the middle of a symmetric
    body) with the surface's friction, whose tangential impulse, h below G, turns the body
    (docs/landing.md (L3)); a corner that rotation drives into the floor then strikes, and
    the other in turn.  corner: the leading corner (on the side u points to) strikes first,
    then the other in turn; without a horizontal velocity no corner leads and the landing is
    flat.
    """
    if contact.landing == LANDING_FACE_FRICTION:
        # s = 0: the point below G; W_nn = 1 there, so never a Painleve case
        mu_k = sliding_friction(math.copysign(1.0, q[IU]), body, contact)
        flags = point_impact(q, 0.0, contact.mu_s, mu_k, body, contact)
        s = striking_corner(q, body)
        if approaches(q, s, body):
            flags |= corner_sequence(q, s, body, contact)
        return flags
    if contact.landing == LANDING_CORNER and q[IU] != 0.0:
        return corner_sequence(q, math.copysign(1.0, q[IU]), body, contact)
    return face_impact(q, body, contact)
