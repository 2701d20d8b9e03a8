"""Equations of motion of the six modes (docs/physics.md section 1.2), in the floor frame.

Each mode integrates only its own degrees of freedom, packed in a compact state ``z``:

=================  ======================  =====================================
mode               z                       derived (``to_full``)
=================  ======================  =====================================
rest               (none)                  x = ctx[CTX_X]
slide              x, u                    y = h, theta = v = omega = 0
rotation           theta, omega            x, y, u, v from the pivot ctx[CTX_X]
slide_rotation     theta, omega, x, u      y, v from the contact constraint
translation_jump   x, y, u, v              theta = omega = 0
rotation_jump      x, y, theta, u, v, w    -
=================  ======================  =====================================

The full state is ``q = (x, y, theta, u, v, omega)`` (G relative to the floor, y = h when
flat).  ``ctx`` holds the contact corner sign s (-1 left, +1 right), the slip direction
sigma, the pivot (rotation) or rest position x, and the floor acceleration last computed
(``floor_at``).  theta > 0 is rotation about the left corner, which a floor acceleration to
the right drives.  Forces are per unit mass.  Each corner has its own half-base b_s
(``half_base``: b1 left, b2 right, docs/bodies.md); the point s = 0 is the point of the base
below G.
"""
import math

from ._jit import jit
from .codes import (CTX_FLOOR_HELD, CTX_FLOOR_T, CTX_FLOOR_X, CTX_FLOOR_Y, CTX_S, CTX_SIGMA,
                    CTX_X, IOMEGA, ITHETA, IU, IV, IX, IY, REST, ROTATION, ROTATION_JUMP, SLIDE,
                    SLIDE_ROTATION, TRANSLATION_JUMP)
from .ground import G, ground


@jit
def n_dof(mode):
    """Number of integrated degrees of freedom (length of z) of a mode."""
    if mode == REST:
        return 0
    if mode == SLIDE or mode == ROTATION:
        return 2
    if mode == ROTATION_JUMP:
        return 6
    return 4


@jit(inline="always")
def half_base(s, body):
    """Horizontal distance b_s from G to corner s (b1 left, b2 right) on the flat body."""
    return body.b2 if s > 0.0 else body.b1


@jit(inline="always")
def corner(s, theta, body):
    """Vector r_c from G to corner s (-1 left, +1 right; 0 the point of the base below G) at
    angle theta (docs/physics.md 1.1, docs/bodies.md): (s b_s cos theta + h sin theta,
    s b_s sin theta - h cos theta)."""
    b = half_base(s, body)
    h = body.h
    c = math.cos(theta)
    sn = math.sin(theta)
    return s * b * c + h * sn, s * b * sn - h * c


@jit(inline="always")
def pivot_inertia(s, body):
    """(i^2 + R_s^2): the moment of inertia per unit mass about corner s."""
    b = half_base(s, body)
    return body.i2 + b * b + body.h * body.h


@jit(inline="always")
def sliding_friction(sigma, body, contact):
    """The surface's kinetic friction as flat sliding with sgn(u) = sigma sees it.

    With mu_k > b_s/h >= mu_edge_k (s = sigma, the leading corner) flat sliding would tip
    the body onto that corner, where the lower edge friction tips it straight back.  The
    body then slides flat on the verge of tipping, with the friction that holds
    theta'' = 0 there: b_s/h.
    """
    return min(contact.mu_k, max(half_base(sigma, body) / body.h, contact.mu_edge_k))


@jit(inline="always")
def rotation_dynamics(theta, omega, s, a_x, g_e, body):
    """Rocking about the fixed corner s: (theta'', F_c/m, N_c/m), docs/physics.md 1.2 (3).

    rho = -r_c points from the pivot to G; (i^2 + R_s^2) theta'' = a_x rho_y - g_e rho_x.
    """
    rcx, rcy = corner(s, theta, body)
    rho_x = -rcx
    rho_y = -rcy
    thdd = (a_x * rho_y - g_e * rho_x) / pivot_inertia(s, body)
    w2 = omega * omega
    F = -thdd * rho_y - w2 * rho_x + a_x
    N = thdd * rho_x - w2 * rho_y + g_e
    return thdd, F, N


@jit(inline="always")
def slide_rotation_dynamics(theta, omega, s, sigma, a_x, g_e, body, mu):
    """One corner on the floor and slipping with sgn(V_cx) = sigma, docs/physics.md 1.2 (4).

    Returns (theta'', u'', N_c/m, D); D <= 0 is the Painleve condition.
    """
    i2 = body.i2
    rcx, rcy = corner(s, theta, body)
    D = 1.0 + (rcx * rcx + mu * sigma * rcx * rcy) / i2
    N = (g_e + omega * omega * rcy) / D
    thdd = N * (rcx + mu * sigma * rcy) / i2
    udd = -mu * sigma * N - a_x
    return thdd, udd, N, D


@jit(inline="always")
def floor_at(t, ctx, scene, rec):
    """``ground(t, scene.floor, rec)``, kept in ctx for the next call at the same t: a step
    asks for the floor at its end twice (DOPRI5's last stage and its end slope) and the event
    functions there once more, and a new mode asks three times at its start."""
    if ctx[CTX_FLOOR_HELD] == 0.0 or ctx[CTX_FLOOR_T] != t:
        ctx[CTX_FLOOR_X], ctx[CTX_FLOOR_Y] = ground(t, scene.floor, rec)
        ctx[CTX_FLOOR_T] = t
        ctx[CTX_FLOOR_HELD] = 1.0
    return ctx[CTX_FLOOR_X], ctx[CTX_FLOOR_Y]


@jit(inline="always")
def rhs(mode, t, z, ctx, scene, rec, out):
    """Write dz/dt of the mode's compact state z into out."""
    a_x, a_y = floor_at(t, ctx, scene, rec)
    g_e = G + a_y
    body = scene.body
    contact = scene.contact
    if mode == SLIDE:                                  # (2): u' = -a_x - mu_k g_e sgn(u)
        sigma = ctx[CTX_SIGMA]
        out[0] = z[1]
        out[1] = -a_x - sliding_friction(sigma, body, contact) * g_e * sigma
    elif mode == ROTATION:                             # (3), theta'' only
        s = ctx[CTX_S]
        rcx, rcy = corner(s, z[0], body)
        out[0] = z[1]
        out[1] = (g_e * rcx - a_x * rcy) / pivot_inertia(s, body)
    elif mode == SLIDE_ROTATION:
        thdd, udd, N, D = slide_rotation_dynamics(z[0], z[1], ctx[CTX_S], ctx[CTX_SIGMA],
                                                  a_x, g_e, body, contact.mu_edge_k)
        out[0] = z[1]
        out[1] = thdd
        out[2] = z[3]
        out[3] = udd
    elif mode == TRANSLATION_JUMP:                     # (5)
        out[0] = z[2]
        out[1] = z[3]
        out[2] = -a_x
        out[3] = -g_e
    else:                                              # (6) rotation jump
        out[0] = z[3]
        out[1] = z[4]
        out[2] = z[5]
        out[3] = -a_x
        out[4] = -g_e
        out[5] = 0.0


@jit
def to_full(mode, z, ctx, body, q):
    """Fill the full state q = (x, y, theta, u, v, omega) from the compact state z."""
    h = body.h
    if mode == REST:
        q[IX] = ctx[CTX_X]
        q[IY] = h
        q[ITHETA] = 0.0
        q[IU] = 0.0
        q[IV] = 0.0
        q[IOMEGA] = 0.0
    elif mode == SLIDE:
        q[IX] = z[0]
        q[IY] = h
        q[ITHETA] = 0.0
        q[IU] = z[1]
        q[IV] = 0.0
        q[IOMEGA] = 0.0
    elif mode == ROTATION or mode == SLIDE_ROTATION:
        theta = z[0]
        omega = z[1]
        rcx, rcy = corner(ctx[CTX_S], theta, body)
        q[ITHETA] = theta
        q[IOMEGA] = omega
        q[IY] = -rcy
        q[IV] = -omega * rcx
        if mode == ROTATION:
            q[IX] = ctx[CTX_X] - rcx
            q[IU] = omega * rcy
        else:
            q[IX] = z[2]
            q[IU] = z[3]
    elif mode == TRANSLATION_JUMP:
        q[IX] = z[0]
        q[IY] = z[1]
        q[ITHETA] = 0.0
        q[IU] = z[2]
        q[IV] = z[3]
        q[IOMEGA] = 0.0
    else:
        for k in range(6):
            q[k] = z[k]


@jit
def from_full(mode, q, ctx, body, z):
    """Pack the full state q into the compact state z of a mode (sets the pivot in ctx)."""
    if mode == REST:
        ctx[CTX_X] = q[IX]
    elif mode == SLIDE:
        z[0] = q[IX]
        z[1] = q[IU]
    elif mode == ROTATION or mode == SLIDE_ROTATION:
        z[0] = q[ITHETA]
        z[1] = q[IOMEGA]
        if mode == ROTATION:
            ctx[CTX_X] = q[IX] + corner(ctx[CTX_S], q[ITHETA], body)[0]
        else:
            z[2] = q[IX]
            z[3] = q[IU]
    elif mode == TRANSLATION_JUMP:
        z[0] = q[IX]
        z[1] = q[IY]
        z[2] = q[IU]
        z[3] = q[IV]
    else:
        for k in range(6):
            z[k] = q[k]


@jit(inline="always")
def corner_velocity(q, s, body):
    """Velocity (V_cx, V_cy) of corner s: V_c = (u - omega r_cy, v + omega r_cx)."""
    rcx, rcy = corner(s, q[ITHETA], body)
    return q[IU] - q[IOMEGA] * rcy, q[IV] + q[IOMEGA] * rcx


@jit
def kinetic_energy(q, i2):
    """Kinetic energy per unit mass, relative to the floor."""
    return 0.5 * (q[IU] * q[IU] + q[IV] * q[IV] + i2 * q[IOMEGA] * q[IOMEGA])
