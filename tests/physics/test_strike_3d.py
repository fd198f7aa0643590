"""The elevated cue (issue 46, item 1): ``strike`` and ``strike_velocity``
with ``theta``, and ``cue_strike_3d``, against closed forms.

Model (physics/strike.py): the cue's force J along its axis
f = cos(theta) d - sin(theta) z at the contact point
r = R(a s + b u - c f), u = sin(theta) d + cos(theta) z, c = sqrt(1 - a^2 - b^2);
v = J f / m, omega = r x J f / I (Leckie & Greenspan 2006; Alciatore TP A-30).
"""
import math

import numpy as np
import pytest

from billiards_env.physics import BallState, Effects, Table, simulate, strike, strike_velocity
from billiards_env.physics import constants as C
from billiards_env.physics.strike import MAX_ELEVATION, apply_strike, cue_strike_3d

N = 2000


def level_strike_before_issue_46(state, phi, speed, a, b, R):
    """``apply_strike`` as it was before the cue had an elevation (commit
    9338ec5), verbatim: the reference the level strike must equal bit for bit."""
    dx, dy = np.cos(phi), np.sin(phi)
    state.vel[:, 0, 0] = speed * dx
    state.vel[:, 0, 1] = speed * dy
    k = 2.5 * speed / R
    state.omega[:, 0, 0] = k * b * (-dy)
    state.omega[:, 0, 1] = k * b * dx
    state.omega[:, 0, 2] = k * a


def _random_shots(rng, n=N):
    """Aims over several turns (cardinal directions, where sines are exact zeros,
    included), speeds with zeros, offsets in the miscue disc with exact zeros
    and negative zeros."""
    phi = rng.uniform(-3 * np.pi, 3 * np.pi, n)
    phi[:8] = np.array([0, 0.5, 1, 1.5, 2, -0.5, -1, 3]) * np.pi
    speed = rng.uniform(0, 12, n)
    speed[8:16] = 0.0
    r, ang = 0.5 * np.sqrt(rng.uniform(0, 1, n)), rng.uniform(0, 2 * np.pi, n)
    a, b = r * np.cos(ang), r * np.sin(ang)
    a[16:40:2] = 0.0
    b[17:41:2] = 0.0
    a[40:50] = -0.0
    b[50:60] = -0.0
    return phi, speed, a, b


def _bits(x):
    return np.ascontiguousarray(x).view(np.int64)


def _frame(phi, theta):
    """Unit vectors d (aim), s (right), z (up), f (cue axis), u (cue's up), [n, 3] each."""
    n = len(phi)
    d = np.stack([np.cos(phi), np.sin(phi), np.zeros(n)], 1)
    z = np.tile([0.0, 0.0, 1.0], (n, 1))
    s = np.cross(d, z)
    ct, st = np.cos(theta)[:, None], np.sin(theta)[:, None]
    return d, s, z, ct * d - st * z, st * d + ct * z


def _contact(a, b, s, u, f, R):
    """[n, 3] the tip's contact point from the ball's centre: offsets a (along s) and b (along u) in the cue's
    frame, on the side of the ball facing the cue (against f)."""
    return R * (a[:, None] * s + b[:, None] * u - np.sqrt(1 - a ** 2 - b ** 2)[:, None] * f)


def test_level_cue_is_todays_strike_bit_for_bit(params):
    """theta = 0 (omitted, a scalar 0, an array of zeros, or cue_strike_3d
    itself) gives the same bits as the strike before the elevation existed,
    zeros' signs included, on random shots."""
    rng = np.random.default_rng(46)
    phi, speed, a, b = _random_shots(rng)
    state = BallState.from_positions(np.full((N, 1, 2), 0.6))
    ref = state.copy()
    level_strike_before_issue_46(ref, phi, speed, a, b, params.R)
    for theta in (None, 0.0, np.zeros(N)):
        kw = {} if theta is None else {"theta": theta}
        out = strike_velocity(state, phi, speed, a, b, params, **kw)
        assert np.array_equal(_bits(out.vel), _bits(ref.vel))
        assert np.array_equal(_bits(out.omega), _bits(ref.omega))
    v, w = cue_strike_3d(phi, speed, a, b, np.zeros(N), params.R)
    assert np.array_equal(_bits(v[:, :2]), _bits(ref.vel[:, 0]))
    assert np.array_equal(_bits(w), _bits(ref.omega[:, 0]))
    direct = state.copy()
    apply_strike(direct, phi, speed, a, b, params.R, np.zeros(N))  # the general path with every theta 0
    assert np.array_equal(_bits(direct.omega), _bits(ref.omega))
    # strike (the cue's draw) too: the same speed law, the same bits
    draw = rng.uniform(0, params.max_draw, N)
    ref2 = state.copy()
    level_strike_before_issue_46(ref2, phi, params.k * params.contact_time * draw / params.m, a, b, params.R)
    out = strike(state, phi, draw, a, b, params, theta=0.0)
    assert np.array_equal(_bits(out.vel), _bits(ref2.vel)) and np.array_equal(_bits(out.omega), _bits(ref2.omega))


def test_mixed_elevations_keep_the_level_rows_bit_for_bit(params):
    rng = np.random.default_rng(1)
    phi, speed, a, b = _random_shots(rng)
    theta = np.where(rng.random(N) < 0.5, 0.0, rng.uniform(0, MAX_ELEVATION, N))
    state = BallState.from_positions(np.full((N, 1, 2), 0.6))
    ref = state.copy()
    level_strike_before_issue_46(ref, phi, speed, a, b, params.R)
    out = strike_velocity(state, phi, speed, a, b, params, theta=theta)
    flat = theta == 0
    assert np.array_equal(_bits(out.vel[flat]), _bits(ref.vel[flat]))
    assert np.array_equal(_bits(out.omega[flat]), _bits(ref.omega[flat]))
    moving = ~flat & (speed > 0)
    assert np.all(np.hypot(*out.vel[moving, 0].T) < speed[moving])  # the horizontal part only


def test_impulse_gives_momentum_and_angular_momentum(params):
    """m v = J f and I omega = r x (J f), with r built from the offsets in the cue's frame."""
    rng = np.random.default_rng(2)
    phi, speed, a, b = _random_shots(rng)
    theta = rng.uniform(0, MAX_ELEVATION, N)
    m, R, I = params.m, params.R, params.inertia
    v, w = cue_strike_3d(phi, speed, a, b, theta, R)
    d, s, z, f, u = _frame(phi, theta)
    r = _contact(a, b, s, u, f, R)
    J = (m * speed)[:, None] * f
    np.testing.assert_allclose(m * v, J, rtol=0, atol=1e-13)
    np.testing.assert_allclose(I * w, np.cross(r, J), rtol=0, atol=1e-13 * R)
    np.testing.assert_allclose(np.linalg.norm(r, axis=1), R, rtol=1e-14)  # r is on the ball
    assert np.all(np.einsum("ij,ij->i", r, f) <= 1e-15)  # on the side facing the cue


def test_kinetic_energy_is_the_work_of_the_impulse(params):
    """An impulse J on a body at rest does the work (1/2) J . (velocity of its
    point of application after): 1/2 m v^2 + 1/2 I w^2 = 1/2 J . (v + w x r);
    both equal 1/2 m v0^2 (1 + 5/2 (a^2 + b^2)) at every elevation."""
    rng = np.random.default_rng(3)
    phi, speed, a, b = _random_shots(rng)
    theta = rng.uniform(0, MAX_ELEVATION, N)
    m, R, I = params.m, params.R, params.inertia
    v, w = cue_strike_3d(phi, speed, a, b, theta, R)
    d, s, z, f, u = _frame(phi, theta)
    r = _contact(a, b, s, u, f, R)
    ke = 0.5 * m * np.sum(v * v, 1) + 0.5 * I * np.sum(w * w, 1)
    work = 0.5 * np.einsum("ij,ij->i", (m * speed)[:, None] * f, v + np.cross(w, r))
    np.testing.assert_allclose(ke, work, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(ke, 0.5 * m * speed ** 2 * (1 + 2.5 * (a ** 2 + b ** 2)), rtol=1e-12, atol=1e-15)


def test_masse_spin_against_its_closed_form(params):
    """omega = 5 v0 / (2R) (a (cos(theta) z + sin(theta) d) - b s): its magnitude
    5 v0 |(a, b)| / (2R) at every elevation, its axis across the cue
    (omega . f = 0), the side offset's spin turning from english about z to
    massé spin about the aim line; a vertical cue gives no english at all."""
    rng = np.random.default_rng(4)
    phi, speed, a, b = _random_shots(rng)
    theta = rng.uniform(0, MAX_ELEVATION, N)
    R = params.R
    v, w = cue_strike_3d(phi, speed, a, b, theta, R)
    d, s, z, f, u = _frame(phi, theta)
    k = 2.5 * speed / R
    np.testing.assert_allclose(np.linalg.norm(w, axis=1), k * np.hypot(a, b), rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(np.einsum("ij,ij->i", w, f), 0, atol=1e-12 * k.max())
    np.testing.assert_allclose(np.einsum("ij,ij->i", w, d), k * a * np.sin(theta), rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(w[:, 2], k * a * np.cos(theta), rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(np.einsum("ij,ij->i", w, s), -k * b, rtol=1e-12, atol=1e-12)
    # a vertical cue, right of centre: pure massé spin about the aim line, none about z
    v, w = cue_strike_3d(0.0, 2.0, 0.3, 0.0, np.pi / 2, R)
    np.testing.assert_allclose(w, [2.5 * 2.0 / R * 0.3, 0, 0], atol=1e-12)
    np.testing.assert_allclose(v, [0, 0, -2.0], atol=1e-15)


def test_right_masse_curves_right_on_the_felt(params):
    """Right of centre with the butt raised: the contact point with the cloth
    slips to the left (u = v - R omega x z), so the felt's friction, opposite
    to it, pulls the ball to the right (and a left offset to the left): the
    sign of the curve, as players see it."""
    for a, side in ((0.3, 1.0), (-0.3, -1.0)):
        v, w = cue_strike_3d(0.0, 2.0, a, 0.0, np.radians(60), params.R)  # aim +x: right is -y
        uy = v[1] + params.R * w[0]  # motion.slip
        friction_y = -np.sign(uy)
        assert friction_y == -side  # +x aim: right is -y


def test_vertical_velocity_into_the_slate(params):
    """A raised butt drives the ball down into the slate: v_z = -v0 sin(theta),
    the horizontal speed v0 cos(theta) (what the planar state keeps)."""
    theta = np.linspace(0, MAX_ELEVATION, 7)
    v, w = cue_strike_3d(np.zeros(7), 3.0, 0.0, 0.0, theta, params.R)
    assert v[0, 2] == 0 and np.all(v[1:, 2] < 0)
    np.testing.assert_allclose(v[:, 2], -3.0 * np.sin(theta), rtol=1e-15)
    np.testing.assert_allclose(np.hypot(v[:, 0], v[:, 1]), 3.0 * np.cos(theta), rtol=1e-15, atol=1e-15)
    np.testing.assert_allclose(w, 0, atol=1e-15)  # through the centre: no spin at any elevation
    state = strike_velocity(BallState.from_positions(np.full((7, 1, 2), 0.6)), 0.0, 3.0, params=params, theta=theta)
    np.testing.assert_allclose(state.vel[:, 0, 0], 3.0 * np.cos(theta), rtol=1e-15, atol=1e-15)


@pytest.mark.parametrize("theta", [-0.01, MAX_ELEVATION + 1e-9, math.nan, math.inf, [0.1, 0.2]])
def test_bad_elevations_are_refused(params, theta):
    s = BallState.from_positions(np.full((3, 1, 2), 0.6))
    with pytest.raises(ValueError, match="theta"):
        strike_velocity(s, 0.0, 1.0, params=params, theta=theta)
    with pytest.raises(ValueError, match="theta"):
        strike(s, 0.0, 0.1, params=params, theta=theta)


def test_masse_slide_ends_where_the_felt_closed_form_says(params):
    """Through the simulator: an elevated right-english stroke on an open
    table slides along a parabola (the felt's friction keeps the slip's
    direction), curving right, and rolls off at v0 - 2/7 u0 (u0 the slip
    after the strike) at t = 2|u0| / (7 mu_s g), where the closed form puts it."""
    table = Table.pool(9)
    theta, a, b, speed = np.radians(50), 0.35, 0.1, 1.0
    start = BallState.from_positions([[[table.width / 2, 0.6]]])
    s = strike_velocity(start, np.pi / 2, speed, a, b, params, theta=theta)
    res = simulate(s, table, params, record=True, effects=Effects())
    log = res.events[0]
    k = list(log.kind).index(C.EV_SLIDE_ROLL)
    assert list(log.kind[1:k]) == []  # nothing before the slide ends
    v0 = s.vel[0, 0]
    w0 = s.omega[0, 0]
    u0 = np.array([v0[0] - params.R * w0[1], v0[1] + params.R * w0[0]])
    ts = 2 * np.linalg.norm(u0) / (7 * params.mu_s * params.g)
    uhat = u0 / np.linalg.norm(u0)
    x_end = start.pos[0, 0] + v0 * ts - 0.5 * params.mu_s * params.g * uhat * ts ** 2
    assert log.time[k] == pytest.approx(ts, rel=1e-9)
    np.testing.assert_allclose(log.states[k, 0, 2:4], v0 - 2 / 7 * u0, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(log.states[k, 0, :2], x_end, rtol=1e-9, atol=1e-12)
    assert log.states[k, 0, 0] > start.pos[0, 0, 0]  # aimed up the table (+y): right is +x


@pytest.mark.parametrize("solver", ["event", "step"])
@pytest.mark.parametrize("seed", [0, 1])
def test_elevated_strikes_keep_the_invariants(solver, seed):
    """The planar simulator after elevated strikes (the spin about every
    axis that massé and jump strokes give; their velocity into the slate
    dropped): the fuzzing's invariants hold (no NaN, no energy gain, no
    overlap, no ball off the table). 64 tables per layout, elevations
    uniform over [0, pi/2]; ``python scripts/fuzz_elevated.py`` runs more."""
    from billiards_env.testing import LAYOUTS, random_batch, run_batch
    rng = np.random.default_rng(seed)
    for layout in LAYOUTS:
        state, table, params = random_batch(rng, 64, layout, "standard")
        n = state.n_envs
        r, ang = params.miscue_limit * np.sqrt(rng.uniform(0, 1, n)) * (1 - 1e-12), rng.uniform(0, 2 * np.pi, n)
        struck = strike(state, rng.uniform(0, 2 * np.pi, n), params.max_draw * rng.uniform(0, 1, n) ** 0.5,
                        r * np.cos(ang), r * np.sin(ang), params, theta=rng.uniform(0, MAX_ELEVATION, n))
        _, violations = run_batch(struck, table, params, solver)
        assert not any(violations), [v for v in violations if v][:3]


@pytest.mark.parametrize("solver, extra", [("event", []), ("step", []), ("event", ["--airborne"]),
                                           ("step", ["--airborne"]), ("event", ["--airborne", "--table", "snooker"]),
                                           ("event", ["--airborne", "--table", "carom"])])
def test_fuzz_elevated_script_quick(tmp_path, solver, extra):
    """scripts/fuzz_elevated.py (docs/physics.md names it) at a tiny size, both solvers, planar and with balls in
    flight (``--airborne``) on each table: runs, strikes with the cue elevated, finds nothing, and its summary says
    so; with ``--airborne`` some balls really leave the table over a rail (none can without it)."""
    import json
    import pathlib
    import subprocess
    import sys
    root = pathlib.Path(__file__).resolve().parents[2]
    out = subprocess.run([sys.executable, str(root / "scripts" / "fuzz_elevated.py"), "--shots", "64", "--batch",
                          "32", "--seed", "5", "--solver", solver, "--summary", str(tmp_path / "s.json"),
                          "--regressions", str(tmp_path / "reg"), *extra], capture_output=True, text=True,
                         timeout=900, cwd=root)
    assert out.returncode == 0, out.stdout[-2000:] + out.stderr[-2000:]
    s = json.loads((tmp_path / "s.json").read_text())
    assert s["solver"] == solver and s["shots"] == 64 and s["shots_with_violations"] == 0 and s["events"] > 64
    assert s["theta_max"] > 0 and s["airborne"] == ("--airborne" in extra)
    assert (s["balls_off_table"] > 0) == ("--airborne" in extra), s
