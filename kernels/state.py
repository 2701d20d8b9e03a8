"""Named records the compiled code passes around (namedtuples of scalars and arrays).

A scene is read once from its parameter row (layout in ``codes``) into a ``Scene`` of
scalars: the ``Body`` (geometry and inertia), the ``Contact`` law (friction and
restitution), the ``Floor`` motion (``ground.Floor``), the ``Solver`` options and the
``Initial`` values.  The record samples a floor component may point into are one array
shared by a chunk of scenes, passed beside the scene as ``rec``.  Arrays stay out of the
scene on purpose: numba counts references to every array a compiled function receives or
takes out of a record, which in the step loop would cost as much as the physics.
``Work`` holds every buffer of a scene, allocated once; a ``Step`` is one taken step,
which the dense output, the event search and the extremes read.  SI units, per unit mass;
b and h are the half-breadth and half-height (PHYSICS.md 1.1).
"""
from collections import namedtuple

import numpy as np

from ._jit import jit
from .codes import (ADAPTIVE, N_CTX, N_MODES, N_STATE, P_ATOL, P_B, P_DT, P_DT_OUT, P_E_X,
                    P_E_Y, P_GX, P_GY, P_H, P_I2, P_LIFT0, P_MAX_EVENTS, P_MAX_STEP,
                    P_MAX_STEPS, P_METHOD, P_MU_EDGE_K, P_MU_EDGE_S, P_MU_K, P_MU_S, P_OMEGA0,
                    P_RTOL, P_T_END, P_THETA0, P_THETA_OVER, P_U0, P_V0, P_ZENO_DT)
from .extremes import N_EXTREMES
from .ground import G, Floor, ground_of
from .tableaus import MAX_STAGES
from .transitions import flat_sliding_friction

Body = namedtuple("Body", "b h i2")
Body.__doc__ = "Half-breadth b and half-height h [m], squared radius of gyration i2 [m^2]."

Contact = namedtuple("Contact", "mu_s mu_k mu_edge_s mu_edge_k e_x e_y")
Contact.__doc__ = """Friction of the surface (mu_s, mu_k: face contact) and of the edge
(mu_edge_s, mu_edge_k: one corner), tangential and normal restitution e_x, e_y."""

Initial = namedtuple("Initial", "theta omega u v lift")
Initial.__doc__ = "Initial rotation [rad], rates [rad/s, m/s] and lift of the lowest corner [m]."

Solver = namedtuple("Solver", "method adaptive rtol atol dt max_step t_end max_steps "
                              "max_events theta_over zeno_dt v_tol dt_out")
Solver.__doc__ = """Integration options: the method (``codes.METHOD_NAMES``; its ``Tableau`` is
``tableaus.tableau(method)``), whether its step size is controlled, tolerances, the fixed
step dt, budgets, the overturning angle, the Zeno time and the corner speed
v_tol = g zeno_dt / 2 that a bounce or slip closing within it has, the history interval."""

Scene = namedtuple("Scene", "body contact floor solver initial")

Values = namedtuple("Values", "old new last")
Values.__doc__ = """Event function values at the step's start (old), at a sample inside it (new)
and at the last sample without an event (last)."""

Scratch = namedtuple("Scratch", "z q g")
Scratch.__doc__ = """Scratch for a state taken from the dense output: compact z, full q, and
the event values g computed on the way."""

Work = namedtuple("Work", "q z z_new z_stage q_end K ctx values scratch extremes mode_time")
Work.__doc__ = """Buffers of one scene: the full state q at the step's start and q_end at
its end, the mode's compact state z and z_new, stage scratch, the stages K, the mode's
contact ``ctx`` (``codes.CTX_*``), the event ``Values``, dense-output ``Scratch``, the
running extremes and the time spent in each mode.  The driver unpacks it once: every
compiled function gets only the buffers it uses."""

Step = namedtuple("Step", "mode n t dt z z_new K P end")
Step.__doc__ = """One taken step of ``mode`` from t to t + dt: the compact states z and z_new
(n entries), the stages K it was taken with, the tableau's interpolation matrix P and the
row ``end`` of K that holds f(t + dt, z_new)."""

MAX_EVENTS = 5        # the most event functions of any mode (``events.n_events``)


@jit
def scene_of(par):
    """The ``Scene`` of a parameter row."""
    b = 0.5 * par[P_B]
    h = 0.5 * par[P_H]
    mu_edge_k = par[P_MU_EDGE_K]
    contact = Contact(par[P_MU_S], flat_sliding_friction(par[P_MU_K], mu_edge_k, b, h),
                      par[P_MU_EDGE_S], mu_edge_k, par[P_E_X], par[P_E_Y])
    method = int(par[P_METHOD])
    zeno_dt = par[P_ZENO_DT]
    solver = Solver(method, method == ADAPTIVE, par[P_RTOL], par[P_ATOL], par[P_DT],
                    par[P_MAX_STEP], par[P_T_END], par[P_MAX_STEPS], par[P_MAX_EVENTS],
                    par[P_THETA_OVER], zeno_dt,
                    0.5 * G * zeno_dt,   # a bounce this slow lands again within zeno_dt
                    par[P_DT_OUT])
    initial = Initial(par[P_THETA0], par[P_OMEGA0], par[P_U0], par[P_V0], par[P_LIFT0])
    return Scene(Body(b, h, par[P_I2]), contact, Floor(ground_of(par, P_GX), ground_of(par, P_GY)),
                 solver, initial)


@jit
def new_work():
    """Every buffer of one scene, zeroed."""
    return Work(np.zeros(N_STATE), np.zeros(N_STATE), np.zeros(N_STATE), np.zeros(N_STATE),
                np.zeros(N_STATE), np.zeros((MAX_STAGES + 1, N_STATE)), np.zeros(N_CTX),
                Values(np.zeros(MAX_EVENTS), np.zeros(MAX_EVENTS), np.zeros(MAX_EVENTS)),
                Scratch(np.zeros(N_STATE), np.zeros(N_STATE), np.zeros(MAX_EVENTS)),
                np.zeros(N_EXTREMES), np.zeros(N_MODES))
