"""Zeno closure (docs/physics.md 3.1): contacts that would close again within ``zeno_dt``.

An accumulation of impacts (a bounce or rocking decaying geometrically) would take
infinitely many events in finite time.  The kernel closes it: a corner moving away from the
floor or along it slower than v_tol = g zeno_dt / 2 (``closing_speed``) would be back or
stopped within zeno_dt, so it is stopped now by the plastic impulse at the corner, never by
dropping velocity components, so that no closure adds energy; and rocking whose next impact
would come within zeno_dt is closed to face contact.  The mode table (``transitions``)
asks these questions; the answers are here.
"""
from ._jit import jit
from .corner_impact import apply_impulse, delassus
from .ground import G


@jit(inline="always")
def closing_speed(zeno_dt):
    """v_tol: a bounce this slow lands again within zeno_dt (flight time 2 v / g)."""
    return 0.5 * G * zeno_dt


@jit(inline="always")
def leaves(V, v_tol):
    """Whether a corner moving away from the floor (or slipping) at speed V stays apart
    (or slipping) for longer than zeno_dt."""
    return V > v_tol


@jit(inline="always")
def rocking_closes(omega, thdd, zeno_dt):
    """Whether rocking about a corner with rate omega and a restoring theta'' would strike
    again within zeno_dt (after 2 |omega| / |theta''|)."""
    return thdd * omega < 0.0 and 2.0 * abs(omega) < zeno_dt * abs(thdd)


@jit
def stop_corner(q, s, body, tangential):
    """Apply at corner s the impulse P that stops its normal velocity (and, if tangential,
    its tangential one too): V_c+ = V_c- + W P with the corner's inverse mass matrix W (per
    unit mass).  The change of energy, P.V_c-/2, is never positive."""
    Vx, Vy, wxx, wxy, wyy = delassus(q, s, body)
    if tangential:
        det = wxx * wyy - wxy * wxy
        Px = -(wyy * Vx - wxy * Vy) / det
        Py = -(wxx * Vy - wxy * Vx) / det
    else:
        Px = 0.0
        Py = -Vy / wyy
    apply_impulse(q, s, Px, Py, body)
