"""The Runge-Kutta tableaus of ``kernels.tableaus`` against the exact order conditions
(Butcher trees up to order 5, Hairer, Norsett & Wanner I, II.2), the identities of an
embedded pair and of a dense output, and the observed convergence order of a pure-numpy RK
loop (written here) on y' = y and on the linear oscillator, whose exact solutions are known.
``integrate.dense`` is fed the stages of that loop and checked against the exact solution.
"""
import math
from fractions import Fraction

import numpy as np
import pytest

from kernels import codes, tableaus
from kernels.integrate import DENSE_DEGREE, dense, fit_dense
from kernels.state import Step

METHODS = {codes.ADAPTIVE: "adaptive", codes.FIXED: "fixed"}


def _tab(method):
    return tableaus.tableau(method)


def _square_A(tab):
    """A as a stages x stages matrix (the stored one has stages - 1 columns)."""
    s = tab.stages
    A = np.zeros((s, s))
    A[:, :tab.A.shape[1]] = tab.A
    return A


def _extended(tab):
    """(A, C) of the method with the FSAL stage f(t + dt, z_new) appended as stage
    ``stages``: its row of A is B and its time is 1 (the 7-stage form of DOPRI5)."""
    s = tab.stages
    A = np.zeros((s + 1, s + 1))
    A[:s, :s] = _square_A(tab)
    A[s, :s] = tab.B
    return A, np.append(tab.C, 1.0)


def _order_conditions(b, A, c):
    """(residual, exact, order) of the 17 Butcher conditions up to order 5."""
    Ac = A @ c
    Ac2 = A @ c ** 2
    AAc = A @ Ac
    return [
        (b.sum(), 1.0, 1),
        (b @ c, 1 / 2, 2),
        (b @ c ** 2, 1 / 3, 3), (b @ Ac, 1 / 6, 3),
        (b @ c ** 3, 1 / 4, 4), (b @ (c * Ac), 1 / 8, 4), (b @ Ac2, 1 / 12, 4),
        (b @ AAc, 1 / 24, 4),
        (b @ c ** 4, 1 / 5, 5), (b @ (c ** 2 * Ac), 1 / 10, 5), (b @ (c * Ac2), 1 / 15, 5),
        (b @ (c * AAc), 1 / 30, 5), (b @ Ac ** 2, 1 / 20, 5), (b @ (A @ c ** 3), 1 / 20, 5),
        (b @ (A @ (c * Ac)), 1 / 40, 5), (b @ (A @ Ac2), 1 / 60, 5),
        (b @ (A @ AAc), 1 / 120, 5),
    ]


# --- the data -------------------------------------------------------------------------------

def test_tableau_returns_the_module_arrays():
    """tableau(ADAPTIVE) is DOPRI5 (6 stages, order 5) and tableau(FIXED) RK4 (4 stages,
    order 4, no E, no P), entry for entry the module's arrays."""
    dp = _tab(codes.ADAPTIVE)
    assert (dp.order, dp.stages) == (5, 6)
    for got, want in ((dp.C, tableaus.DP_C), (dp.A, tableaus.DP_A), (dp.B, tableaus.DP_B),
                      (dp.E, tableaus.DP_E), (dp.P, tableaus.DP_P)):
        np.testing.assert_array_equal(got, want)
    rk = _tab(codes.FIXED)
    assert (rk.order, rk.stages) == (4, 4)
    for got, want in ((rk.C, tableaus.RK4_C), (rk.A, tableaus.RK4_A), (rk.B, tableaus.RK4_B)):
        np.testing.assert_array_equal(got, want)
    assert rk.E.size == 0 and rk.P.shape[0] == 0
    assert tableaus.MAX_STAGES >= max(dp.stages, rk.stages)


@pytest.mark.parametrize("method", METHODS, ids=METHODS.get)
def test_shapes(method):
    """C, B and A have ``stages`` rows; A has stages - 1 columns; E has one weight per stage
    plus the FSAL one and P one row per stage plus the FSAL one (or both are empty)."""
    tab = _tab(method)
    s = tab.stages
    assert tab.C.shape == (s,) and tab.B.shape == (s,) and tab.A.shape == (s, s - 1)
    assert tab.E.size in (0, s + 1)
    assert tab.P.shape[0] in (0, s + 1) and tab.P.shape[1] == 4


@pytest.mark.parametrize("method", METHODS, ids=METHODS.get)
def test_consistency(method):
    """sum B = 1, the row sums of A equal C (to 1e-15), C[0] = 0 and A is strictly lower
    triangular (an explicit method)."""
    tab = _tab(method)
    assert tab.B.sum() == pytest.approx(1.0, abs=1e-15)
    np.testing.assert_allclose(tab.A.sum(axis=1), tab.C, rtol=0, atol=1e-15)
    assert tab.C[0] == 0.0
    A = _square_A(tab)
    assert np.all(np.triu(A) == 0.0)


@pytest.mark.parametrize("method", METHODS, ids=METHODS.get)
def test_order_conditions(method):
    """The Butcher order conditions up to the method's order hold to 1e-14 (1, 1/2, 1/3,
    1/6, 1/4, 1/8, 1/12, 1/24 and for DOPRI5 the nine of order 5: 1/5, 1/10, 1/15, 1/30,
    1/20, 1/20, 1/40, 1/60, 1/120)."""
    tab = _tab(method)
    rows = _order_conditions(tab.B, _square_A(tab), tab.C)
    checked = 0
    for value, exact, order in rows:
        if order <= tab.order:
            assert value == pytest.approx(exact, rel=0, abs=1e-14), (order, exact)
            checked += 1
    assert checked == {4: 8, 5: 17}[tab.order]


def test_rk4_is_not_fifth_order():
    """RK4 fails sum b c^4 = 1/5 (it gives 5/24): the order-5 check can tell."""
    tab = _tab(codes.FIXED)
    assert tab.B @ tab.C ** 4 == pytest.approx(5 / 24, abs=1e-15)


def test_dopri_coefficients_are_exact_fractions():
    """The DOPRI5 floats are the nearest doubles to Dormand & Prince's rationals: the order
    conditions evaluated in exact rational arithmetic on the literature's fractions hold
    exactly, and the module's arrays agree with them to 1 ulp."""
    F = Fraction
    c = [F(0), F(1, 5), F(3, 10), F(4, 5), F(8, 9), F(1)]
    a = [[], [F(1, 5)], [F(3, 40), F(9, 40)], [F(44, 45), F(-56, 15), F(32, 9)],
         [F(19372, 6561), F(-25360, 2187), F(64448, 6561), F(-212, 729)],
         [F(9017, 3168), F(-355, 33), F(46732, 5247), F(49, 176), F(-5103, 18656)]]
    b = [F(35, 384), F(0), F(500, 1113), F(125, 192), F(-2187, 6784), F(11, 84)]
    for i in range(6):
        assert sum(a[i], F(0)) == c[i]
        assert tableaus.DP_C[i] == float(c[i])
        assert tableaus.DP_B[i] == float(b[i])
        for j in range(i):
            assert tableaus.DP_A[i, j] == float(a[i][j])
    Ac = [sum((a[i][j] * c[j] for j in range(i)), F(0)) for i in range(6)]
    assert sum(b[i] * c[i] ** 4 for i in range(6)) == F(1, 5)
    assert sum(b[i] * sum((a[i][j] * Ac[j] for j in range(i)), F(0)) for i in range(6)) \
        == F(1, 24)


# --- embedded estimate (DOPRI5) -------------------------------------------------------------

def test_error_weights_sum_to_zero():
    """sum E = 0: the error estimate of a problem with a constant slope (all stages equal)
    vanishes, and E[1] = 0 like B[1] (the second stage is used by neither)."""
    E = _tab(codes.ADAPTIVE).E
    assert E.sum() == pytest.approx(0.0, abs=1e-16)
    assert E[1] == 0.0


def test_embedded_weights_are_fourth_order_not_fifth():
    """B_hat = B_ext + E (scipy's sign: E = B_hat - B_ext, B_ext = B with 0 for the FSAL
    stage) are Dormand & Prince's 4th-order weights (5179/57600, 0, 7571/16695, 393/640,
    -92097/339200, 187/2100, 1/40): they meet the 8 conditions of order <= 4 on the 7-stage
    form of the method and fail sum b c^4 = 1/5.  (The conditions are linear in b and E
    annihilates those of order <= 4, so B_ext - E meets them too: only the literature's
    fractions fix the sign.)"""
    tab = _tab(codes.ADAPTIVE)
    A7, C7 = _extended(tab)
    b_hat = np.append(tab.B, 0.0) + tab.E
    np.testing.assert_allclose(
        b_hat, [5179 / 57600, 0.0, 7571 / 16695, 393 / 640, -92097 / 339200, 187 / 2100,
                1 / 40], rtol=0, atol=1e-16)
    for value, exact, order in _order_conditions(b_hat, A7, C7):
        if order <= 4:
            assert value == pytest.approx(exact, rel=0, abs=1e-14), (order, exact)
    assert abs(b_hat @ C7 ** 4 - 1 / 5) > 1e-4


# --- dense output (DOPRI5) ------------------------------------------------------------------

def test_dense_output_end_values_and_slopes():
    """The interpolant z + dt sum_j K_j (P_j0 x + P_j1 x^2 + P_j2 x^3 + P_j3 x^4) is 0 at
    x = 0, equals the step's weights B_ext at x = 1 (row sums of P), has slope K_0 at x = 0
    (P[:, 0] = e_0) and slope K_6 = f(t + dt, z_new) at x = 1 (sum_k (k+1) P[:, k] = e_6):
    a C^1 interpolant, to 1e-14."""
    tab = _tab(codes.ADAPTIVE)
    P = tab.P
    B_ext = np.append(tab.B, 0.0)
    powers = lambda x: np.array([x, x ** 2, x ** 3, x ** 4])  # noqa: E731
    np.testing.assert_array_equal(P @ powers(0.0), np.zeros(7))
    np.testing.assert_allclose(P @ powers(1.0), B_ext, rtol=0, atol=1e-14)
    np.testing.assert_allclose(P.sum(axis=1), B_ext, rtol=0, atol=1e-14)
    np.testing.assert_array_equal(P[:, 0], np.eye(7)[0])
    np.testing.assert_allclose(P @ np.array([1.0, 2.0, 3.0, 4.0]), np.eye(7)[6],
                               rtol=0, atol=1e-13)


# --- convergence of a pure-numpy RK loop with the kernel's arrays ----------------------------

def _rk_step(tab, f, t, z, dt):
    """One step of the tableau (test's own loop): (z_new, K) with K[stages] = f(t+dt, z_new)."""
    s = tab.stages
    A = _square_A(tab)
    K = np.zeros((s + 1, z.size))
    K[0] = f(t, z)
    for i in range(1, s):
        K[i] = f(t + tab.C[i] * dt, z + dt * (A[i, :i] @ K[:i]))
    z_new = z + dt * (tab.B @ K[:s])
    K[s] = f(t + dt, z_new)
    return z_new, K


def _integrate(tab, f, z0, t_end, n, weights=None):
    """z(t_end) after n steps; with ``weights`` (stages + 1 of them, on K including the FSAL
    stage) the solution is propagated with those instead of B (the embedded method)."""
    z = np.array(z0, dtype=float)
    dt = t_end / n
    for k in range(n):
        z_new, K = _rk_step(tab, f, k * dt, z, dt)
        z = z_new if weights is None else z + dt * (weights @ K)
    return z


def _growth(t, z):
    return z.copy()


def _oscillator(t, z):
    return np.array([z[1], -z[0]])


def _observed_orders(errors):
    errors = np.asarray(errors)
    return np.log2(errors[:-1] / errors[1:])


@pytest.mark.parametrize("method", METHODS, ids=METHODS.get)
def test_convergence_order_exponential(method):
    """y' = y on [0, 1] from y = 1 (exact e) with 8, 16, 32 steps: the error shrinks by
    2^order per halving of the step (observed order within 0.3 of 5 for DOPRI5, 4 for RK4)."""
    tab = _tab(method)
    errs = [abs(_integrate(tab, _growth, [1.0], 1.0, n)[0] - math.e) for n in (8, 16, 32)]
    assert np.all(np.abs(_observed_orders(errs) - tab.order) < 0.3), errs


@pytest.mark.parametrize("method", METHODS, ids=METHODS.get)
def test_convergence_order_oscillator(method):
    """x'' = -x over one period 2 pi from (1, 0) (exact (cos t, -sin t)) with 16, 32, 64
    steps: observed order within 0.3 of the method's order."""
    tab = _tab(method)
    T = 2.0 * math.pi
    exact = np.array([math.cos(T), -math.sin(T)])
    errs = [np.linalg.norm(_integrate(tab, _oscillator, [1.0, 0.0], T, n) - exact)
            for n in (16, 32, 64)]
    assert np.all(np.abs(_observed_orders(errs) - tab.order) < 0.3), errs


def test_embedded_method_is_fourth_order():
    """Propagating with the embedded weights B_ext + E on x'' = -x over 2 pi (16, 32, 64
    steps): observed order within 0.3 of 4."""
    tab = _tab(codes.ADAPTIVE)
    b_hat = np.append(tab.B, 0.0) + tab.E
    T = 2.0 * math.pi
    exact = np.array([math.cos(T), -math.sin(T)])
    errs = [np.linalg.norm(_integrate(tab, _oscillator, [1.0, 0.0], T, n, b_hat) - exact)
            for n in (16, 32, 64)]
    assert np.all(np.abs(_observed_orders(errs) - 4) < 0.3), errs


def test_error_estimate_is_fifth_power_of_step():
    """The error estimate dt sum E_j K_j of one step of y' = y from y = 1 is the difference
    of a 5th- and a 4th-order step, O(dt^5): halving dt divides it by 2^5 (observed exponent
    within 0.3 of 5); for the constant slope y' = 1 it vanishes (below 1e-17)."""
    tab = _tab(codes.ADAPTIVE)
    ests = []
    for dt in (0.1, 0.05, 0.025):
        _, K = _rk_step(tab, _growth, 0.0, np.array([1.0]), dt)
        ests.append(abs(dt * (tab.E @ K)[0]))
    assert np.all(np.abs(_observed_orders(ests) - 5) < 0.3), ests
    _, K = _rk_step(tab, lambda t, z: np.ones_like(z), 0.0, np.array([1.0]), 0.1)
    assert abs(0.1 * (tab.E @ K)[0]) < 1e-17


# --- the kernel's dense output (integrate.dense) ---------------------------------------------

def _dense_at(method, z, z_new, K, dt, x):
    """integrate.dense on a ``Step`` built from one step of the test's loop."""
    n = z.size
    step = Step(0, n, 0.0, dt, z, z_new, K, _tab(method).stages, np.zeros((DENSE_DEGREE, n)))
    fit_dense(method, step)
    out = np.zeros(n)
    dense(step, x, out)
    return out


@pytest.mark.parametrize("method", METHODS, ids=METHODS.get)
def test_dense_end_points(method):
    """integrate.dense at x = 0 returns z and at x = 1 returns z_new (to 1e-15): the
    interpolant joins the step's end values (DOPRI5's P and RK4's cubic Hermite)."""
    tab = _tab(method)
    z = np.array([1.0, 0.0])
    z_new, K = _rk_step(tab, _oscillator, 0.0, z, 0.1)
    np.testing.assert_allclose(_dense_at(method, z, z_new, K, 0.1, 0.0), z, rtol=0, atol=1e-15)
    np.testing.assert_allclose(_dense_at(method, z, z_new, K, 0.1, 1.0), z_new, rtol=0,
                               atol=1e-15)


@pytest.mark.parametrize("method, order", [(codes.ADAPTIVE, 5), (codes.FIXED, 4)],
                         ids=["adaptive", "fixed"])
def test_dense_local_order(method, order):
    """x'' = -x, one step from (1, 0) with dt = 0.2, 0.1, 0.05: the error of integrate.dense
    at x = 0.5 against (cos, -sin)(dt/2) shrinks like dt^order (local error of a 4th-order
    interpolant is O(dt^5), of the cubic Hermite O(dt^4)): observed >= order - 0.5; at
    dt = 0.1 the DOPRI5 interpolant is within 1e-6 (the cubic Hermite within 1e-5)."""
    tab = _tab(method)
    errs = []
    for dt in (0.2, 0.1, 0.05):
        z = np.array([1.0, 0.0])
        z_new, K = _rk_step(tab, _oscillator, 0.0, z, dt)
        got = _dense_at(method, z, z_new, K, dt, 0.5)
        errs.append(np.linalg.norm(got - [math.cos(dt / 2), -math.sin(dt / 2)]))
    assert np.all(_observed_orders(errs) >= order - 0.5), errs
    assert errs[1] < (1e-6 if method == codes.ADAPTIVE else 1e-5)
