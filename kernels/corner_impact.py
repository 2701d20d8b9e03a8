"""Single-corner impact with the friction-limited impulse (docs/physics.md 2.2).

Pre- to post-impact velocities of the full state q; impulses per unit mass.  The tangential
impulse is (1 + e_x) times the impulse that would stop the corner's tangential velocity
while the normal restitution V_n+ = -e_y V_n- holds: e_x = 0 is the sticking impact
(Housner's law when e_y = 0, 2.1), e_x = -1 gives no tangential impulse (a frictionless
corner).  If that impulse leaves the friction cone |P_t| <= mu_s P_n the corner slips
during the impact and P_t = -sigma mu_k P_n (step 3).  No impact may gain energy (step 6):
a law that would is replaced by the plastic sticking law, and if that still gains energy,
by the frictionless plastic one, which cannot.  A corner takes the edge's friction; the
same law at the point of the base below G (s = 0, the middle of a symmetric body), with the
surface's friction, is the ``face_friction`` landing (docs/landing.md).  Each corner has its
own vector r_c (``motion.corner``): for a body with G off the middle, Housner's ratio about
the new pivot c is 1 - b_c (b1 + b2)/(i^2 + R_c^2) (docs/bodies.md).
"""
import math

from ._jit import jit
from .codes import CLAMPED, IMPACT_PAINLEVE, IOMEGA, ITHETA, IU, IV, SLIPPED
from .motion import corner, corner_velocity, kinetic_energy
from .tolerances import ENERGY_ROUNDOFF, V_ZERO


@jit(inline="always")
def delassus(q, s, body):
    """The velocity (V_x, V_y) of corner s and its inverse mass matrix W (the Delassus
    matrix, per unit mass): V_c+ = V_c- + W P for an impulse P at the corner.
    Returns (V_x, V_y, W_tt, W_tn, W_nn)."""
    i2 = body.i2
    rcx, rcy = corner(s, q[ITHETA], body)
    Vx, Vy = corner_velocity(q, s, body)
    return Vx, Vy, 1.0 + rcy * rcy / i2, -rcx * rcy / i2, 1.0 + rcx * rcx / i2


@jit
def corner_impulse(q, s, e_x, e_y, mu_s, mu_k, body):
    """Impulse (P_t, P_n, flags) at corner s by the law of section 2.2 (steps 1-4)."""
    Vx, Vy, Wtt, Wtn, Wnn = delassus(q, s, body)
    target_n = -(1.0 + e_y) * Vy
    det = Wtt * Wnn - Wtn * Wtn
    Pt = (1.0 + e_x) * (-Wnn * Vx - Wtn * target_n) / det
    Pn = (target_n - Wtn * Pt) / Wnn
    if Pn > 0.0 and abs(Pt) <= mu_s * Pn:
        return Pt, Pn, 0
    if abs(Vx) > V_ZERO:
        sigma = math.copysign(1.0, Vx)
    else:
        sigma = -math.copysign(1.0, Pt)
    den = Wnn - sigma * mu_k * Wtn
    if den <= 0.0:                     # impact Painleve case
        return 0.0, 0.0, IMPACT_PAINLEVE
    Pn = target_n / den
    return -sigma * mu_k * Pn, Pn, SLIPPED


@jit
def apply_impulse(q, s, Pt, Pn, body):
    """Add the impulse (P_t, P_n) at corner s to the velocities of q."""
    rcx, rcy = corner(s, q[ITHETA], body)
    q[IU] += Pt
    q[IV] += Pn
    q[IOMEGA] += (rcx * Pn - rcy * Pt) / body.i2


@jit
def restore_velocities(q, u, v, omega):
    """Put back the velocities of q from before an impulse."""
    q[IU] = u
    q[IV] = v
    q[IOMEGA] = omega


@jit
def point_impact(q, s, mu_s, mu_k, body, contact):
    """Impact of the base point s (a corner, s = +-1, or the point of the base below G, s = 0:
    ``motion.corner``) with the friction (mu_s, mu_k) and the contact's restitution (section
    2.2); updates q, returns the flag bits (``codes.SLIPPED``, ``CLAMPED``,
    ``IMPACT_PAINLEVE``)."""
    i2 = body.i2
    u, v, omega = q[IU], q[IV], q[IOMEGA]
    ke = kinetic_energy(q, i2)
    Pt, Pn, flags = corner_impulse(q, s, contact.e_x, contact.e_y, mu_s, mu_k, body)
    if flags & IMPACT_PAINLEVE:
        return flags
    apply_impulse(q, s, Pt, Pn, body)
    if kinetic_energy(q, i2) <= ke * (1.0 + ENERGY_ROUNDOFF):
        return flags
    restore_velocities(q, u, v, omega)             # energy gained: plastic sticking law
    Pt, Pn, f2 = corner_impulse(q, s, 0.0, 0.0, mu_s, mu_k, body)
    if not f2 & IMPACT_PAINLEVE:
        apply_impulse(q, s, Pt, Pn, body)
        if kinetic_energy(q, i2) <= ke * (1.0 + ENERGY_ROUNDOFF):
            return flags | f2 | CLAMPED
        restore_velocities(q, u, v, omega)
    Vy = corner_velocity(q, s, body)[1]            # frictionless plastic: a projection
    rcx = corner(s, q[ITHETA], body)[0]
    apply_impulse(q, s, 0.0, -Vy / (1.0 + rcx * rcx / i2), body)
    return flags | CLAMPED


@jit
def corner_impact(q, s, body, contact):
    """Impact of corner s with the edge's friction (``point_impact``)."""
    return point_impact(q, s, contact.mu_edge_s, contact.mu_edge_k, body, contact)
