"""Overturning (docs/physics.md 3.4): the exact escape criterion of free rocking and the
declaration at |theta| >= theta_overturn."""
import math

import pytest

from kernels.api import run_scene
from scenes import G, const, rocking_initial, scene, sine


@pytest.mark.parametrize("factor", [0.99, 1.01])
def test_release_beyond_alpha(factor):
    """Released at rest at theta0 = factor alpha: beyond alpha it falls over (to the side of
    theta0), inside alpha it rocks back."""
    c = const(0.1, 0.3)
    r = run_scene(scene(initial={"theta": factor * c.alpha}, t_end=10.0))
    if factor > 1:
        assert r.status == "overturned" and r.overturn_direction == 1
    else:
        assert r.status == "ok" and not r.overturned and len(r.impact_times) > 10


@pytest.mark.parametrize("sign", [1.0, -1.0])
@pytest.mark.parametrize("factor", [0.999, 1.001])
def test_escape_velocity(factor, sign):
    """Pure rocking launched from theta = 0 with omega0: it escapes iff
    (i^2 + r^2) omega0^2 / 2 > g r (1 - cos alpha) (energy over the saddle theta = alpha)."""
    c = const(0.1, 0.3)
    w_esc = math.sqrt(2 * G * c.r * (1 - math.cos(c.alpha)) / (c.i2 + c.r ** 2))
    omega0 = sign * factor * w_esc
    initial = {"theta": 0.0, "omega": omega0,
               "x_dot": omega0 * -c.h}           # no slip at the pivot: u = omega r_cy
    r = run_scene(scene(initial=initial, t_end=10.0))
    assert r.overturned == (factor > 1)
    if factor > 1:
        assert r.overturn_direction == int(sign)
    assert rocking_initial(0.1, 0.3, sign * 1e-300, omega0)["x_dot"] == pytest.approx(
        initial["x_dot"], rel=1e-12)


@pytest.mark.parametrize("theta_over", [0.5, 1.0, 1.2])
def test_overturn_time_is_crossing_time(theta_over):
    """Released at rest at 1.01 alpha, mu = 10: pure rotation about the left corner until
    |theta| = theta_overturn, reached at t = int d(theta)/omega(theta) with
    omega^2 = 2 g r (cos(alpha - theta0) - cos(alpha - theta))/(i^2 + r^2) (energy)."""
    from scipy.integrate import quad
    c = const(0.1, 0.3)
    theta0 = 1.01 * c.alpha
    r = run_scene(scene(initial={"theta": theta0}, t_end=10.0, theta_overturn=theta_over,
                        rtol=1e-12, atol=1e-14))
    assert r.overturned and r.overturn_direction == 1
    assert r.mode_time["rotation"] == r.t_final        # the pivot held all the way
    k = 2 * G * c.r / (c.i2 + c.r ** 2)
    span = theta_over - theta0

    def integrand(u):
        # theta = theta0 + span u^2 removes the 1/sqrt end singularity, and
        # cos(alpha - theta0) - cos(alpha - theta) = -2 sin(alpha - theta0 - d) sin(d),
        # d = span u^2 / 2, avoids the cancellation near u = 0
        d = 0.5 * span * u * u
        sin_d_over_u2 = math.sin(d) / (u * u) if d > 0 else 0.5 * span
        return 2 * span / math.sqrt(-2 * k * math.sin(c.alpha - theta0 - d) * sin_d_over_u2)
    t_ref = quad(integrand, 0.0, 1.0, limit=200, epsabs=0, epsrel=1e-12)[0]
    assert r.t_overturn == pytest.approx(t_ref, rel=1e-8)


def test_max_abs_theta_stops_at_overturning():
    """The simulation ends when |theta| reaches theta_overturn: max_abs_theta = pi/2."""
    r = run_scene(scene(mu=0.5, e_x=-0.5, e_y=0.3, horizontal=sine(0.4 * G, 1.5),
                        t_end=5.0))
    assert r.overturned
    assert r.max_abs_theta == pytest.approx(math.pi / 2, abs=1e-9)
