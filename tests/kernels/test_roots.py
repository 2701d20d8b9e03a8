"""The root finders of ``kernels.roots`` against known roots and maxima: 2^(1/3), the Dottie
number 0.7390851332151607 (cos x = x), a root exactly at a bracket end or hit exactly by the
first iterate, a step at a known x0 (bisection must end on the first double above it), and
the vertex of a parabola.  The factories compile one solver per function, so they are
called here once, at import; the test functions have names unique to this file because
solvers are cached by the name ``<algorithm>_<function>``.
"""
import math

import numpy as np
import pytest

from kernels import roots
from kernels._jit import jit

EPS = 2.2e-16
CBRT2 = 2.0 ** (1.0 / 3.0)
DOTTIE = 0.7390851332151607


@jit
def _unitroots_cube_minus(x, args):
    """args[0] - x^3: positive left of the root args[0]^(1/3)."""
    return args[0] - x * x * x


@jit
def _unitroots_cos_minus_x(x, args):
    """cos(x) - x (args unused): positive left of the Dottie number."""
    return math.cos(x) - x


@jit
def _unitroots_x_minus_cos(x, args):
    """x - cos(x): negative left of the Dottie number."""
    return x - math.cos(x)


@jit
def _unitroots_line(x, args):
    """args[0] (x - args[1]): a line through (args[1], 0)."""
    return args[0] * (x - args[1])


@jit
def _unitroots_step(x, args):
    """1 for x > args[0], -1 otherwise: f > 0 starts right after x0 = args[0]."""
    return 1.0 if x > args[0] else -1.0


@jit
def _unitroots_parabola(x, args):
    """args[2] - (x - args[0])^2 * args[1]: vertex (args[0], args[2])."""
    d = x - args[0]
    return args[2] - args[1] * d * d


brent_cube = roots.brent(_unitroots_cube_minus)
brent_cos = roots.brent(_unitroots_cos_minus_x)
brent_line = roots.brent(_unitroots_line)
falsi_cos = roots.regula_falsi(_unitroots_cos_minus_x)
falsi_x_cos = roots.regula_falsi(_unitroots_x_minus_cos)
falsi_line = roots.regula_falsi(_unitroots_line)
bisect_step = roots.bisect(_unitroots_step)
bisect_x_cos = roots.bisect(_unitroots_x_minus_cos)
peak_parabola = roots.peak_above_zero(_unitroots_parabola)


def test_solver_names():
    """Each solver is named <algorithm>_<function without leading underscores>."""
    assert brent_cube.__name__ == "brent_unitroots_cube_minus"
    assert peak_parabola.__name__ == "peak_above_zero_unitroots_parabola"


# --- brent ----------------------------------------------------------------------------------

@pytest.mark.parametrize("xtol", [1e-6, 1e-12, 0.0])
def test_brent_cube_root(xtol):
    """2 - x^3 on [0, 2] (f(0) = 2 > 0 >= f(2) = -6): within xtol + 4 EPS |x| of 2^(1/3)."""
    args = (2.0,)
    x = brent_cube(args, 0.0, 2.0, 2.0, -6.0, xtol)
    assert abs(x - CBRT2) <= xtol + 4 * EPS * CBRT2
    assert 0.0 <= x <= 2.0


@pytest.mark.parametrize("c", [0.001, 27.0, 1e6])
def test_brent_cube_root_scales(c):
    """c - x^3 on [0, c + 1] for c = 0.001, 27, 1e6: within 1e-14 + 4 EPS x of c^(1/3)."""
    args = (c,)
    b = c + 1.0
    x = brent_cube(args, 0.0, b, c, c - b ** 3, 1e-14)
    want = c ** (1.0 / 3.0)
    assert abs(x - want) <= 1e-14 + 4 * EPS * want + 2 * EPS * want


def test_brent_dottie():
    """cos x - x on [0, 1]: within 1e-13 of 0.7390851332151607."""
    x = brent_cos((0.0,), 0.0, 1.0, 1.0, math.cos(1.0) - 1.0, 1e-13)
    assert abs(x - DOTTIE) <= 1e-13 + 4 * EPS * DOTTIE


def test_brent_root_at_bracket_end():
    """fb = 0 (the root is the right end): returns xb itself."""
    args = (-1.0, 0.75)     # -(x - 0.75): f(0) = 0.75 > 0, f(0.75) = 0
    assert brent_line(args, 0.0, 0.75, 0.75, 0.0, 1e-12) == 0.75


def test_brent_linear_function():
    """-(x - 0.3) on [0, 1]: the secant step hits 0.3 to round-off (1e-15)."""
    args = (-1.0, 0.3)
    x = brent_line(args, 0.0, 1.0, 0.3, -0.7, 1e-12)
    assert abs(x - 0.3) <= 1e-12 + 4 * EPS


# --- regula falsi ---------------------------------------------------------------------------

@pytest.mark.parametrize("xtol", [1e-6, 1e-12])
def test_regula_falsi_dottie(xtol):
    """cos x - x on [0, 1] (fa > 0 > fb): within xtol of 0.7390851332151607."""
    x = falsi_cos((0.0,), 0.0, 1.0, 1.0, math.cos(1.0) - 1.0, xtol)
    assert abs(x - DOTTIE) <= xtol
    assert 0.0 <= x <= 1.0


def test_regula_falsi_other_sign():
    """x - cos x on [0, 1] (fa < 0 < fb): within 1e-12 of the same root."""
    x = falsi_x_cos((0.0,), 0.0, 1.0, -1.0, 1.0 - math.cos(1.0), 1e-12)
    assert abs(x - DOTTIE) <= 1e-12


def test_regula_falsi_exact_first_iterate():
    """x - 0.5 on [0, 1]: the first secant point is 0.5 exactly, where f = 0: returned."""
    assert falsi_line((1.0, 0.5), 0.0, 1.0, -0.5, 0.5, 1e-12) == 0.5


def test_regula_falsi_lopsided_bracket():
    """x - cos x on [-3, 10] (a far, steep right end that plain regula falsi would keep):
    Illinois' halving still reaches the root within 1e-10."""
    x = falsi_x_cos((0.0,), -3.0, 10.0, -3.0 - math.cos(-3.0), 10.0 - math.cos(10.0), 1e-10)
    assert abs(x - DOTTIE) <= 1e-10


# --- bisection ------------------------------------------------------------------------------

@pytest.mark.parametrize("x0, xa, xb", [(0.3, 0.0, 1.0), (5.0, 0.0, 10.0), (-2.5, -4.0, 0.0)])
@pytest.mark.parametrize("tol", [1e-6, 1e-13])
def test_bisect_step(x0, xa, xb, tol):
    """Step at x0 (f > 0 for x > x0): the result lies in (x0, x0 + tol max(1, |x|)]."""
    x = bisect_step((x0,), xa, xb, tol)
    assert x0 < x <= x0 + tol * max(1.0, abs(x))


@pytest.mark.parametrize("x0", [0.3, 5.0, -2.5, 1e-300])
def test_bisect_to_adjacent_doubles(x0):
    """xtol = 0: bisection runs until no double lies between the ends and returns the first
    double above x0, np.nextafter(x0, inf)."""
    x = bisect_step((x0,), x0 - 1.0, x0 + 1.0, 0.0)
    assert x == np.nextafter(x0, np.inf)


def test_bisect_smooth_root():
    """x - cos x on [0, 1]: a point with f > 0 within 1e-13 above the Dottie number."""
    x = bisect_x_cos((0.0,), 0.0, 1.0, 1e-13)
    assert x - math.cos(x) > 0.0
    assert DOTTIE - 1e-16 <= x <= DOTTIE + 1e-13 + 1e-16


def test_bisect_interval_already_short():
    """[xa, xb] shorter than the tolerance: xb is returned unevaluated."""
    assert bisect_step((0.5,), 0.4, 0.6, 0.5) == 0.6


# --- peak above zero ------------------------------------------------------------------------

@pytest.mark.parametrize("c, xa, xb", [(0.3, 0.0, 1.0), (7.25, 2.0, 9.0), (-1.0, -2.0, 0.5)])
def test_peak_below_zero(c, xa, xb):
    """-0.1 - 3 (x - c)^2 (below zero everywhere): the returned point is the maximiser c to
    1e-5 (golden section on a flat maximum), the value returned is f there exactly and is
    -0.1 to 1e-9."""
    args = (c, 3.0, -0.1)
    x, fx = peak_parabola(args, xa, xb, 1e-10)
    assert abs(x - c) <= 1e-5
    assert fx == _unitroots_parabola(x, args)
    assert fx == pytest.approx(-0.1, abs=1e-9)


def test_peak_at_interval_end():
    """Vertex outside [0, 1] at 2 (f increasing on the interval): the maximiser is the right
    end 1 (to 1e-5), value -0.1 - 3 (1 - 2)^2 = -3.1 to 1e-4."""
    args = (2.0, 3.0, -0.1)
    x, fx = peak_parabola(args, 0.0, 1.0, 1e-10)
    assert abs(x - 1.0) <= 1e-5
    assert fx == pytest.approx(-3.1, abs=1e-4)


def test_peak_stops_at_first_positive():
    """Vertex (0.4, 0.05) on [0, 1]: the first probe x1 = 1 - 1/phi = 0.381966... already has
    f > 0, so it is returned at once (not the vertex)."""
    args = (0.4, 3.0, 0.05)
    x1 = 1.0 - roots.INV_PHI
    assert _unitroots_parabola(x1, args) > 0.0
    x, fx = peak_parabola(args, 0.0, 1.0, 1e-10)
    assert x == x1
    assert fx == _unitroots_parabola(x1, args)


def test_peak_finds_narrow_positive_region():
    """Vertex (0.7777, 1e-8) with curvature 1e4: f > 0 only within 1e-6 of the vertex; the
    search returns a point there with its value > 0."""
    c = 0.7777
    args = (c, 1e4, 1e-8)
    x, fx = peak_parabola(args, 0.0, 1.0, 1e-12)
    assert fx > 0.0
    assert fx == _unitroots_parabola(x, args)
    assert abs(x - c) < 1e-6
