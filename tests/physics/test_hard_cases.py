"""Hard cases stay numerically stable, on both solvers.

Every scenario runs with diagnostics=True and asserts the shared invariants
(billiards_env.testing.invariants): finite values, no overlap beyond 1e-9 m, nobody off
the table except through a pocket, total energy never rising from one event
to the next, momentum conserved in every ball-ball impact, every ball at rest
at the end without hitting the event cap, bounded wall time.
"""
import dataclasses
import math

import numpy as np
import pytest

from billiards_env.physics import (BallState, Effects, PhysicsParams, Table, rack, strike,
                                   strike_velocity)
from billiards_env.testing import run_checked

P = PhysicsParams.standard()
R = P.R
POOL = Table.pool(9)
BOX = Table.pocketless()
SOLVERS = ["event", "step"]
EXACT = Effects.minimal()  # point masses, no friction in impacts: exact answers


def place(table, pts):
    return BallState.from_positions(np.array(pts, dtype=np.float64))


def set_rolling(state, i, vx, vy):
    s = state.copy()
    s.vel[0, i] = (vx, vy)
    s.omega[0, i, :2] = (-vy / R, vx / R)
    return s


# ------------------------------------------------------------- the break --
@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("layout", ["nine", "eight"])
@pytest.mark.parametrize("speed", [10.0, 0.3])
def test_break_frozen_rack(solver, layout, speed):
    s = rack(POOL, P, layout, 1, gap=0.0, seed=3)
    if speed < 1.0:
        # a slow break must still reach the rack: cue ball 10 cm before the apex
        apex = s.pos[0, 1:][np.argmin(s.pos[0, 1:, 1])]
        s.pos[0, 0] = (apex[0], apex[1] - 2 * R - 0.10)
    s = strike_velocity(s, math.pi / 2, speed, 0.0, 0.0, P)
    res = run_checked(s, POOL, P, solver)
    assert res.first_contact[0] >= 1
    moved = np.hypot(*(res.state.pos[0] - s.pos[0]).T) > 1e-6
    assert moved[1:].sum() >= (3 if speed > 1 else 1)


# ------------------------------------------------------ Newton's cradle --
def _cradle():
    x, y0 = BOX.width / 2, 1.0
    pts = [(x, y0 - 0.2)] + [(x, y0 + k * 2 * R) for k in range(5)]
    return place(BOX, pts)


@pytest.mark.parametrize("solver", SOLVERS)
def test_newtons_cradle_exact(solver):
    """Perfectly elastic point masses: only the last ball leaves the row, every
    other ball ends exactly where it was (the cue ball where it touched)."""
    params = dataclasses.replace(P, e_b=1.0)
    s0 = _cradle()
    s = strike_velocity(s0, math.pi / 2, 0.5, params=params)
    res = run_checked(s, BOX, params, solver, effects=EXACT)
    pos = res.state.pos[0]
    np.testing.assert_allclose(pos[1:5], s0.pos[0, 1:5], atol=1e-9)
    np.testing.assert_allclose(pos[0], s0.pos[0, 1] - (0, 2 * R), atol=1e-9)
    # a rolling point mass stops after v^2 / (2 mu_r g); the cue ball's run-up
    # to the row is part of that distance
    travel = 0.5 ** 2 / (2 * P.mu_r * P.g) - (0.2 - 2 * R)
    # the step solver's explicit friction update errs by O(v dt) in distance
    np.testing.assert_allclose(pos[5], s0.pos[0, 5] + (0, travel), atol=1e-9 if solver == "event" else 1e-3)


@pytest.mark.parametrize("solver", SOLVERS)
def test_newtons_cradle_full_physics(solver):
    s0 = _cradle()
    s = strike_velocity(s0, math.pi / 2, 0.5, params=P)
    res = run_checked(s, BOX, P, solver)
    d = res.state.pos[0, :, 1] - s0.pos[0, :, 1]
    assert np.argmax(d) == 5 and d[5] > 0.1
    np.testing.assert_allclose(res.state.pos[0, :, 0], s0.pos[0, :, 0], atol=1e-9)  # stays on the line


# --------------------------------------------- two simultaneous impacts --
@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("sep", [1.0, 1.5])
@pytest.mark.parametrize("exact", [True, False])
def test_simultaneous_two_ball_hit(solver, sep, exact):
    """The cue ball meets two balls at the same instant (mirror-symmetric
    about the cue's line). Both solvers resolve the pair in both orders and
    average: the result is mirror-symmetric to 1e-9 m."""
    c = BOX.width / 2
    y1 = 1.2
    s0 = place(BOX, [(c, 0.6), (c - sep * R, y1), (c + sep * R, y1)])
    s = strike_velocity(s0, math.pi / 2, 2.0, params=P)
    res = run_checked(s, BOX, P, solver, effects=EXACT if exact else None)
    pos = res.state.pos[0]
    assert res.n_events[0] >= 2
    assert np.all(np.hypot(*(pos[1:] - s0.pos[0, 1:]).T) > 0.05)  # both object balls driven
    mirror_err = max(abs((pos[1, 0] - c) + (pos[2, 0] - c)), abs(pos[1, 1] - pos[2, 1]), abs(pos[0, 0] - c))
    assert mirror_err < 1e-9


# --------------------------------------------------------- the cushions --
@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("phi", [math.pi / 2, -math.pi / 2, math.pi, math.pi - 0.3])
def test_ball_frozen_to_cushion(solver, phi):
    """Ball touching the left rail (centre exactly R from the nose), struck
    along the rail either way, straight into it, and into it at an angle."""
    s0 = place(POOL, [(R, 0.6), (0.6, 1.8)])
    s = strike_velocity(s0, phi, 3.0, params=P)
    res = run_checked(s, POOL, P, solver)
    if abs(math.cos(phi)) > 0.5:
        assert res.cushion_hits[0, 0] >= 1


@pytest.mark.parametrize("solver", SOLVERS)
def test_frozen_pair_along_cushion(solver):
    """Cue ball and object ball both frozen to the rail and to each other."""
    s0 = place(POOL, [(R, 0.6), (R, 0.6 + 2 * R)])
    s = strike_velocity(s0, math.pi / 2, 2.0, params=P)
    res = run_checked(s, POOL, P, solver)
    assert res.first_contact[0] == 1


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("speed,angle", [(0.5, math.pi / 4 + math.pi), (3.0, math.pi + 0.2),
                                         (4.0, -math.pi / 2 - 0.1)])
def test_ball_in_pocket_jaws(solver, speed, angle):
    """An object ball resting in the corner pocket's mouth between the jaws,
    hit from various directions: it drops or rattles, never escapes the table."""
    jaw = (0.045, 0.045)
    assert POOL.contains(np.array([jaw]), R, 0.0)[0]
    d = 0.4
    cue = (jaw[0] - d * math.cos(angle), jaw[1] - d * math.sin(angle))
    s0 = place(POOL, [cue, jaw])
    s = strike_velocity(s0, angle, speed, params=P)
    run_checked(s, POOL, P, solver)


@pytest.mark.parametrize("solver", SOLVERS)
def test_ball_in_side_pocket_mouth(solver):
    mouth = (0.0, POOL.length / 2)
    s0 = place(POOL, [(0.5, POOL.length / 2 + 0.1), mouth])
    s = strike_velocity(s0, math.atan2(-0.1, -0.5), 2.0, params=P)
    run_checked(s, POOL, P, solver)


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("exact", [True, False])
def test_corner_at_45_degrees(solver, exact):
    """Into the exact corner of a closed box along the diagonal: both
    cushions at the same instant. Without friction the ball comes straight
    back along the diagonal."""
    square = Table.pocketless(1.27, 1.27)
    s0 = place(square, [(0.4, 0.4)])
    s = strike_velocity(s0, -3 * math.pi / 4, 2.0, params=P)
    res = run_checked(s, square, P, solver, effects=EXACT if exact else None)
    assert res.cushion_hits[0].sum() >= 2
    x, y = res.state.pos[0, 0]
    if exact:  # corner to corner along the diagonal until it stops
        assert abs(x - y) < 1e-9 and res.cushion_hits[0].sum() >= 4


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("offset", [0.0, 1e-12, 0.3])
def test_shot_parallel_to_rail(solver, offset):
    """Rolling exactly along the left rail (offset 0: grazing both side-pocket
    jaw tips at distance exactly R) into the far corner pocket."""
    x = R + offset
    s0 = place(POOL, [(x, 0.3)])
    s = strike_velocity(s0, math.pi / 2, 4.0, 0.0, 0.4, P)
    run_checked(s, POOL, P, solver)


# ------------------------------------------------------ grazing contacts --
@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("factor,hits", [(1 - 1e-9, True), (1 + 1e-9, False)])
def test_grazing_pass(solver, factor, hits):
    x0 = 0.5
    s0 = place(POOL, [(x0, 0.5), (x0 + 2 * R * factor, 1.2)])
    s = strike_velocity(s0, math.pi / 2, 2.0, params=P)
    res = run_checked(s, POOL, P, solver, effects=EXACT)
    touched = res.first_contact[0] == 1
    assert touched == hits
    if not hits:
        np.testing.assert_array_equal(res.state.pos[0, 1], s0.pos[0, 1])


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("gap", [0.0, 1e-12, 1e-6])
@pytest.mark.parametrize("rolling", [True, False])
def test_side_by_side_equal_velocity(solver, gap, rolling):
    """Two balls side by side (touching or nearly) with equal velocity: they
    never collide, stop together, and nothing loops."""
    s0 = place(BOX, [(0.5, 0.3), (0.5 + 2 * R + gap, 0.3)])
    s = s0.copy()
    for i in range(2):
        s.vel[0, i] = (0.0, 0.5)
        if rolling:
            s.omega[0, i, :2] = (-0.5 / R, 0.0)
    res = run_checked(s, BOX, P, solver, max_events=10)
    assert res.first_contact[0] == -1
    np.testing.assert_allclose(res.state.pos[0, 1] - res.state.pos[0, 0], (2 * R + gap, 0.0), atol=1e-12)


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("short", [0.0, 1e-12, 1e-9, -1e-9])
def test_collision_as_ball_stops(solver, short):
    """A rolling ball reaches the object ball at (about) the instant it stops."""
    v = 0.6
    travel = v * v / (2 * P.mu_r * P.g)
    s0 = place(POOL, [(0.6, 0.3), (0.6, 0.3 + travel + 2 * R + short)])
    s = set_rolling(s0, 0, 0.0, v)
    run_checked(s, POOL, P, solver, max_events=20)


# --------------------------------------------------------------- extremes --
@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("a,b", [(0.0, -0.5), (0.0, 0.5), (0.5, 0.0), (-0.5, 0.0), (0.35, -0.35)])
def test_max_draw_and_spin(solver, a, b):
    """Longest legal draw (10 m/s) with the largest offsets into a rack."""
    s0 = rack(POOL, P, "nine", 1, seed=5)
    s = strike(s0, math.pi / 2 + 0.01, P.max_draw, a, b, P)
    assert abs(np.hypot(*s.vel[0, 0]) - P.max_speed) < 1e-12
    run_checked(s, POOL, P, solver)


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("speed", [1e-9, 1e-12, 1e-6, 1e-5])
def test_near_zero_speed(solver, speed):
    s0 = place(POOL, [(0.6, 1.0), (0.6, 1.0 + 2 * R)])  # frozen to its target
    s = strike_velocity(s0, math.pi / 2, speed, 0.3, 0.3, P)
    run_checked(s, POOL, P, solver, max_events=20)


@pytest.mark.parametrize("solver,dt", [("event", None), ("step", 1e-3), ("step", 1e-2)])
@pytest.mark.parametrize("angle", [0.02, 0.1])
def test_shallow_angle_top_speed(solver, dt, angle):
    """Top speed at a shallow angle into the rail, with a ball sitting just
    off the rail in the way: no tunnelling through either (dt = 1e-2 moves
    the ball 10 cm, almost two diameters, per step)."""
    for table in (BOX, POOL):
        x0 = 0.3
        y0 = 0.3
        # the ball reaches the rail at y_hit; an object ball sits there
        y_hit = y0 + (x0 - R) / math.tan(angle)
        s0 = place(table, [(x0, y0), (R + 0.5 * R, min(y_hit + 0.3, 1.1))])
        s = strike_velocity(s0, math.pi / 2 + angle, P.max_speed, params=P)
        res = run_checked(s, table, P, solver, dt=dt or 1e-3)
        assert res.cushion_hits[0, 0] >= 1


# ------------------------------------------------------------ long shots --
@pytest.mark.parametrize("solver", SOLVERS)
def test_long_shot_everything_moving(solver):
    """Ten balls with high spin on a slick cloth keep moving for over 60 s."""
    params = dataclasses.replace(P, mu_r=4e-4, mu_sp=1e-4)
    rng = np.random.default_rng(11)
    from billiards_env.physics import random_placement
    s = random_placement(BOX, params, 10, seed=11, margin=0.01).copy()
    ang = rng.uniform(0, 2 * np.pi, 10)
    v = 0.35
    s.vel[0] = v * np.stack([np.cos(ang), np.sin(ang)], 1)
    s.omega[0, :, 0] = -s.vel[0, :, 1] / R
    s.omega[0, :, 1] = s.vel[0, :, 0] / R
    s.omega[0, :, 2] = rng.uniform(-60, 60, 10)
    res = run_checked(s, BOX, params, solver)
    assert res.time[0] > 60.0


# ------------------------------------------------------- the snooker table --
SNK_P = PhysicsParams.snooker()
SNOOKER = Table.snooker()


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("speed, side", [(12.0, 0.0), (4.0, 0.3), (0.5, 0.0)])
def test_snooker_break_frozen_reds(solver, speed, side):
    """The frozen 15-red triangle and its 22-ball opening: a full smash, a
    break-off with side at the side of the pack, a slow roll into the apex."""
    s = rack(SNOOKER, SNK_P, "snooker", 1, gap=0.0)
    apex = s.pos[0, 1]
    if speed < 1.0:  # from beside the pink (it sits 1 mm below the apex), into the apex red
        s.pos[0, 0] = (apex[0] - 0.15, apex[1] + 0.01)
    d = apex + (0.0 if side == 0 else 0.04, 0.0) - s.pos[0, 0]
    s = strike_velocity(s, math.atan2(d[1], d[0]), speed, side, 0.0, SNK_P)
    res = run_checked(s, SNOOKER, SNK_P, solver)
    assert res.first_contact[0] >= 1
    moved = np.hypot(*(res.state.pos[0] - s.pos[0]).T) > 1e-6
    assert moved[1:16].sum() >= (5 if speed > 1 else 1)


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("pocket", [0, 2])  # a corner, a middle pocket
def test_snooker_balls_in_the_jaws(solver, pocket):
    """Two balls touching in a narrow pocket's mouth, one frozen to a jaw's
    tip, struck by a ball driven into them along the pocket's axis and across it."""
    cx, cy, _ = SNOOKER.pockets[pocket]
    R_ = SNK_P.R
    if pocket == 0:   # corner: the axis points into the table at 45 deg
        ax = np.array([1.0, 1.0]) / math.sqrt(2)
        tip = SNOOKER.tips[np.argmin(np.hypot(*(SNOOKER.tips - (cx, cy)).T))]
    else:             # the left middle pocket: its axis is +x
        ax = np.array([1.0, 0.0])
        tip = SNOOKER.tips[np.argmin(np.hypot(*(SNOOKER.tips - (0.0, cy)).T))]
    n = np.array([-ax[1], ax[0]])
    mouth = np.array([cx, cy]) + ax * (0.06 if pocket == 0 else 0.06 + 0.034)
    b1 = tip + R_ * (mouth - tip) / np.linalg.norm(mouth - tip) * (1 + 1e-9)  # frozen to the jaw tip
    b2 = b1 + 2 * R_ * ax
    for across in (False, True):
        cue = b2 + (0.4 * ax if not across else 0.3 * ax + 0.3 * n)
        s = place(SNOOKER, [cue, b1, b2])
        d = b2 - cue
        s = strike_velocity(s, math.atan2(d[1], d[0]), 3.0, 0.0, 0.1, SNK_P)
        ok = SNOOKER.contains(s.pos[0], R_, 1e-9)
        assert ok.all(), "the constructed balls must lie legally on the table"
        run_checked(s, SNOOKER, SNK_P, solver)


# ------------------------------------------------- balls in flight (issue 46) --
AIR = Effects(airborne=True)


def _air(state):
    """``state`` with every ball on the slate, its vertical velocity settable (``BallState.air``)."""
    return BallState(state.pos, state.vel, state.omega, state.pocket, np.zeros(state.pos.shape[:2] + (2,)))


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("theta", [5.0, 30.0])
def test_elevated_break_into_a_frozen_rack(solver, theta):
    """A break at 10 m/s with the cue elevated: the cue ball hops (5 deg) or
    flies into the rack from above (30 deg); the invariants hold with the
    height's energy and 3D gaps, every ball ends on the slate or off the table."""
    s = _air(rack(POOL, P, "nine", 1, seed=0))
    s = strike(s, math.pi / 2, P.max_draw, 0.0, 0.0, P, theta=math.radians(theta))
    run_checked(s, POOL, P, solver, effects=AIR)


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("offset", [0.0, 1e-12, 1e-6, R])
def test_ball_dropped_onto_a_ball(solver, offset):
    """A ball dropped from 20 cm onto a resting ball, exactly on top (the
    unstable balance: ``flight.STACK_TILT`` tips it off), a hair off, and
    half a ball off: it bounces off and both end on the slate, no overlap,
    no energy gained, no truncation."""
    s = place(POOL, [[0.6, 1.0], [0.6 + offset, 1.0]])
    s = BallState(s.pos, s.vel, s.omega, s.pocket, np.array([[[0.2, 0.0], [0.0, 0.0]]]))
    res = run_checked(s, POOL, P, solver, effects=AIR)
    assert np.all(res.state.air == 0)


@pytest.mark.parametrize("solver", SOLVERS)
def test_frozen_pair_struck_into_the_slate(solver):
    """A cue ball frozen to an object ball, struck down into the slate
    towards it: it meets the slate and the ball at one instant; the bounce
    comes first (``airborne.landing_now`` / ``meets_slate``), so no stall."""
    s = _air(place(POOL, [[0.6, 1.0], [0.6, 1.0 + 2 * R]]))
    s = strike_velocity(s, math.pi / 2, 2.0, 0.0, 0.0, P, theta=math.radians(40))
    run_checked(s, POOL, P, solver, effects=AIR, max_events=200)


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("margin", [-1e-9, 1e-9])
def test_ball_in_flight_grazing_the_cushion_nose(solver, margin):
    """A ball in flight reaching the cushion's contact line with its lowest
    point a nanometre below or above the nose (``cushion.rail``): it strikes
    the cushion or leaves the table, nothing in between; invariants hold."""
    t = 0.01 / 2.0  # it reaches the contact line 1 cm away at 2 m/s, falling g t^2 / 2 meanwhile
    s = place(POOL, [[0.635, POOL.length - R - 0.01]])
    s = BallState(s.pos, s.vel, s.omega, s.pocket, np.array([[[P.h_c + margin + 0.5 * P.g * t * t, 0.0]]]))
    s.vel[0, 0, 1] = 2.0
    res = run_checked(s, POOL, P, solver, effects=AIR)
    if margin < 0:
        assert res.state.pocket[0, 0] == -1  # it struck the cushion and stayed on the table
    else:
        assert res.state.pocket[0, 0] >= 100  # over the nose: off the table


@pytest.mark.parametrize("solver", SOLVERS)
def test_extreme_masse(solver):
    """A near-vertical cue (80 deg) at the edge of the miscue disc, fast: the
    ball is driven into the slate with massé spin of hundreds of rad/s."""
    s = _air(place(POOL, [[0.635, 1.27], [0.7, 1.6]]))
    s = strike(s, 1.2, P.max_draw, 0.49, -0.05, P, theta=math.radians(80))
    run_checked(s, POOL, P, solver, effects=AIR)
