"""Free rocking and its Zeno accumulation (docs/physics.md anchor A4, section 3.1).

B = 0.1, H = 0.3 unless stated, released at rest from theta0, mu = 10, e_x = e_y = 0: pure
rocking with Housner's impacts.  The anchors are the printed A4 values; the same numbers are
recomputed by quadrature in ``naive`` (an independent check of the anchors themselves).
"""
import math

import numpy as np
import pytest

import naive
from kernels.api import run_scene
from scenes import const, scene

TIGHT = {"rtol": 1e-12, "atol": 1e-14}

# A4: theta0/alpha -> T_nonlinear = 4 x (time to the first impact) [s]
PERIODS = [(0.1, 0.275972), (0.2, 0.408973), (0.5, 0.774722), (0.8, 1.346058),
           (0.95, 2.164391), (0.99, 3.108617)]
# A4: impact times from theta0 = 0.5 alpha (first six to 5 decimals; t10, t20, t50 to 6)
FIRST_SIX = [0.19368, 0.47162, 0.68867, 0.86407, 1.00839, 1.12842]
LATER = [(10, 1.445128), (20, 1.717269), (50, 1.783179)]
# A4: accumulation (Zeno) time: B, H, theta0/alpha -> t_inf [s]
ZENO = [(0.1, 0.3, 0.5, 1.783685), (0.1, 0.3, 0.2, 1.146607), (0.1, 0.3, 0.8, 2.207335),
        (0.25, 1.0, 0.5, 5.616413)]


def _free(B, H, ratio, t_end, **solver):
    c = const(B, H)
    return run_scene(scene(B, H, initial={"theta": ratio * c.alpha}, t_end=t_end,
                           **{**TIGHT, **solver}))


@pytest.mark.parametrize("ratio, T", PERIODS)
def test_nonlinear_period(ratio, T):
    """4 x (time to the first impact) = T_nonlinear within 1e-6 s."""
    r = _free(0.1, 0.3, ratio, t_end=0.3 * T)
    assert len(r.impact_times) >= 1
    assert 4 * r.impact_times[0] == pytest.approx(T, abs=1e-6)
    ref = 4 * naive.free_rocking_impact_times(0.1, 0.3, ratio * const(0.1, 0.3).alpha, 1)[0]
    assert 4 * r.impact_times[0] == pytest.approx(ref, abs=1e-9)


def test_linear_period_is_a_formula_error():
    """Housner's linear period (4/p) arccosh(1/(1 - theta0/alpha)) reproduces T_linear of A4
    and is below the nonlinear period by 0.7 % ... 0.04 %: the anchors are consistent."""
    p = const(0.1, 0.3).p
    for (ratio, T_nl), T_lin in zip(PERIODS, [0.273972, 0.406518, 0.772371, 1.344468,
                                               2.163091, 3.107348]):
        assert 4 / p * math.acosh(1 / (1 - ratio)) == pytest.approx(T_lin, abs=1e-6)
        assert -0.0075 < T_lin / T_nl - 1 < -0.0003


def test_impact_times_from_half_alpha():
    """The A4 impact sequence from 0.5 alpha: first six, t10, t20, t50."""
    r = _free(0.1, 0.3, 0.5, t_end=3.0)
    t = np.array(r.impact_times)
    assert t.size > 50
    np.testing.assert_allclose(t[:6], FIRST_SIX, atol=5e-6)
    for n, tn in LATER:
        assert t[n - 1] == pytest.approx(tn, abs=1e-6), f"t{n}"
    ref = naive.free_rocking_impact_times(0.1, 0.3, 0.5 * const(0.1, 0.3).alpha, 50)
    for k in range(50):
        np.testing.assert_allclose(t[k], ref[k], rtol=0, atol=1e-9,
                                   err_msg=f"impact {k} at t = {ref[k]:.9f} s")


@pytest.mark.parametrize("B, H, ratio, t_inf", ZENO)
def test_zeno_accumulation(B, H, ratio, t_inf):
    """The kernel reaches rest at the accumulation time: t_rest in [t_inf - slack, t_inf + 1e-4].

    The Zeno closure (docs/physics.md 3.1) stops the impacts once the next half-cycle would last
    less than zeno_dt; the half-cycles left then shrink by eta each, so at most zeno_dt/(1 - eta)
    of the sequence is skipped: slack = 1.5 zeno_dt/(1 - eta) (+1e-6 for the rounding of the
    anchor).  Status ok, a finite number of steps and impacts.
    """
    c = const(B, H)
    zeno_dt = 1e-6
    assert naive.zeno_time(B, H, ratio * c.alpha) == pytest.approx(t_inf, abs=1.5e-6)
    r = _free(B, H, ratio, t_end=t_inf + 1.0, zeno_dt=zeno_dt)
    assert r.status == "ok"
    assert r.t_rest is not None
    slack = 1.5 * zeno_dt / (1 - c.eta) + 1e-6
    assert t_inf - slack <= r.t_rest <= t_inf + 1e-4, (r.t_rest, t_inf, slack)
    assert r.steps < 20_000 and len(r.impact_times) < 2_000
    assert r.mode_time["rest"] == pytest.approx(t_inf + 1.0 - r.t_rest, abs=1e-9)
    assert r.impact_times[-1] <= r.t_rest


def test_zeno_default_tolerances():
    """With the default solver options the closure still lands within the A4 window."""
    c = const(0.1, 0.3)
    r = run_scene(scene(initial={"theta": 0.5 * c.alpha}, t_end=3.0))
    assert r.status == "ok"
    assert 1.783685 - 1.5e-6 / (1 - c.eta) - 1e-6 <= r.t_rest <= 1.783685 + 1e-4
    assert r.steps < 2_000
