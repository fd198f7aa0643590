"""A sixth game added through the registry alone: one rules module (here, this
test module: 3-ball, 9-ball's rules on three balls) and one ``register_game``
call, nothing else edited. The single-agent env, the vector entry point and
the PettingZoo AEC env are generated from the entry; they pass Gymnasium's
and PettingZoo's checks, play random games to the end, hand bots their
views and speak the game's own words."""
from __future__ import annotations

import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

from billiards_env.physics.state import _triangle
from billiards_env.rules import GAMES, GameSpec, GameWords, register_game
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


SPEC = GameSpec(TOY, "3-ball", ThreeBallRules, three_ball_rack, 1, "ghost", "ThreeBall", "ThreeBall",
                "3-ball (9-ball's rules on three balls, a toy game of the tests)", GameWords(call=""))


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
