"""Isolated platforms (sweep.groundmotion.isolator, ``kind: isolated``, docs/isolation.md)
against independent values: the closed-form slide under a constant push, a stick-slip
integration written here, the bound g (mu + D/R), the transmissibility and an ODE solution of
the linear isolator; and the isolator in a scene, its JSON, its caution, its bad input and a
study's dataset."""
import math
import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import sweep
from sweep.bodies import G
from sweep.groundmotion.isolator import Pendulum, response
from sweep.io.problems import FileProblems, InputWarning
from sweep.io.scene_schema import load_scene, resolve_scene
from sweep.runner.cell_checks import load_study
from sweep.runner.cells import run_chunk
from sweep.runner.simulate import to_json_dict

R, MU = 1.5, 0.06
SCENE = {"body": {"B": "0.4 m", "H": "1.2 m"}}


def stick_slip(samples, dt, radius, mu, h=2e-5):
    """Independent integration: steps of h (trapezoidal position), sticking when the
    velocity changes sign and the push |a + (g/R) u| is at most mu g, slipping when it is
    more.  Returns the times, the platform's absolute acceleration and max |u|."""
    w2 = G / radius
    n = round(dt / h)
    h = dt / n
    t = np.arange((len(samples) - 1) * n + 1) * h
    a = np.interp(t, dt * np.arange(len(samples)), samples)
    u = v = umax = 0.0
    sign, out = 0.0, np.empty_like(a)
    for k, ak in enumerate(a):
        push = ak + w2 * u
        if sign == 0.0 and abs(push) > mu * G:
            sign = -math.copysign(1.0, push)
        out[k] = ak if sign == 0.0 else -w2 * u - mu * G * sign
        if sign == 0.0:
            continue
        vn = v + h * (-push - mu * G * sign)
        if vn * sign <= 0.0:
            v, sign = 0.0, 0.0
        else:
            u, v = u + h * (v + vn) / 2.0, vn
        umax = max(umax, abs(u))
    return t, out, umax


def _sine(amplitude, frequency=1.0, dt=0.01, duration=12.0):
    t = np.arange(0.0, duration, dt)
    return amplitude * np.sin(2 * math.pi * frequency * t), dt


def test_below_mu_g_it_sticks_and_the_platform_is_the_ground():
    """A push below mu g never starts a slide: the platform is the ground, read linearly."""
    samples, dt = _sine(0.9 * MU * G)
    out = response(samples, dt, Pendulum(R, MU))
    t = out.dt * np.arange(len(out.acceleration))
    ground = np.interp(t, dt * np.arange(len(samples) + 1), np.append(samples, 0.0))
    assert out.max_displacement == 0.0
    assert np.max(np.abs(out.acceleration - ground)) < 1e-12


@pytest.mark.parametrize("push", [1.5, 2.5])
def test_constant_push_slides_half_a_period_then_sticks(push):
    """Under a constant a = A with mu g < A <= 3 mu g from rest (closed form): the platform
    slides u = -(A - mu g)/w^2 (1 - cos w t) for half a period, then sticks at
    D = 2 (A - mu g) R/g, where the push 2 mu g - A is within mu g; its acceleration is
    -w^2 u + mu g while it slides, A once stuck."""
    A, dt = push * MU * G, 0.01
    w = math.sqrt(G / R)
    samples = np.full(int(2.0 * math.pi / w / dt) + 2, A)
    out = response(samples, dt, Pendulum(R, MU))
    t = out.dt * np.arange(len(out.acceleration))
    stop = math.pi / w
    end = len(samples) - 1  # the input falls to rest after its last sample
    sliding, stuck = t < stop, (t > stop) & (t <= (end * dt))
    closed = MU * G + (A - MU * G) * (1.0 - np.cos(w * t))
    assert out.max_displacement == pytest.approx(2.0 * (A - MU * G) / w ** 2, rel=1e-12)
    assert np.max(np.abs(out.acceleration[sliding] - closed[sliding])) < 1e-9
    assert np.max(np.abs(out.acceleration[stuck] - A)) < 1e-9


@pytest.mark.parametrize("amplitude", [0.3, 0.5])
def test_sliding_agrees_with_an_independent_stick_slip_integration(amplitude):
    """Sliding under a 1 Hz sine: the peak platform acceleration and displacement agree with
    the stick-slip integration above to 0.02 %, and |platform| <= g (mu + D/R)."""
    samples, dt = _sine(amplitude * G)
    out = response(samples, dt, Pendulum(R, MU))
    _, reference, umax = stick_slip(samples, dt, R, MU)
    peak = np.max(np.abs(out.acceleration))
    assert out.max_displacement == pytest.approx(umax, rel=2e-4)
    assert peak == pytest.approx(np.max(np.abs(reference)), rel=2e-4)
    assert peak <= G * (MU + out.max_displacement / R) * (1 + 1e-12)


def _isolated(under, isolator):
    return {**SCENE, "excitation": {"horizontal": {"kind": "isolated", "under": under,
                                                   "isolator": isolator}}}


def _linear_platform(r, zeta, period=2.5, duration=80.0):
    f = r / period
    scene = _isolated({"kind": "sine", "amplitude": "0.1 g", "frequency": f,
                       "duration": f"{duration} s"},
                      {"kind": "linear", "period": f"{period} s", "damping": zeta})
    h = resolve_scene(scene)["excitation"]["horizontal"]
    t = h["dt"] * np.arange(len(h["samples"]))
    return f, t, h["scale"] * h["samples"]


@pytest.mark.parametrize("r", [0.5, 1.0, 2.0, 4.0])
def test_linear_isolator_steady_state_is_the_transmissibility(r):
    """After its transient (e^-20 over the last 20 s), the platform under a 0.1 g sine moves
    with the closed-form transmissibility sqrt((1 + (2 zeta r)^2)/((1 - r^2)^2 + (2 zeta r)^2))."""
    zeta = 0.1
    f, t, a = _linear_platform(r, zeta)
    tail = (t > 60.0) & (t < 80.0)
    basis = np.column_stack([np.sin(2 * math.pi * f * t[tail]), np.cos(2 * math.pi * f * t[tail])])
    coef, *_ = np.linalg.lstsq(basis, a[tail], rcond=None)
    closed = math.sqrt((1 + (2 * zeta * r) ** 2) / ((1 - r * r) ** 2 + (2 * zeta * r) ** 2))
    assert np.hypot(*coef) / (0.1 * G) == pytest.approx(closed, rel=1e-6)


def test_linear_isolator_is_the_ode_solution_from_rest():
    """The platform is x'' = -2 zeta w (x' - v_g) - w^2 (x - u_g) of the oscillator started at
    rest, solved by scipy (rtol 1e-10), to 1e-6 of the ground's amplitude."""
    zeta, period = 0.1, 2.5
    f, t, a = _linear_platform(1.3, zeta, period, duration=10.0)
    w, wg, amp = 2 * math.pi / period, 2 * math.pi * f, 0.1 * G

    def rhs(time, y):  # y: displacement and velocity relative to the ground
        return [y[1], -amp * math.sin(wg * time) - 2 * zeta * w * y[1] - w * w * y[0]]

    keep = t <= 10.0
    sol = solve_ivp(rhs, (0.0, 10.0), [0.0, 0.0], t_eval=t[keep], rtol=1e-10, atol=1e-13)
    platform = -2 * zeta * w * sol.y[1] - w * w * sol.y[0]
    assert np.max(np.abs(a[keep] - platform)) < 1e-6 * amp


def test_linear_isolator_displacement_is_the_ode_solution_from_rest():
    """The JSON's ``max_displacement`` of a linear base under 6 s of a 0.1 g sine is the largest
    |u| of u'' = -a_g - 2 zeta w u' - w^2 u from rest, the free vibration after the sine
    included, solved by scipy (rtol 1e-10): to 1e-3, the sine being sampled 100 times a period
    and the oscillator read at those samples (each about (2 pi/100)^2/8 = 5e-4 at most)."""
    zeta, period, f, amp, duration = 0.1, 2.5, 0.52, 0.1 * G, 6.0
    scene = _isolated({"kind": "sine", "amplitude": "0.1 g", "frequency": f,
                       "duration": f"{duration} s"},
                      {"kind": "linear", "period": f"{period} s", "damping": zeta})
    w, wg = 2 * math.pi / period, 2 * math.pi * f

    def rhs(time, y):
        forcing = amp * math.sin(wg * time) if time < duration else 0.0
        return [y[1], -forcing - 2 * zeta * w * y[1] - w * w * y[0]]

    sol = solve_ivp(rhs, (0.0, duration + period), [0.0, 0.0], max_step=1e-3, rtol=1e-10,
                    atol=1e-13)
    got = to_json_dict(sweep.simulate(scene))["isolator"]["max_displacement"]
    assert got == pytest.approx(np.max(np.abs(sol.y[0])), rel=1e-3)


def test_scene_json_below_mu_g_and_past_the_capacity():
    """In a scene: below mu g the platform's PGA is the ground's (0.03 g, the sine sampled 100
    times a period: within 0.05 %) and the isolator does not move; a slide past
    ``displacement_capacity`` is flagged and cautioned at its dotted path."""
    still = sweep.simulate(_isolated({"kind": "sine", "amplitude": "0.03 g", "frequency": 1.0,
                                      "duration": "5 s"},
                                     {"kind": "friction_pendulum", "radius": "1.5 m",
                                      "mu": MU}))
    out = to_json_dict(still)
    assert out["pga"] == pytest.approx(0.03 * G, rel=5e-4)
    assert out["isolator"] == {"max_displacement": 0.0, "capacity": None, "exceeded": False}
    scene = _isolated({"kind": "sine", "amplitude": "0.3 g", "frequency": 1.0,
                       "duration": "5 s"},
                      {"kind": "friction_pendulum", "radius": "1.5 m", "mu": MU,
                       "displacement_capacity": "1 cm"})
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = sweep.simulate(scene)
    assert result.isolator["exceeded"] and result.isolator["max_displacement"] > 0.01
    paths = [w.message.problem.path for w in caught if issubclass(w.category, InputWarning)]
    assert "excitation.horizontal.isolator.displacement_capacity" in paths


def test_old_scenes_have_no_isolator_key():
    """A scene without an isolator keeps its JSON keys: no ``isolator``."""
    result = sweep.simulate({**SCENE, "excitation": {"horizontal": {
        "kind": "sine", "amplitude": "0.1 g", "frequency": 2.0, "duration": "1 s"}}})
    assert result.isolator is None and "isolator" not in to_json_dict(result)


@pytest.mark.parametrize("isolator, under, path", [
    ({"kind": "friction_pendulum", "radius": "0 m", "mu": 0.06}, None, "isolator.radius"),
    ({"kind": "friction_pendulum", "radius": "1 m", "mu": -0.1}, None, "isolator.mu"),
    ({"kind": "linear", "period": "2 s", "damping": "100 %"}, None, "isolator.damping"),
    ({"kind": "spring"}, None, "isolator.kind"),
    ({"kind": "linear", "period": "2 s"},
     {"kind": "isolated", "under": "none", "isolator": {"kind": "linear", "period": "2 s"}},
     "under.kind"),
])
def test_bad_isolators_are_named_by_their_dotted_path(isolator, under, path):
    """Each bad value is one problem at its dotted path."""
    under = under or {"kind": "sine", "amplitude": "0.1 g", "frequency": 1.0}
    with pytest.raises(FileProblems) as err:
        load_scene(_isolated(under, isolator))
    assert [p.path for p in err.value.problems] == [f"excitation.horizontal.{path}"]


def test_study_dataset_has_the_isolator_displacement():
    """A study's cells: ``isolator_max_displacement`` is 0 for a sine below mu g, positive
    above it with the platform's PGA within g (mu + D/R); a linear isolator's that of the
    scene run alone."""
    isolated = {"kind": "isolated",
                "under": {"kind": "sine", "amplitude": "0.03 g", "frequency": 1.0,
                          "duration": "4 s"},
                "isolator": {"kind": "friction_pendulum", "radius": "1.5 m", "mu": MU}}
    raw = {"name": "t", "scene": {**SCENE, "excitation": {"horizontal": isolated}},
           "grid": {"excitation.horizontal.under.amplitude": {"values": [0.03, 0.3],
                                                              "unit": "g"}}}
    out = run_chunk(load_study(raw, check_cells=False), [0, 1])
    displacement = out["isolator_max_displacement"]
    assert displacement[0] == 0.0 and out["pga"][0] == pytest.approx(0.03 * G, rel=5e-4)
    assert displacement[1] > 0.0 and out["pga"][1] <= G * (MU + displacement[1] / R)
    raw["scene"]["excitation"]["horizontal"]["isolator"] = {"kind": "linear", "period": "2 s"}
    linear = run_chunk(load_study(raw, check_cells=False), [0])
    alone = sweep.simulate(load_study(raw, check_cells=False).scene)
    assert linear["isolator_max_displacement"][0] == alone.isolator["max_displacement"] > 0.0
