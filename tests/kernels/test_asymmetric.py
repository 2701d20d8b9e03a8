"""Bodies with G off the middle of the base (docs/bodies.md), against independent values.

Corner 1 (left) at (-b1, -h) from G, corner 2 (right) at (b2, -h): b1 = B/2 + x_G,
b2 = B/2 - x_G, h = y_G, tan alpha_i = b_i/h, R_i = sqrt(b_i^2 + h^2).  Free rocking about
corner i conserves (i^2 + R_i^2) omega^2/2 + g R_i cos(alpha_i - |theta|); an impact that makes
corner c the pivot keeps the angular momentum about c: omega+ = eta_c omega-,
eta_c = 1 - b_c (b1 + b2)/(i^2 + R_c^2).  Impact times come from the energy integral by
quadrature (scipy), not from the kernel's integrator.
"""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from kernels.api import run_scene
from kernels.codes import HISTORY_NAMES, MODE_NAMES

from .scenes import G, pulse, scene, sine

B, H = 0.2, 0.6
X_G, Y_G = 0.03, 0.25                       # G right of the middle and low: alpha_1 > alpha_2


def sides(x_g=X_G, y_g=Y_G):
    """b, R, alpha, p^2 and eta per corner (1 left, 2 right), and i^2 (uniform default)."""
    b = (0.5 * B + x_g, 0.5 * B - x_g)
    i2 = (B * B + H * H) / 12.0
    R = tuple(math.hypot(bi, y_g) for bi in b)
    return dict(b=b, R=R, alpha=tuple(math.atan2(bi, y_g) for bi in b), i2=i2,
                p2=tuple(G * Ri / (i2 + Ri * Ri) for Ri in R),
                eta=tuple(1.0 - bi * B / (i2 + Ri * Ri) for bi, Ri in zip(b, R)))


def body_scene(x_g=X_G, y_g=Y_G, **kw):
    sc = scene(B, H, **kw)
    sc["body"]["G"] = [x_g, y_g]
    return sc


def quarter_time(phi, alpha, p2):
    """Time from theta = phi (at rest) to theta = 0 rocking about a corner, exact: the energy
    integral with theta = phi (1 - w^2), finite at both ends, and
    cos(alpha - phi) - cos(alpha - theta) = 2 sin(alpha - (phi + theta)/2) sin(phi w^2/2)."""
    def f(w):
        theta = phi * (1.0 - w * w)
        drop = 2.0 * math.sin(alpha - 0.5 * (phi + theta)) * math.sin(0.5 * phi * w * w)
        return 2.0 * phi * w / math.sqrt(2.0 * p2 * drop)
    return quad(f, 0.0, 1.0, epsabs=0.0, epsrel=1e-13, limit=200)[0]


def free_rocking(theta0, n):
    """Closed-form impact times and omega after each of n impacts, from theta0 > 0 at rest."""
    c = sides()
    i, phi, t = 0, theta0, 0.0              # side 0 (left corner, theta > 0) first
    times, omegas = [], []
    for k in range(n):
        a, p2 = c["alpha"][i], c["p2"][i]
        t += quarter_time(phi, a, p2) * (1 if k == 0 else 2)
        w = math.sqrt(2.0 * p2 * (math.cos(a - phi) - math.cos(a)))   # |omega-| at theta = 0
        j = 1 - i                                                     # the new pivot
        w_after = c["eta"][j] * w
        times.append(t)
        omegas.append(-w_after if i == 0 else w_after)                # theta turns to side j
        phi = c["alpha"][j] - math.acos(math.cos(c["alpha"][j]) + w_after ** 2 / (2 * c["p2"][j]))
        i = j
    return np.array(times), np.array(omegas)


# --- G in the middle --------------------------------------------------------------------------

MODE_SCENES = [   # each drives the body through several modes and impact laws
    dict(horizontal=sine(1.6 * G / 3, 2.0), mu=0.8, e_x=-0.8, e_y=0.2, t_end=4.0),
    dict(horizontal=sine(0.5 * G, 3.0), mu=0.2, t_end=2.0),                    # slide
    dict(horizontal=sine(1.2 * G, 2.0), mu_s=0.5, mu_k=0.4, mu_edge_s=0.45, mu_edge_k=0.4,
         e_x=-0.5, e_y=0.3, t_end=3.0),             # slide rotation, rotation jump, overturns
    dict(initial={"theta": 0.2, "omega": 2.0}, mu_s=0.3, mu_k=0.2, mu_edge_s=0.2,
         mu_edge_k=0.15, t_end=2.0),                                          # slide rotation
    dict(initial={"lift": 0.05, "theta": 0.1, "omega": 1.0}, mu=0.6, e_x=-0.3, e_y=0.3,
         t_end=2.0),                                         # rotation jump, corner impacts
    dict(horizontal=sine(0.5 * G, 2.0), vertical=sine(1.3 * G, 4.0), mu=0.5, e_y=0.4,
         t_end=2.0),                                                           # jumps
    dict(initial={"y_dot": 1.0}, mu=0.6, e_x=-0.3, e_y=0.1, t_end=2.0),     # flat landings
]


def _fields(r):
    d = r._asdict()
    d.pop("cpu_s")
    d.pop("history")
    return d


@pytest.mark.parametrize("kw", MODE_SCENES)
def test_G_written_in_the_middle_is_the_default_body(kw):
    """G: [0, H/2] with the default i_g is the body without G, every result bit for bit
    (the comparison with the code before G existed is in the note of this change)."""
    plain = scene(B, H, **kw)
    centred = scene(B, H, **kw)
    centred["body"]["G"] = [0.0, H / 2]
    assert _fields(run_scene(centred)) == _fields(run_scene(plain))


# --- mirror -----------------------------------------------------------------------------------

def _mirrored(kw):
    """The scene seen in a mirror: a_x, theta, omega and x_dot change sign."""
    out = dict(kw)
    if "horizontal" in kw:
        out["horizontal"] = {**kw["horizontal"], "amplitude": -kw["horizontal"]["amplitude"]}
    if "initial" in kw:
        out["initial"] = {key: -value if key in ("theta", "omega", "x_dot") else value
                          for key, value in kw["initial"].items()}
    return out


@pytest.mark.parametrize("kw", MODE_SCENES + [
    dict(horizontal=sine(2.0 * G / 3, 1.5), mu=0.8, t_end=4.0),               # overturns
])
def test_mirroring_G_mirrors_every_result(kw):
    """x_G -> -x_G under the mirrored floor and initial state (a_x, theta, omega, x_dot ->
    their negatives): theta -> -theta, the overturning direction swaps, every other result
    is the same, to round-off growing over the impacts."""
    r = run_scene(body_scene(**kw), history=True)
    m = run_scene(body_scene(x_g=-X_G, **_mirrored(kw)), history=True)
    assert r.status == m.status and r.impact_count == m.impact_count
    if r.overturned:
        assert m.overturn_direction == -r.overturn_direction
    np.testing.assert_allclose(m.impact_times, r.impact_times, rtol=1e-7, atol=1e-7)
    np.testing.assert_allclose(m.omega_after, -np.array(r.omega_after), rtol=1e-7, atol=1e-7)
    for key in ("max_abs_theta", "max_slip", "max_lift", "t_final"):
        assert getattr(m, key) == pytest.approx(getattr(r, key), rel=1e-7, abs=1e-12), key
    for mode in MODE_NAMES:
        assert m.mode_time[mode] == pytest.approx(r.mode_time[mode], abs=1e-7), mode
    sign = {"theta": -1, "omega": -1, "x": -1, "u": -1, "a_x": -1}
    for name in HISTORY_NAMES:
        np.testing.assert_allclose(m.history[name], sign.get(name, 1) * r.history[name],
                                   rtol=1e-7, atol=1e-7, err_msg=name)
    assert max(r.max_abs_theta, r.max_slip, r.max_lift) > 0.0


# --- static tipping -----------------------------------------------------------------------

def _tips(a):
    """Whether a step of floor acceleration a (0.2 s) moves the body (very high friction)."""
    r = run_scene(body_scene(horizontal=pulse(a, 0.2), mu=100.0, t_end=0.3))
    return r.max_abs_theta > 0.0, r.mode_time["rotation"] > 0.0


@pytest.mark.parametrize("side", [1, -1])
def test_static_tipping_acceleration_is_g_tan_alpha_per_side(side):
    """A step to the right (side 1) tips the body about its left corner at g tan alpha_1 =
    g b1/h, to the left at g tan alpha_2; the kernel's threshold, by bisection, to 1e-12."""
    b = sides()["b"][0 if side == 1 else 1]
    want = G * b / Y_G
    lo, hi = 0.5 * want, 2.0 * want
    assert not _tips(side * lo)[0] and _tips(side * hi) == (True, True)
    while hi - lo > 1e-14 * want:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if _tips(side * mid)[0] else (mid, hi)
    assert hi == pytest.approx(want, rel=1e-12)
    other = G * sides()["b"][1 if side == 1 else 0] / Y_G
    assert abs(hi - other) > 0.1 * want                       # the two sides differ


# --- free rocking -------------------------------------------------------------------------

def test_free_rocking_matches_the_closed_form_on_each_side():
    """Released at rest at theta0 = 0.15 alpha_1 about the left corner (more would overturn
    it to the right, alpha_2 = 0.57 alpha_1): the impact times and
    omega after each impact match the energy integral and eta_c of the new pivot c, which
    alternate between the two sides (eta_2 when the right corner strikes, eta_1 after)."""
    c = sides()
    theta0 = 0.15 * c["alpha"][0]
    n = 8
    r = run_scene(body_scene(mu=5.0, initial={"theta": theta0}, rtol=1e-12, atol=1e-13,
                             t_end=3.0, zeno_dt=1e-9))
    times, omegas = free_rocking(theta0, n)
    assert r.impact_count >= n
    np.testing.assert_allclose(r.impact_times[:n], times, rtol=1e-9)
    np.testing.assert_allclose(r.omega_after[:n], omegas, rtol=1e-8)
    ratios = -np.array(r.omega_after[1:n]) / np.array(r.omega_after[:n - 1])
    np.testing.assert_allclose(ratios[0::2], c["eta"][0], rtol=1e-8)     # left corner strikes
    np.testing.assert_allclose(ratios[1::2], c["eta"][1], rtol=1e-8)     # right corner strikes
    assert c["eta"][0] != pytest.approx(c["eta"][1], rel=1e-3)


def test_eta_reduces_to_housner_for_the_uniform_symmetric_block():
    """eta_c = 1 - b_c B/(i^2 + R_c^2) with x_G = 0, i^2 = R^2/3: 1 - (3/2) sin^2 alpha."""
    c = sides(0.0, H / 2)
    assert c["eta"][0] == c["eta"][1] == pytest.approx(1.0 - 1.5 * math.sin(c["alpha"][0]) ** 2,
                                                       rel=1e-14)


def test_energy_is_conserved_between_impacts_and_lost_by_eta_squared():
    """Free rocking: (u^2 + v^2 + i^2 omega^2)/2 + g y is constant between impacts (to the
    integrator's tolerance); at an impact from pivot o to pivot c its kinetic part,
    (i^2 + R^2) omega^2/2 about the pivot, drops by eta_c^2 (i^2 + R_c^2)/(i^2 + R_o^2)."""
    c = sides()
    r = run_scene(body_scene(mu=5.0, initial={"theta": 0.15 * c["alpha"][0]}, rtol=1e-12,
                             atol=1e-13, t_end=1.0, dt_out=1e-3), history=True)
    h = r.history
    E = 0.5 * (h["u"] ** 2 + h["v"] ** 2 + c["i2"] * h["omega"] ** 2) + G * h["y"]
    t_imp = np.array(r.impact_times)
    segment = np.searchsorted(t_imp, h["t"])          # samples between the same two impacts
    checked = 0
    for k in range(4):
        e = E[(segment == k) & (h["mode"] == MODE_NAMES.index("rotation"))]
        assert e.size > 10
        assert np.ptp(e) <= 1e-10 * e[0], k
        checked += 1
        if k:                                          # kinetic part after / before
            new, old = (1, 0) if k % 2 else (0, 1)     # impact k-1: right corner, then left
            kin_before = E[segment == k - 1][-1] - G * Y_G
            kin_after = e[0] - G * Y_G
            I = [c["i2"] + R * R for R in c["R"]]
            assert kin_after / kin_before == pytest.approx(c["eta"][new] ** 2 * I[new] / I[old],
                                                           rel=1e-9)
    assert checked == 4


def test_flat_landing_without_sliding_does_not_turn_the_body():
    """A body dropped flat (no horizontal velocity, e_y = 0) stops: the two normal impulses
    split as b2 P_R = b1 P_L, so G's off-centre position gives no rotation."""
    r = run_scene(body_scene(mu=0.5, initial={"lift": 0.01}, t_end=0.5), history=True)
    assert r.impact_count == 1 and r.max_abs_theta == 0.0
    assert r.omega_after[0] == 0.0 and r.t_rest == pytest.approx(math.sqrt(0.02 / G), rel=1e-9)
