"""Closed-form and limiting-case checks of two interaction models:
Alciatore's speed-dependent ball-ball friction (physics/ball_ball/alciatore.py)
and the Mathavan et al. (2010) ball-cushion impact (physics/cushion/mathavan2010.py).
Each test's docstring gives the equation it checks."""
import dataclasses
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

from billiards_env.physics import PhysicsParams
from billiards_env.physics import constants as C
from billiards_env.physics.ball_ball import alciatore
from billiards_env.physics.ball_ball.alciatore import friction_coefficient
from billiards_env.physics.cushion import mathavan2010


def resolve(vx, vy, wx, wy, wz, nx, ny, e_c, p):
    """The model through its interface, with the approach speed -v.n the
    cushion contact measures."""
    return mathavan2010.resolve(vx, vy, wx, wy, wz, nx, ny, -(vx * nx + vy * ny), e_c, p)

P = PhysicsParams.standard()
PV = P.as_array()
R = P.R
A, B, K = alciatore.ALCIATORE_A, alciatore.ALCIATORE_B, alciatore.ALCIATORE_C
# Rounding of a few dozen float64 operations on O(1) quantities.
ROUND = 1e-12
# Frame rotations round differently, and a rounding-level difference can
# move a contact across the sticking test of one impulse step: agreement to
# well within the discretisation error (see test_mathavan_converges).
ROT_TOL = 1e-7
# Largest integration error allowed in the closed-form case below (a stun
# ball head-on, its felt slip reversing), as a fraction of the incoming
# speed: measured 2.3e-8 (the slip set to zero within 30 STEP_TOL V of it,
# mathavan2010.SNAP); tests/physics/test_mathavan_convergence.py measures
# the general case.
STEP_TOL = 1e-7
# The same for the head-on closed forms (measured: 5e-8 at most).
HEAD_ON_TOL = 2e-7
# The mirrored impact's final approach to a stick is integrated in the
# mirrored direction angle (pi - phi), whose sines and cosines round
# differently: ~1e-12 relative per impact, a few hundred ulps.
MIRROR_TOL = 1e-10


def _params(**kw):
    return dataclasses.replace(P, **kw).as_array()


def _energy2(v):
    """2 E / m of a ball on the table: |v|^2 + (2/5) R^2 |w|^2."""
    return v[0] ** 2 + v[1] ** 2 + 0.4 * R * R * (v[2] ** 2 + v[3] ** 2 + v[4] ** 2)


# --------------------------------------------------------------- Alciatore
def test_alciatore_published_constants():
    """TP A-14's fit, mu = 9.951e-3 + 0.108 exp(-1.088 v_rel) (v_rel in m/s);
    pooltool's ball-ball friction default uses the same three numbers."""
    assert (A, B, K) == (9.951e-3, 0.108, 1.088)
    assert friction_coefficient(1.0, PV) == pytest.approx(9.951e-3 + 0.108 * math.exp(-1.088), rel=ROUND)


def test_alciatore_limits_and_monotone():
    """mu(v) = a + b exp(-c v): mu(0) = a + b, mu' = -b c exp(-c v) < 0, mu -> a."""
    assert friction_coefficient(0.0, PV) == A + B
    assert friction_coefficient(-1.0, PV) == A + B  # a negative speed counts as 0
    v = np.linspace(0.0, 20.0, 2001)
    mu = np.array([friction_coefficient(x, PV) for x in v])
    assert np.all(np.diff(mu) < 0)
    np.testing.assert_allclose(mu, A + B * np.exp(-K * v), rtol=ROUND)
    assert abs(friction_coefficient(60.0, PV) - A) < 1e-20  # b e^{-65} ~ 1e-29
    assert A < mu.min() and mu.max() <= A + B


def _impact(v1, w1, v2, w2, n, e, mu_of_slip):
    """The project's instantaneous impulse for two equal solid balls (m = 1):
    normal impulse jn = (1 + e) w / 2 along n (w the approach speed); friction
    jt = min(mu jn, |u_t| / 7) against the contact slip u_t (m |u_t| / 7 ends
    it: each ball's contact point responds at 1/m + R^2/I = 7/(2m)); each
    ball turns by r x J / I. Returns the velocities, spins and pre-impact slip."""
    v1, w1, v2, w2, n = (np.array(x, float) for x in (v1, w1, v2, w2, n))
    r1, r2 = R * n, -R * n
    u = (v1 + np.cross(w1, r1)) - (v2 + np.cross(w2, r2))
    ut = u - (u @ n) * n
    slip = np.linalg.norm(ut)
    wn = (v1 - v2) @ n  # approach speed along the line of centres
    jn = 0.5 * (1.0 + e) * wn
    J = -jn * n  # on ball 1
    if slip > 0.0:
        J = J - min(mu_of_slip(slip) * jn, slip / 7.0) * ut / slip
    v1, v2 = v1 + J, v2 - J
    w1 = w1 + np.cross(r1, J) / (0.4 * R * R)
    w2 = w2 + np.cross(r2, -J) / (0.4 * R * R)
    return v1, w1, v2, w2, ut


def _throw_deg(v, cut_deg, e=P.e_b):
    """Stun shot (no spin) at speed v and cut angle phi into a ball at rest."""
    phi = math.radians(cut_deg)
    n = (math.cos(phi), math.sin(phi), 0.0)  # from the cue ball to the object ball
    _, _, v2, _, _ = _impact((v, 0, 0), (0, 0, 0), (0, 0, 0), (0, 0, 0), n, e,
                             lambda s: friction_coefficient(s, PV))
    # angle between the object ball's path and the line of centres
    return abs(math.degrees(math.atan2(v2[1] * n[0] - v2[0] * n[1], v2 @ np.array(n))))


def test_alciatore_throw_of_a_stun_cut():
    """Stun shot, cut angle phi, speed v: the contact slip is v sin(phi), the
    normal impulse (1 + e) v cos(phi) / 2, so the object ball is thrown by
    theta = atan(min(mu(v sin phi), 2 tan(phi) / (7 (1 + e)))).
    Alciatore's throw curves (TP A-14) give a few degrees at a 30-degree cut,
    more for slow shots than for fast ones; here: 1 mph (0.447 m/s) and
    7 mph (3.13 m/s)."""
    e, phi = P.e_b, math.radians(30.0)
    for v in (0.447, 1.34, 3.13):
        closed = math.degrees(math.atan(min(friction_coefficient(v * math.sin(phi), PV),
                                            2.0 * math.tan(phi) / (7.0 * (1.0 + e)))))
        assert _throw_deg(v, 30.0) == pytest.approx(closed, rel=1e-12)
    slow, medium, fast = _throw_deg(0.447, 30.0), _throw_deg(1.34, 30.0), _throw_deg(3.13, 30.0)
    assert 3.0 < slow < 6.0 and 1.0 < fast < 3.0
    assert slow > medium > fast
    # the constant mu_b = 0.06 of the standard preset throws 3.4 degrees at every speed
    assert fast < math.degrees(math.atan(P.mu_b)) < slow


def test_alciatore_coulomb_never_reverses_the_slip():
    """With mu(slip) up to a + b = 0.118 and the cap |u_t| / 7, the slip after
    the impulse is u_t' = u_t (1 - 7 jt / |u_t|) with 0 <= 7 jt <= |u_t|: same
    direction, never longer; momentum is conserved and energy never rises.
    Checked on random 3D states (spins up to 400 rad/s)."""
    rng = np.random.default_rng(3)
    for _ in range(2000):
        phi = rng.uniform(-1.5, 1.5)
        n = np.array([math.cos(phi), math.sin(phi), 0.0])
        v1 = np.r_[rng.uniform(-12, 12, 2), 0.0]
        if v1 @ n <= 0:
            v1[:2] = -v1[:2]
        v2 = np.r_[rng.uniform(-1, 1, 2) * abs(v1 @ n) * 0.5, 0.0]
        w1, w2 = rng.uniform(-400, 400, 3), rng.uniform(-400, 400, 3)
        a1, b1, a2, b2, ut = _impact(v1, w1, v2, w2, n, P.e_b, lambda s: friction_coefficient(s, PV))
        u = (a1 + np.cross(b1, R * n)) - (a2 + np.cross(b2, -R * n))
        ut_after = u - (u @ n) * n
        assert ut_after @ ut >= -ROUND * (ut @ ut)
        assert np.linalg.norm(ut_after) <= np.linalg.norm(ut) * (1 + ROUND)
        np.testing.assert_allclose(a1 + a2, v1 + v2, atol=ROUND * 100)
        e_in = v1 @ v1 + v2 @ v2 + 0.4 * R * R * (w1 @ w1 + w2 @ w2)
        e_out = a1 @ a1 + a2 @ a2 + 0.4 * R * R * (b1 @ b1 + b2 @ b2)
        assert e_out <= e_in * (1 + ROUND)


# ---------------------------------------------------------------- Mathavan
def _rolling_head_on(V, p=PV, e=P.e_c):
    """Cushion along the x axis, normal (0, 1); the ball rolls straight in
    (v = (0, -V), w = z x v / R = (V / R, 0, 0))."""
    v = (0.0, -V, V / R, 0.0, 0.0)
    return v, resolve(*v, 0.0, 1.0, e, p)


@pytest.mark.parametrize("e", [0.85, 0.98])
def test_mathavan_rolling_head_on(e):
    """Rolling ball, normal incidence. The equations are homogeneous of
    degree one in (v, R w) and the impulse step scales with the speed, so
    v_out / v_in is the same at every speed; friction at the cushion nose
    and the felt takes some of the bounce: 0.8 e < v_out / v_in < e.
    Energy never rises; no sideways motion or side spin appears."""
    ratios = []
    for V in (0.05, 0.2, 0.5, 1.0, 2.0, 4.0, 8.0, 12.0):
        vin, out = _rolling_head_on(V, e=e)
        ratios.append(out[1] / V)
        assert out[0] == 0.0 and out[4] == 0.0 and out[3] == 0.0
        assert _energy2(out) <= _energy2(vin)
    np.testing.assert_allclose(ratios, ratios[0], rtol=1e-12)
    assert 0.8 * e < ratios[0] < e


def test_mathavan_frictionless_is_the_restitution():
    """f_c = mu_s = 0, no spin: only the normal impulse acts, dv_n / dP =
    cos(theta) / m, so the work released in restitution, e^2 times the
    compression work m v_n^2 / 2, gives v_n' = e v_n exactly (the
    restitution's definition by work, eq. 16b); v_t and the spin keep their
    values."""
    p = _params(f_c=0.0, mu_s=0.0)
    rng = np.random.default_rng(5)
    for _ in range(200):
        a = rng.uniform(-1.5, 1.5)
        V = rng.uniform(0.01, 12.0)
        e = float(rng.choice([0.0, 0.5, 0.85, 1.0, rng.uniform()]))
        g = rng.uniform(-math.pi, math.pi)  # the normal's direction
        nx, ny = math.cos(g), math.sin(g)
        tx, ty = -ny, nx
        vn, vt = -V * math.cos(a), V * math.sin(a)
        out = resolve(vn * nx + vt * tx, vn * ny + vt * ty, 0.0, 0.0, 0.0, nx, ny, e, p)
        assert out[0] * nx + out[1] * ny == pytest.approx(-e * vn, rel=1e-9, abs=1e-12 * V)
        assert out[0] * tx + out[1] * ty == pytest.approx(vt, rel=1e-12, abs=1e-12 * V)
        assert out[2:] == (0.0, 0.0, 0.0)


def test_mathavan_cushion_sliding_throughout():
    """Nose at the equator (h = R: theta = 0), no felt friction; the cushion
    lies below the ball (normal (0, 1)) and the ball comes straight in at V
    with side spin W so large that its contact point slides one way, along
    +x at v_x + R w_z > 0, throughout. The friction mu_w dP then points along
    -x all the way, so with the total normal impulse P = (1 + e) m V (eqs.
    14f, 17a-b at theta = 0): v_x' = -mu_w P / m, v_y' = e V,
    w_z' = W - (5 / 2) mu_w P / (m R), w_x' = w_y' = 0."""
    mu_w, e, V, W = 0.2, 0.85, 2.0, 300.0
    assert 3.5 * mu_w * (1 + e) * V < R * W  # the slip never ends
    p = _params(f_c=mu_w, mu_s=0.0)
    p[C.P_H_C] = R  # outside the validated range on purpose: the theta = 0 limit
    out = resolve(0.0, -V, 0.0, 0.0, W, 0.0, 1.0, e, p)
    Pm = (1 + e) * V
    np.testing.assert_allclose(out, (-mu_w * Pm, e * V, 0.0, 0.0, W - 2.5 * mu_w * Pm / R),
                               rtol=1e-9, atol=1e-12)


def test_mathavan_felt_friction_reverses():
    """Frictionless cushion (f_c = 0), felt friction mu_s, ball without spin
    coming straight in at V (cushion frame: normal (0, -1), so the world and
    the paper's axes agree). The cushion's normal impulse presses the ball
    on the felt with sin(theta) per unit P; the felt friction f = mu_s
    sin(theta) first opposes the slip y_C = v_y + R w_x (eq. 13b), which falls
    at (cos(theta) + 7/2 f) / m per unit P and ends at P_s = m V / (cos(theta)
    + 7/2 f); sticking would need cos(theta) / 3.5 > f, so the slip reverses
    and the friction with it. Then v_y falls at a1 = (cos(theta) + f) / m
    before P_s, a2 = (cos(theta) - f) / m after; compression work
    W_c = cos(theta) [V P_s - a1 P_s^2 / 2 + v_s^2 / (2 a2)], v_s = V - a1 P_s;
    restitution releases e^2 W_c = cos(theta) a2 (P - P_c)^2 / 2, so
    v_y' = -sqrt(2 a2 e^2 W_c / cos(theta)), and w_x' = (5 f / 2 m R)
    (P_f - 2 P_s) with P_f the total impulse."""
    mu_s, e, V = 0.2, 0.85, 1.5
    p = _params(f_c=0.0, mu_s=mu_s)
    M, s_t = P.m, P.h_c / R - 1.0
    c_t = math.sqrt(1.0 - s_t * s_t)
    f = mu_s * s_t
    assert c_t / 3.5 > f
    a1, a2 = (c_t + f) / M, (c_t - f) / M
    Ps = M * V / (c_t + 3.5 * f)
    vs = V - a1 * Ps
    Pc = Ps + vs / a2
    Wc = c_t * (V * Ps - 0.5 * a1 * Ps ** 2 + vs ** 2 / (2 * a2))
    dPr = math.sqrt(2 * e * e * Wc / (c_t * a2))
    Pf = Pc + dPr
    expect = (0.0, -a2 * dPr, 2.5 * f / (M * R) * (Pf - 2 * Ps), 0.0, 0.0)
    out = resolve(0.0, V, 0.0, 0.0, 0.0, 0.0, -1.0, e, p)
    np.testing.assert_allclose(np.array(out) * [1, 1, R, R, R], np.array(expect) * [1, 1, R, R, R],
                               atol=STEP_TOL * V)


def _head_on_exact(V, wx, p_m, R, st, mu_w, mu_s, e):
    """The exact head-on impact, cushion frame (v_y = V into the cushion,
    spin w_x about the cushion line, every x component zero and staying
    zero): each contact's slip is along y only (eqs. 12b, 13b), so its
    friction is constant between the instants a slip reaches zero, where
    the regime that is consistent (a held contact's friction in its cone,
    a sliding one's slip moving the way its friction assumes) takes over;
    v_y and w_x are then piecewise linear in P and W (eq. 16a) piecewise
    quadratic, and every phase ends in closed form. Returns (v_y, w_x)
    after restitution (eq. 16b)."""
    ct = math.sqrt(1 - st * st)
    g = 2.5 - st
    vy, w, W, compressing, target = V, wx, 0.0, True, None

    def frictions(ri, rc):
        if ri == 0 and rc == 0:
            raise AssertionError("both held away from v_y = 0")
        if ri == 0:
            FIy = -(st * ct - g * rc * mu_s * st) / (2.5 + st * st + g * rc * mu_s * ct)
            return FIy, -rc * mu_s * max(st - ct * FIy, 0.0)
        FIy = -ri * mu_w
        if rc == 0:
            return FIy, (ct - g * FIy) / 3.5
        return FIy, -rc * mu_s * max(st - ct * FIy, 0.0)

    def slip_rates(FIy, FCy):
        return (st * ct + (2.5 + st * st) * FIy + g * FCy) / p_m, (-ct + g * FIy + 3.5 * FCy) / p_m

    def sign(x):
        return (x > 0) - (x < 0)

    for _ in range(50):
        yi, yc = -vy * st + R * w, vy + R * w
        regime = None
        for ri in ([sign(yi)] if yi != 0 else [0, 1, -1]):
            for rc in ([sign(yc)] if yc != 0 else [0, 1, -1]):
                try:
                    FIy, FCy = frictions(ri, rc)
                except AssertionError:
                    continue
                di, dc = slip_rates(FIy, FCy)
                ok = True
                if yi == 0:
                    ok &= abs(FIy) <= mu_w if ri == 0 else ri * di > 0
                if yc == 0:
                    ok &= abs(FCy) <= mu_s * max(st - ct * FIy, 0.0) if rc == 0 else rc * dc > 0
                if ok and regime is None:
                    regime = (FIy, FCy, di, dc, ri, rc)
        FIy, FCy, di, dc, ri, rc = regime
        avy = (-ct - st * FIy + FCy) / p_m
        aw = 2.5 / (p_m * R) * (FIy + FCy)
        events = []
        if ri != 0 and yi * di < 0:
            events.append(-yi / di)
        if rc != 0 and yc * dc < 0:
            events.append(-yc / dc)
        if compressing:
            events.append(-vy / avy)
        else:  # W(t) = W + ct (vy t + avy t^2 / 2) = target
            q = (W - target) / ct
            events.append(2 * q / (-vy + math.sqrt(vy * vy - 2 * avy * q)))
        t = min(events)
        W += ct * (vy * t + 0.5 * avy * t * t)
        vy, w = vy + avy * t, w + aw * t
        if t == events[-1]:
            if not compressing:
                return vy, w
            compressing, target, vy = False, (1 - e * e) * W, 0.0
        else:  # a slip reached zero: set it exactly
            if ri != 0 and yi * di < 0 and t == -yi / di:
                w = vy * st / R
            else:
                w = -vy / R
    raise AssertionError("too many phases")


@pytest.mark.parametrize("mu_w, mu_s", [(0.2, 0.2), (0.0, 0.2), (0.2, 0.0), (0.5, 0.3), (0.1, 0.5)])
def test_mathavan_head_on_closed_form(mu_w, mu_s):
    """Head-on impacts (stun, rolling, top and back spin) against their
    closed form (``_head_on_exact``): v_y and w_x within HEAD_ON_TOL of the
    speed scale (measured: 5e-8 at most), and no x component or side spin
    appears."""
    p = _params(f_c=mu_w, mu_s=mu_s)
    st = P.h_c / R - 1.0
    for V, wx in ((2.0, 0.0), (2.0, -2.0 / R), (3.0, 3.0 / R), (1.0, -40.0)):
        vy, w = _head_on_exact(V, wx, P.m, R, st, mu_w, mu_s, P.e_c)
        out = resolve(0.0, V, wx, 0.0, 0.0, 0.0, -1.0, P.e_c, p)
        assert out[0] == 0.0 and out[3] == 0.0 and out[4] == 0.0
        assert max(abs(out[1] - vy), R * abs(out[2] - w)) < HEAD_ON_TOL * (V + R * abs(wx))


def _random_impacts(n, seed):
    rng = np.random.default_rng(seed)
    for _ in range(n):
        V = rng.uniform(0.05, 12.0)
        a = rng.uniform(-1.55, 1.55)
        yield (V * math.sin(a), -V * math.cos(a), *rng.uniform(-400.0, 400.0, 3))


def test_mathavan_mirror_symmetry():
    """Mirror in the plane through the normal (0, 1) and the vertical: v_x,
    and the pseudovector components w_y, w_z change sign (w_x does not);
    the outgoing state is mirrored the same way."""
    for v in _random_impacts(300, 7):
        out = np.array(resolve(*v, 0.0, 1.0, P.e_c, PV))
        m = (-v[0], v[1], v[2], -v[3], -v[4])
        mout = np.array(resolve(*m, 0.0, 1.0, P.e_c, PV))
        np.testing.assert_allclose(mout, out * np.array([-1, 1, 1, -1, -1]), rtol=MIRROR_TOL, atol=ROUND)


def _rot(x, y, g):
    c, s = math.cos(g), math.sin(g)
    return c * x - s * y, s * x + c * y


def test_mathavan_rotation_invariance():
    """Rotate the whole impact (velocity, horizontal spin, normal) about the
    vertical by g: the outgoing velocity and horizontal spin rotate by g and
    w_z is unchanged."""
    rng = np.random.default_rng(11)
    for v in _random_impacts(300, 9):
        out = resolve(*v, 0.0, 1.0, P.e_c, PV)
        g = rng.uniform(-math.pi, math.pi)
        vx, vy = _rot(v[0], v[1], g)
        wx, wy = _rot(v[2], v[3], g)
        nx, ny = _rot(0.0, 1.0, g)
        r = resolve(vx, vy, wx, wy, v[4], nx, ny, P.e_c, PV)
        scale = math.hypot(v[0], v[1]) + R * 400.0
        np.testing.assert_allclose(r[:2], _rot(out[0], out[1], g), atol=ROT_TOL * scale)
        np.testing.assert_allclose(np.array(r[2:4]) * R, np.array(_rot(out[2], out[3], g)) * R,
                                   atol=ROT_TOL * scale)
        assert r[4] * R == pytest.approx(out[4] * R, abs=ROT_TOL * scale)


def test_mathavan_no_approach_is_no_impulse():
    """A ball moving away from (or along) the cushion is returned unchanged."""
    for v in ((0.3, 0.2, 1.0, 2.0, 3.0), (0.3, 0.0, 1.0, 2.0, 3.0)):
        assert resolve(*v, 0.0, 1.0, P.e_c, PV) == v


@settings(max_examples=1500, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(speed=st.floats(0.0, 12.0), angle=st.floats(-math.pi, math.pi),
       spin=st.tuples(*[st.floats(-400.0, 400.0)] * 3), normal=st.floats(-math.pi, math.pi),
       e=st.floats(0.0, 1.0), f_c=st.floats(0.0, 1.0), mu_s=st.floats(0.0, 1.0),
       h=st.floats(1.001, 1.999))
def test_mathavan_fuzz(speed, angle, spin, normal, e, f_c, mu_s, h):
    """Random impacts (speeds to 12 m/s, spins to 400 rad/s, any restitution,
    frictions up to 1, nose heights just above R to just below 2R): the result is finite, the
    energy never rises, and the ball never leaves moving into the cushion
    (for e > 0 its normal velocity is >= 0)."""
    p = _params(f_c=f_c, mu_s=mu_s, h_c=h * R)
    v = (speed * math.cos(angle), speed * math.sin(angle), *spin)
    nx, ny = math.cos(normal), math.sin(normal)
    out = resolve(*v, nx, ny, e, p)
    assert all(math.isfinite(x) for x in out)
    assert _energy2(out) <= _energy2(v) * (1 + ROUND)
    vn_in = v[0] * nx + v[1] * ny
    vn_out = out[0] * nx + out[1] * ny
    if vn_in < 0:
        assert vn_out >= -ROUND * (speed + R * 400.0)


@settings(max_examples=1500, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(u=st.floats(-12.0, 12.0), vn=st.floats(1e-3, 12.0),
       spin=st.tuples(*[st.floats(-400.0, 400.0)] * 3),
       e=st.floats(0.0, 1.0), f_c=st.floats(0.0, 1.0), mu_s=st.floats(0.0, 1.0),
       s_t=st.floats(0.001, 0.999))
def test_mathavan_integration_dissipates(u, vn, spin, e, f_c, mu_s, s_t):
    """The integration itself, before the energy guard, never gains energy:
    every friction term opposes its contact's slip (so does negative work),
    the felt's normal impulse does none (v_z = 0), and the cushion's normal
    impulse returns e^2 <= 1 of the compression work. A friction or torque
    term with a wrong sign fails here even where the guard would hide it."""
    c_t = math.sqrt(1.0 - s_t * s_t)
    v = (u, vn, *spin)
    out = mathavan2010._integrate(mathavan2010.Ball(*v, 0.0), mathavan2010.Contact(R, P.m, s_t, c_t, f_c, mu_s),
                                  e, mathavan2010.STEP_TOL)
    assert _energy2(out) <= _energy2(v) * (1 + ROUND)
