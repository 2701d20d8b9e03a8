"""The loop of ``driver.run_scene`` takes at most one Runge-Kutta step or one interval of a
rest's scan a pass (the step to a located event is the next pass's), counted on the plain
Python kernel; and ``rest_skipping``'s scan, one interval at a time, against the closed-form
intervals and crossing of a sine that starts late.
"""
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest

from kernels import rest_skipping

from test_rest_skipping import G, XTOL, assert_crossing, scene_of

ROOT = Path(__file__).resolve().parents[2]

# Every pass of the loop reads ctl[CTL_STOP] once, at its top: a control array that notes
# those reads cuts the calls of ``step`` and ``rest_interval`` into passes.
COUNT_PASSES = r"""
import json, sys
import numpy as np
from kernels import api, codes, driver

trace = []


class Control(np.ndarray):
    def __getitem__(self, i):
        if i == codes.CTL_STOP:
            trace.append("|")
        return super().__getitem__(i)


def noting(f, mark):
    def call(*args):
        trace.append(mark)
        return f(*args)
    return call


control = api.control
api.control = lambda cell: control(cell).view(Control)
driver.step = noting(driver.step, "S")
driver.rest_interval = noting(driver.rest_interval, "R")
r = api.run_scene(json.loads(sys.argv[1]))
print(json.dumps({"passes": "".join(trace).split("|")[1:], "steps": r.steps,
                  "events": r.events, "impacts": r.impact_count, "status": r.status,
                  "rest": r.mode_time["rest"]}))
"""

FRICTION = {name: 0.8 for name in ("mu_s", "mu_k", "mu_edge_s", "mu_edge_k")}
ROCKING = {"body": {"B": 0.1, "H": 0.3}, "contact": {**FRICTION, "e_x": -0.8, "e_y": 0.2},
           "excitation": {"horizontal": {"kind": "sine", "amplitude": 3.5, "frequency": 2.0,
                                         "start": 0.7, "duration": 0.5}},
           "solver": {"t_end": 2.0}}


@pytest.fixture(scope="module")
def passes():
    """The calls of each pass of a block at rest, then rocking with impacts and at rest
    again, run as plain Python (NUMBA_DISABLE_JIT=1)."""
    env = {**os.environ, "NUMBA_DISABLE_JIT": "1"}
    ran = subprocess.run([sys.executable, "-c", COUNT_PASSES, json.dumps(ROCKING)], env=env,
                         cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert ran.returncode == 0, ran.stderr
    return json.loads(ran.stdout)


def test_at_most_one_step_or_scan_interval_a_pass(passes):
    """No pass calls ``step`` twice, ``rest_interval`` twice or both."""
    assert passes["status"] == "ok" and passes["impacts"] > 10
    assert max(len(p) for p in passes["passes"]) == 1


def test_the_step_to_an_event_is_a_pass_of_its_own(passes):
    """``steps`` counts the steps that the error control took; every event located inside
    one adds a step to it (an event found on the step's start adds none): more calls of
    ``step`` than steps, at most one more per event, each in the pass after a step."""
    calls = "".join(passes["passes"])
    extra = calls.count("S") - passes["steps"]
    assert 0 < extra <= passes["events"]
    assert "SS" in calls            # passes of one step each, back to back


def test_a_rest_is_scanned_over_several_passes(passes):
    """The block (kappa = min(mu_s, b/h) = 1/3) rests until A sin(2 pi f (t - 0.7)) =
    kappa g: its scan takes intervals of 1/(8 f) = 1/16 s, 12 up to the sine's start (the
    12th cut there) and then ceil(16 asin(kappa g / A) / (2 pi f)) more, one a pass, with
    no step before; the rest lasts at least that long."""
    A, f, start, kappa = 3.5, 2.0, 0.7, 1.0 / 3.0
    after = math.asin(kappa * G / A) / (2.0 * math.pi * f)
    calls = "".join(passes["passes"])
    first_step = calls.index("S")
    assert first_step == math.ceil(16 * start) + math.ceil(16 * after)
    assert passes["passes"][:first_step] == ["R"] * first_step
    assert passes["rest"] > start + after


def scan(horizontal, kappa, t_stop):
    """The intervals (ta, tb, t_e, phi_b) of a scan from t = 0, one ``rest_interval`` each."""
    scene, rec = scene_of(horizontal)
    k = (kappa, kappa, 0.0)
    t_e, phi_a, t_scan = rest_skipping.rest_begin(0.0, t_stop, k, scene.floor, rec)
    assert t_e == math.inf and phi_a == pytest.approx(-kappa * G, rel=1e-15)
    ta, out = 0.0, []
    while rest_skipping.rest_scanning(t_e, ta, t_scan):
        t_e, tb, phi_a = rest_skipping.rest_interval(ta, phi_a, t_scan, k, scene.floor, rec)
        out.append((ta, tb, t_e, phi_a))
        ta = tb
    return out


def test_scan_intervals_and_crossing_of_a_late_sine():
    """A sin(2 pi f (t - 0.7)) from 0.7 s, A = 1.02 kappa g, f = 2 Hz: intervals of
    1/(8 f) = 1/16 s from 0, the 12th cut at the start 0.7 s, phi = -kappa g at their ends
    before it and |A sin| - kappa g after; the crossing 0.7 + asin(kappa g / A)/(2 pi f)
    found in the interval [0.7625, 0.825] that holds it."""
    A, f, kappa, start = 1.02 * 0.3 * G, 2.0, 0.3, 0.7
    intervals = scan({"kind": "sine", "amplitude": A, "frequency": f, "start": start},
                     kappa, 10.0)
    ends = [k / 16.0 for k in range(1, 12)] + [start, start + 1 / 16.0, start + 2 / 16.0]
    assert [tb for _, tb, _, _ in intervals] == pytest.approx(ends, rel=1e-15)
    for ta, tb, t_e, phi_b in intervals[:-1]:
        assert t_e == math.inf
        a_x = A * abs(math.sin(2.0 * math.pi * f * (tb - start))) if tb > start else 0.0
        assert phi_b == pytest.approx(a_x - kappa * G, rel=1e-12, abs=1e-12)
    ta, tb, t_e, _ = intervals[-1]
    want = start + math.asin(kappa * G / A) / (2.0 * math.pi * f)
    assert ta < want < tb
    assert_crossing(t_e, want, XTOL)


def test_scan_below_threshold_ends_at_t_stop():
    """A = 0.99 kappa g never moves the body: 16 intervals of 1/16 s up to t_stop = 1 s,
    none with a crossing."""
    intervals = scan({"kind": "sine", "amplitude": 0.99 * 0.3 * G, "frequency": 2.0},
                     0.3, 1.0)
    assert len(intervals) == 16 and intervals[-1][1] == 1.0
    assert all(t_e == math.inf for _, _, t_e, _ in intervals)


def test_scan_starts_where_the_floor_moves_the_body_already():
    """At the quarter period of A sin(2 pi f t), A = 5 > kappa g: rest ends at once, phi =
    A - kappa g there."""
    scene, rec = scene_of({"kind": "sine", "amplitude": 5.0, "frequency": 2.0})
    t_e, phi, _ = rest_skipping.rest_begin(0.125, 10.0, (0.3, 0.3, 0.0), scene.floor, rec)
    assert t_e == 0.125 and phi == pytest.approx(5.0 - 0.3 * G, rel=1e-12)
