"""The shipped ladder (billiards_env/bots/learned): the numpy network
reproduces the torch policy's deterministic actions, a ladder agent loads by
name without stable-baselines3 or torch and plays a seeded game identically
twice, and it is an opponent of the game envs and the match harness."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from billiards_env.bots import is_bot_name, make_bot
from billiards_env.bots.learned import ladder as L
from billiards_env.bots.learned.mlp import MLPPolicy, ObsNorm

ROOT = Path(__file__).resolve().parents[2]
GAMES = ("nine_ball", "eight_ball")


def test_mlp_forward_is_the_hand_computed_argmax():
    """One hidden tanh unit per input, then logits W h + b split 2 + 3:
    the action is each part's argmax of the closed-form logits."""
    w0 = np.eye(2, dtype=np.float32)
    b0 = np.zeros(2, np.float32)
    w1 = np.array([[1, 0], [-1, 0], [0, 1], [0, -1], [0, 0]], np.float32)
    b1 = np.array([0, 0, 0, 0, 0.5], np.float32)
    net = MLPPolicy((w0, w1), (b0, b1), "tanh", (2, 3), ObsNorm(np.array([1.0, 0.0]), np.array([4.0, 1.0])))
    obs = np.array([[3.0, 2.0], [-1.0, -2.0], [1.0, 0.1]])
    h = np.tanh(np.clip((obs - [1.0, 0.0]) / np.sqrt(np.array([4.0, 1.0]) + 1e-8), -10, 10))
    z = h @ w1.T + b1
    want = np.stack([z[:, :2].argmax(1), z[:, 2:].argmax(1)], axis=1)
    assert want.tolist() == [[0, 0], [1, 1], [0, 2]]  # every branch of both heads is taken
    assert np.array_equal(net.act(obs), want)
    with pytest.raises(ValueError, match=r"observations \[N, 2\]"):
        net.act(np.zeros((1, 3)))


@pytest.mark.parametrize("game,env_id", [("nine_ball", "Billiards-NineBall2P-v1"), ("eight_ball", "Billiards-EightBall-v1")])
def test_numpy_network_chooses_the_torch_policys_actions(game, env_id, tmp_path):
    """A PPO over the shot menu (configs/ppo_games.yaml, 8 tables) with its
    normaliser fed a few steps: on seeded game positions the exported numpy
    network's actions equal ``model.predict(deterministic=True)``'s, and the
    exported files play as a ladder agent."""
    pytest.importorskip("stable_baselines3")
    from agents.config import load_config
    from agents.sb3.ladder_export import check, numpy_network
    from agents.sb3.policy import SB3Policy
    from agents.sb3.training import build_env, build_model

    cfg = load_config(str(ROOT / "configs" / "ppo_games.yaml"), env_id, ["n_envs=8", "ppo.batch_size=64"])
    env, vn = build_env(cfg, 0)
    model = build_model(cfg, env, None)
    env.reset()
    for _ in range(3):
        env.step(np.stack([env.action_space.sample() for _ in range(8)]))
    vn.training = False
    policy = SB3Policy(model, vn, features=cfg.features, aim_scale=cfg.aim_scale, action_mode=cfg.action_mode)
    net = numpy_network(policy, "tanh", 10.0)
    assert net.norm is not None and not np.allclose(net.norm.var, 1.0)
    assert check(net, policy, game, 48) >= 24


def _shipped(game):
    names = L.ladder_names(game)
    if not names:
        pytest.skip(f"no ladder agents shipped for {game}")
    return names


def test_ladder_agents_load_without_torch_and_replay_identically(played_twice_without_torch):
    """Every game's strongest rung, by name, in a process where importing
    torch or stable-baselines3 fails: a seeded pairing against ghost played
    twice gives the same winners and shot counts."""
    pairs = [(g, _shipped(g)[-1]) for g in GAMES]
    out = played_twice_without_torch(pairs, n_racks=3, max_shots=60)
    for game in GAMES:
        first, second = out[game]
        assert first == second
        assert sum(first[1]) > 6  # the games were played (shots were taken)


def test_every_shipped_card_is_complete_and_its_weights_load():
    for game in GAMES:
        for name in _shipped(game):
            net, doc = L.load_network(game, name)
            assert doc["game"] == game and doc["version"] >= 1 and doc["training_steps"] > 0
            assert doc["architecture"]["obs_dim"] == net.obs_dim and doc["source_config"]["env_id"] == doc["env_id"]
        steps = [L.card(game, n)["training_steps"] for n in _shipped(game)]
        assert steps == sorted(steps)  # weakest first: the rungs are snapshots at increasing steps


def test_ladder_names_and_errors():
    assert is_bot_name("ladder-3") and not is_bot_name("ladder-x") and not is_bot_name("ladder")
    bot = make_bot("ladder-99")  # loads lazily: the game is the view's
    with pytest.raises(ValueError, match="no ladder agent 'ladder-99' for nine_ball; shipped"):
        bot.player("nine_ball")
    with pytest.raises(ValueError, match="ladder-<k>"):
        L.LadderBot("ghost")


def test_ladder_agent_is_an_opponent_of_the_game_env():
    import gymnasium as gym

    import billiards_env  # noqa: F401

    name = _shipped("eight_ball")[0]
    env = gym.make("Billiards-EightBall-v1", opponent=name)
    env.reset(seed=5)
    total = 0
    for _ in range(6):
        obs, r, term, trunc, info = env.step(env.action_space.sample())
        assert np.isfinite(obs).all()
        total += 1
        if term or trunc:
            break
    assert total >= 1


def test_ladder_agent_plays_the_aec_env():
    """PettingZoo's turn loop with a ladder agent for both players: its
    actions are valid game actions for the agent to move."""
    from billiards_env.envs.games.aec import NineBallAECEnv

    name = _shipped("nine_ball")[0]
    env = NineBallAECEnv()
    env.reset(seed=3)
    bot = make_bot(name, seed=1)
    for _ in range(4):
        obs, r, term, trunc, info = env.last()
        if term or trunc:
            break
        a = env.bot_action(bot.act(env.bot_view()))
        assert env.action_space(env.agent_selection).contains(a)
        env.step(a)


def test_ladder_table_quick_mode_writes_its_tables(tmp_path):
    for game in GAMES:
        _shipped(game)
    res = subprocess.run([sys.executable, "scripts/ladder_table.py", "--quick", "--out", str(tmp_path)], cwd=ROOT,
                         capture_output=True, text=True, timeout=600)
    assert res.returncode == 0, res.stderr[-2000:]
    for game in GAMES:
        assert (tmp_path / f"{game}_none.md").exists() and (tmp_path / f"{game}_none.png").exists()
    rows = (tmp_path / "ratings.csv").read_text().splitlines()
    assert rows[0].startswith("game,noise,entrant") and len(rows) == 1 + 2 * 2  # ladder-1 and ghost per game
    assert "ladder-1" in (tmp_path / "ladder.md").read_text()


def test_a_final_models_card_takes_the_runs_training_steps_and_time(tmp_path):
    """``export_ladder.py`` without ``--steps`` (the run's model.zip) reads the steps and the training wall
    time from the run's ``train_summary.json``; a checkpoint's, from its state file."""
    pytest.importorskip("stable_baselines3")
    import json

    from agents.sb3.ladder_export import training_info
    (tmp_path / "train_summary.json").write_text(json.dumps({"timesteps": 6000640, "train_wall_s": 1013.79803}))
    assert training_info(tmp_path, None) == dict(training_steps=6000640, training_wall_s=1013.8)
    (tmp_path / "checkpoints").mkdir()
    (tmp_path / "checkpoints" / "model_4096_steps_state.json").write_text(json.dumps({"steps": 4096,
                                                                                       "elapsed_s": 2.26}))
    assert training_info(tmp_path, 4096) == dict(training_steps=4096, training_wall_s=2.3)
