"""A learned shot policy as a bot of the two-player games.

``ViewPolicy`` plays a network trained by the agent wrappers
(``configs/ppo_games.yaml``: always player 0, shots chosen through the
one-player view of the game, ``bots.learned.game_view.OnePlayerView``) on
the bot view it is handed: the view's ``observation()`` with the
player-to-move entry set to 0 (the group and foul entries are the
shooter's already), the agent-side features of its config appended
(``bots.learned.features``), the network's deterministic action, and that
action completed to the game's 8 components. The network is anything with
``obs_dim`` and ``act(obs) -> actions``: the numpy MLP of the shipped ladder
(``bots.learned.mlp.MLPPolicy``) or a saved stable-baselines3 model
(``agents.evaluation.entrants.GameModelPolicy``).
"""
from __future__ import annotations

import numpy as np

from ..ghost import GhostBot
from .features import agent_features, check_action_mode, transform_actions
from .game_view import OnePlayerView


class ViewPolicy:
    """``net`` playing every table of a bot view; ``placer_seed`` seeds the
    ghost bot behind the view's placements and breaks (kept across views,
    so its random stream runs on)."""

    def __init__(self, net, name: str, features: bool = True, aim_scale: float = 1.0, action_mode: str = "choice",
                 placer_seed: int = 0):
        check_action_mode(action_mode)
        self.net, self.name = net, name
        self.features, self.aim_scale, self.action_mode = bool(features), float(aim_scale), action_mode
        self.placer_seed = int(placer_seed)
        self.placer = None

    def observe(self, view) -> tuple[np.ndarray, OnePlayerView]:
        """The network's input rows for ``view`` and the one-player view they were taken from."""
        o = view.observation()
        o[:, 4 * view.n_balls + 1] = 0.0  # the player to move: the network always played as player 0
        self.placer = self.placer or GhostBot(seed=self.placer_seed)
        native = OnePlayerView.of_view(view, self.placer)
        extra = agent_features(native, self.features, self.aim_scale, self.action_mode)
        obs = o if extra is None else np.concatenate([o, extra], axis=1)
        if obs.shape[1] != self.net.obs_dim:
            raise ValueError(f"{self.name}: the network takes observations of {self.net.obs_dim} numbers, this game "
                             f"and the agent's features give {obs.shape[1]} (trained on another game or options?)")
        return obs, native

    def act(self, view) -> np.ndarray:
        """The game actions [n, 8] of the view's tables."""
        obs, native = self.observe(view)
        return transform_actions(native, self.net.act(obs), self.action_mode, self.aim_scale)
