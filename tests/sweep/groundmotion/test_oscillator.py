"""The SDOF oscillator and Sa(T) against closed forms and an independent integration; scenes
scaled to a PGV or an Sa(T) reach it."""
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from sweep.groundmotion.oscillator import DAMPING, pseudo_acceleration, response
from sweep.io.records import load_record
from sweep.io.scene_schema import load_scene, resolve_scene

ZETA = DAMPING


def test_sine_at_resonance_gives_the_steady_state_amplitude():
    """a_g = A sin(omega_n t) for 100 periods: the steady amplitude omega_n^2 |u| = A/(2 zeta)
    (Chopra 2017 Eq. 3.2.15 at omega = omega_n); the transient has decayed by e^(-31)."""
    A, T = 1.5, 0.4
    dt = T / 200
    t = np.arange(0.0, 100 * T, dt)
    sa = pseudo_acceleration(A * np.sin(2 * math.pi / T * t), dt, T)
    assert sa == pytest.approx(A / (2 * ZETA), rel=2e-4)  # measured 8e-5: the linear sine


def test_off_resonance_steady_state_against_the_closed_form():
    """omega = omega_n/2: the steady amplitude A/sqrt((1 - r^2)^2 + (2 zeta r)^2)/omega_n^2;
    the largest |u| over the last periods (transient gone) is it."""
    A, Tn, r = 1.0, 0.3, 0.5
    omega_n = 2 * math.pi / Tn
    dt = Tn / 400
    t = np.arange(0.0, 150 * Tn, dt)
    u, _ = response(-A * np.sin(r * omega_n * t), dt, omega_n, ZETA)
    steady = A / math.hypot(1 - r * r, 2 * ZETA * r) / omega_n ** 2
    assert np.max(np.abs(u[t > 100 * Tn])) == pytest.approx(steady, rel=1e-4)


def test_record_against_solve_ivp():
    """El Centro 1940 NS, T = 0.5 s: the exact recursion and scipy's RK45 at rtol 1e-10 on the
    linearly interpolated record agree."""
    rec = load_record("elcentro1940_ns")
    T, omega = 0.5, 2 * math.pi / 0.5
    t = rec.dt * np.arange(rec.samples.size)
    u, v = response(-rec.samples, rec.dt, omega, ZETA)

    def rhs(time, y):
        return [y[1], -np.interp(time, t, rec.samples) - 2 * ZETA * omega * y[1]
                - omega ** 2 * y[0]]

    ref = solve_ivp(rhs, (0.0, t[-1]), [0.0, 0.0], t_eval=t, rtol=1e-10, atol=1e-12,
                    max_step=rec.dt)
    scale = np.max(np.abs(ref.y[0]))
    np.testing.assert_allclose(u, ref.y[0], atol=1e-6 * scale)
    sa = pseudo_acceleration(rec.samples, rec.dt, T)
    assert sa >= omega ** 2 * scale * (1 - 1e-6)  # the ring-down may add to the peak


def test_short_period_is_the_pga_and_sa_is_linear():
    rec = load_record("elcentro1940_ns")
    assert pseudo_acceleration(rec.samples, rec.dt, 0.0) == rec.pga
    assert pseudo_acceleration(rec.samples, rec.dt, 1e-4) == pytest.approx(rec.pga, rel=1e-4)
    for T in (0.2, 1.0):
        assert pseudo_acceleration(-2.5 * rec.samples, rec.dt, T) == pytest.approx(
            2.5 * pseudo_acceleration(rec.samples, rec.dt, T), rel=1e-12)


@pytest.mark.parametrize("motion", [
    {"kind": "record", "name": "elcentro1940_ns"},
    {"kind": "synthetic", "model": "boore2003", "magnitude": 6.5, "distance": "20 km",
     "vs30": "760 m/s", "seed": 3},
])
@pytest.mark.parametrize("key, target", [("pgv", "30 cm/s"),
                                         ("sa", {"period": "0.6 s", "value": "0.5 g"})])
def test_scenes_scaled_to_pgv_or_sa_reach_it(motion, key, target):
    scene = load_scene({"body": {"B": 0.2, "H": 0.6},
                        "excitation": {"horizontal": {**motion, key: target}}})
    ground = resolve_scene(scene)["excitation"]["horizontal"]
    scaled = ground["scale"] * ground["source"].samples
    if key == "pgv":
        assert ground["scale"] * ground["source"].intensity.pgv == pytest.approx(0.30,
                                                                                  rel=1e-12)
    else:
        assert pseudo_acceleration(scaled, ground["dt"], 0.6) == pytest.approx(
            0.5 * 9.80665, rel=1e-12)


def test_one_scale_only():
    with pytest.raises(Exception, match="give one of scale, pga, pgv and sa, not pga and sa"):
        load_scene({"body": {"B": 0.2, "H": 0.6}, "excitation": {"horizontal": {
            "kind": "record", "name": "elcentro1940_ns", "pga": "0.3 g",
            "sa": {"period": 0.5, "value": "0.5 g"}}}})


def test_a_study_axis_sa_scales_each_cell():
    """Axis ``sa`` (``excitation.horizontal.sa.value``): each cell's applied PGA is its Sa
    level times PGA/Sa(T) of the record."""
    import sweep
    from sweep.runner.cell_checks import load_study

    study = load_study({"name": "s", "output": "unused.nc", "grid": {"sa": ["0.2 g", "0.4 g"]},
                        "scene": {"body": {"B": 0.2, "H": 0.6}, "solver": {"t_end": 2.0},
                                  "excitation": {"horizontal": {
                                      "kind": "record", "name": "elcentro1940_ns",
                                      "sa": {"period": 0.5, "value": "0.3 g"}}}}})
    ds = sweep.run_study(study)
    rec = load_record("elcentro1940_ns")
    ratio = rec.pga / pseudo_acceleration(rec.samples, rec.dt, 0.5)
    np.testing.assert_allclose(ds["pga"].values, ds["sa"].values * ratio, rtol=1e-12)
    np.testing.assert_allclose(ds["sa"].values, [0.2 * 9.80665, 0.4 * 9.80665])
