"""Trained models as entrants of the two-player games, beside the library's bots.

The built-in bots (``random``, ``ghost``, ``ghost-safety``, ``search<K>``)
and ``module:factory`` bots come from ``billiards_env.bots.make_bot``;
``bot_factory`` adds saved stable-baselines3 models (a run directory or a
``.zip``), played by ``GameModelPolicy``.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from billiards_env.bots import BOT_NAMES, is_bot_name, make_bot

ENTRANTS = BOT_NAMES + ("<path to a saved model>",)


class GameModelPolicy:
    """A saved stable-baselines3 model (a run directory or a ``.zip``, with
    its normaliser statistics; ``SB3Policy.load``) trained on a game env,
    playing deterministically; it returns the env's actions [n, 8]. A model
    trained against an opponent with the agent wrappers
    (``configs/ppo_games.yaml``) was always player 0 and chose its shots
    through ``game_view.GameView``: it plays through that adapter over the
    bot view it is handed (its ``observation()`` and action ``codec``) and
    sees every table as player 0 saw it (the player-to-move entry set to 0;
    the group and foul entries are the shooter's already). A model of the
    env's own 8 action components plays on the raw observation."""

    def __init__(self, path, name: str | None = None):
        from ..sb3.policy import SB3Policy
        self.model = SB3Policy.load(path)
        self.viewed = self.model.model.action_space.shape != (8,)
        self.name = name or f"model:{path}"
        self.placer = None  # the ghost bot behind the adapter's placements and breaks

    def act(self, view) -> np.ndarray:
        o = view.observation()
        policy = self.model
        if self.viewed:
            from billiards_env.bots.ghost import GhostBot

            from ..interface.game_view import GameView
            o[:, 4 * view.n_balls + 1] = 0.0  # the player to move: the model always played as player 0
            self.placer = self.placer or GhostBot(seed=0)
            policy = self.model.bind(GameView.of_view(view, self.placer))
        a = np.asarray(policy.act(o), dtype=np.float32)
        if a.shape[1] != 8:
            raise ValueError(f"{self.name}: the model gives {a.shape[1]} action components, a game needs 8")
        return a


def bot_factory(spec, seed: int = 0):
    """An entrant by spec: a bot (``billiards_env.bots.make_bot``: a name,
    ``module:factory`` or a bot object) or the path of a saved model."""
    if not isinstance(spec, str) or is_bot_name(spec):
        return make_bot(spec, seed=seed)
    if Path(spec).exists():
        return GameModelPolicy(spec)
    raise ValueError(f"unknown entrant {spec!r}; choose one of {ENTRANTS}")
