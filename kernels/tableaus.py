"""Explicit Runge-Kutta methods as data (scipy's names: C, A, B, E, P).

A method is a ``Tableau``; ``integrate.step`` runs any of them, so a new method is a new
tableau here, a name in ``codes.METHOD_NAMES`` and a branch in ``integrate``, not new code.
Stage s of a step is f(t + C[s] dt, z + dt sum_j A[s, j] K[j]); z_new = z + dt sum_j B[j]
K[j]; the stage row ``stages`` of K holds f(t + dt, z_new), which the next step reuses
(FSAL), the error estimate weighs with the last entry of E and the dense output needs.

* ``DOPRI5``: Dormand-Prince 5(4), the 4th-order dense output of scipy's RK45 (Dormand &
  Prince 1980; Hairer, Norsett & Wanner, Solving ODEs I, II.5).
* ``RK4``: the classical fourth-order method for the fixed step; no error estimate (E
  empty) and no interpolation matrix (P empty): its dense output is the cubic Hermite
  interpolant of the step's end values and slopes.
"""
from collections import namedtuple

import numpy as np

from ._jit import jit
from .codes import ADAPTIVE

Tableau = namedtuple("Tableau", "C A B E P order stages")
Tableau.__doc__ = """An explicit Runge-Kutta method.

C, A, B : stage times, coefficients and weights (``stages`` rows); E : error weights, one
per stage and one for f(t + dt, z_new) (empty: no estimate); P : dense-output polynomial
coefficients of x, x^2, ... per stage (empty: cubic Hermite); order : the order the step
size controller scales with."""

DP_C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0])
DP_A = np.array([
    [0.0, 0.0, 0.0, 0.0, 0.0],
    [1 / 5, 0.0, 0.0, 0.0, 0.0],
    [3 / 40, 9 / 40, 0.0, 0.0, 0.0],
    [44 / 45, -56 / 15, 32 / 9, 0.0, 0.0],
    [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0.0],
    [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656],
])
DP_B = np.array([35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84])
DP_E = np.array([-71 / 57600, 0.0, 71 / 16695, -71 / 1920, 17253 / 339200, -22 / 525, 1 / 40])
DP_P = np.array([
    [1.0, -8048581381 / 2820520608, 8663915743 / 2820520608, -12715105075 / 11282082432],
    [0.0, 0.0, 0.0, 0.0],
    [0.0, 131558114200 / 32700410799, -68118460800 / 10900136933, 87487479700 / 32700410799],
    [0.0, -1754552775 / 470086768, 14199869525 / 1410260304, -10690763975 / 1880347072],
    [0.0, 127303824393 / 49829197408, -318862633887 / 49829197408, 701980252875 / 199316789632],
    [0.0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844],
    [0.0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423],
])

RK4_C = np.array([0.0, 0.5, 0.5, 1.0])
RK4_A = np.array([
    [0.0, 0.0, 0.0],
    [0.5, 0.0, 0.0],
    [0.0, 0.5, 0.0],
    [0.0, 0.0, 1.0],
])
RK4_B = np.array([1 / 6, 1 / 3, 1 / 3, 1 / 6])
NO_E = np.zeros(0)
NO_P = np.zeros((0, 4))

MAX_STAGES = 6        # the most stages of any method here (K has MAX_STAGES + 1 rows)


DOPRI5 = Tableau(DP_C, DP_A, DP_B, DP_E, DP_P, 5, 6)
RK4 = Tableau(RK4_C, RK4_A, RK4_B, NO_E, NO_P, 4, 4)


@jit(runtime=True)           # its arrays go to Python when it is called from there
def tableau(method):
    """The ``Tableau`` of a method code (``codes.ADAPTIVE``, ``codes.FIXED``)."""
    if method == ADAPTIVE:
        return DOPRI5
    return RK4
