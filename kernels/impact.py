"""Impact laws (PHYSICS.md section 2): pre- to post-impact velocities of the full state q.

Impulses are per unit mass.  The tangential law: the tangential impulse is (1 + e_x) times
the impulse that would stop the contact's tangential velocity while the normal restitution
V_n+ = -e_y V_n- holds.  e_x = 0 is the sticking impact (Housner's law when e_y = 0), e_x = -1
gives no tangential impulse (a frictionless corner), and where the Delassus matrix W is
diagonal (a flat, rotation-free landing) this is exactly V_t+ = -e_x V_t-.  If that impulse
leaves the friction cone |P_t| <= mu_s P_n the corner slips during the impact and
P_t = -sigma mu_k P_n (section 2.2, step 3).  No impact may gain energy (step 6): a law
that would is replaced by the plastic sticking law, and if that still gains energy, by
the frictionless plastic one, which cannot.
"""
import math

from ._jit import jit
from .motion import IOMEGA, IU, IV, ITHETA, corner, corner_velocity, kinetic_energy

SLIPPED = 1          # flag bits returned by the impact functions
CLAMPED = 2
IMPACT_PAINLEVE = 4
SEQUENTIAL_IMPACTS = 50  # at most this many alternating corner impacts in one face impact


@jit
def _corner_impulse(q, s, e_x, e_y, mu_s, mu_k, b, h, i2):
    """Impulse (P_t, P_n, flags) at corner s by the law of section 2.2."""
    rcx, rcy = corner(s, q[ITHETA], b, h)
    Vx, Vy = corner_velocity(q, s, b, h)
    Wtt = 1.0 + rcy * rcy / i2
    Wtn = -rcx * rcy / i2
    Wnn = 1.0 + rcx * rcx / i2
    target_n = -(1.0 + e_y) * Vy
    det = Wtt * Wnn - Wtn * Wtn
    Pt = (1.0 + e_x) * (-Wnn * Vx - Wtn * target_n) / det
    Pn = (target_n - Wtn * Pt) / Wnn
    if Pn > 0.0 and abs(Pt) <= mu_s * Pn:
        return Pt, Pn, 0
    if abs(Vx) > 1e-14:
        sigma = math.copysign(1.0, Vx)
    else:
        sigma = -math.copysign(1.0, Pt)
    den = Wnn - sigma * mu_k * Wtn
    if den <= 0.0:                     # impact Painleve case
        return 0.0, 0.0, IMPACT_PAINLEVE
    Pn = target_n / den
    return -sigma * mu_k * Pn, Pn, SLIPPED


@jit
def _apply(q, s, Pt, Pn, b, h, i2):
    rcx, rcy = corner(s, q[ITHETA], b, h)
    q[IU] += Pt
    q[IV] += Pn
    q[IOMEGA] += (rcx * Pn - rcy * Pt) / i2


@jit
def _restore(q, u, v, omega):
    q[IU] = u
    q[IV] = v
    q[IOMEGA] = omega


@jit
def corner_impact(q, s, e_x, e_y, mu_s, mu_k, b, h, i2):
    """Single-corner impact at corner s (section 2.2); updates q, returns flag bits."""
    u, v, omega = q[IU], q[IV], q[IOMEGA]
    ke = kinetic_energy(q, i2)
    Pt, Pn, flags = _corner_impulse(q, s, e_x, e_y, mu_s, mu_k, b, h, i2)
    if flags & IMPACT_PAINLEVE:
        return flags
    _apply(q, s, Pt, Pn, b, h, i2)
    if kinetic_energy(q, i2) <= ke * (1.0 + 1e-12):
        return flags
    _restore(q, u, v, omega)                       # energy gained: plastic sticking law
    Pt, Pn, f2 = _corner_impulse(q, s, 0.0, 0.0, mu_s, mu_k, b, h, i2)
    if not f2 & IMPACT_PAINLEVE:
        _apply(q, s, Pt, Pn, b, h, i2)
        if kinetic_energy(q, i2) <= ke * (1.0 + 1e-12):
            return flags | f2 | CLAMPED
        _restore(q, u, v, omega)
    Vy = corner_velocity(q, s, b, h)[1]            # frictionless plastic: a projection
    rcx = corner(s, q[ITHETA], b, h)[0]
    _apply(q, s, 0.0, -Vy / (1.0 + rcx * rcx / i2), b, h, i2)
    return flags | CLAMPED


@jit
def _solve3(M, r):
    """Solve the 3x3 system M x = r by Cramer's rule (M given as a 9-tuple, row major)."""
    a, b_, c, d, e, f, g, h, k = M
    det = a * (e * k - f * h) - b_ * (d * k - f * g) + c * (d * h - e * g)
    x0 = (r[0] * (e * k - f * h) - b_ * (r[1] * k - f * r[2]) + c * (r[1] * h - e * r[2])) / det
    x1 = (a * (r[1] * k - f * r[2]) - r[0] * (d * k - f * g) + c * (d * r[2] - r[1] * g)) / det
    x2 = (a * (e * r[2] - r[1] * h) - b_ * (d * r[2] - r[1] * g) + r[0] * (d * h - e * g)) / det
    return x0, x1, x2


@jit
def _face_impulses(q, e_x, e_y, mu_s, mu_k, b, h, i2):
    """Two-contact impact with the face flat (theta = 0): (P_L, P_R, P_t, flags).

    Both corners get Newton's normal target -e_y V_n- (0 for a corner not approaching);
    the total tangential impulse acts at height -h below G (PHYSICS 2.3, generalised to
    omega != 0 as the velocity-level two-contact problem).
    """
    u, v, omega = q[IU], q[IV], q[IOMEGA]
    VL = v - omega * b
    VR = v + omega * b
    Vx = u + omega * h
    dL = -VL - e_y * min(VL, 0.0)
    dR = -VR - e_y * min(VR, 0.0)
    k1 = b * b / i2
    k2 = b * h / i2
    k3 = h * h / i2
    Mfull = (1.0 + k1, 1.0 - k1, -k2,
             1.0 - k1, 1.0 + k1, k2,
             -k2, k2, 1.0 + k3)
    Pt = (1.0 + e_x) * _solve3(Mfull, (dL, dR, -Vx))[2]
    # normals with the tangential impulse fixed
    det = (1.0 + k1) ** 2 - (1.0 - k1) ** 2
    rL = dL + k2 * Pt
    rR = dR - k2 * Pt
    PL = ((1.0 + k1) * rL - (1.0 - k1) * rR) / det
    PR = ((1.0 + k1) * rR - (1.0 - k1) * rL) / det
    if omega != 0.0 and min(PL, PR) < -1e-12 * (abs(PL) + abs(PR)):
        # a rocking impact whose sticking two-contact solution pulls a corner down: the old
        # pivot lifts (Housner's case); a flat landing goes on to the friction cap (2.3)
        return PL, PR, Pt, 0
    if abs(Pt) <= mu_s * (PL + PR):
        return PL, PR, Pt, 0
    sigma = math.copysign(1.0, Vx) if abs(Vx) > 1e-14 else -math.copysign(1.0, Pt)
    c = -sigma * mu_k                      # P_t = c (P_L + P_R)
    a11 = 1.0 + k1 - k2 * c
    a12 = 1.0 - k1 - k2 * c
    a21 = 1.0 - k1 + k2 * c
    a22 = 1.0 + k1 + k2 * c
    det = a11 * a22 - a12 * a21
    if det == 0.0:
        return 0.0, 0.0, 0.0, IMPACT_PAINLEVE
    PL = (a22 * dL - a12 * dR) / det
    PR = (a11 * dR - a21 * dL) / det
    return PL, PR, c * (PL + PR), SLIPPED


@jit
def face_impact(q, e_x, e_y, mu_s, mu_k, mu_edge_s, mu_edge_k, b, h, i2):
    """Impact with theta = 0, both corners on the floor; updates q, returns flag bits.

    The two-contact solution is taken when both normal impulses are >= 0 (a flat landing,
    or a squat block whose old pivot cannot lift); otherwise only the striking corner
    takes the impulse with the edge friction (Housner's case), PHYSICS 2.2-2.3.
    """
    u, v, omega = q[IU], q[IV], q[IOMEGA]
    ke = kinetic_energy(q, i2)
    PL, PR, Pt, flags = _face_impulses(q, e_x, e_y, mu_s, mu_k, b, h, i2)
    tol = 1e-12 * (abs(PL) + abs(PR))
    if not flags & IMPACT_PAINLEVE and PL >= -tol and PR >= -tol:
        q[IU] += Pt
        q[IV] += PL + PR
        q[IOMEGA] += (b * (PR - PL) + h * Pt) / i2
        if kinetic_energy(q, i2) <= ke * (1.0 + 1e-12):
            return flags
        _restore(q, u, v, omega)
    # Only the corner striking harder takes the impulse.  If that drives the other corner
    # into the floor (a squat block, restitution), the other corner is struck in turn, and so
    # on: a sequence of single-corner impacts, each dissipative, until neither approaches.
    s = -1.0 if v - omega * b < v + omega * b else 1.0
    flags = 0
    for _ in range(SEQUENTIAL_IMPACTS):
        flags |= corner_impact(q, s, e_x, e_y, mu_edge_s, mu_edge_k, b, h, i2)
        if flags & IMPACT_PAINLEVE:
            return flags
        s = -s
        if corner_velocity(q, s, b, h)[1] >= -1e-12 * (abs(q[IV]) + b * abs(q[IOMEGA])):
            return flags
    return flags | CLAMPED
