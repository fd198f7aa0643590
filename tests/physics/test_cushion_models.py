"""Closed-form and limiting-case checks of every cushion model (the
``cushion.MODELS`` registry: han2005, mathavan2010, stronge,
impulse_frictional), and of the Stronge regimes. Each test's docstring gives
the equation it checks."""
import dataclasses
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

from billiards_env.physics import PhysicsParams
from billiards_env.physics import constants as C
from billiards_env.physics.cushion import MODELS, stronge

P = PhysicsParams.standard()
R = P.R
# Rounding of a few dozen float64 operations on O(1) quantities.
ROUND = 1e-12
# mathavan2010 integrates: its closed forms hold to its discretisation
# error (tests/physics/test_mathavan_convergence.py), in units of the speed.
STEP = {"mathavan2010": 1e-5}
NAMES = sorted(MODELS)


def _params(**kw):
    return dataclasses.replace(P, **kw).as_array()


def _resolve(name, v, n=(0.0, 1.0), e=P.e_c, p=None):
    p = P.as_array() if p is None else p
    nx, ny = n
    return np.array(MODELS[name].resolve(*v, nx, ny, -(v[0] * nx + v[1] * ny), e, p))


def _energy2(v):
    """2 E / m: |v|^2 + (2/5) R^2 |w|^2."""
    return v[0] ** 2 + v[1] ** 2 + 0.4 * R * R * (v[2] ** 2 + v[3] ** 2 + v[4] ** 2)


@pytest.mark.parametrize("name", NAMES)
def test_frictionless_nose_at_equator_is_reflection(name):
    """f_c = mu_s = 0, nose at the equator (h_c = R, outside the validated
    range on purpose: the theta = 0 limit): every model is the reflection
    with restitution, v_n' = -e v_n, v_t and the spin unchanged."""
    p = _params(f_c=0.0, mu_s=0.0)
    p[C.P_H_C] = R
    rng = np.random.default_rng(1)
    for _ in range(50):
        V, a, e = rng.uniform(0.05, 10.0), rng.uniform(-1.5, 1.5), rng.uniform(0.0, 1.0)
        v = (V * math.sin(a), -V * math.cos(a), *rng.uniform(-300, 300, 3))
        out = _resolve(name, v, e=e, p=p)
        tol = STEP.get(name, ROUND) * (V + R * 600)
        np.testing.assert_allclose(out[0], v[0], atol=tol)
        np.testing.assert_allclose(out[1], -e * v[1], atol=tol)
        np.testing.assert_allclose(out[2:] * R, np.array(v[2:]) * R, atol=tol)


@pytest.mark.parametrize("name", ["han2005", "impulse_frictional", "stronge"])
def test_frictionless_impulse_models_above_the_equator(name):
    """f_c = 0, h_c = 0.04 m: the impulse models push along the contact
    normal N = (cos(theta) n, -sin(theta)) and drop the vertical velocity,
    so v_n' = v_n (1 - (1 + e) cos^2(theta)); v_t unchanged; the spin
    unchanged (the normal passes through the centre). mathavan2010 keeps
    the ball on the felt during the impact and gives -e v_n instead
    (tests/physics/test_new_models.py)."""
    p = _params(f_c=0.0, mu_s=0.0)
    s = P.h_c / R - 1.0
    c2 = 1.0 - s * s
    for V, a in ((1.0, 0.0), (3.0, 0.7), (8.0, -1.2)):
        v = (V * math.sin(a), -V * math.cos(a), 10.0, -20.0, 30.0)
        out = _resolve(name, v, p=p)
        assert out[1] == pytest.approx(v[1] * (1.0 - (1.0 + P.e_c) * c2), rel=ROUND)
        assert out[0] == pytest.approx(v[0], rel=ROUND, abs=ROUND)
        np.testing.assert_allclose(out[2:], v[2:], rtol=ROUND)


@pytest.mark.parametrize("name", NAMES)
def test_head_on_stun_ball(name):
    """A stun ball (no spin) straight into the cushion: by symmetry no
    sideways velocity and no side spin (w_z) or spin about the normal (w_y)
    appear; it comes back (v_n' > 0) slower than it came (v_n' <= e |v_n|),
    with backspin-free... spin about the cushion line only (w_x)."""
    for V in (0.3, 2.0, 8.0):
        out = _resolve(name, (0.0, -V, 0.0, 0.0, 0.0))
        assert out[0] == 0.0 and out[3] == 0.0 and out[4] == 0.0
        assert 0.0 < out[1] <= P.e_c * V * (1 + STEP.get(name, ROUND))


@pytest.mark.parametrize("name", ["impulse_frictional", "stronge"])
def test_head_on_stun_ball_closed_form(name):
    """Stun ball head-on, nose at theta: the contact slips downward-in at
    u_t = V sin(theta) (the normal approach is w = V cos(theta)). The
    impulse model sticks if (2/7) u_t <= f_c (1 + e) w, i.e. here
    tan(theta) <= 3.5 f_c (1 + e) (0.44 <= 1.295: it sticks), and the
    friction impulse is -(2/7) u_t along the slip. Stronge: v0 = tan(theta)
    = 0.436 lies between mu eta^2 = 0.242 and the gross-slip bound 1.010:
    slip, stick, reverse slip; checked against ``stronge.final_slip``."""
    V = 2.0
    s = P.h_c / R - 1.0
    c = math.sqrt(1.0 - s * s)
    w, ut = V * c, V * s
    if name == "impulse_frictional":
        vf = 0.0  # the slip ends
    else:
        vf = stronge.final_slip(ut / w, P.f_c, P.e_c, P.kt_kn) * w
    jt = (vf - ut) / 3.5  # along the slip direction (c e_y... see below)
    jn = (1 + P.e_c) * w
    # contact frame: N = (0, c, -s) (cushion normal (0, 1)); the slip of the
    # contact point of a stun ball is v - (v.N) N = -V (0, 1, 0) + V c (0, c, -s)
    # = V s (0, -s, -c): unit t = (0, -s, -c)
    J = jn * np.array([0.0, c, -s]) + jt * np.array([0.0, -s, -c])
    r = R * np.array([0.0, -c, s])
    dw = np.cross(r, J) / (0.4 * R * R)
    out = _resolve(name, (0.0, -V, 0.0, 0.0, 0.0))
    np.testing.assert_allclose(out, [0.0, -V + J[1], dw[0], dw[1], dw[2]], rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("name", NAMES)
@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(speed=st.floats(0.0, 12.0), angle=st.floats(-math.pi, math.pi),
       spin=st.tuples(*[st.floats(-400.0, 400.0)] * 3), normal=st.floats(-math.pi, math.pi),
       e=st.floats(0.0, 1.0), f_c=st.floats(0.0, 1.0), mu_s=st.floats(0.0, 1.0),
       h=st.floats(1.001, 1.999), kt=st.floats(0.2858, 1.1428))
def test_never_gains_energy(name, speed, angle, spin, normal, e, f_c, mu_s, h, kt):
    """Random impacts (speeds to 12 m/s, spins to 400 rad/s, any
    restitution, frictions to 1, nose heights in (R, 2R), stiffness ratios
    over Stronge's range): finite and no energy gained. mathavan2010 never
    leaves moving into the cushion; the impulse models can, when
    (1 + e) cos^2(theta) < 1 (a high nose and a low restitution: their
    horizontal normal velocity is v_n (1 - (1 + e) cos^2(theta)) without
    friction), which the interface's resting-contact rule then removes
    (cushion/contact.py)."""
    p = _params(f_c=f_c, mu_s=mu_s, h_c=h * R, kt_kn=kt)
    v = (speed * math.cos(angle), speed * math.sin(angle), *spin)
    nx, ny = math.cos(normal), math.sin(normal)
    vn_in = v[0] * nx + v[1] * ny
    if not vn_in < 0.0:
        return
    out = _resolve(name, v, (nx, ny), e, p)
    assert np.all(np.isfinite(out))
    assert _energy2(out) <= _energy2(v) * (1 + 1e-12) + 1e-24
    if name == "mathavan2010":
        assert out[0] * nx + out[1] * ny >= -1e-12 * (speed + R * 400.0)


def test_stronge_regimes_and_continuity():
    """``final_slip`` (units of the normal approach): gross slip above
    mu ((1 + e) beta_t - eta^2 / e) is v0 - mu beta_t (1 + e) exactly; the
    initial-stick and slip-stick-slip branches meet the neighbouring ones
    continuously at v0 = mu eta^2 and at the gross-slip bound; f_c = 0
    leaves the slip unchanged; and the slip never grows, |v_f| <= v0 +
    ROUND (friction only takes energy out of the tangential motion...
    the spring's returns at most what it stored)."""
    mu, e, kt = 0.2, 0.85, 0.826
    eta2 = 1.0 / kt
    gross = mu * ((1 + e) * 3.5 - eta2 / e)
    v = 1.5 * gross
    assert stronge.final_slip(v, mu, e, kt) == pytest.approx(v - mu * 3.5 * (1 + e), rel=ROUND)
    for edge in (mu * eta2, gross):
        a = stronge.final_slip(edge * (1 - 1e-9), mu, e, kt)
        b = stronge.final_slip(edge * (1 + 1e-9), mu, e, kt)
        assert abs(a - b) < 1e-6
    assert stronge.final_slip(0.7, 0.0, e, kt) == 0.7
    for v0 in np.linspace(0.0, 2.0 * gross, 401):
        assert abs(stronge.final_slip(v0, mu, e, kt)) <= max(v0, 1e-15) * (1 + 1e-9)


def test_stronge_initial_stick_closed_form():
    """Initial stick, v0 < mu eta^2: u(theta) = (v0 / r) sin(r theta) until
    |u| = mu eta^2 F(theta); checked by bisecting that equation here,
    independently, and the final slip v(ts) - mu beta_t (p(tf) - p(ts))
    sgn(u)."""
    mu, e, kt = 0.2, 0.85, 0.826
    r, eta2 = math.sqrt(3.5 * kt), 1.0 / kt
    v0 = 0.5 * mu * eta2
    F = lambda t: math.sin(t) if t <= math.pi / 2 else math.cos((t - math.pi / 2) / e)
    p = lambda t: 1 - math.cos(t) if t <= math.pi / 2 else 1 + e * math.sin((t - math.pi / 2) / e)
    g = lambda t: abs(v0 / r * math.sin(r * t)) - mu * eta2 * F(t)
    ts_grid = np.linspace(1e-6, (1 + e) * math.pi / 2, 100001)
    k = int(np.argmax([g(t) > 0 for t in ts_grid]))
    lo, hi = ts_grid[k - 1], ts_grid[k]
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if g(mid) > 0 else (mid, hi)
    ts = hi
    u = v0 / r * math.sin(r * ts)
    vf = v0 * math.cos(r * ts) - math.copysign(mu * 3.5 * (p((1 + e) * math.pi / 2) - p(ts)), u)
    assert stronge.final_slip(v0, mu, e, kt) == pytest.approx(vf, abs=1e-10)


def test_stronge_kt_kn_validated():
    with pytest.raises(ValueError, match="kt_kn"):
        PhysicsParams(kt_kn=1.5)
