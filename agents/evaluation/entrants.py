"""Trained models as entrants of the two-player games, beside the library's bots.

The built-in bots (``random``, ``ghost``, ``ghost-safety``, ``search<K>``,
``lookahead``, the shipped ladder ``ladder-<k>``)
and ``module:factory`` bots come from ``billiards_env.bots.make_bot``;
``bot_factory`` adds saved stable-baselines3 models (a run directory or a
``.zip``), played by ``GameModelPolicy``, and value networks saved as
``<stem>.npz`` / ``.json`` (a league's snapshots, ``agents.league``) as
``value@<stem>``: ``value-lookahead`` searching with that network on its
blind leaves, or ``value-all@<stem>`` on every leaf
(``billiards_env.bots.learned.value.LeafValue``).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from billiards_env.bots import BOT_NAMES, is_bot_name, make_bot
from billiards_env.bots.learned.policy import ViewPolicy

SNAPSHOTS = {"value@": "blind", "value-all@": "all"}  # entrant prefix of a value network -> the leaves it values
ENTRANTS = BOT_NAMES + ("<path to a saved model>", "value@<stem>", "value-all@<stem>")


def value_entrant(spec: str, seed: int = 0):
    """``value-lookahead`` with the value network of a ``value@<stem>`` or ``value-all@<stem>`` spec."""
    from billiards_env.bots.learned.value import ValueLookahead, load_value
    prefix = next(p for p in SNAPSHOTS if spec.startswith(p))
    net, doc = load_value(spec[len(prefix):])
    bot = ValueLookahead(seed=seed, nets={doc["game"]: net}, where=SNAPSHOTS[prefix])
    bot.name = spec
    return bot


class GameModelPolicy:
    """A saved stable-baselines3 model (a run directory or a ``.zip``, with
    its normaliser statistics; ``SB3Policy.load``) trained on a game env,
    playing deterministically; it returns the env's actions [n, 8]. A model
    trained against an opponent with the agent wrappers
    (``configs/ppo_games.yaml``) plays through the library's
    ``bots.learned.policy.ViewPolicy`` (the shipped ladder's path, with the
    model's network in place of the numpy one). A model of the env's own 8
    action components plays on the raw observation."""

    def __init__(self, path, name: str | None = None):
        from ..sb3.policy import SB3Network, SB3Policy
        self.model = SB3Policy.load(path)
        self.viewed = self.model.model.action_space.shape != (8,)
        self.name = name or f"model:{path}"
        m = self.model
        self.player = ViewPolicy(SB3Network(m.model, m.vecnormalize), self.name, m.features, m.aim_scale,
                                 m.action_mode) if self.viewed else None

    def act(self, view) -> np.ndarray:
        a = self.player.act(view) if self.viewed else self.model.act(view.observation())
        a = np.asarray(a, dtype=np.float32)
        if a.shape[1] != 8:
            raise ValueError(f"{self.name}: the model gives {a.shape[1]} action components, a game needs 8")
        return a


def bot_factory(spec, seed: int = 0):
    """An entrant by spec: a bot (``billiards_env.bots.make_bot``: a name,
    ``module:factory`` or a bot object), the path of a saved model or a
    value network (``value@<stem>``, ``value-all@<stem>``)."""
    if isinstance(spec, str) and spec.startswith(tuple(SNAPSHOTS)):
        return value_entrant(spec, seed)
    if not isinstance(spec, str) or is_bot_name(spec):
        return make_bot(spec, seed=seed)
    if Path(spec).exists():
        return GameModelPolicy(spec)
    raise ValueError(f"unknown entrant {spec!r}; choose one of {ENTRANTS}")
