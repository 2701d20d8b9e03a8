"""Stability on hard cases (docs/physics.md section 3): impact accumulation near West's threshold,
grazing contact and lift-off, stick-slip with friction near b/h, the Painleve region, bouncing
with e_y near 1, and overturning statistics of chaotic rocking.  Scenes and checks come from
``tests/hard_cases.py`` (the report's stability section runs the same ones); every check is
against something independent of the kernel: scipy re-integrating each flight, closed forms,
energy conservation, binomial statistics.
"""
import math

import numpy as np
import pytest

import hard_cases as hc
from naive import body_constants, zeno_time
from kernels.api import run_scene

ETA = body_constants(hc.B, hc.H)[5]
ZENO_DT = 1e-6                      # the default Zeno closure time (README, Conventions)
EVENT_CAP = 20_000                  # far inside the default budget of 1e6 events
OK = ("ok", "overturned")


def _finite(r):
    values = [r.max_abs_theta, r.max_slip, r.max_lift, r.t_final, *r.mode_time.values(),
              *r.impact_times, *r.omega_after]
    return all(math.isfinite(v) for v in values)


def _times_add_up(r, t_end):
    t_sim = r.t_overturn if r.overturned else (r.t_final if r.status != "ok" else t_end)
    return sum(r.mode_time.values()) == pytest.approx(t_sim, abs=1e-9)


# --- impact accumulation (Zeno) near West's threshold -------------------------------------------

@pytest.mark.parametrize("excess", [1e-3, 1e-2, 3e-2])
def test_zeno_bursts_impact_by_impact(excess):
    """(1 + excess) West at 2 Hz for 5 s, Housner contact: hundreds of impacts in bursts that
    end by the Zeno closure.  Each flight re-integrated by scipy from the kernel's state after
    the previous impact lands within 1e-7 s of the kernel's impact; omega+ = eta omega-
    (docs/physics.md 2.1), so energy is never gained; every closure, and only a closure, follows an
    impact whose next flight would last less than zeno_dt; a burst has no more impacts than twice
    the free-rocking count from a half-period flight down to zeno_dt."""
    sc = hc.resolved(hc.near_threshold(excess, hc.HOUSNER))
    r = run_scene(sc)
    assert r.status == "ok" and _finite(r)
    check = hc.lockstep(r, sc)
    assert check.max_time_error < 1e-7
    assert check.max_ratio_error < 1e-4
    assert check.gained == 0 and check.bad_closures == 0
    assert check.closures >= 1
    assert check.impacts <= 2 * hc.burst_bound(2.0, ZENO_DT, ETA) * check.closures


EXCESSES = [1e-9, 1e-7, 1e-5, 1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 2e-2, 4e-2]


@pytest.mark.parametrize("contact", [hc.HOUSNER, hc.PAPER], ids=["housner", "paper"])
def test_zeno_many_amplitudes_end(contact):
    """Ten amplitudes from 1 + 1e-9 to 1.04 West, forcing for 5 s then a still floor: every
    run ends ok with finite results, far inside the event budget, mode times adding up; with
    Housner's contact the block rests no later than the A4 accumulation time of free rocking
    from its largest amplitude after the floor stops."""
    for excess in EXCESSES:
        r = run_scene(hc.resolved(hc.near_threshold(excess, contact)))
        assert r.status == "ok" and _finite(r), excess
        assert r.events < EVENT_CAP, excess
        assert _times_add_up(r, 8.0), excess
        assert r.t_rest is not None, excess
        if contact is hc.HOUSNER and r.max_abs_theta > 0:
            assert r.t_rest <= 5.0 + zeno_time(hc.B, hc.H, r.max_abs_theta) + 1e-3, excess


# --- grazing ---------------------------------------------------------------------------------

def test_grazing_from_below_never_moves():
    """(1 - 1e-9) West: the floor never quite reaches the threshold; the block never moves."""
    r = run_scene(hc.resolved(hc.near_threshold(-1e-9, hc.HOUSNER)))
    assert r.status == "ok" and r.max_abs_theta == 0.0 and not r.impact_times
    assert r.mode_time["rest"] == 8.0


@pytest.mark.parametrize("excess", [1e-9, 1e-6])
def test_grazing_from_above_one_impact_per_half_period(excess):
    """(1 + excess) West at 2 Hz for 5 s: the floor exceeds the threshold for microseconds
    each half period; the block tips by far less than a micro-radian and falls back with one
    impact that the Zeno closure ends: 20 impacts, each in its own half period."""
    r = run_scene(hc.resolved(hc.near_threshold(excess, hc.HOUSNER)))
    assert r.status == "ok" and _finite(r)
    assert r.max_abs_theta < 1e-6
    t = np.array(r.impact_times)
    assert t.size == 20
    np.testing.assert_array_equal(np.floor(t / 0.25), np.arange(20))


@pytest.mark.parametrize("delta", [1e-2, 1e-3, 1e-4, 1e-6])
def test_grazing_liftoff(delta):
    """a_y = -(1 + delta) g sin(2 pi 5 t) for one cycle: a flat hop that barely leaves the
    floor.  Landing time, flight time and largest lift match the closed form of
    ``liftoff_closed_form`` (relative error O(delta)); one landing, then rest."""
    t_land, flight, lift = hc.liftoff_closed_form(delta)
    r = run_scene(hc.resolved(hc.grazing_liftoff(delta, rtol=1e-10, atol=1e-12)))
    assert r.status == "ok" and _finite(r) and r.max_abs_theta == 0.0
    assert len(r.impact_times) == 1
    assert r.impact_times[0] == pytest.approx(t_land, abs=5 * delta * flight + 1e-6)
    assert r.mode_time["translation_jump"] == pytest.approx(flight,
                                                            abs=5 * delta * flight + 1e-6)
    assert r.max_lift == pytest.approx(lift, rel=5 * delta, abs=1e-10)


# --- stick-slip with friction near b/h ----------------------------------------------------------

@pytest.mark.parametrize("excess", [-1e-2, -1e-6, 0.0, 1e-6, 1e-2])
def test_stick_slip_near_b_over_h(excess):
    """mu = (b/h)(1 + excess) under 1.2 West at 2 Hz for 10 s: stick, slip, slide-rotation
    chatter.  Every run ends with finite results far inside the budget; with mu <= b/h the
    block only slides (a flat slide cannot start rocking, and from stick the rest table of
    docs/physics.md 1.3 gives slide since mu_s < mu_req and mu_edge_k <= b/h)."""
    r = run_scene(hc.resolved(hc.stick_slip(excess)))
    assert r.status in OK and _finite(r)
    assert r.events < EVENT_CAP
    assert _times_add_up(r, 10.0)
    if excess <= 0:
        assert r.max_abs_theta == 0.0 and not r.impact_times
        assert r.mode_time["slide"] > 0


# --- the Painleve region ----------------------------------------------------------------------

def test_painleve_region():
    """Edge friction 1.0, 1.3 (below 4/3), 1.34, 1.5, 2.0, 5.0 (above), three blocks, a
    2-west sine and El Centro NS + UD x3, e_x = -1, -0.8, 0 (108 runs): each run ends ok,
    overturned or with status painleve (never a hang, a budget exhaustion or a NaN); none is
    painleve below 4/3."""
    for label, sc, mu in hc.painleve_scenes():
        r = run_scene(hc.resolved(sc))
        assert r.status in ("ok", "overturned", "painleve"), label
        assert _finite(r) and r.t_final <= 20.0, label
        assert r.events < EVENT_CAP, label
        if mu < hc.MU_PAINLEVE:
            assert r.status != "painleve", label    # docs/physics.md 3.2: none below 4/3


# --- bouncing with e_y near 1 ---------------------------------------------------------------------

@pytest.mark.parametrize("e_y", [0.9, 0.99, 1.0])
def test_bouncing_energy_never_rises(e_y):
    """1.5 West at 4 Hz for 2 s, then a still floor, e_y near 1 (e_x = -0.8, mu = 0.8): with
    the floor still, the mechanical energy from the history (every 1 ms) never rises, across
    hundreds of impacts and jumps, by more than 1e-9 of itself."""
    sc = hc.resolved(hc.bouncing(e_y, rtol=1e-10, atol=1e-12))
    r = run_scene(sc, history=True)
    assert r.status == "ok" and _finite(r)
    assert len(r.impact_times) > 100 and r.mode_time["rotation_jump"] > 0
    e0, rise, _ = hc.energy_after(r, sc, 2.0)
    assert rise < 1e-9 * e0


def test_elastic_frictionless_conserves_energy():
    """e_y = 1, e_x = -1, mu = 0: no contact can dissipate; after the floor stops the energy
    stays constant to 1e-8 over 4 s of bouncing."""
    sc = hc.resolved(hc.bouncing(1.0, e_x=-1.0, mu=0.0, rtol=1e-11, atol=1e-13))
    r = run_scene(sc, history=True)
    assert r.status == "ok" and _finite(r) and len(r.impact_times) > 50
    e0, rise, e1 = hc.energy_after(r, sc, 2.0)
    assert e1 == pytest.approx(e0, rel=1e-8)
    assert rise < 1e-9 * e0


# --- chaotic rocking: statistics agree, trajectories do not ------------------------------------

def _statistics_agree(n, seed, solvers):
    """Overturning over n random phases under each solver setting, against the first: the
    fractions agree within binomial sampling error (exact McNemar test on the discordant
    pairs, p >= 0.01); returns the result rows of the first two settings."""
    phases = hc.ensemble_phases(n, seed)
    runs = [hc.phase_ensemble(phases, **solver) for solver in solvers]
    reference = hc.overturned(runs[0])
    assert 0.1 * n <= reference.sum() <= 0.9 * n     # a fraction a sample can measure
    for solver, run in zip(solvers[1:], runs[1:]):
        stats = hc.compare_fractions(hc.overturned(run), reference)
        assert stats.p_value >= 0.01, (solver, stats)
    return runs


def test_overturning_statistics_agree_between_tolerances():
    """200 random phases of the vertical excitation, rtol 1e-9 and 1e-6: the overturning
    fractions agree within binomial sampling error, while single trajectories do not (some
    overturning times differ by more than 1 ms)."""
    tight, loose = _statistics_agree(200, 1, [hc.tolerance(1e-9), hc.tolerance(1e-6)])
    both = hc.overturned(tight) & hc.overturned(loose)
    t_tight, t_loose = (r["t_overturn"] for r in (tight, loose))
    assert np.any(np.abs(t_tight[both] - t_loose[both]) > 1e-3)


@pytest.mark.slow
def test_overturning_statistics_agree_many():
    """1,000 phases: rtol 1e-9 against rtol 1e-6 and against the paper's fixed 1 ms step."""
    _statistics_agree(1000, 2, [hc.tolerance(1e-9), hc.tolerance(1e-6),
                                {"method": "fixed", "dt": 1e-3}])
