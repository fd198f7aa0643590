"""``gym.make_vec(game id, render_mode="rgb_array")`` renders every table
(self-play and against an opponent), and the frames show the tables' own
balls; a wrong render mode is a clear error."""
import gymnasium as gym
import numpy as np
import pytest

import billiards_env  # noqa: F401  (registers the ids)
from billiards_env.rendering.game import render_game

GAME_IDS = ["Billiards-NineBall2P-v1", "Billiards-EightBall-v1", "Billiards-TenBall-v1"]


@pytest.mark.parametrize("env_id", GAME_IDS)
def test_make_vec_renders_each_table(env_id):
    env = gym.make_vec(env_id, num_envs=2, render_mode="rgb_array")
    env.reset(seed=3)
    env.step(np.tile(np.linspace(-0.9, 0.9, env.single_action_space.shape[0]), (2, 1)))
    frames = env.render()
    assert isinstance(frames, tuple) and len(frames) == 2
    for k, f in enumerate(frames):
        assert f.dtype == np.uint8 and f.ndim == 3 and f.shape[2] == 3
        np.testing.assert_array_equal(f, render_game(env.unwrapped.core, k))
    assert not np.array_equal(frames[0], frames[1])  # two racks, two pictures
    assert all(log is not None for log in env.unwrapped.core.last_events)  # the shots' logs are kept for replays
    env.close()


def test_make_vec_against_an_opponent_renders():
    env = gym.make_vec("Billiards-NineBall2P-v1", num_envs=2, render_mode="rgb_array", opponent="ghost")
    env.reset(seed=1)
    assert len(env.render()) == 2


def test_make_vec_bad_render_mode():
    with pytest.raises(ValueError, match="render_mode must be one of"):
        gym.make_vec("Billiards-NineBall2P-v1", num_envs=2, render_mode="human")
    env = gym.make_vec("Billiards-NineBall2P-v1", num_envs=2)
    env.reset(seed=0)
    with pytest.warns(UserWarning, match="without a render_mode"):
        assert env.render() is None
    assert env.render_mode is None
