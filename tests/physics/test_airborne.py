"""Airborne motion (physics/airborne.py, issue 46 item 2) against its closed
forms: the flight's parabola, time and range; the slate impact's
restitution, friction and sticking cap; bounce heights falling by e^2; the
tolerance that ends the bounces; and ``Effects(airborne=...)``, an opt-in
effect that leaves every default set, key and record as it was."""
import math

import numpy as np
import pytest

from billiards_env.physics import Effects
from billiards_env.physics.airborne import (SETTLE_HEIGHT, SLATE_RESTITUTION, bounces, flight, landing_time,
                                            settles, slate_impact)
from billiards_env.physics.ball_ball.flight import flight_contact_time
from billiards_env.physics.strike import cue_strike_3d

G = 9.81
R = 0.028575
MU = 0.2


def _energy(v, w):
    """Kinetic energy per unit mass: |v|^2 / 2 + (2/5 R^2) |w|^2 / 2."""
    return 0.5 * float(np.dot(v, v)) + 0.2 * R * R * float(np.dot(w, w))


def test_flight_from_the_slate_lands_after_two_vz_over_g():
    """From the slate at (vh, vz): flight time 2 vz / g, range 2 vz vh / g,
    apex vz^2 / (2g) at half time, landing at -vz."""
    for vz, vh in ((0.5, 2.0), (1.7, 0.3), (3.0, 5.0)):
        t = landing_time(R, vz, R, G)
        assert t == pytest.approx(2 * vz / G, rel=1e-15)
        x, y, z, vz_end = flight(0.0, 0.0, R, vh, 0.0, vz, t, G)
        assert x == pytest.approx(2 * vz * vh / G, rel=1e-14)
        assert z == pytest.approx(R, abs=1e-15) and vz_end == pytest.approx(-vz, rel=1e-14)
        apex = flight(0.0, 0.0, R, vh, 0.0, vz, t / 2, G)[2]
        assert apex - R == pytest.approx(vz * vz / (2 * G), rel=1e-14)


def test_landing_time_from_a_height():
    """Dropped from height h above the slate: sqrt(2h/g); thrown down at
    -vz: the root of h - vz t - g t^2 / 2 = 0 (no cancellation); on the slate
    moving into it: 0 (the impact is now)."""
    h = 0.1
    assert landing_time(R + h, 0.0, R, G) == pytest.approx(math.sqrt(2 * h / G), rel=1e-15)
    vz = -2.0
    t = landing_time(R + h, vz, R, G)
    assert h + vz * t - 0.5 * G * t * t == pytest.approx(0.0, abs=1e-16)
    assert landing_time(R, -1.0, R, G) == 0.0 and landing_time(R, 0.0, R, G) == 0.0
    tiny = landing_time(R + 1e-12, -5.0, R, G)  # stable where the textbook form cancels
    assert tiny == pytest.approx(1e-12 / 5.0, rel=1e-9)


def test_slate_impact_restitution_and_sliding_friction():
    """A ball without spin landing with (vx, 0, vz): vz' = -e vz; friction
    mu (1 + e) |vz| against the slip while it slides (not capped here), the
    spin it gives 5/(2R) times that impulse about the axis across the motion."""
    vx, vz = 3.0, -1.0
    out = slate_impact(vx, 0.0, vz, 0.0, 0.0, 0.0, R, SLATE_RESTITUTION, MU)
    pn = (1 + SLATE_RESTITUTION) * 1.0
    assert out[2] == pytest.approx(SLATE_RESTITUTION * 1.0, rel=1e-15)
    assert out[0] == pytest.approx(vx - MU * pn, rel=1e-15)
    assert out[1] == 0.0 and out[5] == 0.0
    assert out[4] == pytest.approx(2.5 / R * MU * pn, rel=1e-14)  # topspin: w_y > 0 for +x motion
    # the slip fell by 7/2 of the friction impulse, and kept its direction
    u_after = out[0] - R * out[4]
    assert u_after == pytest.approx(vx - 3.5 * MU * pn, rel=1e-13)


def test_slate_impact_sticks_where_the_slip_ends():
    """Friction stronger than the slip: the cap 2/7 m |u| ends it exactly,
    the ball leaves the slate rolling (u = 0), with v' = v - 2/7 u (the
    felt's slide-end velocity) and the spin about z untouched."""
    v = np.array([0.4, -0.3, -2.0])
    w = np.array([5.0, -3.0, 7.0])
    out = slate_impact(*v, *w, R, SLATE_RESTITUTION, MU)
    ux, uy = v[0] - R * w[1], v[1] + R * w[0]
    assert out[0] - R * out[4] == pytest.approx(0.0, abs=1e-15)
    assert out[1] + R * out[3] == pytest.approx(0.0, abs=1e-15)
    np.testing.assert_allclose(out[:2], v[:2] - 2 / 7 * np.array([ux, uy]), rtol=1e-14)
    assert out[5] == 7.0


def test_slate_impact_never_adds_energy_and_never_reverses_the_slip():
    rng = np.random.default_rng(0)
    for _ in range(2000):
        v = rng.normal(0, 3, 3)
        v[2] = -abs(v[2])
        w = rng.normal(0, 150, 3)
        e, mu = rng.uniform(0, 1), rng.uniform(0, 0.6)
        out = slate_impact(*v, *w, R, e, mu)
        assert _energy(out[:3], out[3:]) <= _energy(v, w) * (1 + 1e-12)
        u0 = np.array([v[0] - R * w[1], v[1] + R * w[0]])
        u1 = np.array([out[0] - R * out[4], out[1] + R * out[3]])
        assert np.dot(u0, u1) >= -1e-12 and np.linalg.norm(u1) <= np.linalg.norm(u0) * (1 + 1e-12)
        assert out[2] == pytest.approx(-e * v[2], rel=1e-15)
    assert slate_impact(1.0, 2.0, 0.5, 3.0, 4.0, 5.0, R, 0.5, 0.2) == (1.0, 2.0, 0.5, 3.0, 4.0, 5.0)  # leaving


def test_bounce_heights_fall_by_e_squared_until_the_tolerance():
    """Dropped from h: rebound heights h e^2, h e^4, ... (the vertical motion
    does not feel the friction); the bounces end at the first rebound lower
    than SETTLE_HEIGHT, at the time the geometric series gives, the ball on
    the slate (z = R) and at rest vertically."""
    h, e = 0.2, SLATE_RESTITUTION
    out = bounces((0.0, 0.0, R + h), (1.0, 0.0, 0.0), (0.0, 0.0, 0.0), R, G, MU)
    vz = [o[2][2] for o in out]
    heights = [v * v / (2 * G) for v in vz[:-1]]
    np.testing.assert_allclose(heights, h * e ** (2 * np.arange(1, len(heights) + 1)), rtol=1e-12)
    assert heights[-1] >= SETTLE_HEIGHT > heights[-1] * e * e  # the next one would have been too low
    assert vz[-1] == 0.0
    n = len(out)
    assert n == math.ceil(math.log(SETTLE_HEIGHT / h) / math.log(e * e))
    v1 = math.sqrt(2 * G * h)
    t_expected = math.sqrt(2 * h / G) + sum(2 * v1 * e ** k / G for k in range(1, n))
    assert out[-1][0] == pytest.approx(t_expected, rel=1e-12)
    assert all(o[1][2] == R for o in out)  # every impact exactly on the slate, never under it
    # the first impact sticks (1 m/s of slip against mu (1 + e) 1.98 m/s of impulse):
    # the ball rolls, later impacts need no friction, and it goes on at 5/7 m/s
    assert out[0][2][0] == pytest.approx(5 / 7, rel=1e-14) and out[-1][2][0] == pytest.approx(5 / 7, rel=1e-14)
    x_expected = math.sqrt(2 * h / G) * 1.0 + (out[-1][0] - math.sqrt(2 * h / G)) * 5 / 7
    assert out[-1][1][0] == pytest.approx(x_expected, rel=1e-12)


def test_settle_tolerance_ends_the_bounces():
    """A rebound below SETTLE_HEIGHT ends them at once; a slate without
    restitution settles at the first impact; e = 1 (never settling) and a
    ball under the slate are refused."""
    slow = math.sqrt(2 * G * SETTLE_HEIGHT) * 0.999
    assert settles(slow, G, SETTLE_HEIGHT) and not settles(slow / 0.998, G, SETTLE_HEIGHT)
    out = bounces((0.0, 0.0, R), (0.0, 0.0, -slow / SLATE_RESTITUTION), (0.0, 0.0, 0.0), R, G, MU)
    assert len(out) == 1 and out[0][0] == 0.0 and out[0][2][2] == 0.0
    out = bounces((0.0, 0.0, R + 0.3), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), R, G, MU, e=0.0)
    assert len(out) == 1 and out[0][2][2] == 0.0
    with pytest.raises(ValueError, match="restitution"):
        bounces((0.0, 0.0, R + 0.3), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), R, G, MU, e=1.0)
    with pytest.raises(ValueError, match="below the slate"):
        bounces((0.0, 0.0, R - 1e-6), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), R, G, MU)


def test_a_jump_stroke_leaves_the_slate_and_lands_where_the_parabola_says():
    """A cue elevated 30 degrees through the centre: into the slate at
    v0 sin(theta), off it at e v0 sin(theta), the horizontal velocity cut by
    the slate's friction (capped by the rolling it reaches); the first
    flight's time and range are the parabola's."""
    v0, theta = 4.0, math.radians(30)
    v, w = cue_strike_3d(0.0, v0, 0.0, 0.0, theta, R)
    out = bounces((0.0, 0.0, R), v, w, R, G, MU)
    t0, p0, v1, w1 = out[0]
    assert t0 == 0.0 and v1[2] == pytest.approx(SLATE_RESTITUTION * v0 * math.sin(theta), rel=1e-14)
    pt = min(MU * (1 + SLATE_RESTITUTION) * v0 * math.sin(theta), 2 / 7 * v0 * math.cos(theta))
    assert v1[0] == pytest.approx(v0 * math.cos(theta) - pt, rel=1e-14)
    t1, p1 = out[1][0], out[1][1]
    assert t1 == pytest.approx(2 * v1[2] / G, rel=1e-14)
    assert p1[0] == pytest.approx(2 * v1[2] * v1[0] / G, rel=1e-13)
    assert (v1[2] ** 2 / (2 * G)) > 0.01  # it jumps about 1.2 cm: a real hop


def _distance(D, v, t):
    w = np.array(D) + np.array(v) * t + 0.5 * np.array([0.0, 0.0, -G]) * t * t
    return float(np.linalg.norm(w))


@pytest.mark.parametrize("ratio", [1.001, 0.999, 0.5])
def test_a_jump_clears_a_ball_when_its_apex_is_2R_above_it(ratio):
    """A ball leaving the slate at (vh, vz) passes straight over a resting
    ball under the apex of its flight (vh vz / g ahead). With vh^2 > g h the
    apex is the nearest point of the pass, so it clears the ball exactly
    when the apex h = vz^2 / (2g) is at least 2R: the quartic has no root
    before the landing; below that it touches on the way up, 2R from the
    resting ball's centre, and never nearer before."""
    h = 2 * R * ratio
    vz, vh = math.sqrt(2 * G * h), 2.0
    assert vh * vh > G * h
    L = vh * vz / G
    D, v = (-L, 0.0, 0.0), (vh, 0.0, vz)
    t = flight_contact_time(*D, *v, R, G, landing_time(R, vz, R, G))
    if ratio > 1:
        assert t == math.inf
        return
    assert 0 < t < vz / G  # before the apex
    assert _distance(D, v, t) == pytest.approx(2 * R, rel=1e-12)
    assert min(_distance(D, v, x) for x in np.linspace(0, t, 200)[:-1]) > 2 * R


def test_a_ball_dropped_on_a_ball_touches_it_when_free_fall_says():
    """Dropped from h0 straight above a resting ball's centre: contact when
    h0 - g t^2 / 2 = 2R; dropped 2R + 1 um beside it: none."""
    h0 = 0.3
    t = flight_contact_time(0.0, 0.0, h0, 0.0, 0.0, 0.0, R, G, 1.0)
    assert t == pytest.approx(math.sqrt(2 * (h0 - 2 * R) / G), rel=1e-12)
    assert flight_contact_time(2 * R + 1e-6, 0.0, h0, 0.0, 0.0, 0.0, R, G, 1.0) == math.inf


def test_airborne_is_opt_in():
    """Off (the default) it is invisible: each_off's sets, their kernel keys
    and to_dict are what they were; on, both solvers simulate it
    (test_airborne_solver.py)."""
    sets = Effects.each_off()
    assert "no airborne" not in sets and len(sets) == 8
    assert Effects().key() == (True,) * 6
    assert Effects().to_dict() == {k: True for k in ("spin", "sliding", "vertical_spin", "ball_friction",
                                                      "cushion_friction", "pockets")}
    on = Effects(airborne=True)
    assert on.to_dict()["airborne"] is True and on.key() != Effects().key()
    assert Effects.from_dict(on.to_dict()) == on and Effects.from_dict(Effects().to_dict()) == Effects()
