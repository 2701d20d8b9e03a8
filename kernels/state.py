"""Named records the compiled code passes around (namedtuples of scalars and arrays).

A scene comes to the compiled code as its parameter row viewed as a record of
``codes.SCENE_DTYPE`` (fields by name, passed as one pointer).  ``scene_of`` makes the
``Scene``: the ``Body`` (half sizes and inertia) and the ``Contact`` law (friction and
restitution, with the surface's kinetic friction as flat sliding sees it) beside the row's
floor, solver and initial records.  The record samples a floor component may point into
are one array shared by a chunk of scenes, passed beside the scene as ``rec``.  Arrays
stay out of the scene on purpose: numba counts references to every array a compiled
function receives or takes out of a record, and passes a record of many scalars as many
arguments; in the step loop either would cost as much as the physics.
``Work`` holds every buffer of a scene, allocated once; a ``Step`` is one taken step,
which the dense output, the event search and the extremes read.  SI units, per unit mass;
b and h are the half-breadth and half-height (PHYSICS.md 1.1).
"""
from collections import namedtuple

import numpy as np

from ._jit import jit
from .codes import N_CTX, N_MODES, N_STATE
from .extremes import N_EXTREMES
from .tableaus import MAX_STAGES
from .transitions import flat_sliding_friction

Body = namedtuple("Body", "b h i2")
Body.__doc__ = "Half-breadth b and half-height h [m], squared radius of gyration i2 [m^2]."

Contact = namedtuple("Contact", "mu_s mu_k mu_edge_s mu_edge_k e_x e_y")
Contact.__doc__ = """Friction of the surface (mu_s, mu_k: face contact) and of the edge
(mu_edge_s, mu_edge_k: one corner), tangential and normal restitution e_x, e_y."""

Scene = namedtuple("Scene", "body contact floor solver initial")
Scene.__doc__ = """``Body`` and ``Contact`` (derived from the row), and the row's own records of
``codes.SCENE_DTYPE``: floor (x, y: ``codes.GROUND_DTYPE``), solver options and initial
values, read by name."""

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


@jit(inline="always")          # it returns records, which have no Python form
def scene_of(row):
    """The ``Scene`` of a scene row (a record of ``codes.SCENE_DTYPE``)."""
    b = 0.5 * row.body.B
    h = 0.5 * row.body.H
    c = row.contact
    contact = Contact(c.mu_s, flat_sliding_friction(c.mu_k, c.mu_edge_k, b, h), c.mu_edge_s,
                      c.mu_edge_k, c.e_x, c.e_y)
    return Scene(Body(b, h, row.body.i2), contact, row.floor, row.solver, row.initial)


@jit
def new_work():
    """Every buffer of one scene, zeroed."""
    return Work(np.zeros(N_STATE), np.zeros(N_STATE), np.zeros(N_STATE), np.zeros(N_STATE),
                np.zeros(N_STATE), np.zeros((MAX_STAGES + 1, N_STATE)), np.zeros(N_CTX),
                Values(np.zeros(MAX_EVENTS), np.zeros(MAX_EVENTS), np.zeros(MAX_EVENTS)),
                Scratch(np.zeros(N_STATE), np.zeros(N_STATE), np.zeros(MAX_EVENTS)),
                np.zeros(N_EXTREMES), np.zeros(N_MODES))
