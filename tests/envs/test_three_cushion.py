"""Three-cushion environments: Billiards-ThreeCushion-v3 (gym.make and make_vec), the self-play vector env,
the PettingZoo AEC env; thousands of random games; the opening, each player's own ball, balls in contact."""
import gymnasium as gym
import numpy as np
import pytest

import billiards_env  # noqa: F401 (registers the ids)
from billiards_env.envs.games import GameConfig, GameCore
from billiards_env.contract import ShotPlan
from billiards_env.physics.strike import Shots
from billiards_env.rules.respot import hand_over, restart_position
from billiards_env.envs.games.vector import GameVectorEnv
from billiards_env.physics.table import Table
from billiards_env.rules import records as R
from billiards_env.rules.three_cushion import OPENING_OFFSET
from billiards_env.testing.positions import game_table

ID = "Billiards-ThreeCushion-v3"
SHORT = {"max_innings": 6}  # short games keep the tests fast


def _aec(**kw):
    from billiards_env.envs.games.aec import ThreeCushionAECEnv
    return ThreeCushionAECEnv(**kw)


def test_pettingzoo_api():
    pytest.importorskip("pettingzoo")
    from pettingzoo.test import api_test
    api_test(_aec(max_shots=40, rule_options=SHORT), num_cycles=300, verbose_progress=False)


def test_single_agent_check_env_and_make_vec():
    from gymnasium.utils.env_checker import check_env
    env = gym.make(ID, max_shots=30, opponent="random", rule_options=SHORT)
    check_env(env.unwrapped, skip_render_check=True)
    obs, _ = env.reset(seed=3)
    assert env.observation_space.contains(obs) and env.action_space.shape == (8,) and obs.shape == (4 * 3 + 19,)
    assert env.unwrapped.core.table.style == "carom" and env.unwrapped.core.params.R == 0.03075
    v = gym.make_vec(ID, num_envs=3, vectorization_mode="vector_entry_point")
    assert isinstance(v, GameVectorEnv) and v.single_action_space.shape == (8,)
    v.reset(seed=0)
    _, _, _, _, info = v.step(np.zeros((3, 8), dtype=np.float32))
    assert info["score"].shape == (3, 2) and info["points"].shape == (3,)
    # the default opponent is the three-cushion bot
    assert gym.make(ID).unwrapped._opponent_spec == "carom"


def test_vector_env_equals_single_games():
    """Table k of a vector env seeded s plays exactly like the AEC env seeded s + k under the same actions."""
    pytest.importorskip("pettingzoo")
    N, seed = 4, 11
    vec = GameVectorEnv(N, game="three_cushion", noise="tournament")
    obs, info = vec.reset(seed=seed)
    singles = [_aec(noise="tournament") for _ in range(N)]
    for k, s in enumerate(singles):
        s.reset(seed=seed + k)
    rng = np.random.default_rng(0)
    for _ in range(12):
        a = rng.uniform(-1, 1, (N, 8))
        for k, s in enumerate(singles):
            np.testing.assert_array_equal(obs[k], s.observe(s.agent_selection))
            assert info["to_move"][k] == int(s.agent_selection[-1])
            s.step(a[k].astype(np.float32))
        obs, r, term, trunc, info = vec.step(a.astype(np.float32))
        for k, s in enumerate(singles):
            np.testing.assert_array_equal(obs[k], s.observe(s.possible_agents[0]))
            assert info["points"][k] == s.infos["player_0"]["points"]
        assert not (term | trunc).any()


def test_opening_spots_and_each_players_own_ball():
    core = GameCore(GameConfig(game="three_cushion"), 2)
    core.streams.seed([0, 1], [5, 6])
    core.reset_tables([0, 1], [0, 1])
    t = core.table
    for k in range(2):
        pos = core.state.pos[k]
        assert np.allclose(pos[1], (t.width / 2, t.length / 4)) and np.allclose(pos[2], (t.width / 2, 3 * t.length / 4))
        assert np.isclose(abs(pos[0, 0] - t.width / 2), OPENING_OFFSET) and np.isclose(pos[0, 1], t.length / 4)
        assert core.game.shooter[k] == k and core.game.innings[k].tolist() == ([1, 0] if k == 0 else [0, 1])
    # a miss hands the table over: the incoming player's ball (where it lay) is now in slot 0
    before = core.state.pos[0].copy()
    a = np.zeros((1, 8))
    a[0, 1] = -0.9  # a soft shot at the red: it cannot make a point
    out = core.step(a, [0])
    assert out["record"].turn_over[0] and core.game.shooter[0] == 1
    assert np.allclose(core.state.pos[0, 0], before[1])  # the opponent's ball did not move: it is slot 0 now


def _frozen_table():
    """Player 0's ball frozen to the red (centres 2R apart along +x), the opponent's ball up the table."""
    R_ = 0.03075
    return game_table("three_cushion", {0: (0.6, 0.8), 1: (0.3, 2.0), 2: (0.6 + 2 * R_, 0.8)})


def test_balls_in_contact_replaced_by_a6():
    """With the cue ball touching a ball the constraints and the view allow the replace declaration;
    0 < a6 <= 0.5 has the balls replaced on the starting position (UMB Art. 27): no shot (no events), the
    same player to play the opening shot from there (the red first)."""
    core = _frozen_table()
    c = core.constraints()
    assert c.may_replace[0] and c.touching[0].tolist() == [False, False, True]
    assert core.view([0]).may_replace[0] and core.view([0]).touching[0, 2]
    a = np.zeros((1, 8))
    a[0, 6] = 0.25
    out = core.step(a, [0])
    rec, t = out["record"], core.table
    assert rec.replaced[0] and rec.restart[0] and out["info"]["passed"][0] and not rec.turn_over[0]
    assert out["info"]["replaced"][0]
    assert out["info"]["n_events"][0] == 0 and core.game.shots[0] == 0 and core.game.shooter[0] == 0
    pos = core.state.pos[0]
    assert np.allclose(pos[0], (t.width / 2 + OPENING_OFFSET, t.length / 4))  # the mover's ball beside the head spot
    assert np.allclose(pos[1], (t.width / 2, t.length / 4)) and np.allclose(pos[2], (t.width / 2, 3 * t.length / 4))
    c = core.constraints()
    assert c.is_break[0] and c.targets[0].tolist() == [False, False, True] and not c.may_replace[0]


def test_balls_in_contact_the_default_action_plays_from_where_the_ball_lies():
    """a6 <= 0 (the default of a zero action) or a6 > 0.5 plays the shot: a0 = 0 aims at the opponent's
    ball, away from the red it touches, and is fair; a shot aimed straight into the red is a foul."""
    for a6 in (0.0, 1.0):
        core = _frozen_table()
        a = np.zeros((1, 8))
        a[0, 6] = a6
        out = core.step(a, [0])
        assert not out["record"].replaced[0] and out["info"]["n_events"][0] > 0
        assert out["info"]["first_contact"][0] == 1 and out["record"].foul[0] == R.FOUL_NONE
    core = _frozen_table()
    into = ShotPlan.of(Shots(np.array([0.0]), np.array([2.0]), 0.0, 0.0))
    out = core.step(core.actions_of(into, [0]), [0])
    assert out["record"].foul[0] == R.FOUL_PUSH and out["record"].turn_over[0] and out["info"]["points"][0] == 0


def test_random_games_end_and_scores_follow_the_shot_records():
    """3,000 random games: every game ends within the shot cap (by the innings limit or the target), the
    scores are the sums of the recorded points, the player to move follows the records, no ball is lost."""
    n, cap = 3000, 60
    core = GameCore(GameConfig(game="three_cushion", max_shots=cap, noise="tournament",
                               rule_options={"target": 2, "max_innings": 8}), n)
    core.streams.seed(np.arange(n), np.arange(n) + 7)
    core.reset_tables(np.arange(n))
    rng = np.random.default_rng(1)
    live = np.ones(n, dtype=bool)
    points = np.zeros((n, 2), dtype=np.int64)
    steps = 0
    while live.any():
        idx = np.nonzero(live)[0]
        before = core.game.shooter[idx].copy()
        out = core.step(rng.uniform(-1, 1, (len(idx), 8)), idx)
        rec = out["record"]
        steps += 1
        np.add.at(points, (idx, rec.shooter), rec.points)
        assert rec.turn_over[(rec.points == 0) & ~rec.game_over & ~rec.replaced].all()  # a miss ends the inning
        assert not (rec.turn_over & (rec.points > 0) & (core.game.phase[idx] != R.PHASE_FINAL)
                    & (core.game.phase[idx] != R.PHASE_FINAL_OPENING)).any()
        assert (core.game.shooter[idx] == np.where(rec.turn_over, 1 - before, before)).all()
        assert (core.state.pocket[idx] == -1).all()
        pos = core.state.pos[idx]
        d = np.linalg.norm(pos[:, :, None] - pos[:, None], axis=-1) + np.eye(3) * 9
        assert (d >= 2 * core.params.R - 1e-9).all()
        live[idx[out["terminated"] | out["truncated"]]] = False
        assert steps <= 2 * cap + 1  # a replace (no shot) is always followed by a shot from the starting position
    g = core.game
    assert (g.score == points).all() and points.sum() > 0
    assert g.over.all()  # the innings limit ends every game well inside the cap
    won = g.winner >= 0
    assert (g.score[won, g.winner[won]] >= g.score[won, 1 - g.winner[won]]).all()
    assert ((g.score.max(axis=1) >= 2) | (g.innings.min(axis=1) == 8)).all()


def test_point_task_success_and_shaped_reward():
    """Billiards-ThreeCushionPoint-v1: success is the point read from the contact order, and the reward is
    the sum of its spec's terms (success 1.0, both balls 0.2, 0.3 x cushions before the second / 3, foul -0.1)."""
    from gymnasium.utils.env_checker import check_env
    check_env(gym.make("Billiards-ThreeCushionPoint-v1").unwrapped, skip_render_check=True)
    n = 1024
    v = gym.make_vec("Billiards-ThreeCushionPoint-v1", num_envs=n, vectorization_mode="vector_entry_point")
    obs, _ = v.reset(seed=2)
    assert obs.shape == (n, 13) and v.unwrapped._core.table.style == "carom"
    rng = np.random.default_rng(4)
    _, r, term, trunc, info = v.step(rng.uniform(-1, 1, (n, 4)).astype(np.float32))
    assert term.all() and not trunc.any()
    terms = info["reward_terms"]
    np.testing.assert_allclose(r, sum(terms[k] for k in terms), atol=1e-12)
    assert (terms["success"] == 1.0 * info["success"]).all() and (terms["foul"] == -0.1 * info["foul"]).all()
    assert info["success"].sum() >= 1 and (terms["contact"] > 0).sum() > info["success"].sum()
    # a point always reached both balls with the full shaping term
    s = info["success"]
    assert (terms["contact"][s] == 0.2).all() and np.allclose(terms["shaping"][s], 0.3)
    assert (terms["pocket"] == 0).all() and (terms["scratch"] == 0).all()


def test_restart_position_puts_the_movers_ball_beside_the_head_spot():
    """``setup.restart_position`` (the equal-innings last inning): after ``hand_over`` slot 0 is the incoming
    player's ball; on the marked tables the three balls go to the starting position, the others stay."""
    t = Table.carom()
    pos = np.array([[[0.3, 0.4], [1.1, 2.0], [0.5, 2.5]], [[0.3, 0.4], [1.1, 2.0], [0.5, 2.5]]])
    hand_over(pos, np.array([True, True]))
    restart_position(pos, np.array([True, False]), t, 0.03075)
    w, l = t.width, t.length
    assert np.allclose(pos[0], [(w / 2 + OPENING_OFFSET, l / 4), (w / 2, l / 4), (w / 2, 3 * l / 4)])
    assert np.allclose(pos[1], [(1.1, 2.0), (0.3, 0.4), (0.5, 2.5)])


def test_equal_innings_last_inning_played_from_the_starting_position():
    """Through the simulator: tables where the starter, one point short, plays random shots; where a shot makes
    the point the starter has reached the target, and the opponent's last inning begins with the balls at the
    starting position, the opponent's own ball beside the head spot, the red to be struck first."""
    n = 512
    core = GameCore(GameConfig(game="three_cushion", noise="none",
                               rule_options={"target": 3, "equal_innings": True}), n)
    core.streams.seed(np.arange(n), np.arange(n) + 1)
    core.reset_tables(np.arange(n), np.zeros(n, dtype=np.int64))
    core.game.phase[:] = R.PHASE_PLAY
    core.game.score[:, 0] = 2
    core.state.pos[:] = [(0.35, 0.45), (0.95, 1.25), (0.45, 2.25)]
    core._changed()
    out = core.step(np.random.default_rng(3).uniform(-1, 1, (n, 8)), np.arange(n))
    rec = out["record"]
    hit = np.nonzero(rec.points > 0)[0]
    assert len(hit) and rec.restart[hit].all() and not rec.restart[rec.points == 0].any()
    t = core.table
    start = [(t.width / 2 + OPENING_OFFSET, t.length / 4), (t.width / 2, t.length / 4), (t.width / 2, 3 * t.length / 4)]
    assert np.allclose(core.state.pos[hit], np.array(start)[None])
    g, c = core.game, core.constraints()
    assert (g.shooter[hit] == 1).all() and (g.phase[hit] == R.PHASE_FINAL_OPENING).all()
    assert c.is_break[hit].all() and not c.targets[hit, 1].any()
