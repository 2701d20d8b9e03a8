"""Floors of buildings (sweep.groundmotion.floor, docs/floors.md) against independent values:
the transmissibility of a sine's steady state, scipy's lsim for a record, the ground itself
for a rigid building; and the floor as a scene's excitation and a study's axis."""
import math

import numpy as np
import pytest
from scipy import signal

from sweep.groundmotion.floor import (Mode, floor_of_motion, floor_of_record, floor_of_sine,
                                      record_response, shear_beam_modes, sine_response)
from sweep.io.problems import FileProblems
from sweep.io.scene_schema import load_scene, resolve_scene


def transmissibility(r, zeta):
    return math.sqrt((1 + (2 * zeta * r) ** 2) / ((1 - r * r) ** 2 + (2 * zeta * r) ** 2))


@pytest.mark.parametrize("r", [0.3, 0.9, 1.0, 1.7, 4.0])
def test_sine_steady_state_is_the_transmissibility(r):
    """After the transient has decayed (e^-40), the floor's amplitude under a unit sine with
    participation 1 is the transmissibility, to 1e-9."""
    period, zeta, f = 0.5, 0.05, r / 0.5
    modes = (Mode(period, zeta, 1.0),)
    t0 = 40.0 / (zeta * 2 * math.pi / period)
    t = t0 + np.linspace(0.0, 1.0 / f, 2001)
    a = sine_response(t, f, 0.3, math.inf, modes)
    # least squares of a sinusoid at f: its amplitude
    basis = np.column_stack([np.sin(2 * math.pi * f * t), np.cos(2 * math.pi * f * t)])
    coef, residual, *_ = np.linalg.lstsq(basis, a, rcond=None)
    assert np.hypot(*coef) == pytest.approx(transmissibility(r, zeta), rel=1e-9, abs=0)
    assert np.max(np.abs(basis @ coef - a)) < 1e-9


def test_sine_starts_from_rest_and_rings_down():
    """At the start the floor moves with (1 - participation) times the ground; after a sine of
    finite duration the floor rings down at the damped natural frequency."""
    modes = shear_beam_modes(0.6, 0.05, 1.0)
    t = np.array([0.0, 5.0 - 1e-12])
    a = sine_response(t, 2.0, 0.7, 5.0, modes)
    assert a[0] == pytest.approx((1 - modes[0].participation) * math.sin(0.7), abs=1e-15)
    wd = 2 * math.pi / 0.6 * math.sqrt(1 - 0.05 ** 2)
    tail = 5.0 + np.arange(4) * 2 * math.pi / wd
    ratios = sine_response(tail, 2.0, 0.7, 5.0, modes)
    assert ratios[1:] / ratios[:-1] == pytest.approx(np.exp(-0.05 * 2 * math.pi / 0.6 * 2 *
                                                            math.pi / wd), rel=1e-9)


def test_record_matches_lsim():
    """A synthetic-like record through two modes against scipy's lsim (first-order hold) of
    the same oscillators."""
    rng = np.random.default_rng(3)
    dt = 0.01
    ground = np.convolve(rng.standard_normal(1500), np.hanning(15), "same")
    modes = (Mode(0.5, 0.05, 1.27), Mode(0.17, 0.03, -0.42))
    floor = record_response(ground, dt, modes)
    t = dt * np.arange(ground.size)
    expected = ground.copy()
    for m in modes:
        w = 2 * math.pi / m.period
        # states (u, u'), output u'' = -a_g - 2 zeta w u' - w^2 u
        system = signal.StateSpace([[0, 1], [-w * w, -2 * m.damping * w]], [[0], [-1]],
                                   [[-w * w, -2 * m.damping * w]], [[-1]])
        expected += m.participation * signal.lsim(system, ground, t)[1]
    assert np.max(np.abs(floor - expected)) < 1e-10 * np.max(np.abs(expected))


def test_record_matches_the_sine_closed_form():
    """The recursion on a finely sampled sine converges to the closed form (O(dt^2))."""
    modes = shear_beam_modes(0.5, 0.05, 1.0, 2)
    dt = 1e-4
    t = dt * np.arange(50001)
    exact = sine_response(t, 2.5, 0.4, math.inf, modes)
    floor = record_response(np.sin(2 * math.pi * 2.5 * t + 0.4), dt, modes)
    assert np.max(np.abs(floor - exact)) < 1e-6


def _spec(**ground):
    return tuple(sorted({"start": 0.0, "amplitude": 1.0, "phase": 0.0, **ground}.items()))


def test_sweep_at_one_frequency_is_the_sine():
    """A sweep from 2 Hz to 2 Hz (whole cycles, no jump at its end) through the sampled path is
    the sine's closed form to the linear reading of 100 samples per period: (2 pi/100)^2/12
    = 3.3e-4 of the floor's peak (measured 3.1e-4)."""
    modes = shear_beam_modes(0.6, 0.05, 1.0)
    spec = _spec(kind="sweep", hold="acceleration", f_start=2.0, f_stop=2.0, duration=6.0,
                 law="log")
    rec = floor_of_motion(spec, modes)
    t = rec.dt * np.arange(rec.samples.size)
    exact = sine_response(t, 2.0, 0.0, 6.0, modes)
    assert np.max(np.abs(rec.samples - exact)) < (2 * math.pi / 100) ** 2 / 12 * np.max(exact)
    assert rec.samples.size * rec.dt > 6.0 + math.log(100) / (0.05 * 2 * math.pi / 0.6)


def test_triangular_pulse_matches_lsim():
    """A triangular pulse is piecewise linear: its floor is exact at the samples (lsim)."""
    modes = (Mode(0.4, 0.05, 1.0),)
    rec = floor_of_motion(_spec(kind="pulse", shape="triangular", duration=0.5), modes)
    t = rec.dt * np.arange(rec.samples.size)
    ground = np.clip(1.0 - np.abs(2.0 * t / 0.5 - 1.0), 0.0, None)
    w = 2 * math.pi / 0.4
    system = signal.StateSpace([[0, 1], [-w * w, -0.1 * w]], [[0], [-1]], [[-w * w, -0.1 * w]],
                               [[0]])
    expected = signal.lsim(system, ground, t)[1]
    assert np.max(np.abs(rec.samples - expected)) < 1e-9


def test_rigid_building_gives_the_ground():
    """Period 0 is the ground exactly; a stiff building (1 ms) nearly, for a ground that
    starts from 0 (a jump at the start rings a stiff building for some ms)."""
    rng = np.random.default_rng(5)
    ground = np.convolve(rng.standard_normal(2000), np.hanning(9), "same")
    ground[0] = 0.0
    assert np.array_equal(record_response(ground, 0.01, shear_beam_modes(0.0, 0.05, 1.0)),
                          ground)
    for period, tolerance in ((1e-3, 1e-4), (1e-4, 1e-12)):
        stiff = record_response(ground, 0.01, shear_beam_modes(period, 0.05, 1.0))
        assert np.max(np.abs(stiff - ground)) < tolerance * np.max(np.abs(ground))
    t = np.linspace(0, 3, 301)
    assert np.array_equal(sine_response(t, 2.0, 0.1, math.inf, ()), np.sin(4 * math.pi * t + 0.1))


def test_shear_beam_participations():
    """First mode (4/pi) sin(pi z/2H); the modes sum to 1 at any height (Fourier series)."""
    assert shear_beam_modes(1.2, 0.05, 1.0)[0] == (1.2, 0.05, pytest.approx(4 / math.pi))
    modes = shear_beam_modes(1.2, 0.05, 0.5, 4000)
    assert modes[1].period == pytest.approx(0.4)
    assert sum(m.participation for m in modes) == pytest.approx(1.0, abs=1e-3)


def test_floor_computed_once_per_ground_and_building():
    """Equal ground samples and modes give the same Record object (a cache hit)."""
    from sweep.io.records import load_record
    rec = load_record("elcentro1940_ns")
    modes = shear_beam_modes(0.8, 0.05, 1.0)
    first = floor_of_record(rec, modes)
    assert floor_of_record(rec, list(modes)) is first
    assert floor_of_sine(2.0, 0.0, 3.0, 10.0, modes) is floor_of_sine(2.0, 0.0, 3.0, 10.0, modes)
    assert first.samples.size > rec.samples.size  # the ring-down


SCENE = {"body": {"B": 0.2, "H": 0.8}, "solver": {"t_end": 4.0}}


def _floor_scene(building, ground=None):
    ground = ground or {"kind": "sine", "amplitude": "0.1 g", "frequency": 2.0}
    return {**SCENE, "excitation": {"horizontal": {"kind": "floor", "ground": ground,
                                                   "building": building}}}


def test_scene_floor_resolves_into_a_record():
    """A floor over a sine is a record of the closed form, its amplitude the sine's scale; over
    a record, the record's scale."""
    r = resolve_scene(_floor_scene({"period": "0.6 s", "damping": "5 %"}))
    h = r["excitation"]["horizontal"]
    assert h["kind"] == "record" and h["scale"] == pytest.approx(0.1 * 9.80665)
    assert h["ground"]["kind"] == "sine"
    assert h["dt"] * len(h["samples"]) >= 4.0
    r = resolve_scene(_floor_scene({"period": 0.6, "height_ratio": 0.5},
                                   {"kind": "record", "name": "elcentro1940_ns", "scale": 2.0}))
    h = r["excitation"]["horizontal"]
    assert h["scale"] == 2.0 and h["dt"] == 0.02 and r["solver"]["t_end"] == 4.0


@pytest.mark.parametrize("building, path", [
    ({"period": -0.5}, "excitation.horizontal.building.period"),
    ({"period": 0.5, "damping": 1.0}, "excitation.horizontal.building.damping"),
    ({"period": 0.5, "damping": "120 %"}, "excitation.horizontal.building.damping"),
    ({"period": 0.5, "height_ratio": 1.5}, "excitation.horizontal.building.height_ratio"),
    ({"damping": 0.05}, "excitation.horizontal.building.period"),
    ({"period": 0.5, "modes": [{"period": 0.5, "participation": 1.2}]},
     "excitation.horizontal.building.period"),
    ({"modes": [{"period": 0.0, "participation": 1.2}]},
     "excitation.horizontal.building.modes[0].period"),
])
def test_bad_building_named_by_its_path(building, path):
    with pytest.raises(FileProblems) as err:
        load_scene(_floor_scene(building))
    assert [p.path for p in err.value.problems] == [path]


def test_bad_ground_named_by_its_path():
    with pytest.raises(FileProblems) as err:
        load_scene(_floor_scene({"period": 0.5}, {"kind": "record", "name": "nowhere"}))
    assert [p.path for p in err.value.problems] == ["excitation.horizontal.ground.name"]


def test_study_sweeps_the_building_period():
    """building.period is an axis like any other (a time, named period in the dataset); the
    floor is computed once per ground and building: two periods, four cells, two floors."""
    import sweep
    from sweep.groundmotion import floor
    floor._floor_of_samples.cache_clear()
    study = {"name": "floors", "scene": _floor_scene(
        {"period": 0.5}, {"kind": "record", "name": "elcentro1940_ns", "duration": 3.0}),
        "grid": {"excitation.horizontal.building.period": {"values": [0.0, 0.5], "unit": "s"},
                 "excitation.horizontal.ground.scale": [1.0, 2.0]}}
    ds = sweep.run_study(study)
    assert floor._floor_of_samples.cache_info().misses == 2
    assert ds["period"].attrs["units"] == "s" and list(ds["period"].values) == [0.0, 0.5]
    ground = ds["pga"].sel(period=0.0).values
    assert ground[1] == pytest.approx(2 * ground[0]) and np.all(ds["outcome"] >= 0)


def test_scene_on_a_rigid_building_is_the_scene_on_the_ground():
    """Period 0: the body does on the floor exactly what it does on the ground."""
    import sweep
    ground = {"kind": "record", "name": "elcentro1940_ns", "pga": "0.4 g", "duration": 4.0}
    on_floor = sweep.simulate(_floor_scene({"period": 0.0}, ground))
    on_ground = sweep.simulate({**SCENE, "excitation": {"horizontal": ground}})
    assert on_floor.impact_times == on_ground.impact_times and on_floor.impact_count > 0
    assert on_floor.max_abs_theta == on_ground.max_abs_theta
