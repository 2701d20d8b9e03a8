"""Scene builders and body constants shared by the kernel tests (plain Python, no kernel code).

``scene(...)`` writes the resolved-scene dict of ``kernels.api`` with one friction value for
all four coefficients unless they are given separately; ``const(B, H)`` gives the docs/physics.md
1.1 constants of a uniform rectangle.  g = 9.80665 m/s^2.
"""
import math
import os
from collections import namedtuple

G = 9.80665

# ``make test-nojit`` runs test_impact.py as plain Python: loops over many scenes shrink
NO_JIT = os.environ.get("NUMBA_DISABLE_JIT", "0") not in ("", "0")


def count(n, n_nojit):
    """n with the compiled kernel, n_nojit under NUMBA_DISABLE_JIT=1."""
    return n_nojit if NO_JIT else n

Const = namedtuple("Const", "b h r alpha beta i2 p eta")


def const(B, H):
    """Uniform rectangle B x H: b, h, r, alpha, beta = b/h, i^2 = r^2/3, p, Housner's eta."""
    b, h = 0.5 * B, 0.5 * H
    r = math.hypot(b, h)
    i2 = r * r / 3.0
    return Const(b, h, r, math.atan2(b, h), b / h, i2, math.sqrt(G * r / (i2 + r * r)),
                 1.0 - 2.0 * b * b / (i2 + r * r))


def sine(amplitude, frequency, **kw):
    return {"kind": "sine", "amplitude": amplitude, "frequency": frequency, **kw}


def pulse(amplitude, duration, **kw):
    return {"kind": "pulse", "shape": "rectangular", "amplitude": amplitude,
            "duration": duration, **kw}


def scene(B=0.1, H=0.3, mu=10.0, e_x=0.0, e_y=0.0, horizontal=None, vertical=None,
          initial=None, mu_s=None, mu_k=None, mu_edge_s=None, mu_edge_k=None, landing=None,
          **solver):
    """A resolved scene; ``mu`` sets the four friction coefficients not given explicitly;
    ``landing`` the landing law (default: the kernel's)."""
    contact = {"mu_s": mu if mu_s is None else mu_s, "mu_k": mu if mu_k is None else mu_k,
               "mu_edge_s": mu if mu_edge_s is None else mu_edge_s,
               "mu_edge_k": mu if mu_edge_k is None else mu_edge_k,
               "e_x": e_x, "e_y": e_y}
    if landing is not None:
        contact["landing"] = landing
    return {"body": {"B": B, "H": H}, "contact": contact,
            "excitation": {"horizontal": horizontal or {"kind": "none"},
                           "vertical": vertical or {"kind": "none"}},
            "initial": dict(initial or {}), "solver": solver}


def rocking_initial(B, H, theta, omega):
    """Initial values for pure rocking about the lower corner (no slip: x_dot = omega r_cy)."""
    c = const(B, H)
    s = -math.copysign(1.0, theta)
    r_cy = s * c.b * math.sin(theta) - c.h * math.cos(theta)
    return {"theta": theta, "omega": omega, "x_dot": omega * r_cy}


def omega_at_impact(B, H, theta0, omega0=0.0):
    """|omega| of pure rocking on reaching theta = 0 from (theta0, omega0), by energy:
    (i^2 + r^2) omega^2 / 2 = (i^2 + r^2) omega0^2 / 2 + g r (cos(alpha - |theta0|) - cos alpha).
    """
    c = const(B, H)
    drop = c.r * (math.cos(c.alpha - abs(theta0)) - math.cos(c.alpha))
    return math.sqrt(omega0 ** 2 + 2.0 * G * drop / (c.i2 + c.r * c.r))
