"""The fixed-step integrator (RK4, events interpolated in the step) against the adaptive one
and against ``naive`` where both should agree (docs/design.md 3: 'fixed' reproduces the paper's 1
ms step)."""
import math

import numpy as np
import pytest

import naive
from kernels.api import run_scene
from scenes import G, const, scene, sine

STEADY = dict(horizontal=sine(0.5 * G, 4.0), t_end=10.0)


@pytest.fixture(scope="module")
def adaptive():
    return run_scene(scene(**STEADY, rtol=1e-12, atol=1e-14))


@pytest.mark.parametrize("dt, tol", [(1e-4, 1e-6), (1e-3, 1e-4)])
def test_fixed_step_steady_rocking(adaptive, dt, tol):
    """Steady rocking (1.5 west at 4 Hz, 10 s): impact times of method 'fixed' within 1e-6 s
    (dt = 0.1 ms) and 1e-4 s (dt = 1 ms) of the adaptive run, and of the naive reference."""
    r = run_scene(scene(**STEADY, method="fixed", dt=dt))
    assert r.status == "ok"
    t, t_a = np.array(r.impact_times), np.array(adaptive.impact_times)
    assert t.size == t_a.size == 79
    for k in range(t.size):
        np.testing.assert_allclose(t[k], t_a[k], rtol=0, atol=tol,
                                   err_msg=f"impact {k} at t = {t_a[k]:.9f} s")
    ref = naive.housner_rocking(0.1, 0.3, a_x=lambda s: 0.5 * G * math.sin(8 * math.pi * s),
                                t_end=10.0)
    np.testing.assert_allclose(t, ref["impact_times"], rtol=0, atol=tol)
    assert r.steps == pytest.approx(10.0 / dt, rel=0.05)


@pytest.mark.parametrize("dt", [1e-4, 1e-3])
def test_fixed_step_free_rocking_to_rest(dt):
    """Free rocking from 0.5 alpha with the fixed step: the A4 impact times (5 decimals) and
    the Zeno closure to rest near 1.783685 s."""
    c = const(0.1, 0.3)
    r = run_scene(scene(initial={"theta": 0.5 * c.alpha}, t_end=3.0, method="fixed", dt=dt))
    assert r.status == "ok"
    np.testing.assert_allclose(r.impact_times[:6], [0.19368, 0.47162, 0.68867, 0.86407,
                                                    1.00839, 1.12842], atol=1e-5)
    assert r.t_rest == pytest.approx(1.783685, abs=1e-4)
