"""``rest_skipping.rest_exit``: the first time in [t, t_stop) at which
|a_x| - kappa (g + a_y) > 0, against closed-form crossing times of sines, pulses, records
and a combined horizontal and vertical motion (asin of the threshold ratio, linear ramps),
and ``rest_threshold`` = min(mu_s, b/h).
"""
import math
from types import SimpleNamespace

import numpy as np
import pytest

from kernels import api, rest_skipping, state

G = 9.80665
TWO_PI = 2.0 * math.pi
XTOL = 2e-13       # the crossing is bisected to 1e-13 (relative to max(1, t))


def scene_of(horizontal=None, vertical=None, **contact):
    records = []
    row = api.scene_row({"body": {"B": 0.1, "H": 0.3}, "contact": contact,
                         "excitation": {"horizontal": horizontal, "vertical": vertical}},
                        records)
    b, h = 0.5 * row.body.B, 0.5 * row.body.H
    c = row.contact
    scene = SimpleNamespace(floor=row.floor, body=state.Body(b, b, h, row.body.i2),
                            contact=state.Contact(*(float(c[name]) for name in c.dtype.names)))
    return scene, api.record_buffer(records)


def exit_time(horizontal=None, vertical=None, kappa=0.3, t=0.0, t_stop=10.0):
    scene, rec = scene_of(horizontal, vertical)
    return rest_skipping.rest_exit(t, t_stop, (kappa, kappa, 0.0), scene.floor, rec)


def sine(A, f, **kw):
    return {"kind": "sine", "amplitude": A, "frequency": f, **kw}


def assert_crossing(got, want, tol=XTOL):
    """got within tol of want and not before it (up to round-off)."""
    assert want - 1e-15 <= got <= want + tol, (got, want, got - want)


# --- horizontal sine ------------------------------------------------------------------------

@pytest.mark.parametrize("phase", [0.0, math.pi], ids=["positive", "negative"])
def test_sine_above_threshold(phase):
    """A sin(2 pi f t + phase), A = 5 > kappa g (kappa = 0.3, f = 2 Hz): exit at
    asin(kappa g / A) / (2 pi f) whether the first half-cycle is positive or negative
    (|a_x| counts), to 2e-13 s."""
    A, f, kappa = 5.0, 2.0, 0.3
    got = exit_time(sine(A, f, phase=phase), kappa=kappa)
    assert_crossing(got, math.asin(kappa * G / A) / (TWO_PI * f))


def test_sine_with_delayed_start():
    """A sine starting at 0.7 s: exit at 0.7 + asin(kappa g / A) / (2 pi f)."""
    A, f, kappa = 4.0, 3.0, 0.2
    got = exit_time(sine(A, f, start=0.7), kappa=kappa)
    assert_crossing(got, 0.7 + math.asin(kappa * G / A) / (TWO_PI * f))


def test_sine_below_threshold():
    """A = 0.99 kappa g never exceeds the threshold: inf (scanned up to t_stop = 5 s)."""
    kappa = 0.3
    assert exit_time(sine(0.99 * kappa * G, 2.0), kappa=kappa, t_stop=5.0) == math.inf


def test_sine_exceeding_at_start_time():
    """Starting at the quarter period (A sin = A > kappa g already): returns t itself."""
    A, f = 5.0, 2.0
    t = 0.25 / f
    assert exit_time(sine(A, f), kappa=0.3, t=t) == t


def test_later_start_time_finds_next_half_cycle():
    """Starting just after the first half-cycle's excursion (at half a period), the exit is
    in the negative half-cycle: (pi + asin(kappa g / A)) / (2 pi f)."""
    A, f, kappa = 5.0, 2.0, 0.3
    got = exit_time(sine(A, f), kappa=kappa, t=0.5 / f)
    assert_crossing(got, (math.pi + math.asin(kappa * G / A)) / (TWO_PI * f))


def test_crossing_after_t_stop_or_window():
    """The crossing at asin(kappa g / A)/(2 pi f) = 0.0271 s lies after t_stop = 0.02 s: inf;
    a sine whose window [0, 0.02) ends before it: inf."""
    A, f, kappa = 2.0, 3.0, 0.1
    t_cross = math.asin(kappa * G / A) / (TWO_PI * f)
    assert 0.02 < t_cross < 0.03
    assert exit_time(sine(A, f), kappa=kappa, t_stop=0.02) == math.inf
    assert exit_time(sine(A, f, duration=0.02), kappa=kappa) == math.inf
    assert_crossing(exit_time(sine(A, f), kappa=kappa, t_stop=0.03), t_cross)


def test_brief_excursion_between_scan_samples():
    """A = kappa g (1 + 1e-6), phase 0.3, f = 2 Hz: |a_x| exceeds kappa g only within
    +-1.1e-5 s of the peak at (pi/2 - 0.3)/(2 pi f), which the scan samples (every 1/32 s)
    miss; the exit is the closed-form crossing (asin(kappa g / A) - 0.3)/(2 pi f), to 1e-12 s
    (a flat crossing)."""
    kappa, f, phase = 0.3, 2.0, 0.3
    A = kappa * G * (1.0 + 1e-6)
    got = exit_time(sine(A, f, phase=phase), kappa=kappa)
    assert_crossing(got, (math.asin(kappa * G / A) - phase) / (TWO_PI * f), tol=1e-12)


# --- pulses and records ---------------------------------------------------------------------

def test_short_triangular_pulse_barely_above():
    """Triangular pulse of 1 ms from 0.3 s with peak A = kappa g (1 + 1e-6): exit at
    start + (kappa g / A) dur / 2 on its rising side."""
    kappa, dur, start = 0.3, 1e-3, 0.3
    A = kappa * G * (1.0 + 1e-6)
    got = exit_time({"kind": "pulse", "shape": "triangular", "amplitude": A, "duration": dur,
                     "start": start}, kappa=kappa)
    assert_crossing(got, start + (kappa * G / A) * dur / 2)


def test_triangular_pulse_below_threshold():
    """The same pulse with peak kappa g (1 - 1e-6): inf."""
    kappa = 0.3
    pulse = {"kind": "pulse", "shape": "triangular", "amplitude": kappa * G * (1 - 1e-6),
             "duration": 1e-3, "start": 0.3}
    assert exit_time(pulse, kappa=kappa) == math.inf


def test_rectangular_pulse_exit_at_its_start():
    """A rectangular pulse above the threshold from 0.3 s: the exit is its start, 0.3."""
    pulse = {"kind": "pulse", "amplitude": -4.0, "duration": 0.1, "start": 0.3}
    assert exit_time(pulse, kappa=0.3) == 0.3


def test_record_ramp():
    """Record samples (0, 0, 10, 0) m/s^2 every 0.25 s: a_x rises linearly from 0 at 0.25 s to
    10 at 0.5 s, so the exit is 0.25 + 0.25 kappa g / 10."""
    kappa = 0.3
    rec = {"kind": "record", "samples": np.array([0.0, 0.0, 10.0, 0.0]), "dt": 0.25}
    assert_crossing(exit_time(rec, kappa=kappa), 0.25 + 0.25 * kappa * G / 10.0)


# --- vertical motion ------------------------------------------------------------------------

def test_vertical_sine_free_fall():
    """Vertical A sin(2 pi f t), A = 12 > g: the floor falls faster than g (a_y < -g) from
    (pi + asin(g / A)) / (2 pi f) on, whatever kappa."""
    A, f = 12.0, 2.0
    want = (math.pi + math.asin(G / A)) / (TWO_PI * f)
    for kappa in (0.1, 0.5):
        assert_crossing(exit_time(None, sine(A, f), kappa=kappa), want)


def test_vertical_sine_below_g():
    """Vertical A = 0.95 g alone never lifts the body: inf."""
    assert exit_time(None, sine(0.95 * G, 2.0), t_stop=3.0) == math.inf


def test_combined_horizontal_and_vertical():
    """a_x = 2.5 sin(2 pi f t) alone stays below kappa g = 2.94 (inf); with a_y = -3 sin(2 pi
    f t) the effective gravity drops in the positive half-cycle and the exit is at
    asin(kappa g / (2.5 + 3 kappa)) / (2 pi f)."""
    kappa, f = 0.3, 2.0
    assert exit_time(sine(2.5, f), kappa=kappa, t_stop=3.0) == math.inf
    got = exit_time(sine(2.5, f), sine(-3.0, f), kappa=kappa)
    assert_crossing(got, math.asin(kappa * G / (2.5 + 3.0 * kappa)) / (TWO_PI * f))


# --- threshold ------------------------------------------------------------------------------

@pytest.mark.parametrize("mu_s, want", [(0.2, 0.2), (0.5, 1 / 3)])
def test_rest_threshold(mu_s, want):
    """kappa = min(mu_s, b/h) towards each side and no constant term (a free body); the
    0.1 x 0.3 block has b/h = 1/3."""
    scene, _ = scene_of(mu_s=mu_s)
    assert rest_skipping.rest_threshold(scene.body, scene.contact) == pytest.approx(
        (want, want, 0.0), rel=1e-15)
