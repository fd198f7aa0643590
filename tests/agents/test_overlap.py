"""PPO whose update overlaps the next rollout (agents.sb3.overlap.OverlappedPPO)."""
from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("stable_baselines3")

from stable_baselines3.common.callbacks import BaseCallback  # noqa: E402

from agents.config import load_config  # noqa: E402
from agents.sb3.overlap import OverlappedPPO  # noqa: E402
from agents.sb3.training import build_env, build_model  # noqa: E402

SETS = ["n_envs=8", "ppo.n_steps=4", "ppo.batch_size=32", "ppo.n_epochs=2", "policy.net_arch=[16]",
        "train.overlap_updates=true"]
ROLLOUTS = 4


def _weights(policy) -> np.ndarray:
    return np.concatenate([p.detach().numpy().ravel().copy() for p in policy.parameters()])


class ActingWeights(BaseCallback):
    """The weights ``model.policy`` shows the rollout thread at each rollout's end."""

    def __init__(self):
        super().__init__()
        self.seen = []

    def _on_step(self) -> bool:
        return True

    def _on_rollout_end(self) -> None:
        self.seen.append(_weights(self.model.policy))


def test_rollouts_are_collected_one_update_behind():
    """Rollouts 1 and 2 are collected with the initial weights (update 1
    runs during rollout 2), rollout 3 with the weights after update 1, and
    every rollout gets its update (n_epochs each)."""
    cfg = load_config("configs/ppo_games.yaml", "Billiards-NineBall2P-v1", SETS)
    env, _ = build_env(cfg, 0)
    model = build_model(cfg, env, None)
    assert isinstance(model, OverlappedPPO)
    start = _weights(model.policy)
    cb = ActingWeights()
    model.learn(ROLLOUTS * 32, callback=cb)
    assert len(cb.seen) == ROLLOUTS and model._n_updates == ROLLOUTS * 2
    np.testing.assert_array_equal(cb.seen[0], start)
    np.testing.assert_array_equal(cb.seen[1], start)
    assert not np.array_equal(cb.seen[2], start) and not np.array_equal(cb.seen[3], cb.seen[2])
    # after learn no update runs: the policy is the learner's, updated past what the last rollout saw
    assert model._updating is None and not np.array_equal(_weights(model.policy), cb.seen[3])
    np.testing.assert_array_equal(_weights(model._acting), _weights(model.policy))
    env.close()


def test_an_update_error_reaches_the_caller(monkeypatch):
    cfg = load_config("configs/ppo_games.yaml", "Billiards-NineBall2P-v1", SETS)
    env, _ = build_env(cfg, 0)
    model = build_model(cfg, env, None)

    def broken():
        raise FloatingPointError("update failed")
    monkeypatch.setattr(model, "train", broken)
    with pytest.raises(FloatingPointError, match="update failed"):
        model.learn(ROLLOUTS * 32)
    env.close()


def test_overlap_is_for_ppo_only():
    with pytest.raises(ValueError, match="overlap_updates is for PPO"):
        load_config(None, overrides=["algo=sac", "train.overlap_updates=true"])


def test_a_checkpoint_holds_every_update_of_its_steps(tmp_path):
    """Checkpoints every two rollouts: the update of rollout 2 runs before the
    checkpoint, not beside rollout 3, so the checkpoint has both rollouts'
    updates and rollout 3 is collected with its weights; then the overlap
    goes on (rollout 4 with the same weights, update 3 running beside it)."""
    from agents.sb3.checkpoints import latest_checkpoint
    from agents.sb3.training import EpisodeLogger

    cfg = load_config("configs/ppo_games.yaml", "Billiards-NineBall2P-v1", SETS)
    env, vecnorm = build_env(cfg, 0)
    model = build_model(cfg, env, None)
    seen = ActingWeights()
    model.learn(ROLLOUTS * 32, callback=[EpisodeLogger(tmp_path, 2 * 32, vecnorm), seen])
    env.close()
    ck = latest_checkpoint(tmp_path)
    assert ck is not None and ck.steps == 2 * 32
    saved = OverlappedPPO.load(ck.model_path)
    assert saved._n_updates == 2 * 2  # two rollouts, n_epochs=2 each
    np.testing.assert_array_equal(seen.seen[2], _weights(saved.policy))
    np.testing.assert_array_equal(seen.seen[3], seen.seen[2])
    assert not np.array_equal(seen.seen[1], seen.seen[2])
