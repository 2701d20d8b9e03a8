"""Slow, obviously correct reference versions of single kernel modes (STUMPY's ``naive.py``).

Plain numpy/scipy, written from PHYSICS.md and independent of ``kernels``.  They live in
``benchmarks/`` (the work-precision benchmark runs the same programs against the kernel) and
are gathered here under the names the tests use:

* ``housner_rocking``: the rocking-only model (mode 3 of PHYSICS 1.2, no slip, no lift-off)
  integrated by ``scipy.integrate.solve_ivp`` (DOP853, rtol 1e-11) with event location, and
  Housner's impact omega+ = eta omega- (PHYSICS 2.1) at every return to theta = 0;
* ``free_rocking_impact_times`` and ``zeno_time``: free rocking from rest at theta0 by
  quadrature of the energy integral and the amplitude map of PHYSICS A4;
* ``rigid_plastic_slide``: flat stick-slip sliding (mode 2) under a_x(t), Newmark's
  rigid-plastic block (PHYSICS A6), integrated piecewise with solve_ivp.
"""
from benchmarks.references import free_rocking_impact_times, rigid_plastic_slide, zeno_time
from benchmarks.scipy_rocking import G, body_constants, housner_rocking

__all__ = ["G", "body_constants", "housner_rocking", "free_rocking_impact_times", "zeno_time",
           "rigid_plastic_slide"]
