"""Named records the compiled code passes around (namedtuples of scalars and arrays).

A scene comes to the compiled code as one record of ``codes.SCENE_DTYPE`` (fields by name,
passed as one pointer); ``scene_of`` makes its ``Scene``: the ``Body`` (the corners'
distances from G and the inertia) and the ``Contact`` law (friction and restitution)
beside the row's floor, solver and initial records.  The record samples a floor component
may point into are one array shared by a chunk of scenes, passed beside the scene as
``rec``.  Arrays stay out of the scene, and the scene is a record, not a tuple of fifty
scalars: numba passes a tuple element by element, which in the step loop would cost as much
as the physics.  ``WORK_DTYPE`` holds every buffer of a scene in one record (one
allocation); a ``Step`` is one taken step, which the dense output, the event search and the
extremes read.  SI units, per unit mass; b1, b2 are the distances from G to the corners
along the base and h the height of G (docs/physics.md 1.1, docs/bodies.md).
"""
from collections import namedtuple

import numpy as np

from ._jit import DISABLED, jit
from .codes import LANDING_FLAT, N_CTX, N_MODES, N_STATE
from .extremes import N_EXTREMES
from .integrate import DENSE_DEGREE
from .tableaus import MAX_STAGES

Body = namedtuple("Body", "b1 b2 h i2")
Body.__doc__ = """Horizontal distances b1, b2 from G to the left and right corner, height h of G
above the base [m], squared radius of gyration about G i2 [m^2] (docs/bodies.md; symmetric:
b1 = b2 = B/2, h = H/2)."""

Contact = namedtuple("Contact", "mu_s mu_k mu_edge_s mu_edge_k e_x e_y landing",
                     defaults=(float(LANDING_FLAT),))
Contact.__doc__ = """Friction of the surface (mu_s, mu_k: face contact) and of the edge
(mu_edge_s, mu_edge_k: one corner), tangential and normal restitution e_x, e_y, and the law
of a landing after a translation jump (a ``codes.LANDING_*`` code, default flat).  Flat
sliding sees mu_k through ``motion.sliding_friction``."""

Scene = namedtuple("Scene", "body contact floor solver initial restraint")
Scene.__doc__ = """``Body`` and ``Contact`` (derived from the row), and the row's own records of
``codes.SCENE_DTYPE``: floor (x, y: ``codes.GROUND_DTYPE``), solver options, initial
values and the restraint, read by name."""

MAX_EVENTS = 5        # the most event functions of any mode (``events.n_events``)

VALUES_DTYPE = np.dtype([("old", "f8", (MAX_EVENTS,)), ("new", "f8", (MAX_EVENTS,)),
                         ("last", "f8", (MAX_EVENTS,))], align=True)
"""Event function values at the step's start (old), at a sample inside it (new) and at the
last sample without an event (last)."""

SCRATCH_DTYPE = np.dtype([("z", "f8", (N_STATE,)), ("q", "f8", (N_STATE,)),
                          ("g", "f8", (MAX_EVENTS,))], align=True)
"""Scratch for a state taken from the dense output: compact z, full q, and the event
values g computed on the way."""

WORK_DTYPE = np.dtype([("q", "f8", (N_STATE,)), ("z", "f8", (N_STATE,)),
                       ("z_new", "f8", (N_STATE,)), ("z_stage", "f8", (N_STATE,)),
                       ("q_end", "f8", (N_STATE,)), ("K", "f8", (MAX_STAGES + 1, N_STATE)),
                       ("D", "f8", (DENSE_DEGREE, N_STATE)), ("ctx", "f8", (N_CTX,)),
                       ("values", VALUES_DTYPE),
                       ("scratch", SCRATCH_DTYPE), ("extremes", "f8", (N_EXTREMES,)),
                       ("mode_time", "f8", (N_MODES,))], align=True)
"""The buffers of one scene, as one record: the full state q at the step's start and q_end
at its end, the mode's compact state z and z_new, stage scratch, the stages K, the
coefficients D of the dense output, the mode's contact ``ctx`` (``codes.CTX_*``), the event
values, dense-output scratch, the running extremes and the time spent in each mode."""

Step = namedtuple("Step", "mode n t dt z z_new K end D")
Step.__doc__ = """One taken step of ``mode`` from t to t + dt: the compact states z and z_new
(n entries), the stages K it was taken with, the row ``end`` of K that holds
f(t + dt, z_new) and the coefficients D of its dense output (``integrate.fit_dense``)."""



@jit(inline="always")          # it returns records, which have no Python form
def scene_of(row):
    """The ``Scene`` of a scene row (a record of ``codes.SCENE_DTYPE``)."""
    b = 0.5 * row.body.B
    c = row.contact
    contact = Contact(c.mu_s, c.mu_k, c.mu_edge_s, c.mu_edge_k, c.e_x, c.e_y, c.landing)
    return Scene(Body(b + row.body.x_g, b - row.body.x_g, row.body.y_g, row.body.i2), contact,
                 row.floor, row.solver, row.initial, row.restraint)


@jit(runtime=True)
def new_work():
    """The buffers of one scene, zeroed: a one-element array of ``WORK_DTYPE`` (keep it while
    its record, ``[0]``, is used)."""
    return np.zeros(1, WORK_DTYPE)


if DISABLED:
    def new_work():         # noqa: F811 -- plain Python reads fields by name through recarray
        """The buffers of one scene, zeroed (plain Python)."""
        return np.zeros(1, WORK_DTYPE).view(np.recarray)
