"""A trained stable-baselines3 model as a policy of the evaluation harness.

``SB3Policy`` has the harness's interface, ``act(obs) -> actions [N, 4]``
(batched over the tables of a vector env): deterministic, observations
normalised with the run's VecNormalize statistics, with the agent-side
features and action transform of its config (``agents.interface``).
``SB3Policy.load`` reads a run directory or a ``.zip`` (a checkpoint too).

The baseline bots (random, ghost-ball, search, lookahead) live in the
library, ``billiards_env.bots``; ``agents.evaluation.policies.make_policy``
builds them and saved models by name.
"""
from __future__ import annotations

import numpy as np

from ..interface.features import agent_features, transform_actions
from ..interface.game_view import native_env


class SB3Policy:
    """A trained SB3 model; observations normalised with its VecNormalize stats."""

    def __init__(self, model, vecnormalize=None, name: str = "model", features: bool = False,
                 aim_scale: float = 1.0, env=None, action_mode: str = "direct", env_kwargs: dict | None = None):
        self.model, self.vecnormalize, self.name = model, vecnormalize, name
        self.env_kwargs = dict(env_kwargs or {})  # the env options it was trained with (its run's config)
        self.features, self.aim_scale, self.action_mode = features, aim_scale, action_mode
        needs_env = features or action_mode != "direct"
        self.env = native_env(env) if (env is not None and needs_env) else env

    def bind(self, env) -> "SB3Policy":
        """The same model playing on another (native) vector env."""
        return SB3Policy(self.model, self.vecnormalize, self.name, self.features, self.aim_scale, env,
                         self.action_mode, self.env_kwargs)

    def act(self, obs: np.ndarray) -> np.ndarray:
        extra = agent_features(self.env, self.features, self.aim_scale, self.action_mode) if self.env else None
        if extra is not None:
            obs = np.concatenate([obs, extra], axis=1)
        want = self.model.observation_space.shape[0]
        if obs.shape[1] != want:
            raise ValueError(f"{self.name}: the model takes observations of {want} numbers, this env and the agent's "
                             f"features give {obs.shape[1]} (trained with other env options, features or menu?)")
        if self.vecnormalize is not None:
            obs = self.vecnormalize.normalize_obs(obs)
        action, _ = self.model.predict(obs, deterministic=True)
        return transform_actions(self.env, action, self.action_mode, self.aim_scale)

    @classmethod
    def load(cls, path, env=None, name: str | None = None) -> "SB3Policy":
        """Load ``<run>/model.zip`` (or a path to a .zip, e.g. a checkpoint)
        and the VecNormalize statistics saved beside it (``vecnormalize.pkl``,
        or a checkpoint's ``_normalizer.npz``), if any."""
        import pickle
        from pathlib import Path

        from stable_baselines3 import PPO, SAC

        path = Path(path)
        zip_path = path / "model.zip" if path.is_dir() else path
        run_dir = zip_path.parent
        algo, meta = None, {}
        cfg = run_dir / "config.yaml"
        if not cfg.exists() and run_dir.name == "checkpoints":
            cfg = run_dir.parent / "config.yaml"
        if cfg.exists():
            import yaml
            meta = yaml.safe_load(cfg.read_text()) or {}
            algo = meta.get("algo")
        cls_ = {"ppo": PPO, "sac": SAC}.get(algo)
        if cls_ is None:  # guess from the zip
            try:
                model = PPO.load(zip_path, device="cpu")
            except Exception:
                model = SAC.load(zip_path, device="cpu")
        else:
            model = cls_.load(zip_path, device="cpu")
        vn = None
        stem = zip_path.stem
        npz = run_dir / f"{stem}_normalizer.npz"
        if npz.exists():
            from .checkpoints import ObsNormalizer
            clip = float((meta.get("normalize") or {}).get("clip_obs", 10.0))
            vn = ObsNormalizer.from_npz(npz, clip) if (meta.get("normalize") or {}).get("obs", True) else None
        pickles = () if npz.exists() else (run_dir / f"{stem}_vecnormalize.pkl", run_dir / "vecnormalize.pkl")
        for cand in pickles:
            if cand.exists():
                with open(cand, "rb") as f:
                    vn = pickle.load(f)
                vn.training = False
                vn.norm_reward = False
                break
        return cls(model, vn, name=name or (algo or "model"), features=bool(meta.get("features", False)),
                   aim_scale=float(meta.get("aim_scale", 1.0)), env=env,
                   action_mode=meta.get("action_mode", "direct"), env_kwargs=meta.get("env_kwargs"))


class SB3Network:
    """A stable-baselines3 model's deterministic action on observations it
    normalises with its run's statistics: the network interface of
    ``ViewPolicy`` (``obs_dim``, ``act``)."""

    def __init__(self, model, vecnormalize=None):
        self.model, self.vecnormalize = model, vecnormalize
        self.obs_dim = int(model.observation_space.shape[0])

    def act(self, obs: np.ndarray) -> np.ndarray:
        if self.vecnormalize is not None:
            obs = self.vecnormalize.normalize_obs(obs)
        return self.model.predict(obs, deterministic=True)[0]
