"""The position-playing search baseline (billiards_env.bots.lookahead) on constructed positions."""
import gymnasium as gym
import numpy as np

import billiards_env  # noqa: F401
from billiards_env.bots import geometry as G
from agents.evaluation.policies import make_policy
from agents.evaluation.harness import evaluate
from billiards_env.bots.lookahead import LookaheadPolicy

RUNOUT = "Billiards-RunOut-v1"
# A straight-in pot of ball 1 into the top-right corner from the same cue
# position, and ball 2 with ball 3 frozen beside it (a blocker). Both
# candidate shots pot ball 1 every time under tournament noise; the stun shot
# stops the cue ball near (1.07, 2.34), the draw shot brings it back to about
# (0.93, 2.20). In table 0 ball 3 hides ball 2 from the stun spot, in table 1
# from the draw spot (leave values 0.125 vs 1.0, with 16 noise samples).
POSITIONS = np.array([
    [[0.7, 1.97], [1.0, 2.27], [1.1, 1.1], [1.095, 1.16]],     # draw leaves a shot, stun does not
    [[0.7, 1.97], [1.0, 2.27], [0.862, 1.1], [0.87, 1.16]],    # stun leaves a shot, draw does not
])
STUN_B, DRAW_B, DRAW_SPEED = 0.0, -0.5, 1.6
TOP_RIGHT = 5


def _env(n):
    env = gym.make_vec(RUNOUT, num_envs=n, vectorization_mode="vector_entry_point", n_balls=3)
    env.reset(seed=0)
    return env


def test_prefers_the_pot_whose_leave_has_a_shot():
    env = _env(2)
    u = env.unwrapped
    u.set_state(POSITIONS)
    pol = LookaheadPolicy(n_noise=16, n_noise_next=16, seed=3)
    view = u.view()
    sh = G.ghost_shots(POSITIONS, np.ones((2, 4), bool), np.ones(2, int), u.table, u.params, 0.0)
    phi = sh["phi"][:, TOP_RIGHT]
    v0 = G.required_speed(sh["d_cg"][:, TOP_RIGHT], sh["d_op"][:, TOP_RIGHT], sh["cut"][:, TOP_RIGHT], u.params,
                          margin=1.0)

    def two_candidates(view, state, target):  # stun first, then draw
        cand = (np.stack([phi, phi], 1), np.stack([v0, DRAW_SPEED * v0], 1), np.zeros((2, 2)),
                np.tile([STUN_B, DRAW_B], (2, 1)), np.zeros((2, 2)))
        return cand

    pol.search.candidates = two_candidates
    # both shots pot ball 1 and keep the table: they are equally easy pots
    for b, sp in ((STUN_B, 1.0), (DRAW_B, DRAW_SPEED)):
        _, cls = pol.play(view, u.state, (phi, sp * v0, np.zeros(2), np.full(2, b)))
        assert (cls == 0).all()
    shots = pol.shots(view, u.state, u.legal_target())
    assert np.allclose(shots.b, [DRAW_B, STUN_B]), shots
    # reversed candidate order: the same choices
    pol.search.candidates = lambda v, s, t: tuple(x[:, ::-1] for x in two_candidates(v, s, t))
    shots = pol.shots(view, u.state, u.legal_target())
    assert np.allclose(shots.b, [DRAW_B, STUN_B]), shots


def test_leave_value_sees_a_snooker():
    env = _env(2)
    u = env.unwrapped
    pos = POSITIONS.copy()
    pos[:, 1] = [0.3, 0.4]           # ball 1 out of the way
    pos[:, 0] = [[0.93, 2.20], [0.93, 2.20]]
    u.set_state(pos)
    pol = LookaheadPolicy(n_noise_next=16, seed=1)
    state = u.state
    state.pocket[:, 1] = 0           # ball 1 pocketed: ball 2 is the target
    v = pol.leave_value(u.view(), state)
    assert v[0] >= 0.75 and v[1] <= 0.25, v


def test_lookahead_registered_and_clears_runout_tables():
    res = evaluate(lambda env: make_policy("lookahead", env), RUNOUT, 16, seed=12345, batch_size=16)
    assert res.policy == "lookahead"
    assert res.success_rate >= 0.75, res   # search64 clears 0.765 of RunOut tables
