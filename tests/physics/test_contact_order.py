"""The cue ball's contacts in order (SimOptions(contacts=K), SimResult.contacts)."""
import numpy as np
import pytest

from billiards_env.physics import constants as C
from billiards_env.physics.params import PhysicsParams
from billiards_env.physics.simulate import SimOptions, simulate
from billiards_env.physics.state import BallState
from billiards_env.physics.strike import strike_velocity
from billiards_env.physics.table import Table

T, P = Table.carom(), PhysicsParams.carom()
BOTTOM, RIGHT, TOP, LEFT = 0, 1, 2, 3  # Table.box_segments order


def _shot(pos, phi, speed, solver="event", contacts=16):
    s = strike_velocity(BallState.from_positions(pos), phi, speed, params=P)
    kw = {"dt": 1e-4} if solver == "step" else {}
    return simulate(s, T, P, solver, options=SimOptions(contacts=contacts), **kw), s


@pytest.mark.parametrize("solver", ["event", "step"])
def test_straight_up_and_back_through_the_balls(solver):
    # cue ball at the bottom, a ball in its way up the long axis: ball, top cushion, ball again or bottom
    r, _ = _shot([[0.71, 0.3], [0.3, 1.0], [0.71, 1.4]], np.pi / 2, 3.0, solver)
    n = int(r.n_contacts[0])
    seq = [tuple(c) for c in r.contacts[0, :n]]
    assert seq[0] == (C.EV_BALL_BALL, 2)
    assert (r.contacts[0, n:] == -1).all()
    assert r.first_contact[0] == 2


def test_order_counts_every_cushion_and_matches_the_cushion_tally():
    rng = np.random.default_rng(3)
    pos = np.array([[[0.3, 0.4], [1.0, 1.5], [0.5, 2.3]]] * 32)
    s = BallState.from_positions(pos)
    s = strike_velocity(s, rng.uniform(0, 2 * np.pi, 32), rng.uniform(1, 6, 32), rng.uniform(-0.4, 0.4, 32) * 0,
                        rng.uniform(-0.4, 0.4, 32), params=P)
    on = simulate(s, T, P, options=SimOptions(contacts=64))
    off = simulate(s, T, P)
    assert off.contacts is None and off.n_contacts is None
    # the option changes no physics: the same final states and tallies, bit for bit
    assert np.array_equal(on.state.pos, off.state.pos) and np.array_equal(on.n_events, off.n_events)
    for e in range(32):
        n = min(int(on.n_contacts[e]), 64)
        kinds = on.contacts[e, :n, 0]
        assert (kinds == C.EV_CUSHION).sum() == on.cushion_hits[e, 0] or on.n_contacts[e] > 64
        balls = on.contacts[e, :n][kinds == C.EV_BALL_BALL, 1]
        assert (balls[0] if len(balls) else -1) == on.first_contact[e]


def test_capacity_keeps_the_first_contacts_and_counts_the_rest():
    r, s = _shot([[0.3, 0.4], [1.0, 1.5], [0.5, 2.3]], 0.7, 8.0, contacts=2)
    full = simulate(s, T, P, options=SimOptions(contacts=256))
    assert r.n_contacts[0] == full.n_contacts[0] > 2
    assert np.array_equal(r.contacts[0], full.contacts[0, :2])


def test_a_cushion_first_shot_names_the_cushion():
    # straight at the right cushion, then back to the left: right, left, ...
    r, _ = _shot([[0.71, 1.42], [0.2, 0.3], [1.2, 2.6]], 0.0, 2.0)
    assert tuple(r.contacts[0, 0]) == (C.EV_CUSHION, RIGHT) and tuple(r.contacts[0, 1]) == (C.EV_CUSHION, LEFT)


def test_bad_capacity_is_refused():
    s = BallState.from_positions([[0.7, 0.5], [0.7, 1.5]])
    with pytest.raises(ValueError, match="contacts"):
        simulate(s, T, P, options=SimOptions(contacts=-1))
