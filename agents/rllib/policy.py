"""A policy trained by the RLlib backend (``agents.rllib.backend``), in the
evaluation harness's interface, and the run directory's checkpoints.

``RLlibPolicy.load(run_dir)`` reads the last checkpoint's RLModule and the
EnvRunners' observation filter; ``act(obs)`` is deterministic (the
Gaussian's mean), with the agent-side features and action transform of the
run's config. Needs Ray RLlib installed (the ``ray`` extra), not a running
Ray instance.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..config import TrainConfig

CHECKPOINT_PREFIX = "steps_"  # checkpoints/steps_<env steps>/


def checkpoints(run_dir) -> list[Path]:
    """The run's checkpoints, oldest first (named by env steps)."""
    ck = Path(run_dir) / "checkpoints"
    if not ck.is_dir():
        return []
    found = [p for p in ck.iterdir() if p.is_dir() and p.name.startswith(CHECKPOINT_PREFIX)]
    return sorted(found, key=lambda p: int(p.name[len(CHECKPOINT_PREFIX):]))


def is_rllib_run(path) -> bool:
    """Whether ``path`` is a run directory of this backend or one of its checkpoints."""
    path = Path(path)
    return (path / "rllib_checkpoint.json").exists() or any(
        (c / "rllib_checkpoint.json").exists() for c in checkpoints(path))


class RLlibPolicy:
    """A trained RLlib PPO policy in the evaluation harness's interface
    (``act(obs) -> actions``, deterministic: the Gaussian's mean): the
    RLModule and the observation filter's statistics read from a checkpoint,
    the agent-side features and action transform from the run's config."""

    def __init__(self, module, obs_filter, cfg: TrainConfig, name: str = "rllib_ppo", env=None):
        self.module, self.obs_filter, self.cfg, self.name, self.env = module, obs_filter, cfg, name, env

    def bind(self, env) -> "RLlibPolicy":
        from ..interface.game_view import native_env

        return RLlibPolicy(self.module, self.obs_filter, self.cfg, self.name, native_env(env))

    @property
    def env_kwargs(self) -> dict:
        """The env options it was trained with (its run's config)."""
        return dict(self.cfg.env_kwargs)

    def act(self, obs: np.ndarray) -> np.ndarray:
        import torch

        from ..interface.features import shot_features, transform_actions

        cfg = self.cfg
        if cfg.features:
            obs = np.concatenate([obs, shot_features(self.env, cfg.aim_scale)], axis=1)
        obs = np.asarray(obs, dtype=np.float32)
        if self.obs_filter is not None:  # the EnvRunners' own filter code, its statistics frozen
            obs = self.obs_filter(obs, update=False)
        with torch.no_grad():
            out = self.module.forward_inference({"obs": torch.as_tensor(obs, dtype=torch.float32)})
        mean = out["action_dist_inputs"].numpy()[:, :out["action_dist_inputs"].shape[1] // 2]
        return transform_actions(self.env, np.clip(mean, -1.0, 1.0), cfg.action_mode, cfg.aim_scale)

    @classmethod
    def load(cls, path, name: str | None = None) -> "RLlibPolicy":
        """From a run directory (its last checkpoint) or one checkpoint directory."""
        from ray.rllib.core.rl_module.rl_module import RLModule

        path = Path(path)
        run_dir, ckpt = (path, checkpoints(path)[-1]) if (path / "checkpoints").is_dir() else (path.parents[1], path)
        cfg = load_run_config(run_dir)
        module = RLModule.from_checkpoint(ckpt / "learner_group" / "learner" / "rl_module" / "default_policy")
        obs_filter = _observation_filter(ckpt) if cfg.normalize.obs else None
        return cls(module, obs_filter, cfg, name or "rllib_ppo")


def load_run_config(run_dir: Path) -> TrainConfig:
    import yaml

    return TrainConfig.from_dict(yaml.safe_load((run_dir / "config.yaml").read_text()))


def _observation_filter(ckpt: Path):
    """The EnvRunners' observation filter (RLlib's ``MeanStdFilter``) with
    the running statistics saved in the checkpoint ``ckpt``."""
    import pickle

    from ray.rllib.utils.filter import MeanStdFilter, RunningStat

    state_file = ckpt / "env_runner" / "env_to_module_connector" / "MeanStdFilter" / "state.pkl"
    if not state_file.exists():
        raise FileNotFoundError(f"{ckpt}: no observation filter state ({state_file})")
    with open(state_file, "rb") as f:
        state = pickle.load(f)[None]  # single-agent: the one filter, keyed by agent id None
    filt = MeanStdFilter(tuple(state["shape"]), demean=state["de_mean_to_zero"], destd=state["de_std_to_one"],
                         clip=state["clip_by_value"])
    filt.running_stats = RunningStat.from_state(state["running_stats"][0])
    return filt
