"""Exact invariances of the model (docs/physics.md anchor A1).

(a) Mirror: a_x -> -a_x gives x -> -x, theta -> -theta, u -> -u, omega -> -omega, the same y,
v and impact times, and the opposite overturning direction.  (b) Similarity: lengths x lambda,
times x sqrt(lambda) (frequencies / sqrt(lambda)), accelerations, friction and restitution
kept: theta(t) and x(t)/lambda are the same functions of t/sqrt(lambda).
"""
import math

import numpy as np
import pytest

from kernels.api import run_scene
from scenes import G, pulse, scene, sine

# (name, scene keyword arguments) of scenes that visit different modes
MIRROR_SCENES = [
    ("rocking", dict(mu=10.0, horizontal=sine(0.5 * G, 4.0))),
    ("slide_rock_jump", dict(mu=0.4, e_x=-0.8, e_y=0.2, horizontal=sine(0.5 * G, 4.0))),
    ("sliding", dict(B=0.3, H=0.3, mu=0.2, e_x=-0.8, e_y=0.2, horizontal=sine(0.5 * G, 2.0))),
    ("overturning", dict(mu=0.5, e_x=-0.5, e_y=0.3, horizontal=sine(0.4 * G, 1.5))),
    ("pulse_with_vertical", dict(mu=0.6, e_x=0.0, e_y=0.3, horizontal=pulse(0.6 * G, 0.15),
                                 vertical=sine(0.4 * G, 5.0))),
]


def _mirrored(ground):
    return {**ground, "amplitude": -ground["amplitude"]}


@pytest.mark.parametrize("name, kw", MIRROR_SCENES, ids=[n for n, _ in MIRROR_SCENES])
def test_mirror(name, kw):
    kw_m = {**kw, "horizontal": _mirrored(kw["horizontal"])}
    r = run_scene(scene(**kw, t_end=5.0, dt_out=0.01), history=True)
    m = run_scene(scene(**kw_m, t_end=5.0, dt_out=0.01), history=True)
    assert r.status == m.status
    h, hm = r.history, m.history
    for key, sign in (("x", -1), ("theta", -1), ("u", -1), ("omega", -1), ("y", 1), ("v", 1),
                      ("a_x", -1), ("a_y", 1)):
        np.testing.assert_allclose(hm[key], sign * h[key], rtol=0, atol=1e-12,
                                   err_msg=f"{name}: {key}")
    np.testing.assert_array_equal(hm["mode"], h["mode"])
    np.testing.assert_allclose(m.impact_times, r.impact_times, rtol=0, atol=1e-12)
    np.testing.assert_allclose(m.omega_after, -np.array(r.omega_after), rtol=0, atol=1e-12)
    assert m.mode_time == pytest.approx(r.mode_time, abs=1e-12)
    assert m.max_abs_theta == pytest.approx(r.max_abs_theta, abs=1e-12)
    assert m.max_slip == pytest.approx(r.max_slip, abs=1e-12)
    if name == "overturning":
        assert r.overturned and m.overturned
        assert m.overturn_direction == -r.overturn_direction
        assert m.t_overturn == pytest.approx(r.t_overturn, abs=1e-12)
    if name == "sliding":
        assert r.mode_time["slide"] > 1.0 and r.max_abs_theta == 0.0


SIMILAR_SCENES = [
    ("rocking", dict(mu=10.0), 0.5 * G, 4.0),
    ("slide_rock_jump", dict(mu=0.4, e_x=-0.8, e_y=0.2), 0.5 * G, 4.0),
    ("overturning", dict(mu=0.5, e_x=-0.5, e_y=0.3), 0.4 * G, 1.5),
]


@pytest.mark.parametrize("name, kw, A, f", SIMILAR_SCENES, ids=[n for n, *_ in SIMILAR_SCENES])
def test_similarity(name, kw, A, f):
    """B = 0.2, H = 0.6 under f/sqrt(2) reproduces B = 0.1, H = 0.3 under f, times x sqrt(2).

    Every time-like solver option (zeno_dt, max_step, dt_out) is scaled too, so that the
    two runs are the same computation in scaled units; impact times agree to 1e-6 relative.
    """
    lam, s = 2.0, math.sqrt(2.0)
    solver = dict(rtol=1e-10, atol=1e-12)
    r = run_scene(scene(0.1, 0.3, horizontal=sine(A, f), t_end=5.0, dt_out=0.01,
                        zeno_dt=1e-6, max_step=0.05, **kw, **solver), history=True)
    q = run_scene(scene(0.1 * lam, 0.3 * lam, horizontal=sine(A, f / s), t_end=5.0 * s,
                        dt_out=0.01 * s, zeno_dt=1e-6 * s, max_step=0.05 * s, **kw,
                        rtol=1e-10, atol=1e-12 * lam), history=True)
    assert r.status == q.status
    t, tq = np.array(r.impact_times), np.array(q.impact_times) / s
    assert t.size == tq.size and t.size > 5
    for k in range(t.size):
        np.testing.assert_allclose(tq[k], t[k], rtol=1e-6, err_msg=f"impact {k} at {t[k]:.6f}")
    np.testing.assert_allclose(np.array(q.omega_after) * s, r.omega_after, rtol=1e-5,
                               atol=1e-8)
    n = min(r.history["t"].size, q.history["t"].size)
    np.testing.assert_allclose(q.history["theta"][:n], r.history["theta"][:n], atol=1e-7)
    np.testing.assert_allclose(q.history["x"][:n] / lam, r.history["x"][:n], atol=1e-7)
    if r.overturned:
        assert q.t_overturn / s == pytest.approx(r.t_overturn, rel=1e-6)
