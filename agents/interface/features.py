"""The agent-side observation features and action modes as training wrappers.

The features and the action transforms themselves (``shot_features``,
``agent_features``, ``transform_actions``: the ghost-ball features, the shot
menu, residual and scaled actions) live in the library,
``billiards_env.bots.learned.features`` (numpy only, what the shipped ladder
bots play with), and are re-exported here; this module adds the wrappers
that apply them to a stable-baselines3 ``VecEnv`` (``ShotFeatures``) or a
Gymnasium ``VectorEnv`` (``VectorShotFeatures``, RLlib's EnvRunners).
"""
from __future__ import annotations

import gymnasium as gym
import numpy as np
from gymnasium import spaces
from stable_baselines3.common.vec_env.base_vec_env import VecEnvWrapper

from billiards_env.bots.learned import menu as choice
from billiards_env.bots.learned.features import (  # noqa: F401 (re-exported)
    N_FEAT_PER_POCKET, agent_features, check_action_mode, n_agent_features, n_features, residual_actions,
    scale_actions, shot_features, transform_actions)

from . import game_view


def policy_action_space(native, mode: str, env_space):
    """The policy's action space: the menu's for ``choice``; otherwise the
    env's, or on a game (``GameView``) its shot components a0..a3."""
    if mode == "choice":
        return choice.action_space(native)
    return game_view.policy_space() if isinstance(native, game_view.GameView) else env_space


class ShotFeatures(VecEnvWrapper):
    """Appends ``shot_features`` to observations and scales a0 by ``aim_scale``.
    Terminal observations get zero features (the table has already been reset
    when they are reported; one-shot episodes never bootstrap from them)."""

    def __init__(self, venv, native, features: bool = True, aim_scale: float = 1.0, action_mode: str = "direct"):
        check_action_mode(action_mode)
        native = game_view.agent_native(native)
        self.native, self.features, self.aim_scale = native, features, float(aim_scale)
        self.action_mode = action_mode
        base = venv.observation_space
        self.k = k = n_agent_features(native, features, action_mode)
        obs_space = spaces.Box(-np.inf, np.inf, shape=(base.shape[0] + k,), dtype=np.float32) if k else base
        super().__init__(venv, observation_space=obs_space,
                         action_space=policy_action_space(native, action_mode, venv.action_space))

    def _aug(self, obs):
        f = agent_features(self.native, self.features, self.aim_scale, self.action_mode)
        return obs if f is None else np.concatenate([obs, f], axis=1)

    def reset(self):
        return self._aug(self.venv.reset())

    def step_async(self, actions):
        self.venv.step_async(transform_actions(self.native, actions, self.action_mode, self.aim_scale))

    def step_wait(self):
        obs, rew, dones, infos = self.venv.step_wait()
        if self.k:
            k = self.k
            for i in np.flatnonzero(dones):
                t = infos[i].get("terminal_observation")
                if t is not None:
                    infos[i]["terminal_observation"] = np.concatenate([t, np.zeros(k, dtype=np.float32)])
        return self._aug(obs), rew, dones, infos


class VectorShotFeatures(gym.vector.VectorWrapper):
    """``ShotFeatures`` for a Gymnasium ``VectorEnv`` (what Ray RLlib's
    EnvRunners step): the same features appended to observations and the same
    action transform, on the native vector env under ``env``. Final
    observations reported in ``infos["final_obs"]`` (same-step autoreset) get
    zero features, as the SB3 wrapper's terminal observations do."""

    def __init__(self, env: gym.vector.VectorEnv, features: bool = True, aim_scale: float = 1.0,
                 action_mode: str = "direct"):
        check_action_mode(action_mode)
        super().__init__(env)
        self.native = game_view.agent_native(env.unwrapped)
        self.features, self.aim_scale, self.action_mode = features, float(aim_scale), action_mode
        self.k = k = n_agent_features(self.native, features, action_mode)
        if k:
            base = env.single_observation_space
            self.single_observation_space = spaces.Box(-np.inf, np.inf, shape=(base.shape[0] + k,), dtype=np.float32)
            self.observation_space = gym.vector.utils.batch_space(self.single_observation_space, env.num_envs)
        self.single_action_space = policy_action_space(self.native, action_mode, env.single_action_space)
        self.action_space = gym.vector.utils.batch_space(self.single_action_space, env.num_envs)

    def _aug(self, obs):
        f = agent_features(self.native, self.features, self.aim_scale, self.action_mode)
        return obs if f is None else np.concatenate([obs, f], axis=1)

    def reset(self, *, seed=None, options=None):
        obs, info = self.env.reset(seed=seed, options=options)
        return self._aug(obs), info

    def step(self, actions):
        obs, rew, term, trunc, info = self.env.step(
            transform_actions(self.native, actions, self.action_mode, self.aim_scale))
        if self.k and "final_obs" in info:
            final = np.asarray(info["final_obs"], dtype=np.float32)
            info["final_obs"] = np.concatenate([final, np.zeros((len(final), self.k), np.float32)], axis=1)
        return self._aug(obs), rew, term, trunc, info
