"""An anchored body (docs/anchors.md) against the closed form of its threshold (1): held
at rest below it, its tie broken above it at the instant the floor's acceleration reaches it,
asin(threshold/amplitude)/(2 pi f) for a slow sine; each corner's own threshold with G off
the middle, the mirrored body giving the mirrored result; no sliding before a weak tie breaks;
and the vertical acceleration entering through g_e."""
import math

import pytest

from kernels import api

G = 9.80665
B, H, MASS, STRENGTH, F = 0.4, 1.2, 100.0, 800.0, 0.2   # m, m, kg, N, Hz
h = H / 2
TIE = STRENGTH * B / (MASS * h)        # T B/(m h): the far corner's tie, arm B


def _scene(amplitude, *, strength=STRENGTH, x_g=0.0, phase=0.0, half=False, mu=0.8,
           vertical=None):
    """A sine of ``amplitude`` [m/s^2] at F over one period (``half``: its first half),
    ``vertical`` the amplitude of a vertical sine of the same frequency, phase and length;
    the body anchored with ``strength`` (None: free)."""
    duration = 1.0 / F / (2 if half else 1)
    sine = {"kind": "sine", "frequency": F, "duration": duration}
    excitation = {"horizontal": {**sine, "amplitude": amplitude, "phase": phase}}
    if vertical is not None:
        excitation["vertical"] = {**sine, "amplitude": vertical, "phase": phase}
    scene = {"body": {"B": B, "H": H, "G": [x_g, h], "mass": MASS},
             "contact": {"mu_s": mu, "mu_k": 0.9 * mu, "mu_edge_s": mu, "mu_edge_k": 0.9 * mu},
             "excitation": excitation, "solver": {"t_end": 1.0 / F + 1.0}}
    if strength is not None:
        scene["restraint"] = {"kind": "anchor", "strength": strength}
    return scene


def _t_reached(threshold, amplitude):
    """When A sin(2 pi F t) first reaches ``threshold``."""
    return math.asin(threshold / amplitude) / (2 * math.pi * F)


def _held(result):
    return (result.status == "ok" and result.max_abs_theta == 0.0 and result.max_slip == 0.0
            and not result.restraint_broken and result.t_broken is None)


def test_symmetric_threshold_holds_below_and_breaks_above():
    """g b/h + 2 T b/(m h) (b = B/2): 2 % below, at rest; 2 % above, the tie breaks when the
    sine reaches it and the body, free, overturns towards -x (about its left corner)."""
    threshold = G * (B / 2) / h + 2 * STRENGTH * (B / 2) / (MASS * h)
    assert _held(api.run_scene(_scene(0.98 * threshold)))
    broke = api.run_scene(_scene(1.02 * threshold))
    assert broke.restraint_broken and broke.max_abs_theta > 0.0
    assert broke.t_broken == pytest.approx(_t_reached(threshold, 1.02 * threshold), abs=1e-6)
    assert broke.overturned and broke.overturn_direction == 1


@pytest.mark.parametrize("x_g, phase, direction", [(0.05, math.pi, -1), (-0.05, 0.0, 1)])
def test_off_centre_body_breaks_at_its_near_corner_threshold(x_g, phase, direction):
    """G 5 cm off the middle, the sine pushing first towards the near corner: the tie breaks
    at g b_near/h + T B/(m h), 2 % below it holds; G and the sine mirrored, the same instant
    and the opposite way."""
    b_near = B / 2 - abs(x_g)
    threshold = G * b_near / h + TIE
    assert _held(api.run_scene(_scene(0.98 * threshold, x_g=x_g, phase=phase)))
    broke = api.run_scene(_scene(1.02 * threshold, x_g=x_g, phase=phase))
    assert broke.restraint_broken
    assert broke.t_broken == pytest.approx(_t_reached(threshold, 1.02 * threshold), abs=1e-6)
    assert broke.overturn_direction == direction


def test_off_centre_body_holds_up_to_its_far_corner_threshold():
    """G 5 cm right of the middle, half a sine towards +x tips about the far (left) corner:
    held 2 % below g b1/h + T B/(m h), though far above the near corner's threshold."""
    threshold = G * (B / 2 + 0.05) / h + TIE
    assert 0.98 * threshold > 1.1 * (G * (B / 2 - 0.05) / h + TIE)
    assert _held(api.run_scene(_scene(0.98 * threshold, x_g=0.05, half=True)))
    broke = api.run_scene(_scene(1.02 * threshold, x_g=0.05, half=True))
    assert broke.t_broken == pytest.approx(_t_reached(threshold, 1.02 * threshold), abs=1e-6)


def test_zero_strength_breaks_where_a_free_body_tips_and_never_slides_before():
    """T = 0: the tie gives way at g b/h, though mu_s = 0.2 < b/h; below it the body neither
    slides nor rocks, where the free body slides (above mu_s g)."""
    mu = 0.2
    threshold = G * (B / 2) / h
    assert mu * G < 0.98 * threshold
    assert _held(api.run_scene(_scene(0.98 * threshold, strength=0.0, mu=mu)))
    free = api.run_scene(_scene(0.98 * threshold, strength=None, mu=mu))
    assert free.max_slip > 0.0 and free.mode_time["slide"] > 0.0
    broke = api.run_scene(_scene(1.02 * threshold, strength=0.0, mu=mu), history=True)
    assert broke.t_broken == pytest.approx(_t_reached(threshold, 1.02 * threshold), abs=1e-6)
    before = broke.history["t"] < broke.t_broken
    assert before.any() and (broke.history["mode"][before] == 0).all()   # rest
    assert (broke.history["x"][before] == broke.history["x"][0]).all()


@pytest.mark.parametrize("sign", [1, -1])
def test_vertical_acceleration_moves_the_threshold_through_g_e(sign):
    """Half a horizontal sine with half a vertical one of amplitude +-0.2 g in phase: the tie
    breaks where A s = (b/h)(g + V s) + T B/(m h), s = sin(2 pi F t); the threshold on A
    moves by (b/h) V."""
    vertical = sign * 0.2 * G
    still = G * (B / 2) / h + TIE                     # the threshold without vertical motion
    threshold = still + (B / 2) / h * vertical
    below = api.run_scene(_scene(0.98 * threshold, half=True, vertical=vertical))
    assert _held(below)
    amplitude = 1.02 * threshold
    broke = api.run_scene(_scene(amplitude, half=True, vertical=vertical))
    expected = _t_reached(still, amplitude - (B / 2) / h * vertical)
    assert broke.restraint_broken
    assert broke.t_broken == pytest.approx(expected, abs=1e-6)
