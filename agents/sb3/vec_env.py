"""A stable-baselines3 ``VecEnv`` over a native Gymnasium ``VectorEnv``.

The native billiards vector env steps every table in one batched simulator
call; this adapter keeps that (no DummyVecEnv of single envs on the hot path)
and translates Gymnasium 1.x vector conventions into SB3's:

- ``step`` returns ``(obs, rewards, dones, infos)`` with ``dones =
  terminated | truncated`` and ``infos`` the per-env dicts, as a
  ``VecInfos`` (agents/sb3/infos.py: a list that converts a row's values
  when they are read);
- for a done env the returned observation is already the *reset*
  observation, and the last observation of the finished episode is in
  ``infos[i]["terminal_observation"]``; ``infos[i]["TimeLimit.truncated"]``
  is True when the episode was cut by a time limit rather than terminated;
- the native env's autoreset mode (``metadata["autoreset_mode"]``) is
  honoured: ``SAME_STEP`` (reset obs returned, final obs in
  ``infos["final_obs"]``), ``DISABLED`` (the adapter resets finished envs
  itself with ``reset(options={"reset_mask": done})``) and ``NEXT_STEP``
  (when every env finished, the adapter takes the env's own autoreset step
  at once, which ignores the actions and simulates nothing; when only some
  finished, a masked reset, which the env must support);
- ``seed(seed)`` seeds the next ``reset()`` (env i gets ``seed + i``).

``get_attr``/``set_attr``/``env_method`` act on the one native env (the
attributes of a batch are shared); ``get_attr`` returns one entry per env.
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium.vector import AutoresetMode
from stable_baselines3.common.vec_env.base_vec_env import VecEnv, VecEnvIndices

from .infos import VecInfos


def _autoreset_mode(env) -> AutoresetMode:
    mode = (getattr(env, "metadata", None) or {}).get("autoreset_mode", AutoresetMode.NEXT_STEP)
    if isinstance(mode, str):
        mode = AutoresetMode(mode)
    return mode


def env_indices(n: int, indices: VecEnvIndices) -> list[int]:
    """SB3's ``indices`` argument (None: all ``n`` envs, an int, or a sequence) as a list."""
    if indices is None:
        return list(range(n))
    if isinstance(indices, int):
        return [indices]
    return list(indices)


def native_vec_env(env) -> "NativeVecEnv":
    """The ``NativeVecEnv`` under SB3 wrappers (VecNormalize, features)."""
    from billiards_env.contract.unwrap import env_chain

    for e in env_chain(env):
        if isinstance(e, NativeVecEnv):
            return e
    raise TypeError("no NativeVecEnv under this env")


class NativeVecEnv(VecEnv):
    """SB3 ``VecEnv`` over a native ``gymnasium.vector.VectorEnv``."""

    def __init__(self, venv: gym.vector.VectorEnv):
        self.venv = venv
        self.autoreset_mode = _autoreset_mode(venv)
        self._actions: np.ndarray | None = None
        self._obs: np.ndarray | None = None
        super().__init__(venv.num_envs, venv.single_observation_space, venv.single_action_space)

    # -- attribute access ------------------------------------------------
    @property
    def unwrapped(self):
        return self.venv.unwrapped if hasattr(self.venv, "unwrapped") else self.venv

    def _indices(self, indices: VecEnvIndices) -> list[int]:
        return env_indices(self.num_envs, indices)

    def get_attr(self, attr_name: str, indices: VecEnvIndices = None) -> list[Any]:
        target = self.venv
        if not hasattr(target, attr_name) and hasattr(self.unwrapped, attr_name):
            target = self.unwrapped
        value = getattr(target, attr_name)
        return [value for _ in self._indices(indices)]

    def set_attr(self, attr_name: str, value: Any, indices: VecEnvIndices = None) -> None:
        setattr(self.unwrapped, attr_name, value)

    def env_method(self, method_name: str, *method_args, indices: VecEnvIndices = None, **method_kwargs) -> list[Any]:
        target = self.venv if hasattr(self.venv, method_name) else self.unwrapped
        result = getattr(target, method_name)(*method_args, **method_kwargs)
        return [result for _ in self._indices(indices)]

    def env_is_wrapped(self, wrapper_class, indices: VecEnvIndices = None) -> list[bool]:
        return [False for _ in self._indices(indices)]

    def has_attr(self, attr_name: str) -> bool:
        return hasattr(self.venv, attr_name) or hasattr(self.unwrapped, attr_name)

    # -- core API --------------------------------------------------------
    def reset(self) -> np.ndarray:
        seed = self._seeds[0]
        if seed is not None and any(s is not None and s != seed + i for i, s in enumerate(self._seeds)):
            seed = [s for s in self._seeds]  # non-consecutive seeds: pass the list
        options = self._options[0] if self._options and self._options[0] else None
        obs, _ = self.venv.reset(seed=seed, options=options)
        self._reset_seeds()
        self._reset_options()
        self._obs = obs
        return obs

    def step_async(self, actions: np.ndarray) -> None:
        self._actions = np.asarray(actions)

    def _masked_reset(self, done: np.ndarray):
        obs, info = self.venv.reset(options={"reset_mask": done})
        return obs, info

    def step_wait(self):
        obs, rewards, terminated, truncated, infos = self.venv.step(self._actions)
        terminated = np.asarray(terminated, dtype=bool)
        truncated = np.asarray(truncated, dtype=bool)
        dones = terminated | truncated
        n = self.num_envs
        info_list = VecInfos(infos, n)
        if dones.any():
            idx = np.flatnonzero(dones)
            if self.autoreset_mode == AutoresetMode.SAME_STEP:
                final_obs = infos["final_obs"]
                final_info = VecInfos(infos["final_info"], n) if "final_info" in infos else None
                for i in idx:
                    if final_info is not None:
                        # the per-step info of a finished env is its final info
                        info_list[i] = final_info[i]
                    info_list[i]["terminal_observation"] = final_obs[i]
            else:
                final_obs = np.array(obs, copy=True)
                for i in idx:
                    info_list[i]["terminal_observation"] = final_obs[i]
                obs = self._reset_done(obs, dones)
            for i in idx:
                info_list[i]["TimeLimit.truncated"] = bool(truncated[i] and not terminated[i])
        self._obs = obs
        return obs, np.asarray(rewards, dtype=np.float32), dones, info_list

    def _reset_done(self, obs: np.ndarray, dones: np.ndarray) -> np.ndarray:
        obs = np.array(obs, copy=True)
        if self.autoreset_mode == AutoresetMode.NEXT_STEP and dones.all():
            # every env finished (one-shot tasks): the env's own autoreset
            # step resets them all, ignores the actions and simulates nothing
            new_obs, *_ = self.venv.step(self._actions)
            return np.array(new_obs, copy=True)
        # DISABLED, or NEXT_STEP with some envs still playing: reset the
        # finished ones now (the env then has no pending autoreset for them)
        new_obs, _ = self._masked_reset(dones)
        obs[dones] = new_obs[dones]
        return obs

    def close(self) -> None:
        self.venv.close()

    def get_images(self) -> Sequence[np.ndarray | None]:
        return [None for _ in range(self.num_envs)]

    def render(self, mode: str | None = None):
        return self.venv.render()


def make_sb3_vec_env(env_id: str, n_envs: int, seed: int | None = None, autoreset_mode: str = "same_step",
                     **kwargs) -> NativeVecEnv:
    """``gymnasium.make_vec(env_id, num_envs=n_envs, vectorization_mode="vector_entry_point")``
    wrapped for SB3 (``kwargs`` go to the env, e.g. ``noise="tournament"``).
    The native env resets finished tables within the step (``same_step``),
    so no call is spent on resets."""
    import billiards_env  # noqa: F401  (registers the ids)

    venv = gym.make_vec(env_id, num_envs=n_envs, vectorization_mode="vector_entry_point",
                        autoreset_mode=autoreset_mode, **kwargs)
    env = NativeVecEnv(venv)
    if seed is not None:
        env.seed(seed)
    return env
