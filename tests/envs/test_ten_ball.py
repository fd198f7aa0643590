"""Billiards-TenBall-v1: the rack, the rules that read contacts played
through the simulator, the spaces, properties of thousands of random games,
and the 9-ball bots calling their shots in matches (PettingZoo's and
Gymnasium's checks and the vector env against single games run for every
game in tests/envs/test_games.py)."""
import math

import gymnasium as gym
import numpy as np
import pytest

import billiards_env  # noqa: F401 (registers the ids)
from billiards_env.envs.games import GameConfig, GameCore
from billiards_env.envs.games.vector import GameVectorEnv
from billiards_env.physics.strike import Shots
from billiards_env.rules import records as R
from billiards_env.testing.positions import game_table
from billiards_env.rules.placement import FOOT_SPOT

ID = "Billiards-TenBall-v1"


# ------------------------------------------------------------------- the rack --
def test_rack_one_on_the_foot_spot_ten_in_the_centre_frozen_and_shuffled():
    core = GameCore(GameConfig(game="ten_ball", rack="perfect"), 200)  # realistic racks: tests/envs/test_racks.py
    core.streams.seed(np.arange(200), np.arange(200))
    core.reset_tables(np.arange(200))
    t, R_ = core.table, core.params.R
    pos = core.state.pos
    np.testing.assert_allclose(pos[:, 1], np.tile([t.width / 2, FOOT_SPOT * t.length], (200, 1)))
    row3 = FOOT_SPOT * t.length + 2 * (2 * R_) * math.sqrt(3) / 2  # the third row, its middle slot
    np.testing.assert_allclose(pos[:, 10], np.tile([t.width / 2, row3], (200, 1)))
    d = np.linalg.norm(pos[:, 1:, None] - pos[:, None, 1:], axis=-1)
    d[:, np.arange(10), np.arange(10)] = np.inf
    assert d.min() >= 2 * R_ - 1e-12 and np.isclose(d.min(axis=2), 2 * R_).all()  # frozen, every ball touching
    assert len({tuple(np.round(pos[e, 2:10].ravel(), 6)) for e in range(200)}) > 150  # balls 2-9 shuffled
    assert (core.game.phase == R.PHASE_BREAK).all() and (core.constraints().ball_in_hand == R.IN_HAND_KITCHEN).all()
    assert not core.constraints().call_needed.any()


# ------------------------------------------------ rules through the simulator --
PARKED = {b: (0.2 + 0.1 * (b - 2), 2.2) for b in range(2, 11)}  # balls 2..10 out of the way at the foot end


def ten_ball_table(balls: dict, phase=R.PHASE_PLAY, hand=R.IN_HAND_NONE):
    """A 10-ball core of one table in ``phase`` with the balls of ``balls`` on the table (``testing.positions``)."""
    return game_table("ten_ball", balls, phase, hand)


def shoot(core, phi, speed, ball=None, pocket=None, declare=None, placement=None):
    a = core.codec([0]).encode(Shots(np.array([phi]), np.array([speed]), np.zeros(1), np.zeros(1)), placement,
                         None if declare is None else np.array([declare]),
                         None if pocket is None else np.array([pocket]), None if ball is None else np.array([ball]))
    return core.step(a, [0])


STRAIGHT = {0: (0.32, 0.32), 1: (0.2, 0.2)}  # the 1 straight into the head-left corner pocket (pocket 0)
DIAGONAL = math.atan2(-1, -1)


def test_sim_the_called_ball_in_the_called_pocket_keeps_the_table():
    core = ten_ball_table({**STRAIGHT, **PARKED})
    out = shoot(core, DIAGONAL, 1.5, ball=1, pocket=0)
    i = out["info"]
    assert i["pocketed"][0, 1] and core.state.pocket[0, 1] == 0 and i["called_ball"][0] == 1
    assert i["called_pocket"][0] == 0 and out["record"].legal[0] and not out["record"].turn_over[0]


@pytest.mark.parametrize("ball,pocket", [(1, 3), (5, 0), (R.CALL_SAFETY, 0)])
def test_sim_an_illegal_pot_passes_the_turn_with_the_option(ball, pocket):
    """The same pot called into another pocket, with another ball called, or
    on a called safety: the turn passes and the incoming player may shoot
    or hand the table back (a6 > 0)."""
    core = ten_ball_table({**STRAIGHT, **PARKED})
    out = shoot(core, DIAGONAL, 1.5, ball=ball, pocket=pocket)
    assert out["info"]["pocketed"][0, 1] and out["record"].option[0] and out["record"].turn_over[0]
    c = core.constraints()
    assert c.shooter[0] == 1 and c.may_pass[0] and c.ball_in_hand[0] == R.IN_HAND_NONE
    cue = core.state.pos[0, 0].copy()
    out = shoot(core, 0.0, 1.0, declare=True)  # player 1 passes: no shot, player 0 shoots from the position
    assert out["info"]["passed"][0] and out["info"]["n_events"][0] == 0
    np.testing.assert_array_equal(core.state.pos[0, 0], cue)
    assert core.constraints().shooter[0] == 0 and not core.constraints().may_pass[0]


def test_sim_a_called_ten_wins_and_an_uncalled_ten_is_spotted():
    balls = {0: (0.32, 0.32), 10: (0.2, 0.2), **{b: PARKED[b] for b in range(2, 10)}}
    for b in range(1, 10):
        balls.pop(b, None)
    core = ten_ball_table(balls)
    out = shoot(core, DIAGONAL, 1.5, ball=10, pocket=0)
    assert out["record"].game_over[0] and out["record"].winner[0] == 0 and out["record"].end[0] == R.END_TEN
    core = ten_ball_table(balls)
    out = shoot(core, DIAGONAL, 1.5, ball=10, pocket=1)  # called into the head-right corner
    # (info["pocketed"] lists the balls down after the shot: a spotted ball is in ``respotted``)
    assert out["record"].respot[0, 10] and out["record"].option[0] and not out["record"].game_over[0]
    assert core.state.pocket[0, 10] == -1 and core.state.pos[0, 10, 1] >= FOOT_SPOT * core.table.length - 1e-9
    assert core.constraints().may_pass[0]


def test_sim_the_ten_on_the_break_is_spotted_and_the_breaker_continues():
    """A 'break' from behind the head string: the 1 full on the 10, the 10 into the corner."""
    core = ten_ball_table({0: (0.5, 0.5), 1: (0.35, 0.35), 10: (0.2, 0.2), **{b: PARKED[b] for b in range(2, 10)}},
                          phase=R.PHASE_BREAK, hand=R.IN_HAND_KITCHEN)
    out = shoot(core, DIAGONAL, 3.0, placement=np.array([[0.5, 0.5]]))
    i = out["info"]
    assert i["first_contact"][0] == 1 and i["respotted"][0, 10] and i["called_ball"][0] == R.CALL_NONE
    assert out["record"].legal[0] and out["record"].respot[0, 10] and not out["record"].game_over[0]
    assert not out["record"].turn_over[0] and core.state.pocket[0, 10] == -1
    c = core.constraints()
    assert c.shooter[0] == 0 and c.push_out_allowed[0] and c.call_needed[0]


def test_sim_wrong_ball_first_gives_ball_in_hand_anywhere():
    core = ten_ball_table({0: (0.635, 1.0), 1: (0.2, 0.4), **PARKED})  # straight at the 6 at (0.6, 2.2)
    out = shoot(core, math.atan2(1.2, -0.035), 2.0, ball=6, pocket=4)
    assert out["info"]["first_contact"][0] == 6 and out["record"].foul[0] == R.FOUL_WRONG_BALL
    c = core.constraints()
    assert c.ball_in_hand[0] == R.IN_HAND_ANYWHERE and c.shooter[0] == 1 and not c.may_pass[0]


def test_sim_push_out_after_a_legal_break_only():
    core = ten_ball_table({0: (0.635, 1.0), 1: (0.2, 0.4), **PARKED}, phase=R.PHASE_AFTER_BREAK)
    out = shoot(core, math.pi / 2, 0.3, declare=True)  # a soft push-out touching nothing
    assert out["record"].push_out[0] and out["record"].legal[0] and core.constraints().may_pass[0]
    core = ten_ball_table({0: (0.635, 1.0), 1: (0.2, 0.4), **PARKED}, phase=R.PHASE_PLAY)
    out = shoot(core, math.pi / 2, 0.3, declare=True)  # not after the break: an ordinary shot, a foul
    assert not out["record"].push_out[0] and out["record"].foul[0] == R.FOUL_NO_CONTACT


def test_ghost_calls_its_pot():
    from billiards_env.bots import make_bot
    from billiards_env.envs.games.play import bot_actions
    for name in ("ghost", "search16"):
        core = ten_ball_table({**STRAIGHT, **PARKED})
        out = core.step(bot_actions(core, make_bot(name, seed=0), [0]), [0])
        i = out["info"]
        assert i["called_ball"][0] == 1 and i["pocketed"][0, 1] and i["called_pocket"][0] == core.state.pocket[0, 1]
        assert out["record"].legal[0] and not out["record"].turn_over[0], name


# ---------------------------------------------------------- the env checks --
# (PettingZoo's api_test, check_env and the vector env against AEC singles: tests/envs/test_games.py)
def test_spaces_and_the_action_shape():
    env = gym.make(ID, max_shots=40)
    obs, info = env.reset(seed=3)
    assert env.observation_space.contains(obs) and obs.shape == (4 * 11 + 14,) and env.action_space.shape == (9,)
    with pytest.raises(ValueError, match=r"shape \(9,\)"):
        env.step(np.zeros(8, dtype=np.float32))
    v = gym.make_vec(ID, num_envs=3, vectorization_mode="vector_entry_point")
    assert isinstance(v, GameVectorEnv) and v.single_action_space.shape == (9,)
    v = gym.make_vec(ID, num_envs=3, vectorization_mode="vector_entry_point", opponent="ghost")
    obs, _ = v.reset(seed=0)
    obs, r, term, trunc, info = v.step(v.action_space.sample())
    assert obs.shape == (3, 58) and info["called_ball"].shape == (3,)


def test_random_games_properties():
    """2,000 random 10-ball games: every game ends within the shot cap; no
    ball is lost or duplicated; the player to move, the foul counts and the
    winner follow the shot records exactly; the 10 leaves the table only to
    end the game (a called, legal pot) or is spotted."""
    n_tables, cap = 2000, 150
    core = GameCore(GameConfig(game="ten_ball", max_shots=cap, noise="tournament"), n_tables)
    core.streams.seed(np.arange(n_tables), np.arange(n_tables) + 7)
    core.reset_tables(np.arange(n_tables))
    rng = np.random.default_rng(1)
    R_ = core.params.R
    live = np.ones(n_tables, dtype=bool)
    fouls = np.zeros((n_tables, 2), dtype=np.int64)  # consecutive fouls as the records tell them
    winner = np.full(n_tables, -1)
    steps = options = passes = 0
    while live.any():
        idx = np.nonzero(live)[0]
        before = core.game.shooter[idx].copy()
        on_before = core.state.pocket[idx] < 0
        may_pass = core.constraints().may_pass[idx].copy()
        out = core.step(rng.uniform(-1.1, 1.1, (len(idx), 9)), idx)
        rec, info = out["record"], out["info"]
        steps += 1
        assert (rec.shooter == before).all()
        assert (core.game.shooter[idx] == np.where(rec.turn_over, 1 - before, before)).all()
        assert not (rec.passed & ~may_pass).any() and not (rec.option & (rec.foul > 0)).any()
        options += rec.option.sum()
        passes += rec.passed.sum()
        f = fouls[idx, before]
        fouls[idx, before] = np.where(rec.passed, f, np.where(rec.foul > 0, f + 1, 0))
        np.testing.assert_array_equal(core.game.fouls[idx], fouls[idx])
        three = rec.end == R.END_THREE_FOULS
        assert (fouls[idx[three], before[three]] == 3).all() and (rec.winner[three] == 1 - before[three]).all()
        won = rec.end == R.END_TEN
        assert (info["called_ball"][won] == 10).all() and info["pocketed"][won, 10].all() and rec.legal[won].all()
        assert (rec.winner[won] == before[won]).all() and not rec.respot[won].any()
        assert (rec.respot[:, 1:10] == 0).all()  # only the 10 is ever spotted
        winner[idx] = rec.winner
        on = core.state.pocket[idx] < 0
        came_back = on & ~on_before
        assert not came_back[:, 1:][~rec.respot[:, 1:]].any()
        pk = info["pocketed"][:, 1:]
        assert (pk == (on_before & ~on)[:, 1:] | (pk & rec.respot[:, 1:])).all()
        assert (on[:, 10] | won).all()  # the 10 is always on the table until the game is won
        pos = core.state.pos[idx]
        d = np.linalg.norm(pos[:, :, None] - pos[:, None], axis=-1)
        both = on[:, :, None] & on[:, None]
        d[:, np.arange(d.shape[1]), np.arange(d.shape[1])] = np.inf
        assert (d[both] >= 2 * R_ - 1e-9).all(), "two balls overlap (a duplicated ball)"
        done = out["terminated"] | out["truncated"]
        assert not (out["terminated"] & out["truncated"]).any()
        live[idx[done]] = False
        assert steps <= cap + 1
    g = core.game
    assert ((g.winner >= 0) == g.over).all() and (g.over | (g.shots >= cap)).all()
    np.testing.assert_array_equal(g.winner, winner)
    assert g.over.mean() > 0.5 and options > 0 and passes > 0


# ------------------------------------------------------------- bot matches --
def test_bots_play_ten_ball_matches():
    """The match harness on 10-ball (ghost against random: tests/envs/test_games.py):
    ghost-safety and search16 finish their games against ghost."""
    from billiards_env.studies.matches import play_pairing
    for other in ("ghost-safety", "search16"):
        r = play_pairing(other, "ghost", "ten_ball", n_racks=8, seed=0, noise="tournament")
        assert r.n == 16 and (r.winner >= 0).all(), r.summary()


def test_match_script_plays_ten_ball(tmp_path):
    import json
    import subprocess
    import sys
    from pathlib import Path
    root = Path(__file__).resolve().parents[2]
    out = subprocess.run([sys.executable, str(root / "scripts" / "match.py"), "--game", "ten_ball", "--racks", "2",
                          "--max-shots", "60", "--policies", "random", "ghost", "--out", str(tmp_path)],
                         capture_output=True, text=True, cwd=root, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    doc = json.loads((tmp_path / "ten_ball_tournament.json").read_text())
    assert doc["game"] == "ten_ball" and doc["pairings"][0]["games"] == 4
