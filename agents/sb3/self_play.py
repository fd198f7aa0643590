"""PPO on the self-play game env: one policy plays both seats.

A two-player game id trained with no ``opponent`` (``TrainConfig.self_play``)
steps ``GameVectorEnv``: on every table the player to move acts, so every
shot of both seats is a training sample, all tables' shots go through one
forward pass, and no opponent bot runs (its decisions and previews were most
of an env step against ``ghost``: docs/agents_benchmark.md).

The reward of a step goes to the player who just shot, and the observation
is the next shooter's (its group, fouls and legal targets are the shooter's
own). So the next step's value is the *opponent's* whenever the turn passed,
and SB3's GAE, which reads it as the same player's, would add it with the
wrong sign. ``TurnRolloutBuffer`` uses the negamax form of GAE for a
turn-taking zero-sum game, with ``s_t = +1`` when the player who shot at
``t`` shoots again at ``t + 1`` and ``-1`` when the turn passed:

    delta_t = r_t + gamma * s_t * V(o_{t+1}) - V(o_t)
    A_t     = delta_t + gamma * lambda * s_t * A_{t+1}

(each value is the mover's, as in AlphaZero's player-to-move values; with
``s_t = 1`` throughout it is SB3's GAE). ``TurnRecorder``, a callback, writes
``s_t`` from each step's info (``shooter``, and ``to_move``, the next
shooter) into the buffer before SB3 adds the step. A game cut at
``max_shots`` is a draw and its end, so it is not bootstrapped: SB3 would
add the terminal observation's value, which is the other seat's.
"""
from __future__ import annotations

import numpy as np
from stable_baselines3.common.buffers import RolloutBuffer
from stable_baselines3.common.callbacks import BaseCallback

from .infos import VecInfos


def turn_signs(infos) -> np.ndarray:
    """``s_t`` [n] of one step's per-env infos (a ``VecInfos`` or a list of
    dicts): +1 where the shooter shoots again, else -1."""
    if isinstance(infos, VecInfos):  # the arrays as they are, no per-env conversion
        same = infos.column("to_move") == infos.column("shooter")
    else:
        same = np.fromiter((i["to_move"] == i["shooter"] for i in infos), bool, len(infos))
    return np.where(same, 1.0, -1.0).astype(np.float32)


class TurnRolloutBuffer(RolloutBuffer):
    """SB3's rollout buffer with the turn-passing GAE of the module docstring."""

    def reset(self) -> None:
        super().reset()
        self.turn_sign = np.ones((self.buffer_size, self.n_envs), dtype=np.float32)

    def record_turns(self, signs: np.ndarray) -> None:
        """``s_t`` of the step SB3 adds next (at ``self.pos``)."""
        self.turn_sign[self.pos] = signs

    def compute_returns_and_advantage(self, last_values, dones: np.ndarray) -> None:
        last_values = last_values.clone().cpu().numpy().flatten()
        gae = np.zeros(self.n_envs, dtype=np.float32)
        for step in reversed(range(self.buffer_size)):
            if step == self.buffer_size - 1:
                live, next_values = 1.0 - dones.astype(np.float32), last_values
            else:
                live, next_values = 1.0 - self.episode_starts[step + 1], self.values[step + 1]
            s = self.turn_sign[step]
            delta = self.rewards[step] + self.gamma * s * next_values * live - self.values[step]
            gae = delta + self.gamma * self.gae_lambda * s * live * gae
            self.advantages[step] = gae
        self.returns = self.advantages + self.values


class TurnRecorder(BaseCallback):
    """Writes each step's ``s_t`` into the rollout buffer being filled, and
    makes a game cut at ``max_shots`` an end (a draw) rather than a time limit."""

    def _on_step(self) -> bool:
        infos = self.locals["infos"]
        self.locals["rollout_buffer"].record_turns(turn_signs(infos))
        for i in np.flatnonzero(self.locals["dones"]):
            infos[i]["TimeLimit.truncated"] = False
        return True
