"""Typed training configuration: RL-Zoo style YAML keyed by env id, loaded
into frozen dataclasses, with dotted command-line overrides.

``configs/ppo.yaml`` / ``configs/sac.yaml`` map an env id to a block::

    Billiards-PotOne-v1:
      algo: ppo
      n_envs: 128
      ppo: {learning_rate: 3.0e-4, n_steps: 4, ...}   # SB3 constructor kwargs
      rllib: {num_env_runners: 2, lr: 3.0e-4, ...}    # RLlib PPO (agents.rllib.backend)
      policy: {net_arch: [256, 256], log_std_init: -0.7, ...}
      normalize: {obs: true, reward: false, ...}
      train: {total_timesteps: ..., eval_episodes: ..., ...}

Overrides: ``--set ppo.learning_rate=1e-4 --set n_envs=64`` (values parsed
as YAML, so ``1e-4``, ``true``, ``[64, 64]`` work). Every key must exist in
the dataclass (or be an SB3 constructor argument for the ``ppo``/``sac``
block), so a typo is an error, not a silently ignored setting.
"""
from __future__ import annotations

import dataclasses
import inspect
from pathlib import Path
from typing import Any

import yaml

from billiards_env.envs.config import check_keys

CONFIG_VERSION = 1
ROOT = Path(__file__).resolve().parents[1]
CONFIG_DIR = ROOT / "configs"


@dataclasses.dataclass(frozen=True)
class PolicyConfig:
    net_arch: tuple = (256, 256)
    activation: str = "tanh"          # tanh | relu
    log_std_init: float = -0.7        # PPO initial action noise (std = exp(log_std_init))
    ortho_init: bool = True
    squash_output: bool = False

    def policy_kwargs(self, algo: str) -> dict:
        import torch.nn as nn

        act = {"tanh": nn.Tanh, "relu": nn.ReLU}[self.activation]
        kw: dict[str, Any] = dict(net_arch=list(self.net_arch), activation_fn=act)
        if algo == "ppo":
            kw.update(log_std_init=self.log_std_init, ortho_init=self.ortho_init)
        elif algo == "sac":
            kw.update(log_std_init=self.log_std_init)
        return kw


@dataclasses.dataclass(frozen=True)
class NormalizeConfig:
    obs: bool = True
    reward: bool = False
    clip_obs: float = 10.0
    clip_reward: float = 10.0
    gamma: float = 0.99


@dataclasses.dataclass(frozen=True)
class TrainSettings:
    total_timesteps: int = 1_000_000
    seed: int = 0
    checkpoint_every: int = 250_000   # env steps between checkpoints (0: none)
    eval_episodes: int = 1000         # final evaluation episodes (0: skip)
    eval_seed: int = 12345
    eval_baselines: tuple = ("random", "ghost", "search")
    search_k: int = 256
    eval_noise: tuple = ("none", "tournament")
    # held-seed evaluations during training (``agents.sb3.training.HeldOutEvaluation``):
    # every ``eval_every`` env steps (0: none), ``eval_every_episodes`` episodes
    # of seed ``eval_seed`` at noise ``eval_every_noise``; their time is not training time;
    # ``eval_target``: the baseline bot measured once at the start, whose success the curve is
    # compared with ("ghost"; a game's own bot where ghost cannot play it; "" for none)
    eval_every: int = 0
    eval_every_episodes: int = 1000
    eval_every_noise: str = "none"
    eval_target: str = "ghost"
    # a self-play run (a two-player game with no env_kwargs.opponent) is evaluated against this bot
    eval_opponent: str = "ghost"
    torch_threads: int = 1           # 1: PPO minibatches are small; a 2nd thread fights numba on 2 cores
    numba_threads: int = 2
    # processes holding the training tables (agents.sb3.worker_vec_env): 1 keeps them in the
    # trainer's process; k > 1 splits n_envs over k workers that step at once (n_envs % k == 0)
    env_workers: int = 1
    # PPO only: update rollout k in a thread while rollout k + 1 is collected with the policy
    # before that update (agents.sb3.overlap.OverlappedPPO); False: SB3's PPO, update then collect
    overlap_updates: bool = False
    device: str = "cpu"
    progress_bar: bool = True
    tensorboard: bool = True


# How the policy's action becomes the env's (billiards_env.bots.learned.features.transform_actions).
from billiards_env.bots.learned.features import ACTION_MODES, check_action_mode  # noqa: E402,F401 (re-exported)


@dataclasses.dataclass(frozen=True)
class TrainConfig:
    env_id: str
    algo: str = "ppo"
    version: int = CONFIG_VERSION
    n_envs: int = 128
    env_kwargs: dict = dataclasses.field(default_factory=dict)
    features: bool = True     # agent-side ghost-ball features (agents.interface.features)
    aim_scale: float = 1.0    # policy a0 -> env a0 = aim_scale * a0
    action_mode: str = "direct"  # ACTION_MODES: direct | residual (ghost-ball corrections) | choice (billiards_env.bots.learned.menu)
    ppo: dict = dataclasses.field(default_factory=dict)   # SB3 PPO kwargs
    sac: dict = dataclasses.field(default_factory=dict)   # SB3 SAC kwargs
    rllib: dict = dataclasses.field(default_factory=dict)  # RLlib PPO settings (agents.rllib.backend)
    policy: PolicyConfig = dataclasses.field(default_factory=PolicyConfig)
    normalize: NormalizeConfig = dataclasses.field(default_factory=NormalizeConfig)
    train: TrainSettings = dataclasses.field(default_factory=TrainSettings)

    def __post_init__(self):
        if self.algo not in ("ppo", "sac"):
            raise ValueError(f"algo must be 'ppo' or 'sac', got {self.algo!r}")
        if self.version != CONFIG_VERSION:
            raise ValueError(f"config version {self.version} is not supported (expected {CONFIG_VERSION})")
        if not isinstance(self.n_envs, int) or self.n_envs < 1:
            raise ValueError(f"n_envs must be a positive integer, got {self.n_envs!r}")
        check_action_mode(self.action_mode)
        w = self.train.env_workers
        if not isinstance(w, int) or w < 1 or self.n_envs % w:
            raise ValueError(f"train.env_workers must be a positive integer dividing n_envs={self.n_envs}, got {w!r}")
        if self.train.overlap_updates and self.algo != "ppo":
            raise ValueError(f"train.overlap_updates is for PPO, not {self.algo!r}")
        if self.self_play and self.algo != "ppo":
            raise ValueError(f"{self.env_id} with no env_kwargs.opponent trains by self-play, which is PPO's "
                             f"(agents.sb3.self_play), not {self.algo!r}; name an opponent to train {self.algo!r}")
        from billiards_env.physics.noise import NOISE_LEVELS
        if self.train.eval_every_noise not in NOISE_LEVELS:
            raise ValueError(f"train.eval_every_noise must be one of {tuple(NOISE_LEVELS)}, "
                             f"got {self.train.eval_every_noise!r}")
        for name in ("ppo", "sac"):
            _check_algo_kwargs(name, getattr(self, name))

    @property
    def self_play(self) -> bool:
        """A two-player game with no ``env_kwargs.opponent``: the policy plays both seats
        (``agents.sb3.self_play``)."""
        from billiards_env.envs.registration import GAME_IDS
        return self.env_id in GAME_IDS and "opponent" not in self.env_kwargs

    @property
    def eval_env_kwargs(self) -> dict:
        """The env options of the run's evaluations: a self-play run's add ``train.eval_opponent``."""
        return {**self.env_kwargs, "opponent": self.train.eval_opponent} if self.self_play else dict(self.env_kwargs)

    @property
    def algo_kwargs(self) -> dict:
        return dict(getattr(self, self.algo))

    def to_dict(self) -> dict:
        def conv(v):
            if dataclasses.is_dataclass(v):
                return {f.name: conv(getattr(v, f.name)) for f in dataclasses.fields(v)}
            if isinstance(v, tuple):
                return [conv(x) for x in v]
            if isinstance(v, dict):
                return {k: conv(x) for k, x in v.items()}
            return v
        return conv(self)

    @classmethod
    def from_dict(cls, d: dict) -> "TrainConfig":
        d = dict(d)
        check_keys(cls, d, "training config")
        nested = {"policy": PolicyConfig, "normalize": NormalizeConfig, "train": TrainSettings}
        for k, sub in nested.items():
            if k in d and not dataclasses.is_dataclass(d[k]):
                v = dict(d[k] or {})
                check_keys(sub, v, f"{k} config")
                for f in dataclasses.fields(sub):
                    if f.name in v and isinstance(v[f.name], list):
                        v[f.name] = tuple(v[f.name])
                d[k] = sub(**v)
        for k in ("ppo", "sac", "rllib", "env_kwargs"):
            if k in d:
                d[k] = dict(d[k] or {})
        return cls(**d)


def _check_algo_kwargs(algo: str, kw: dict) -> None:
    if not kw:
        return
    from stable_baselines3 import PPO, SAC

    cls = {"ppo": PPO, "sac": SAC}[algo]
    allowed = set(inspect.signature(cls.__init__).parameters) - {"self", "policy", "env", "policy_kwargs",
                                                                   "tensorboard_log", "seed", "device", "verbose"}
    unknown = set(kw) - allowed
    if unknown:
        raise ValueError(f"unknown {algo.upper()} argument(s) {sorted(unknown)}; known: {sorted(allowed)}")


def parse_override(item: str) -> tuple[list[str], Any]:
    """``"ppo.learning_rate=1e-4"`` -> (["ppo", "learning_rate"], 1e-4)."""
    if "=" not in item:
        raise ValueError(f"override {item!r} must look like key.sub=value")
    key, raw = item.split("=", 1)
    value = yaml.safe_load(raw)
    if isinstance(value, str):  # YAML reads 1e-4 as a string; numbers as floats where possible
        try:
            value = float(value)
        except ValueError:
            pass
    return key.strip().split("."), value


def apply_overrides(d: dict, overrides: list[str]) -> dict:
    d = yaml.safe_load(yaml.safe_dump(d))  # deep copy of plain data
    for item in overrides or []:
        path, value = parse_override(item)
        node = d
        for k in path[:-1]:
            if k not in node or node[k] is None:
                node[k] = {}
            if not isinstance(node[k], dict):
                raise ValueError(f"override {item!r}: {k!r} is not a mapping")
            node = node[k]
        node[path[-1]] = value
    return d


def load_config(path=None, env_id: str | None = None, overrides: list[str] | None = None,
                algo: str | None = None) -> TrainConfig:
    """The block of ``env_id`` (default: the file's ``default_env``) from the
    YAML file ``path`` (default ``configs/<algo>.yaml``), with overrides."""
    if path is None:
        path = CONFIG_DIR / f"{algo or 'ppo'}.yaml"
    with open(path) as f:
        doc = yaml.safe_load(f) or {}
    env_id = env_id or doc.get("default_env")
    if env_id is None:
        raise ValueError(f"{path}: no env id given and no default_env in the file")
    if env_id not in doc:
        raise ValueError(f"{path}: no block for env id {env_id!r}; available: "
                         f"{sorted(k for k in doc if k != 'default_env')}")
    block = dict(doc[env_id])
    block["env_id"] = env_id
    block = apply_overrides(block, overrides or [])
    # RL-Zoo style: total_timesteps may sit in the algorithm block
    # (``--set ppo.total_timesteps=512``); it belongs to the run settings.
    for algo_key in ("ppo", "sac", "rllib"):
        sub = block.get(algo_key)
        if isinstance(sub, dict) and "total_timesteps" in sub:
            block.setdefault("train", {})
            block["train"] = dict(block["train"] or {}, total_timesteps=int(sub.pop("total_timesteps")))
    try:
        return TrainConfig.from_dict(block)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{path} [{env_id}]: {exc}") from exc


def save_config(cfg: TrainConfig, path) -> None:
    with open(path, "w") as f:
        yaml.safe_dump(cfg.to_dict(), f, sort_keys=False)


def load_run_config(run_dir) -> TrainConfig:
    """The resolved config a run saved beside its model (``<run>/config.yaml``)."""
    path = Path(run_dir) / "config.yaml"
    if not path.exists():
        raise FileNotFoundError(f"{run_dir}: no config.yaml (is it a run directory of scripts/train.py?)")
    with open(path) as f:
        return TrainConfig.from_dict(yaml.safe_load(f))
