"""A sixth game added through the registry alone: one rules module (here, this
test module: 3-ball, 9-ball's rules on three balls), its default
configuration (``tests/envs/games/three_ball.yaml``, named by the spec's
``config_path``) and one ``register_game`` call, nothing else edited. The
single-agent env, the vector entry point and the PettingZoo AEC env are
generated from the entry; they pass Gymnasium's and PettingZoo's checks,
play random games to the end, hand bots their views and speak the game's
own words."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

from billiards_env.physics.state import _triangle
from billiards_env.rules import GAMES, GameSpec, GameWords, StudyPresets, register_game
from billiards_env.rules.nine_ball import NineBallRules
from billiards_env.rules.placement import FOOT_SPOT

TOY = "three_ball"


class ThreeBallRules(NineBallRules):
    """3-ball: balls 1-3 in rotation, the 3 wins (9-ball's rules otherwise)."""

    name = TOY
    n_balls = 3
    game_ball = 3


def three_ball_rack(table, R: float, u: np.ndarray) -> np.ndarray:
    """A frozen triangle of three on the foot spot: the 1 at the apex, the 2 and the 3 behind it in the order of ``u``."""
    slots = _triangle(2, (table.width / 2, FOOT_SPOT * table.length), R, 0.0, slice(None))
    pos = np.zeros((len(u), 4, 2))
    pos[:, 1] = slots[0]
    order = np.where(u[:, :1] < 0.5, [[2, 3]], [[3, 2]])
    pos[np.arange(len(u))[:, None], order] = slots[1:3][None]
    return pos


# the benchmark's games section times it: a quick run's games spot the 3 on the break, two games a table
TOY_PRESETS = StudyPresets(benchmarked=True, quick_rules=(("spot_break_nine", True),), games_per_table=2)
SPEC = GameSpec(TOY, "3-ball", ThreeBallRules, three_ball_rack, 1, "ghost", "ThreeBall", "ThreeBall",
                "3-ball (9-ball's rules on three balls, a toy game of the tests)", GameWords(call=""),
                presets=TOY_PRESETS,
                config_path=str(Path(__file__).parent / "games" / f"{TOY}.yaml"))


@pytest.fixture(scope="module")
def toy():
    from gymnasium.envs.registration import registry

    from billiards_env.envs.registration import register_envs
    register_game(SPEC, replace=True)
    register_envs()  # the ids of a game added after import
    yield SPEC
    GAMES.pop(TOY, None)
    registry.pop(SPEC.env_id, None)


def test_the_registry_alone_registers_the_gymnasium_id(toy):
    import gymnasium as gym
    assert toy.env_id == "Billiards-ThreeBall-v1"
    env = gym.make(toy.env_id, max_shots=20)
    obs, _ = env.reset(seed=0)
    assert env.observation_space.contains(obs)
    vec = gym.make_vec(toy.env_id, num_envs=2, vectorization_mode="vector_entry_point")
    obs, _ = vec.reset(seed=0)
    assert obs.shape[0] == 2


def test_the_registry_alone_makes_the_envs(toy):
    from billiards_env.envs.games.catalog import game_classes
    from billiards_env.envs.games.single import ThreeBallEnv
    classes = game_classes(TOY)
    assert classes.single is ThreeBallEnv and ThreeBallEnv().core.n_balls == 4
    check_env(ThreeBallEnv(max_shots=20), skip_render_check=True)


def test_random_games_play_to_the_end_and_vector_equals_singles(toy):
    from billiards_env.envs.games.single import single_class
    from billiards_env.envs.games.vector import three_ball_vector
    vec = three_ball_vector(4, max_shots=30)
    obs, _ = vec.reset(seed=3)
    rng = np.random.default_rng(0)
    ended = np.zeros(4, dtype=bool)
    for _ in range(30):
        obs, r, term, trunc, info = vec.step(rng.uniform(-1, 1, vec.action_space.shape).astype(np.float32))
        assert np.isfinite(obs).all()
        ended |= term | trunc
    assert ended.all(), "every table's game ended within 30 shots"
    env = single_class(TOY)(opponent="ghost", max_shots=30)
    obs, _ = env.reset(seed=5)
    for _ in range(40):
        obs, r, term, trunc, info = env.step(env.action_space.sample())
        if term or trunc:
            assert info["winner"] in (-1, 0, 1)
            break
    else:
        pytest.fail("a 3-ball game against ghost did not end in 40 shots")


def test_pettingzoo_api(toy):
    from pettingzoo.test import api_test
    from billiards_env.envs.games.aec import aec_class
    api_test(aec_class(TOY)(max_shots=10), num_cycles=20)


def test_the_games_own_words(toy):
    from billiards_env.rendering.game_words import call_words, game_words
    assert game_words(TOY) == "3-ball" and call_words(TOY) == "call the shot"


def test_the_play_server_offers_it_and_plays_it(toy):
    """The lobby's game list and bots, a new game's request and a game played through a session: from the
    registry (no own_bots: the pool bots; the bots written for other games refused)."""
    from billiards_env.play.app import POOL_BOTS, bot_problem, game_bots, new_request
    from billiards_env.play.session import HUMAN, Session
    offered = game_bots(TOY)  # no ladder shipped for it, no Expert Iteration network, no champion-fast measured
    assert offered == ["ghost"] + [b for b in POOL_BOTS if b != "ghost"] + ["champion"], offered
    assert "champion-fast has no player for 3-ball" in bot_problem("champion-fast", TOY)
    assert new_request({"game": TOY, "seed": 1})["players"] == [HUMAN, "ghost"]
    assert bot_problem("search16", TOY) is None
    assert bot_problem("carom", TOY) == "the carom bot plays three-cushion only, not 3-ball"
    assert "plays snooker only" in bot_problem("snooker", TOY)
    s = Session("toy", TOY, [HUMAN, "ghost"], 1)
    assert s.state()["title"] == "3-ball" and s.state()["hint_bot"] == "ghost"
    _play_turns(s)
    _play_turns(Session("toy2", TOY, [HUMAN, "champion"], 2))  # the strongest bot it offers plays it too


def _play_turns(s, turns: int = 4) -> None:
    """Up to ``turns`` turns of session ``s``: the person plays the hint (its default bot's shot), the bot its own;
    at least two are played and recorded."""
    for turn in range(turns):
        if s.state()["over"]:
            break
        if s.state()["to_move"] == 0:
            s.human_shot({**s.hint(), "player": 0})
        else:
            s.bot_shot(turn)
    assert s.turn >= 2 and s.n_shots() == s.turn


def test_recorded_rulings_read_its_balls(toy):
    """A recorded 3-ball game's states and rulings (``rendering.game_replay``): no groups (its rules' ``groups``),
    games won, the balls by number."""
    from billiards_env.bots import make_bot
    from billiards_env.envs.games import GameConfig, GameCore
    from billiards_env.envs.games.play import play_round
    from billiards_env.rendering.game_replay import GameRecorder
    core = GameCore(GameConfig(game=TOY, noise="tournament", max_shots=20), 1, record=True)
    core.streams.seed([0], [2])
    core.reset_tables([0])
    rec = GameRecorder(core, [0])
    bots = [make_bot("ghost", 0), make_bot("ghost", 1)]
    for _ in range(20):
        out = play_round(core, bots, np.arange(1), {"bots": 0.0})
        if out["terminated"][0] or out["truncated"][0]:
            break
    shots = [s["info"]["game"] for rep in rec.games(0) for s in rep.data["shots"]]
    assert shots and all(s["after"]["groups"] is None and s["after"]["score_of"] == "games won" for s in shots)
    assert any("pots the " in s["ruling"] for s in shots), [s["ruling"] for s in shots]


def test_the_studies_play_it_from_its_spec(toy):
    """The break study reads its game ball from its rules (the 3); the games benchmark times it (its presets:
    benchmarked, a quick run's rule settings, games per table) between its default bots."""
    from billiards_env.studies import games_bench
    from billiards_env.studies.breaks import break_outcomes
    out = break_outcomes(TOY, n_racks=8, noise="tournament")
    assert out["racks"] == 8 and 0 <= out["game ball down"]["rate"] <= out["pockets a ball"]["rate"]
    assert TOY in games_bench.benchmarked_games()
    games, steps = games_bench.rows((TOY,), n_tables=4, n_games=100, n_steps=2, quick=True)
    assert games["policies"] == ["ghost", "ghost"] and games["rule_options"] == {"spot_break_nine": True}
    assert 8 <= games["games"] < 100 and steps["steps"] == 2
