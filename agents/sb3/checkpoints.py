"""Checkpoints a stopped or killed training run resumes from.

A checkpoint is taken at the start of a rollout (after the previous update),
every ``train.checkpoint_every`` env steps, as three files in
``<run>/checkpoints/``, all named ``model_<steps>_steps*``:

- ``.zip``: the stable-baselines3 model (weights, optimiser, step counter).
  SB3 model files hold pickled Python objects (the learning-rate schedule,
  the spaces): loading one runs code from it, so load only your own runs;
- ``_normalizer.npz``: the VecNormalize statistics as plain arrays (running
  mean, variance and count of observations and returns, the per-table
  discounted returns);
- ``_state.json``: the step counter, the training wall time so far and the
  random state: the tables' random streams (keys and counters), numpy's and
  Python's global generators; torch's generator goes into the ``.npz``.

Resuming loads the newest complete checkpoint, restores all of it and
starts a new rollout; the tables in play are dealt afresh from the restored
streams (a one-shot task deals every table at every step anyway). SAC's
replay buffer is not saved: a resumed SAC run refills it.
"""
from __future__ import annotations

import json
import random
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .vec_env import native_vec_env
from .worker_vec_env import find_workers

CHECKPOINT_DIR = "checkpoints"
_NAME = re.compile(r"^model_(\d+)_steps\.zip$")


def _streams(env):
    """The table streams of the native env under ``env`` (a task's ``_core`` or a game's ``core``)."""
    u = native_vec_env(env).unwrapped
    core = getattr(u, "_core", None)
    return (core if core is not None else u.core).streams


def stream_state(env) -> tuple[np.ndarray, np.ndarray]:
    """Copies of the tables' stream keys and counters, in table order (across the workers, if any)."""
    w = find_workers(env)
    if w is not None:
        parts = w.apply(stream_state)
        return np.concatenate([k for k, _ in parts]), np.concatenate([c for _, c in parts])
    s = _streams(env)
    return s.keys.copy(), s.counters.copy()


def restore_streams(env, keys: np.ndarray, counters: np.ndarray) -> None:
    """Set the tables' streams; the next unseeded reset continues them."""
    w = find_workers(env)
    if w is not None:
        w._reset_seeds()
        w.apply_slices(restore_streams, keys, counters)
        return
    native = native_vec_env(env)
    native._reset_seeds()
    streams = _streams(native)
    streams.keys[:] = keys
    streams.counters[:] = counters
    native.unwrapped._seeded = True


@dataclass(frozen=True)
class Checkpoint:
    steps: int
    model_path: Path

    @property
    def normalizer_path(self) -> Path:
        return self.model_path.with_name(f"model_{self.steps}_steps_normalizer.npz")

    @property
    def state_path(self) -> Path:
        return self.model_path.with_name(f"model_{self.steps}_steps_state.json")

    def state(self) -> dict:
        return json.loads(self.state_path.read_text())


def save_checkpoint(run_dir, model, vecnorm, elapsed_s: float) -> Checkpoint:
    """Write the checkpoint of ``model`` at its current step count. The state
    file is written last, so a checkpoint cut short by a kill has none and is
    skipped by ``latest_checkpoint``."""
    import torch

    ck_dir = Path(run_dir) / CHECKPOINT_DIR
    ck_dir.mkdir(parents=True, exist_ok=True)
    ck = Checkpoint(int(model.num_timesteps), ck_dir / f"model_{int(model.num_timesteps)}_steps.zip")
    model.save(ck.model_path)
    arrays = {"torch_rng": torch.get_rng_state().numpy()}
    if vecnorm is not None:
        arrays.update(obs_mean=vecnorm.obs_rms.mean, obs_var=vecnorm.obs_rms.var,
                      obs_count=np.float64(vecnorm.obs_rms.count), ret_mean=vecnorm.ret_rms.mean,
                      ret_var=vecnorm.ret_rms.var, ret_count=np.float64(vecnorm.ret_rms.count),
                      returns=vecnorm.returns)
    keys, counters = stream_state(model.get_env())
    arrays.update(stream_keys=keys, stream_counters=counters)
    np.savez(ck.normalizer_path, **arrays)
    np_state = np.random.get_state()
    state = dict(steps=ck.steps, elapsed_s=float(elapsed_s),
                 numpy_rng=[np_state[0], np_state[1].tolist(), *np_state[2:]],
                 python_rng=[random.getstate()[0], list(random.getstate()[1]), random.getstate()[2]])
    ck.state_path.write_text(json.dumps(state))
    return ck


def latest_checkpoint(run_dir) -> Checkpoint | None:
    """The complete checkpoint with the most steps in ``run_dir``, or None."""
    found = []
    for p in (Path(run_dir) / CHECKPOINT_DIR).glob("model_*_steps.zip"):
        m = _NAME.match(p.name)
        if m:
            ck = Checkpoint(int(m.group(1)), p)
            if ck.normalizer_path.exists() and ck.state_path.exists():
                found.append(ck)
    return max(found, key=lambda c: c.steps) if found else None


def restore_normalizer(vecnorm, path) -> None:
    """Set ``vecnorm``'s statistics from a checkpoint's ``.npz``."""
    with np.load(path) as z:
        if "obs_mean" not in z.files:
            raise ValueError(f"{path}: no normaliser statistics (the run was saved without VecNormalize)")
        vecnorm.obs_rms.mean, vecnorm.obs_rms.var = z["obs_mean"].copy(), z["obs_var"].copy()
        vecnorm.obs_rms.count = float(z["obs_count"])
        vecnorm.ret_rms.mean, vecnorm.ret_rms.var = z["ret_mean"].copy(), z["ret_var"].copy()
        vecnorm.ret_rms.count = float(z["ret_count"])
        vecnorm.returns = z["returns"].copy()


def load_checkpoint(ck: Checkpoint, algo, env, vecnorm, device: str = "cpu", tensorboard_log=None):
    """The model of ``ck`` bound to ``env``, with the normaliser statistics
    and every random state of the checkpoint restored. ``algo``: ``"ppo"``,
    ``"sac"`` or the model class (``agents.sb3.training.model_class``)."""
    import torch
    from stable_baselines3 import PPO, SAC

    cls = {"ppo": PPO, "sac": SAC}[algo] if isinstance(algo, str) else algo
    model = cls.load(ck.model_path, env=env, device=device,
                                                  tensorboard_log=tensorboard_log)
    # loading seeds the env's next reset with the run's seed: restore_streams
    # drops that, the tables continue from the restored streams instead
    if vecnorm is not None:
        restore_normalizer(vecnorm, ck.normalizer_path)
    with np.load(ck.normalizer_path) as z:
        torch.set_rng_state(torch.from_numpy(z["torch_rng"].copy()))
        if len(z["stream_keys"]) != env.num_envs:
            raise ValueError(f"{ck.model_path}: saved with {len(z['stream_keys'])} tables, the env has "
                             f"{env.num_envs}; resume with the run's own config")
        restore_streams(env, z["stream_keys"], z["stream_counters"])
    st = ck.state()
    np.random.set_state((st["numpy_rng"][0], np.array(st["numpy_rng"][1], dtype=np.uint32), *st["numpy_rng"][2:]))
    random.setstate((st["python_rng"][0], tuple(st["python_rng"][1]), st["python_rng"][2]))
    return model


def last_logged_steps(run_dir) -> int:
    """Steps of the last rollout logged to ``progress.csv`` (0 when none)."""
    import csv

    path = Path(run_dir) / "progress.csv"
    if not path.exists():
        return 0
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return int(rows[-1]["timesteps"]) if rows else 0


class ObsNormalizer:
    """Observation normalisation from a checkpoint's statistics, as
    VecNormalize applies it (``normalize_obs``), without its pickle."""

    EPS = 1e-8  # VecNormalize's default epsilon under the square root

    def __init__(self, mean: np.ndarray, var: np.ndarray, clip_obs: float):
        self.mean, self.var, self.clip_obs = mean, var, float(clip_obs)

    @classmethod
    def from_npz(cls, path, clip_obs: float) -> "ObsNormalizer | None":
        with np.load(path) as z:
            return cls(z["obs_mean"].copy(), z["obs_var"].copy(), clip_obs) if "obs_mean" in z.files else None

    def normalize_obs(self, obs: np.ndarray) -> np.ndarray:
        return np.clip((obs - self.mean) / np.sqrt(self.var + self.EPS), -self.clip_obs, self.clip_obs)
