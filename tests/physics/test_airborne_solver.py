"""The event solver with balls in flight (``Effects(airborne=True)``, issue
46): a jump stroke's flights and bounces against their closed forms, a jump
over a blocking ball and one that strikes it, balls driven off the table
onto the rail and the floor, a ball in flight into a pocket, the 3D impact's
conservation laws, the strike into the slate carried by ``BallState.air``,
the step solver's flight against the event solver's, and input checks. Invariants under random elevated strikes are the fuzz
quick mode (tests/physics/test_strike_3d.py)."""
import math

import numpy as np
import pytest

from billiards_env.physics import BallState, Effects, PhysicsParams, Table, simulate, strike_velocity
from billiards_env.physics import constants as C
from billiards_env.physics.airborne import SETTLE_HEIGHT, SLATE_RESTITUTION, settles, slate_impact
from billiards_env.physics.cushion.rail import RAIL_WIDTH

AIR = Effects(airborne=True)
P = PhysicsParams()
R, G = P.R, P.g
TABLE = Table.pool()


def _state(pos, air=None):
    s = BallState.from_positions(np.array([pos], dtype=np.float64))
    a = np.zeros((1, len(pos), 2)) if air is None else np.array([air], dtype=np.float64)
    return BallState(s.pos, s.vel, s.omega, s.pocket, a)


def _jump(pos, speed, theta_deg, phi=math.pi / 2, a=0.0, b=0.0):
    s = strike_velocity(_state(pos), phi, speed, a, b, P, theta=math.radians(theta_deg))
    return s, simulate(s, TABLE, P, effects=AIR, record=True, diagnostics=True)


def _events(r, kind, ball=0):
    ev = r.events[0]
    k = np.array(ev.kind)
    return ev.time[(k == kind) & (ev.balls[:, 0] == ball)]


def test_a_jump_stroke_flies_and_bounces_as_the_closed_forms_say():
    """Struck 30 degrees down through the centre: the slate at t = 0 sends it
    up at e v0 sin(theta); each flight lasts 2 vz / g and the next one e
    times as long (bounce heights falling by e^2) until a rebound would rise
    less than SETTLE_HEIGHT; then it rolls on the felt, at rest on it."""
    v0, theta = 4.0, math.radians(30)
    s, r = _jump([[0.635, 0.5]], v0, 30)
    slate = _events(r, C.EV_SLATE)
    assert slate[0] == 0.0
    vz = SLATE_RESTITUTION * v0 * math.sin(theta)
    flights = np.diff(slate)
    assert flights[0] == pytest.approx(2 * vz / G, rel=1e-12)
    assert np.allclose(flights[1:] / flights[:-1], SLATE_RESTITUTION, rtol=1e-9)
    last = vz * SLATE_RESTITUTION ** (len(flights) - 1)  # the last flight's take-off speed
    assert last ** 2 / (2 * G) >= SETTLE_HEIGHT > (SLATE_RESTITUTION * last) ** 2 / (2 * G)
    # range of the first flight: the horizontal speed the slate's friction left it
    vx, vy, *_ = slate_impact(0.0, v0 * math.cos(theta), -v0 * math.sin(theta), *s.omega[0, 0], R,
                              SLATE_RESTITUTION, P.mu_s)
    rec = r.events[0]
    second = np.flatnonzero((rec.kind == C.EV_SLATE) & (rec.balls[:, 0] == 0))[1]
    assert rec.states[second, 0, 1] == pytest.approx(0.5 + vy * flights[0], rel=1e-12)
    assert r.diagnostics[0, 0] <= 1e-12 and np.all(r.state.air == 0) and r.state.pocket[0, 0] == C.ON_TABLE


@pytest.mark.parametrize("clears", [True, False])
def test_a_jump_clears_a_blocking_ball_or_strikes_it(clears):
    """A blocker under the first flight's apex: a jump whose apex clears it
    by 2R (ball centre 2R above the blocker's) passes it untouched; the same
    jump with half the height strikes it, 2R from its centre in 3D."""
    v0, theta = 5.0, math.radians(40 if clears else 12)
    s = strike_velocity(_state([[0.635, 0.4]]), math.pi / 2, v0, 0.0, 0.0, P, theta=math.radians(40 if clears else 12))
    vx, vy, vz, *_ = slate_impact(0.0, v0 * math.cos(theta), -v0 * math.sin(theta), *s.omega[0, 0], R,
                                  SLATE_RESTITUTION, P.mu_s)
    apex_t = vz / G
    blocker = 0.4 + vy * apex_t
    assert (vz ** 2 / (2 * G) > 2 * R) == clears
    s, r = _jump([[0.635, 0.4], [0.635, blocker]], v0, 40 if clears else 12)
    hits = _events(r, C.EV_BALL_BALL)
    if clears:
        assert len(hits) == 0 or hits[0] > 2 * apex_t  # untouched in flight
        rec = r.events[0]
        landing = np.flatnonzero((rec.kind == C.EV_SLATE) & (rec.balls[:, 0] == 0))[1]
        assert rec.states[landing, 0, 1] > blocker + 2 * R  # it came down beyond the blocker
        return
    t = hits[0]
    y, h = 0.4 + vy * t, vz * t - 0.5 * G * t * t
    assert t < 2 * apex_t and math.hypot(blocker - y, h) == pytest.approx(2 * R, rel=1e-9)
    assert r.state.pos[0, 1, 1] > blocker  # the blocker was driven on
    assert r.diagnostics[0, 0] <= 1e-12 and r.diagnostics[0, 2] >= -C.OVERLAP_TOL


def test_a_ball_jumped_over_the_rail_leaves_the_table():
    """Jumped hard at the foot rail it clears the cushion's nose and lands on
    the floor (OFF_FLOOR): out of play as a pocketed ball is, in no pocket;
    a slow high lob that comes down within RAIL_WIDTH of the cushion line
    lands on the rail (OFF_RAIL)."""
    s, r = _jump([[0.635, 2.2]], 6.0, 45)
    assert r.state.pocket[0, 0] == C.OFF_FLOOR and len(_events(r, C.EV_OFF_TABLE)) == 1
    assert r.pocketed[0, 0] and not r.state.on_table[0, 0]
    # rolling (no slip: the slate takes no speed) into the slate 3 cm short of the
    # cushion's contact line, so that it reaches the line at its apex, 5 mm above
    # the nose, and comes down to the nose's height 1 cm beyond: on the rail top
    vz = math.sqrt(2 * G * (P.h_c + 0.005))
    vy = 0.03 / (vz / G)
    s = _state([[0.635, TABLE.length - R - 0.03]], air=[[0.0, -vz / SLATE_RESTITUTION]])
    s.vel[0, 0, 1] = vy
    s.omega[0, 0, 0] = -vy / R
    r = simulate(s, TABLE, P, effects=AIR, record=True, diagnostics=True)
    assert r.state.pocket[0, 0] == C.OFF_RAIL
    assert r.diagnostics[0, 0] <= 1e-12


def test_a_ball_in_flight_drops_into_a_pocket_below_the_nose():
    """Lobbed low towards a corner pocket it drops in (a pocket id, not an
    off-table code)."""
    s = _state([[0.3, 0.3]], air=[[0.0, 0.3]])
    s.vel[0, 0] = (-0.8, -0.8)
    r = simulate(s, TABLE, P, effects=AIR, diagnostics=True)
    assert 0 <= r.state.pocket[0, 0] < C.OFF_TABLE


def _first_impact(r):
    """The (upper, lower) balls' logged states after the first ball-ball
    event: x, y, vx, vy, wx, wy, wz, state, h, vz."""
    rec = r.events[0]
    first = np.flatnonzero(rec.kind == C.EV_BALL_BALL)[0]
    a, b = rec.states[first, 0], rec.states[first, 1]
    return (a, b) if a[8] >= b[8] else (b, a)


def _dropped(offset, drop):
    """A ball falling from rest onto a resting one, its centre ``offset``
    (times 2R) to the side, touching after falling ``drop`` metres."""
    dz = 2 * R * math.sqrt(1 - offset * offset)
    s = _state([[0.6, 1.0], [0.6 + offset * 2 * R, 1.0]], air=[[dz + drop, 0.0], [0.0, 0.0]])
    return simulate(s, TABLE, P, effects=AIR, record=True, diagnostics=True)


def _sound(r):
    assert r.diagnostics[0, 0] <= 1e-12 and r.diagnostics[0, 2] >= -C.OVERLAP_TOL and not r.truncated[0]


def test_a_gentle_drop_on_a_ball_is_held_by_the_slate():
    """Falling 0.5 mm onto a resting ball off its centre, the blow is too
    gentle to make the lower ball hop (its rebound would settle): the slate
    holds it (vz stays 0), horizontal momentum is kept, the upper ball
    leaves with the restitution e_b along the normal, energy never rises."""
    r = _dropped(0.6, 5e-4)
    upper, lower = _first_impact(r)
    assert lower[9] == 0.0 and lower[7] != C.AIRBORNE
    assert upper[2] + lower[2] == pytest.approx(0.0, abs=1e-15)  # vx: both started at rest horizontally
    assert lower[2] > 0 and upper[2] < 0
    _sound(r)


def test_a_blow_from_above_is_the_sequential_impulses():
    """Dropped 15 cm onto a resting ball, 0.6 of the way to its side: the
    balls' free impact, the slate's rebound of the lower ball (restitution
    and friction: ``slate_impact``), again while they approach, written out
    here from the scalar laws; the kernel's result agrees."""
    r = _dropped(0.6, 0.15)
    upper, lower = _first_impact(r)
    n = np.array([0.6, 0.0, -0.8])  # from the upper centre to the lower one
    vu, vl, wl = np.array([0.0, 0.0, -math.sqrt(2 * G * 0.15)]), np.zeros(3), np.zeros(3)
    while (w := -(vl - vu) @ n) > 0:
        imp = 0.5 * (1 + P.e_b) * w
        vu, vl = vu - imp * n, vl + imp * n
        if vl[2] < 0:
            *v, wx, wy, wz = slate_impact(*vl, *wl, R, SLATE_RESTITUTION, P.mu_s)
            vl, wl = np.array(v), np.array([wx, wy, wz])
            if settles(vl[2], G, SETTLE_HEIGHT):
                vl[2] = 0.0
    assert np.allclose(upper[[2, 3, 9]], vu, rtol=1e-9, atol=1e-12)
    assert np.allclose(lower[[2, 3, 9]], vl, rtol=1e-9, atol=1e-12)
    assert np.allclose(lower[[4, 5, 6]], wl, rtol=1e-9, atol=1e-12)


def test_a_ball_dropped_on_the_top_of_another_is_held_by_the_slate():
    """Dropped 5 cm onto a resting ball 0.3 of the way to its side (within
    ``TOP_ZONE`` of the top): the slate holds the lower ball, the upper one
    bounces off with e_b along the normal."""
    r = _dropped(0.3, 0.05)
    upper, lower = _first_impact(r)
    assert lower[9] == 0.0 and lower[7] != C.AIRBORNE
    _sound(r)


def test_a_hard_blow_from_above_knocks_the_ball_off_the_slate():
    """Falling 15 cm onto a resting ball off its centre: the lower ball is
    driven into the slate and rebounds off it (it flies, then lands again);
    energy never rises and no ball sinks into another."""
    r = _dropped(0.6, 0.15)
    upper, lower = _first_impact(r)
    assert lower[7] == C.AIRBORNE and lower[9] > 0.0
    assert len(_events(r, C.EV_SLATE, ball=1)) > 0
    _sound(r)


def test_a_jumped_cue_ball_knocks_an_object_ball_off_the_table():
    """A cue ball coming down at 2 m/s and forward at 3 m/s onto an object
    ball 6 cm from the cushion, 0.7 of the way to its side: the object ball
    is driven into the slate, jumps, clears the cushion's nose and comes down
    on the rail top; the cue ball stays on the table."""
    y = TABLE.length - R - 0.06
    dy = 0.7 * 2 * R
    s = _state([[0.635, y - dy - 1e-6], [0.635, y]], air=[[math.sqrt(4 * R * R - dy * dy) + 1e-6, -2.0], [0.0, 0.0]])
    s.vel[0, 0] = (0.0, 3.0)
    r = simulate(s, TABLE, P, effects=AIR, diagnostics=True)
    assert r.state.pocket[0, 1] == C.OFF_RAIL and r.state.pocket[0, 0] < 0
    _sound(r)


@pytest.mark.parametrize("dt", [1e-3, 1e-4])
def test_the_step_solver_flies_the_same_jump(dt):
    """The step solver flies a ball on the same parabola (its height exact
    within a step): the jump over the blocker's first impact, the bounces'
    times and the final layout agree with the event solver's, closer at the
    finer step, and energy never rises."""
    s = strike_velocity(_state([[0.635, 0.6], [0.635, 0.9], [0.635, 1.5]]), math.pi / 2, 4.0, 0.0, 0.0, P,
                        theta=math.radians(30))
    exact = simulate(s, TABLE, P, effects=AIR, record=True)
    step = simulate(s, TABLE, P, solver="step", dt=dt, effects=AIR, record=True, diagnostics=True)
    for kind in (C.EV_SLATE, C.EV_BALL_BALL):
        a, b = _events(exact, kind), _events(step, kind)
        assert np.allclose(a[:3], b[:3], atol=10 * dt)
    gap = np.abs(exact.state.pos - step.state.pos).max()
    assert gap < (2e-3 if dt == 1e-3 else 3e-4), gap
    assert step.diagnostics[0, 0] <= 1e-12 and np.all(step.state.air == 0)


def test_planar_states_and_bad_heights():
    """A planar state (no ``air``) simulates as before with the effect on;
    a ball moving vertically is refused by the planar simulator by name, a
    ball below the slate by both."""
    s = BallState.from_positions(np.array([[[0.635, 0.5], [0.635, 1.5]]]))
    s.vel[0, 0, 1] = 2.0
    planar = simulate(s, TABLE, P)
    flat = simulate(s, TABLE, P, effects=AIR)
    assert np.array_equal(planar.state.pos, flat.state.pos) and np.array_equal(planar.n_events, flat.n_events)
    up = _state([[0.635, 0.5]], air=[[0.0, 1.0]])
    with pytest.raises(ValueError, match="airborne=True"):
        simulate(up, TABLE, P)
    below = _state([[0.635, 0.5]], air=[[-1e-3, 0.0]])
    with pytest.raises(ValueError, match="below the slate"):
        simulate(below, TABLE, P, effects=AIR)
