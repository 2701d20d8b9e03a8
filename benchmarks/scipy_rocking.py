"""The rocking-only block written with ``scipy.integrate.solve_ivp``: what a user would write.

The program is the tests' reference, ``tests/naive.py`` (the tests never import
``benchmarks``); the work-precision benchmark runs it under this name.
"""
from tests.naive import G, body_constants, housner_rocking, record, sine, sweep

__all__ = ["G", "body_constants", "housner_rocking", "record", "sine", "sweep"]
