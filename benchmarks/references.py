"""Reference solutions that need no event-driven integrator, written from docs/physics.md alone.

They live in the tests' reference module, ``tests/naive.py`` (the tests never import
``benchmarks``); the benchmarks use them under this name.
"""
from tests.naive import free_rocking_impact_times, rigid_plastic_slide, zeno_time

__all__ = ["free_rocking_impact_times", "rigid_plastic_slide", "zeno_time"]
