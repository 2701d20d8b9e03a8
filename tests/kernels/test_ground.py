"""The floor motion of ``kernels.ground`` against closed forms: A sin(2 pi f t + phase) in
its window, sweeps psi(t) = 2 pi f0 (e^{kt} - 1)/k + phase (log law, k = ln(f1/f0)/T) or
2 pi (f0 t + (f1 - f0) t^2 / (2T)) + phase (linear law) holding acceleration A sin(psi),
velocity -V cos(psi) or displacement -D sin(psi) (checked by finite differences of those
laws and by quadrature of the kernel's acceleration), records (linear interpolation of the
samples times the scale), pulses; the breaks, the end time and the amplitudes.
"""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from kernels import api, codes, ground

TWO_PI = 2.0 * math.pi


def floor_of(horizontal=None, vertical=None):
    """(floor, rec) of a scene with the given ground components (api's dict format)."""
    records = []
    row = api.scene_row({"body": {"B": 0.1, "H": 0.3},
                         "excitation": {"horizontal": horizontal, "vertical": vertical}},
                        records)
    return row.floor, api.record_buffer(records)


def a_x(t, floor, rec):
    return ground.ground(t, floor, rec)[0]


def a_y(t, floor, rec):
    return ground.ground(t, floor, rec)[1]


def psi_log(tau, f0, f1, T, phase=0.0):
    k = math.log(f1 / f0) / T
    return TWO_PI * f0 * math.expm1(k * tau) / k + phase


def psi_linear(tau, f0, f1, T, phase=0.0):
    return TWO_PI * (f0 * tau + 0.5 * (f1 - f0) / T * tau * tau) + phase


def freq_log(tau, f0, f1, T):
    return f0 * (f1 / f0) ** (tau / T)


def freq_linear(tau, f0, f1, T):
    return f0 + (f1 - f0) * tau / T


LAWS = {"log": (psi_log, freq_log), "linear": (psi_linear, freq_linear)}


def sweep(hold, amplitude, law, f0=1.0, f1=3.0, T=4.0, start=0.5, phase=0.3):
    return {"kind": "sweep", "hold": hold, "amplitude": amplitude, "f_start": f0,
            "f_stop": f1, "duration": T, "law": law, "start": start, "phase": phase}


# --- none and sine --------------------------------------------------------------------------

def test_no_motion():
    """Both components 'none': (0, 0) at any time, no break (inf), still from t = 0."""
    floor, rec = floor_of()
    for t in (0.0, 1.0, 1e6):
        assert ground.ground(t, floor, rec) == (0.0, 0.0)
    assert ground.next_break(0.0, floor) == math.inf
    assert ground.ground_end(floor) == 0.0


def test_sine_inside_window():
    """A sin(2 pi f (t - start) + phase) inside [start, start + duration), to 1e-13 A."""
    A, f, phase, start, dur = 2.5, 3.0, 0.7, 0.4, 2.0
    floor, rec = floor_of({"kind": "sine", "amplitude": A, "frequency": f, "phase": phase,
                           "start": start, "duration": dur})
    for t in np.linspace(start, start + dur, 41)[:-1]:
        want = A * math.sin(TWO_PI * f * (t - start) + phase)
        assert a_x(t, floor, rec) == pytest.approx(want, rel=0, abs=1e-13 * A)
        assert a_y(t, floor, rec) == 0.0


def test_sine_outside_window():
    """Zero before the start and from start + duration on (the window is half-open), though
    the sine there (phase 0.7) is not zero."""
    A, f, phase, start, dur = 2.5, 3.0, 0.7, 0.4, 2.0
    floor, rec = floor_of({"kind": "sine", "amplitude": A, "frequency": f, "phase": phase,
                           "start": start, "duration": dur})
    assert a_x(start, floor, rec) == pytest.approx(A * math.sin(phase), abs=1e-15)
    for t in (0.0, start - 1e-9, start + dur, start + dur + 1e-9, 100.0):
        assert a_x(t, floor, rec) == 0.0


def test_sine_without_end_on_vertical():
    """A vertical sine with no duration: a_y = A sin(2 pi f t) at t = 1000.1 s (to 1e-9 A:
    the phase 2 pi f t is large), a_x = 0."""
    floor, rec = floor_of(None, {"kind": "sine", "amplitude": 4.0, "frequency": 2.0})
    t = 1000.1
    ax, ay = ground.ground(t, floor, rec)
    assert ax == 0.0
    assert ay == pytest.approx(4.0 * math.sin(TWO_PI * 2.0 * t), abs=1e-9 * 4.0)


# --- sweeps ---------------------------------------------------------------------------------

@pytest.mark.parametrize("law", LAWS)
def test_sweep_holding_acceleration(law):
    """A sin(psi(t - start)) with the closed-form phase of the law, to 1e-12 A; zero
    outside [start, start + T)."""
    A, f0, f1, T, start, phase = 1.7, 1.0, 3.0, 4.0, 0.5, 0.3
    psi = LAWS[law][0]
    floor, rec = floor_of(sweep("acceleration", A, law, f0, f1, T, start, phase))
    for tau in np.linspace(0.0, T, 57)[:-1]:
        want = A * math.sin(psi(tau, f0, f1, T, phase))
        assert a_x(start + tau, floor, rec) == pytest.approx(want, rel=0, abs=1e-12 * A)
    for t in (0.0, start - 1e-9, start + T, start + T + 1.0):
        assert a_x(t, floor, rec) == 0.0


def _d1(fun, t, h):
    """4th-order central first derivative."""
    return (-fun(t + 2 * h) + 8 * fun(t + h) - 8 * fun(t - h) + fun(t - 2 * h)) / (12 * h)


def _d2(fun, t, h):
    """4th-order central second derivative."""
    return (-fun(t + 2 * h) + 16 * fun(t + h) - 30 * fun(t) + 16 * fun(t - h)
            - fun(t - 2 * h)) / (12 * h * h)


@pytest.mark.parametrize("law", LAWS)
def test_sweep_holding_velocity_is_derivative_of_velocity_law(law):
    """Holding velocity V: the kernel's a_x equals d/dt of the floor velocity -V cos(psi(t))
    (4th-order finite differences, h = 1e-3 s) to 1e-7 of the largest acceleration V w1."""
    V, f0, f1, T, start, phase = 0.2, 1.0, 3.0, 4.0, 0.5, 0.3
    psi = LAWS[law][0]
    floor, rec = floor_of(sweep("velocity", V, law, f0, f1, T, start, phase))
    vel = lambda t: -V * math.cos(psi(t - start, f0, f1, T, phase))  # noqa: E731
    scale = V * TWO_PI * f1
    for t in np.linspace(start + 0.01, start + T - 0.01, 23):
        assert a_x(t, floor, rec) == pytest.approx(_d1(vel, t, 1e-3), rel=0, abs=1e-7 * scale)


@pytest.mark.parametrize("law", LAWS)
def test_sweep_holding_displacement_is_second_derivative_of_displacement_law(law):
    """Holding displacement D: the kernel's a_x equals d^2/dt^2 of the floor displacement
    -D sin(psi(t)) (4th-order finite differences, h = 1e-3 s) to 1e-6 of D w1^2."""
    D, f0, f1, T, start, phase = 0.01, 1.0, 3.0, 4.0, 0.5, 0.3
    psi = LAWS[law][0]
    floor, rec = floor_of(sweep("displacement", D, law, f0, f1, T, start, phase))
    disp = lambda t: -D * math.sin(psi(t - start, f0, f1, T, phase))  # noqa: E731
    scale = D * (TWO_PI * f1) ** 2
    for t in np.linspace(start + 0.01, start + T - 0.01, 23):
        assert a_x(t, floor, rec) == pytest.approx(_d2(disp, t, 1e-3), rel=0,
                                                   abs=1e-6 * scale)


@pytest.mark.parametrize("law", LAWS)
def test_sweep_velocity_by_quadrature(law):
    """Holding velocity V: the integral of the kernel's a_x from the start to t equals
    -V cos(psi(t)) + V cos(phase) (the change of the velocity law), to 1e-11 V."""
    V, f0, f1, T, start, phase = 0.2, 1.0, 3.0, 4.0, 0.5, 0.3
    psi = LAWS[law][0]
    floor, rec = floor_of(sweep("velocity", V, law, f0, f1, T, start, phase))
    for tau in (0.37, 1.9, 3.99):
        got, _ = quad(a_x, start, start + tau, args=(floor, rec), epsabs=1e-13, limit=200)
        want = -V * math.cos(psi(tau, f0, f1, T, phase)) + V * math.cos(phase)
        assert got == pytest.approx(want, rel=0, abs=1e-11 * V)


@pytest.mark.parametrize("law", LAWS)
def test_sweep_displacement_by_quadrature(law):
    """Holding displacement D: the kernel's a_x integrated twice from the start,
    int_0^tau (tau - s) a(s) ds, equals x(tau) - x(0) - v(0) tau of the displacement law
    x = -D sin(psi), v = -D psi' cos(psi) (psi'(0) = 2 pi f0), to 1e-11 D."""
    D, f0, f1, T, start, phase = 0.01, 1.0, 3.0, 4.0, 0.5, 0.3
    psi = LAWS[law][0]
    floor, rec = floor_of(sweep("displacement", D, law, f0, f1, T, start, phase))
    v0 = -D * TWO_PI * f0 * math.cos(phase)
    for tau in (0.37, 1.9, 3.99):
        got, _ = quad(lambda s: (start + tau - s) * a_x(s, floor, rec), start, start + tau,
                      epsabs=1e-13, limit=200)
        want = -D * math.sin(psi(tau, f0, f1, T, phase)) + D * math.sin(phase) - v0 * tau
        assert got == pytest.approx(want, rel=0, abs=1e-11 * D)


# --- records --------------------------------------------------------------------------------

REC = dict(kind="record", samples=np.array([0.0, 1.0, -2.0, 0.5]), dt=0.25, scale=2.0,
           start=0.5)


def test_record_interpolation():
    """scale * (linear interpolation of the samples) at sample instants, quarter and
    mid points (start 0.5 s, dt 0.25 s: all instants exact binaries), to 1e-15."""
    floor, rec = floor_of(REC)
    s, dt, start, scale = REC["samples"], REC["dt"], REC["start"], REC["scale"]
    for i in range(3):
        for frac in (0.0, 0.25, 0.5, 0.75):
            t = start + (i + frac) * dt
            want = scale * (s[i] + frac * (s[i + 1] - s[i]))
            assert a_x(t, floor, rec) == pytest.approx(want, rel=0, abs=1e-15)


def test_record_ends_at_last_sample():
    """The last sample (scaled) exactly at its instant; zero before the start and after
    the last sample (the record has no duration); ground_end = start + (n - 1) dt."""
    floor, rec = floor_of(REC)
    end = REC["start"] + 3 * REC["dt"]
    assert a_x(end, floor, rec) == REC["scale"] * REC["samples"][-1]
    for t in (0.0, REC["start"] - 1e-9, end + 1e-9, end + REC["dt"], 10.0):
        assert a_x(t, floor, rec) == 0.0
    assert ground.ground_end(floor) == end


def test_two_records_use_their_own_samples():
    """Horizontal and vertical records share one buffer: each reads its own slice
    (a_x = 2 * 0.5 at its second sample, a_y = -3 * 7 at its first)."""
    floor, rec = floor_of(REC, {"kind": "record", "samples": [7.0, 8.0, 9.0], "dt": 0.1,
                                "scale": -3.0})
    assert rec.size == 7
    ax, ay = ground.ground(0.0, floor, rec)
    assert (ax, ay) == (0.0, -21.0)
    assert a_x(0.75, floor, rec) == pytest.approx(2.0 * 1.0, abs=1e-15)
    assert a_y(0.15, floor, rec) == pytest.approx(-3.0 * 8.5, abs=1e-13)
    assert ground.ground_end(floor) == 1.25


def test_record_duration_cuts_it():
    """A record with a duration shorter than its samples: zero from start + duration on,
    and that is its end."""
    floor, rec = floor_of({**REC, "duration": 0.4})
    assert a_x(0.5 + 0.375, floor, rec) == pytest.approx(2.0 * -0.5, abs=1e-15)
    assert a_x(0.9, floor, rec) == 0.0
    assert ground.ground_end(floor) == pytest.approx(0.9, abs=1e-15)


# --- pulses ---------------------------------------------------------------------------------

def test_rectangular_pulse():
    """amplitude inside [start, start + duration), zero outside (negative amplitude too)."""
    floor, rec = floor_of({"kind": "pulse", "shape": "rectangular", "amplitude": -3.0,
                           "duration": 0.2, "start": 0.1})
    for t in (0.1, 0.15, 0.2999):
        assert a_x(t, floor, rec) == -3.0
    for t in (0.0, 0.0999, 0.1 + 0.2, 0.5):
        assert a_x(t, floor, rec) == 0.0
    assert ground.ground_end(floor) == pytest.approx(0.3, abs=1e-16)


def test_triangular_pulse():
    """A (1 - |2 tau/T - 1|): 0 at the start, A/2 at a quarter, A at the middle, A/2 at
    three quarters, zero outside (to 1e-15 A)."""
    A, T, start = 4.0, 0.5, 0.25
    floor, rec = floor_of({"kind": "pulse", "shape": "triangular", "amplitude": A,
                           "duration": T, "start": start})
    for frac, want in ((0.0, 0.0), (0.1, 0.2 * A), (0.25, 0.5 * A), (0.5, A), (0.75, 0.5 * A),
                       (0.9, 0.2 * A)):
        assert a_x(start + frac * T, floor, rec) == pytest.approx(want, abs=1e-15 * A)
    for t in (0.0, start - 1e-9, start + T, 2.0):
        assert a_x(t, floor, rec) == 0.0


# --- breaks, end, amplitudes ----------------------------------------------------------------

def test_next_break_sine_window():
    """A sine in [1, 3): the next break is 1 before, 3 inside, none (inf) from 3 on; with
    no duration, only the start."""
    floor, _ = floor_of({"kind": "sine", "amplitude": 1.0, "frequency": 5.0, "start": 1.0,
                         "duration": 2.0})
    assert ground.next_break(0.0, floor) == 1.0
    assert ground.next_break(1.0, floor) == 3.0
    assert ground.next_break(2.5, floor) == 3.0
    assert ground.next_break(3.0, floor) == math.inf
    assert ground.ground_end(floor) == 3.0
    floor, _ = floor_of({"kind": "sine", "amplitude": 1.0, "frequency": 5.0, "start": 1.0})
    assert ground.next_break(0.5, floor) == 1.0
    assert ground.next_break(1.5, floor) == math.inf
    assert ground.ground_end(floor) == math.inf


def test_next_break_record_samples():
    """A record (start 0.5, dt 0.25, 4 samples): the next break after t is the next sample
    instant strictly after t, the start before it, inf after the last sample."""
    floor, _ = floor_of(REC)
    cases = [(0.0, 0.5), (0.5, 0.75), (0.6, 0.75), (0.75, 1.0), (0.99, 1.0), (1.0, 1.25),
             (1.1, 1.25), (1.25, math.inf), (3.0, math.inf)]
    for t, want in cases:
        assert ground.next_break(t, floor) == pytest.approx(want, abs=1e-15), t


def test_next_break_triangular_apex():
    """A triangular pulse on [0.25, 0.75): breaks at the start, the apex 0.5, the end 0.75;
    a rectangular one only at its edges."""
    floor, _ = floor_of({"kind": "pulse", "shape": "triangular", "amplitude": 1.0,
                         "duration": 0.5, "start": 0.25})
    for t, want in ((0.0, 0.25), (0.25, 0.5), (0.4, 0.5), (0.5, 0.75), (0.6, 0.75),
                    (0.75, math.inf)):
        assert ground.next_break(t, floor) == want, t
    floor, _ = floor_of({"kind": "pulse", "shape": "rectangular", "amplitude": 1.0,
                         "duration": 0.5, "start": 0.25})
    for t, want in ((0.0, 0.25), (0.25, 0.75), (0.5, 0.75), (0.75, math.inf)):
        assert ground.next_break(t, floor) == want, t


def test_next_break_and_end_of_both_components():
    """The floor's next break is the earlier of its components' and its end the later
    (horizontal sine [0, 2), vertical rectangular pulse [0.5, 0.6))."""
    floor, _ = floor_of({"kind": "sine", "amplitude": 1.0, "frequency": 2.0, "duration": 2.0},
                        {"kind": "pulse", "amplitude": 1.0, "duration": 0.1, "start": 0.5})
    assert ground.next_break(0.1, floor) == 0.5
    assert ground.next_break(0.5, floor) == pytest.approx(0.6, abs=1e-16)
    assert ground.next_break(0.7, floor) == 2.0
    assert ground.ground_end(floor) == 2.0


def test_amplitudes_sine():
    """A sine: (f, |A|, |A|/(2 pi f)) at any time."""
    floor, _ = floor_of({"kind": "sine", "amplitude": -3.0, "frequency": 2.5})
    f, A, V = ground.amplitudes(1.234, floor.x)
    assert (f, A) == (2.5, 3.0)
    assert V == pytest.approx(3.0 / (TWO_PI * 2.5), rel=1e-15)


@pytest.mark.parametrize("law", LAWS)
@pytest.mark.parametrize("hold", ["acceleration", "velocity", "displacement"])
def test_amplitudes_sweep(law, hold):
    """A sweep at start + tau: f(tau) of the law (f0 (f1/f0)^(tau/T) or f0 + (f1 - f0)
    tau/T, clamped to f0 before and f1 after), and with w = 2 pi f: A = a, V = a/w (hold
    acceleration a); A = V w, V (hold velocity V); A = D w^2, V = D w (hold displacement D);
    to 1e-13 relative."""
    amp, f0, f1, T, start = 0.3, 1.0, 3.0, 4.0, 0.5
    freq = LAWS[law][1]
    floor, _ = floor_of(sweep(hold, amp, law, f0, f1, T, start))
    for t, tau in ((0.0, 0.0), (start, 0.0), (start + 1.3, 1.3), (start + T, T),
                   (start + T + 5.0, T)):
        fw = freq(tau, f0, f1, T)
        w = TWO_PI * fw
        want_A, want_V = {"acceleration": (amp, amp / w), "velocity": (amp * w, amp),
                          "displacement": (amp * w * w, amp * w)}[hold]
        got = ground.amplitudes(t, floor.x)
        np.testing.assert_allclose(got, (fw, want_A, want_V), rtol=1e-13, atol=0)


def test_amplitudes_of_other_kinds_are_nan():
    """A pulse or a record has no amplitudes: (nan, nan, nan)."""
    floor, _ = floor_of({"kind": "pulse", "amplitude": 1.0, "duration": 0.1}, REC)
    assert all(math.isnan(v) for v in ground.amplitudes(0.05, floor.x))
    assert all(math.isnan(v) for v in ground.amplitudes(0.6, floor.y))


def test_kinds_are_packed_as_codes():
    """The api packs each kind into the code the kernel dispatches on."""
    floor, _ = floor_of({"kind": "pulse", "shape": "triangular", "amplitude": 1.0,
                         "duration": 0.1}, sweep("velocity", 0.1, "linear"))
    assert floor.x.kind == codes.G_PULSE_TRI
    assert (floor.y.kind, floor.y.law, floor.y.hold) == (codes.G_SWEEP, codes.LAW_LINEAR,
                                                        codes.HOLD_VELOCITY)
