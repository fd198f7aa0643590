"""Self-play PPO on the two-player games (agents/sb3/self_play.py): the
turn-passing GAE against closed forms and SB3's own, the turn signs a real
rollout records, and the configs that cannot self-play."""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from gymnasium import spaces

pytest.importorskip("stable_baselines3")

import torch  # noqa: E402
from stable_baselines3.common.buffers import RolloutBuffer  # noqa: E402
from stable_baselines3.common.callbacks import BaseCallback  # noqa: E402

from agents.config import load_config  # noqa: E402
from agents.sb3.self_play import TurnRecorder, TurnRolloutBuffer, turn_signs  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
GAMES = ROOT / "configs" / "ppo_games.yaml"
# the smallest self-play run: 8 tables of 9-ball, 8 steps per rollout, one core
SMALL = ["env_kwargs={}", "n_envs=8", "ppo.n_steps=8", "ppo.batch_size=64", "ppo.n_epochs=1",
         "policy.net_arch=[16, 16]", "train.env_workers=1", "train.overlap_updates=false",
         "train.progress_bar=false", "train.eval_every=0"]


def _buffer(cls, n_steps: int, n_envs: int, gamma: float, lam: float):
    buf = cls(n_steps, spaces.Box(-1, 1, (2,)), spaces.Discrete(3), "cpu", gae_lambda=lam, gamma=gamma,
              n_envs=n_envs)
    buf.reset()
    return buf


def _fill(buf, rewards, values, starts, signs=None):
    for t in range(buf.buffer_size):
        if signs is not None:
            buf.record_turns(np.asarray(signs[t], np.float32))
        n = buf.n_envs
        buf.add(np.zeros((n, 2), np.float32), np.zeros((n, 1)), np.asarray(rewards[t], np.float32),
                np.asarray(starts[t], np.float32), torch.as_tensor(values[t], dtype=torch.float32).reshape(n, 1),
                torch.zeros(n))


def _game(lam: float, v=(0.3, -0.2, 0.6)):
    """A passes (miss), B pots a ball and shoots again, B wins: one env, gamma 1."""
    buf = _buffer(TurnRolloutBuffer, 3, 1, 1.0, lam)
    _fill(buf, [[0.0], [0.0], [1.0]], [[v[0]], [v[1]], [v[2]]], [[1.0], [0.0], [0.0]],
          signs=[[-1.0], [1.0], [1.0]])
    buf.compute_returns_and_advantage(torch.tensor([[0.9]]), np.array([True]))
    return buf.returns[:, 0]


def test_turn_gae_matches_the_negamax_closed_form():
    # lambda = 1: the Monte-Carlo returns of each mover, -1 for the loser's shot
    np.testing.assert_allclose(_game(1.0), [-1.0, 1.0, 1.0], atol=1e-6)
    # lambda = 0: one-step targets r_t + s_t V(o_{t+1}); the last is the win itself
    np.testing.assert_allclose(_game(0.0), [0.2, 0.6, 1.0], atol=1e-6)


def test_turn_gae_with_no_turn_passing_is_sb3s_gae():
    rng = np.random.default_rng(3)
    T, n = 16, 4
    rewards, values = rng.normal(size=(T, n)), rng.normal(size=(T, n))
    starts = (rng.random((T, n)) < 0.2).astype(float)
    last, dones = torch.as_tensor(rng.normal(size=(n, 1))), rng.random(n) < 0.5
    ours, sb3 = _buffer(TurnRolloutBuffer, T, n, 0.97, 0.9), _buffer(RolloutBuffer, T, n, 0.97, 0.9)
    _fill(ours, rewards, values, starts, signs=np.ones((T, n)))
    _fill(sb3, rewards, values, starts)
    for b in (ours, sb3):
        b.compute_returns_and_advantage(last.clone(), dones)
    np.testing.assert_allclose(ours.advantages, sb3.advantages, rtol=1e-5, atol=1e-6)
    np.testing.assert_allclose(ours.returns, sb3.returns, rtol=1e-5, atol=1e-6)


def test_turn_signs_read_shooter_and_next_shooter():
    infos = [{"shooter": 0, "to_move": 0}, {"shooter": 0, "to_move": 1}, {"shooter": 1, "to_move": 1}]
    np.testing.assert_array_equal(turn_signs(infos), [1.0, -1.0, 1.0])


class _SignSpy(BaseCallback):
    """Keeps each step's turn signs and the step's infos, as SB3 saw them."""

    def __init__(self):
        super().__init__()
        self.signs, self.truncated = [], []

    def _on_step(self) -> bool:
        self.signs.append(turn_signs(self.locals["infos"]))
        self.truncated += [i.get("TimeLimit.truncated", False) for i in self.locals["infos"]]
        return True


def test_self_play_rollout_records_the_turns_it_played():
    from agents.sb3.training import build_env, build_model
    cfg = load_config(GAMES, overrides=SMALL)
    assert cfg.self_play and "opponent" not in cfg.env_kwargs
    env, _ = build_env(cfg, seed=0)
    try:
        model = build_model(cfg, env, None)
        spy = _SignSpy()
        model.learn(cfg.n_envs * cfg.ppo["n_steps"], callback=[TurnRecorder(), spy])
    finally:
        env.close()
    buf = model.rollout_buffer
    assert isinstance(buf, TurnRolloutBuffer)
    np.testing.assert_array_equal(buf.turn_sign, np.stack(spy.signs))
    assert (buf.turn_sign == -1).any(), "eight breaks and follow-ups with no turn passed"
    assert not any(spy.truncated), "a game cut at max_shots is a draw, not bootstrapped"


def test_self_play_training_evaluates_against_its_eval_opponent(tmp_path):
    from agents.sb3.training import train_and_evaluate
    cfg = load_config(GAMES, overrides=SMALL + ["train.total_timesteps=128", "train.eval_episodes=8",
                                                "train.eval_baselines=[ghost]", "train.eval_noise=[none]",
                                                "train.checkpoint_every=64"])
    assert cfg.eval_env_kwargs == {"opponent": "ghost"}
    train_and_evaluate(cfg, tmp_path / "sp", "pytest")
    run = tmp_path / "sp"
    ev = json.loads((run / "eval.json").read_text())
    assert {r["policy"] for r in ev} == {"ppo", "ghost"} and all(r["n_episodes"] == 8 for r in ev)
    rows = (run / "progress.csv").read_text().splitlines()[1:]
    assert rows and all(math.isnan(float(r.split(",")[3])) for r in rows), "self-play has no training success"
    assert (run / "learning_curve.png").exists()


def test_self_play_is_ppos_only():
    with pytest.raises(ValueError, match="self-play"):
        load_config(GAMES, overrides=["env_kwargs={}", "algo=sac", "train.overlap_updates=false"])


def test_rllib_refuses_self_play_configs(tmp_path):
    from agents.rllib.backend import train
    cfg = load_config(GAMES, overrides=["env_kwargs={}"])
    with pytest.raises(ValueError, match="self-play"):
        train(cfg, tmp_path / "r")
    assert not (tmp_path / "r").exists(), "the refusal changes nothing"


def test_named_opponent_is_not_self_play():
    cfg = load_config(GAMES, overrides=["env_kwargs={opponent: ghost}"])
    assert not cfg.self_play and cfg.eval_env_kwargs == cfg.env_kwargs
    default = load_config(GAMES)  # the games' default config trains by self-play, evaluated against ghost
    assert default.self_play and default.eval_env_kwargs == {"opponent": "ghost"}
