"""Landing after a translation jump (docs/landing.md): the face_friction law against its
closed forms (L1)-(L5), energy never gained (L6), no rotation with e_x = -1, the tilt
direction by the moment balance, Ishiyama's Eq. (8) and its threshold v_H, and the four
panels of Fig. 5 under each law (only face_friction gives the paper's four outcomes)."""
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from kernels.api import DEFAULTS, run_scene
from kernels.codes import (HISTORY_NAMES, IMPACT_PAINLEVE, LANDING_CORNER,
                           LANDING_FACE_FRICTION, LANDING_NAMES, SLIPPED)
from kernels.corner_impact import corner_impact
from kernels.face_impact import landing_impact
from kernels.state import Body, Contact
from scenes import G, const, scene, sine
from sweep import simulate

STUDIES = Path(__file__).resolve().parents[2] / "studies"
FACE = float(LANDING_FACE_FRICTION)


def _ke(q, i2):
    return 0.5 * (q[3] ** 2 + q[4] ** 2 + i2 * q[5] ** 2)


def _land(u, v, body, e_x, e_y, mu_s, mu_k, landing=FACE, mu_edge=None):
    """State after ``landing_impact`` of a flat landing at (u, v) and its flag bits."""
    q = np.array([0.0, body.h, 0.0, u, v, 0.0])
    edge = (mu_s, mu_k) if mu_edge is None else mu_edge
    flags = landing_impact(q, body, Contact(mu_s, mu_k, *edge, e_x, e_y, landing))
    return q, flags


def face_friction(u, v, e_x, e_y, mu_s, mu_k, b, h, i2):
    """(u+, v+, omega+, slipped) of the impulse at the middle of the base, (L1)-(L3)."""
    Pn = -(1.0 + e_y) * v                              # (L1)
    Pt = -(1.0 + e_x) * u * i2 / (i2 + h * h)          # (L2), the base sticks
    slipped = abs(Pt) > mu_s * Pn
    if slipped:                                        # (L2), it slips
        Pt = -math.copysign(mu_k * Pn, u)
    return u + Pt, v + Pn, h * Pt / i2, slipped        # (L3)


# B, H, u-, v-, e_x, e_y, mu_s, mu_k: no corner driven into the floor after (L3), i.e. not (L4)
NO_CORNER = [
    (0.1, 0.3, 1.0, -1.7152, -0.9, 0.2, 0.4, 0.3),     # Fig. 5b's landing
    (0.1, 0.3, 1.0, -1.7152, -0.9, 0.8, 0.4, 0.3),     # Fig. 5d's landing
    (0.1, 0.3, -0.6, -2.0, -0.5, 0.5, 0.4, 0.3),       # moving left
    (0.4, 0.4, 2.0, -1.5, -0.5, 0.9, 0.5, 0.5),        # a square
    (0.1, 0.3, 3.0, -1.0, 0.0, 0.5, 0.4, 0.3),         # friction-bounded: the base slips
    (0.2, 0.3, -2.5, -0.8, 0.5, 0.7, 0.3, 0.2),        # slips, e_x > 0, mu_k < mu_s
]


@pytest.mark.parametrize("B, H, u, v, e_x, e_y, mu_s, mu_k", NO_CORNER)
def test_face_friction_closed_form(B, H, u, v, e_x, e_y, mu_s, mu_k):
    """Without a corner struck after it, the landing is (L1)-(L3) exactly, the base slipping
    (flag SLIPPED) when the sticking impulse leaves the surface's friction cone."""
    c = const(B, H)
    up, vp, wp, slipped = face_friction(u, v, e_x, e_y, mu_s, mu_k, c.b, c.h, c.i2)
    assert min(vp - c.b * wp, vp + c.b * wp) > 0.0     # (L4) does not hold: no corner strikes
    q, flags = _land(u, v, Body(c.b, c.b, c.h, c.i2), e_x, e_y, mu_s, mu_k)
    np.testing.assert_allclose(q[3:], [up, vp, wp], rtol=1e-13, atol=1e-15)
    assert bool(flags & SLIPPED) == slipped
    assert math.copysign(1.0, wp) == -math.copysign(1.0, u)   # tilts forward (L0): M = h P_t


def test_friction_bounded_case_is_in_the_cases():
    """The cases above hold sticking and slipping bases."""
    slipped = [face_friction(u, v, ex, ey, ms, mk, 0.5 * B, 0.5 * H, (B * B + H * H) / 12)[3]
               for B, H, u, v, ex, ey, ms, mk in NO_CORNER]
    assert any(slipped) and not all(slipped)


@pytest.mark.parametrize("B, H, u, v", [(0.1, 0.3, 1.0, -1.7152), (0.2, 0.5, 0.7, -2.0),
                                        (0.1, 0.3, -0.4, -1.0), (0.6, 0.3, 0.3, -0.5)])
def test_eq8_when_the_leading_corner_strikes(B, H, u, v):
    """e_x = e_y = 0 and enough friction: the leading corner strikes after (L3) and the body
    rocks about it with omega = -h u-/(i^2 + r^2), Ishiyama's Eq. (8) (L5): the corner stops,
    so G moves at u = h^2 u-/(i^2 + r^2), v = b h |u-|/(i^2 + r^2)."""
    c = const(B, H)
    body = Body(c.b, c.b, c.h, c.i2)
    w = face_friction(u, v, 0.0, 0.0, 1.0, 1.0, c.b, c.h, c.i2)[2]
    assert c.b * abs(w) > 0.0                          # (L4) with e_y = 0: the corner strikes
    q, flags = _land(u, v, body, 0.0, 0.0, 1.0, 1.0)
    den = c.i2 + c.r * c.r
    np.testing.assert_allclose(q[3:], [c.h ** 2 * u / den, c.b * c.h * abs(u) / den,
                                       -c.h * u / den], rtol=1e-12, atol=1e-15)
    assert not flags & SLIPPED


def _cases():
    """A grid of landings: e_x in [-1, 1], e_y in [0, 1], three frictions, speeds both ways,
    two bodies."""
    for B, H in ((0.1, 0.3), (0.4, 0.4)):
        c = const(B, H)
        for e_x in np.linspace(-1.0, 1.0, 11):
            for e_y in np.linspace(0.0, 1.0, 6):
                for mu in (0.1, 0.4, 1.0):
                    for u in (-2.0, 0.3, 1.0, 3.0):
                        for v in (-0.3, -1.7, -3.0):
                            yield Body(c.b, c.b, c.h, c.i2), u, v, e_x, e_y, mu


@pytest.mark.parametrize("landing", [LANDING_FACE_FRICTION, LANDING_CORNER])
def test_landing_never_gains_energy(landing):
    """No landing gains energy (L6 and docs/physics.md 2.2 step 6), and none leaves a corner moving
    into the floor."""
    for body, u, v, e_x, e_y, mu in _cases():
        q, flags = _land(u, v, body, e_x, e_y, mu, 0.75 * mu, float(landing))
        msg = (body, u, v, e_x, e_y, mu, flags)
        assert not flags & IMPACT_PAINLEVE, msg
        assert _ke(q, body.i2) <= 0.5 * (u * u + v * v) * (1.0 + 1e-12), msg
        assert min(q[4] - body.b1 * q[5], q[4] + body.b2 * q[5]) >= -1e-12 * abs(v), msg


def test_energy_loss_closed_form():
    """A sticking base loses (1 - e_y^2) v-^2/2 + (1 - e_x^2) u-^2 i^2/(2 (i^2 + h^2)) (L6)."""
    c = const(0.1, 0.3)
    body = Body(c.b, c.b, c.h, c.i2)
    for e_x, e_y in ((-0.9, 0.2), (-0.5, 0.8), (0.5, 0.9)):
        q, flags = _land(1.0, -1.7152, body, e_x, e_y, 0.4, 0.3)
        loss = 0.5 * (1 - e_y ** 2) * 1.7152 ** 2 + 0.5 * (1 - e_x ** 2) * c.i2 / (c.i2 + c.h ** 2)
        assert not flags & SLIPPED
        assert 0.5 * (1.0 + 1.7152 ** 2) - _ke(q, c.i2) == pytest.approx(loss, rel=1e-12)


def test_no_tangential_impulse_no_rotation():
    """e_x = -1: omega+ = 0 exactly, u+ = u-, v+ = -e_y v-, whatever e_y, friction and body
    (Fig. 5a)."""
    for body, u, v, e_x, e_y, mu in _cases():
        if e_x == -1.0:
            q, _ = _land(u, v, body, e_x, e_y, mu, 0.75 * mu)
            assert q[5] == 0.0 and q[3] == u
            assert q[4] == pytest.approx(-e_y * v, rel=1e-14)


def test_tilt_direction_is_forward_at_the_landing():
    """e_x > -1 and no corner struck after it: the friction impulse, h below G, turns the body
    towards u- (sgn omega+ = -sgn u-, (L0)); the normal impulse has no moment."""
    checked = 0
    for body, u, v, e_x, e_y, mu in _cases():
        up, vp, wp, _ = face_friction(u, v, e_x, e_y, mu, 0.75 * mu, body.b1, body.h, body.i2)
        if e_x > -1.0 and min(vp - body.b1 * wp, vp + body.b2 * wp) > 0.0:
            q, _ = _land(u, v, body, e_x, e_y, mu, 0.75 * mu)
            assert np.sign(q[5]) == -np.sign(u) == np.sign(wp)
            checked += 1
    assert checked > 500


def test_corner_law_tilts_back_without_friction():
    """corner, e_x = -1: the leading corner's normal impulse alone, arm b, tilts the body back,
    omega+ = -(1 + e_y) v- b/(i^2 + b^2) = 9.50 rad/s at Fig. 5's landing (docs/landing.md 3)."""
    c = const(0.1, 0.3)
    body = Body(c.b, c.b, c.h, c.i2)
    q = np.array([0.0, c.h, 0.0, 1.0, -1.7152, 0.0])
    corner_impact(q, 1.0, body, Contact(0.4, 0.3, 0.4, 0.3, -1.0, 0.2))
    w = 1.2 * 1.7152 * c.b / (c.i2 + c.b ** 2)
    assert q[5] == pytest.approx(w, rel=1e-12) and w == pytest.approx(9.50, abs=5e-3)
    q, _ = _land(1.0, -1.7152, body, -1.0, 0.2, 0.4, 0.3, float(LANDING_CORNER))
    assert q[5] > 0.0                                  # after the corners' sequence: still back


def v_H(B, H):
    """Eq. (9): v_H^2 = (2 g / r)(i^2 + r^2)(1 - cos alpha)/cos^2 alpha (docs/physics.md A11)."""
    c = const(B, H)
    return math.sqrt(2 * G / c.r * (c.i2 + c.r ** 2) * (1 - math.cos(c.alpha))
                     / math.cos(c.alpha) ** 2)


@pytest.mark.parametrize("lift", [0.05, 0.30])
@pytest.mark.parametrize("factor, falls", [(0.99, False), (1.01, True)])
def test_eq9_threshold_whatever_the_fall(lift, factor, falls):
    """face_friction with e_x = e_y = 0 (Fig. 5's friction): the body overturns forward iff
    u- >= v_H, from any height (L5)."""
    assert v_H(0.1, 0.3) == pytest.approx(0.485554, abs=5e-7)
    sc = scene(mu_s=0.4, mu_k=0.3, mu_edge_s=0.4, mu_edge_k=0.3, t_end=3.0,
               initial={"lift": lift, "x_dot": factor * v_H(0.1, 0.3)})
    sc["contact"]["landing"] = "face_friction"
    r = run_scene(sc)
    c = const(0.1, 0.3)
    assert r.overturned == falls
    assert r.omega_after[0] == pytest.approx(-c.h * factor * v_H(0.1, 0.3) / (c.i2 + c.r ** 2),
                                             rel=1e-12)
    if falls:
        assert r.overturn_direction == -1


# --- Fig. 5 -------------------------------------------------------------------------------

PAPER = {"a": "slides", "b": "tilts", "c": "overturns forward", "d": "overturns back"}
EXPECTED = {  # our panels under each law (docs/landing.md 4)
    "flat": {"a": "slides", "b": "slides", "c": "slides", "d": "slides"},
    "face_friction": PAPER,
    "corner": {"a": "overturns back", "b": "overturns forward", "c": "tilts",
               "d": "overturns back"},
}


def _outcome(r):
    """What the body did, moving right: slides (|theta| < 0.05 alpha), tilts, overturns."""
    if r.overturned:
        return "overturns forward" if r.overturn_direction == -1 else "overturns back"
    return "tilts" if r.max_abs_theta >= 0.05 * r.alpha else "slides"


def _panel(p, landing=None):
    raw = yaml.safe_load((STUDIES / f"fig05{p}_after_jump.yaml").read_text())
    if landing is not None:
        raw["contact"]["landing"] = landing
    return raw


@pytest.mark.parametrize("landing", LANDING_NAMES)
def test_fig5_panels_under_each_law(landing):
    """Our Fig. 5 panels: face_friction gives the paper's four outcomes, flat slides in all,
    corner overturns 5a."""
    got = {p: _outcome(simulate(_panel(p, landing))) for p in "abcd"}
    assert got == EXPECTED[landing]
    assert (got == PAPER) == (landing == "face_friction")


def test_fig5_panel_files():
    """The files select face_friction; 5a slides without any rotation and bounces (repeated
    impacts), 5b first tilts forward, 5c rocks about its leading corner with Eq. (8)'s
    omega = -4.5 rad/s."""
    results = {p: simulate(STUDIES / f"fig05{p}_after_jump.yaml") for p in "abcd"}
    assert all(_panel(p)["contact"]["landing"] == "face_friction" for p in "abcd")
    a = results["a"]
    assert a.max_abs_theta == 0.0 and a.impact_count > 1 and a.mode_time["slide"] > 0.0
    assert results["b"].omega_after[0] < 0.0
    assert results["c"].omega_after[0] == pytest.approx(-4.5, rel=1e-12)


def test_fig5_panels_with_the_default_contact():
    """Without contact.landing a scene lands face_friction: the four panels give the paper's
    outcomes, impact for impact as with landing: face_friction written out."""
    assert DEFAULTS["contact"]["landing"] == "face_friction"
    got = {}
    for p in "abcd":
        raw = _panel(p)
        del raw["contact"]["landing"]
        default, face = simulate(raw), simulate(_panel(p, "face_friction"))
        assert default.impact_times == face.impact_times
        assert default.omega_after == face.omega_after
        got[p] = _outcome(default)
    assert got == PAPER


# --- mirror ---------------------------------------------------------------------------------

def _thrown(sign, landing, x_dot, x_g, excited):
    """B 20 x H 60 cm lifted 5 cm, thrown at sign x_dot, G at (sign x_g, 30 cm), on a still
    floor or a sine of sign 0.3 g at 2 Hz: the scene (sign 1) and its mirror image (-1)."""
    sc = scene(0.2, 0.6, mu=0.6, e_x=-0.3, e_y=0.1, landing=landing,
               horizontal=sine(sign * 0.3 * G, 2.0) if excited else None,
               initial={"lift": 0.05, "x_dot": sign * x_dot}, t_end=2.0, dt_out=0.005)
    sc["body"]["G"] = [sign * x_g, 0.3]
    return sc


@pytest.mark.parametrize("landing", LANDING_NAMES)
@pytest.mark.parametrize("x_dot", [0.3, 0.8, 1.5])
@pytest.mark.parametrize("x_g, excited", [(0.0, False), (0.0, True), (0.03, False)],
                         ids=["still", "sine", "G_off_middle"])
def test_mirrored_landing_mirrors_every_result(landing, x_dot, x_g, excited):
    """x_dot, x_G and a_x -> their negatives: theta, omega, x, u and the overturning
    direction change sign, all else is the same, under every law.  A flat landing whose
    two-contact impulse would pull the trailing corner is taken by the leading one (docs/physics.md
    2.3), not by the right one whatever the direction.  Bit for bit here; asserted to 1e-12."""
    r = run_scene(_thrown(1.0, landing, x_dot, x_g, excited), history=True)
    m = run_scene(_thrown(-1.0, landing, x_dot, x_g, excited), history=True)
    assert r.impact_count > 0 and r.max_abs_theta > 0.0
    assert m.status == r.status and m.impact_count == r.impact_count
    assert m.overturn_direction == (-r.overturn_direction if r.overturned else None)
    np.testing.assert_allclose(m.impact_times, r.impact_times, rtol=0, atol=1e-12)
    np.testing.assert_allclose(m.omega_after, -np.array(r.omega_after), rtol=0, atol=1e-12)
    for key in ("max_abs_theta", "max_slip", "max_lift", "max_travel", "t_final"):
        assert getattr(m, key) == pytest.approx(getattr(r, key), rel=0, abs=1e-12), key
    sign = {"theta": -1, "omega": -1, "x": -1, "u": -1, "a_x": -1}
    for name in HISTORY_NAMES:
        np.testing.assert_allclose(m.history[name], sign.get(name, 1) * r.history[name],
                                   rtol=0, atol=1e-12, err_msg=name)
