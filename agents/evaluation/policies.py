"""Policies by name: the one-player baselines of ``billiards_env.bots.one_player``,
the lookahead search of ``billiards_env.bots.lookahead``, the game bots of
``billiards_env.bots`` and saved models (``agents.sb3.policy.SB3Policy``; what
``scripts/evaluate.py --policy`` and the training's final evaluation accept)."""
from __future__ import annotations

import numpy as np

from billiards_env.bots import make_bot
from billiards_env.bots.registry import parse_bot_name
from billiards_env.bots.lookahead import LookaheadPolicy
from billiards_env.envs.games.play import bot_actions

from billiards_env.bots.one_player import BotPolicy, GhostBallPolicy, Policy, RandomPolicy, SearchPolicy

from ..sb3.policy import SB3Policy
from ..interface.game_view import game_view_of, native_env

BASELINE_NAMES = ("random", "ghost", "lookahead")  # besides search<K>
GAME_ONLY_NAMES = ("ghost-safety",)                 # game policies without a one-player twin


def is_policy_name(name: str) -> bool:
    """Whether ``name`` names a built-in policy (else it is a saved model's path): the bots' grammar
    (``bots.registry.parse_bot_name``), restricted to the baselines."""
    parsed = parse_bot_name(name)
    return parsed is not None and parsed.family in BASELINE_NAMES + GAME_ONLY_NAMES + ("search",)


def make_policy(name: str, env, seed: int = 0, k: int = 256) -> Policy:
    """A baseline by name: ``random``, ``ghost``, ``search`` (``search<K>``
    sets K, e.g. ``search64``), ``lookahead`` (``billiards_env.bots.lookahead``), or a
    path to a saved model / run directory. On a two-player game env against
    an opponent the names are the game bots' (``billiards_env.bots.make_bot``)."""
    view = game_view_of(env)
    if view is not None and is_policy_name(name):
        return GamePolicy(name, view.env, seed=seed)
    if name in GAME_ONLY_NAMES:
        raise ValueError(f"{name!r} plays the two-player games only (Billiards-NineBall2P-v1, Billiards-EightBall-v1)")
    if name == "random":
        return RandomPolicy(seed=seed)
    if name == "ghost":
        return BotPolicy(GhostBallPolicy(), native_env(env))
    if name == "lookahead":
        return BotPolicy(LookaheadPolicy(seed=seed), native_env(env))
    parsed = parse_bot_name(name)
    if parsed is not None and parsed.family == "search":
        return BotPolicy(SearchPolicy(k=parsed.k or k, seed=seed), native_env(env))
    return SB3Policy.load(name, env=env)


class GamePolicy:
    """A named bot (``billiards_env.bots.make_bot``) as the agent of a game
    env against an opponent: it acts on every table (the agent is to move on
    all of them)."""

    def __init__(self, name: str, env, seed: int = 0):
        self.core = env.core
        self.bot = make_bot(name, seed=seed)
        self.name = self.bot.name

    def act(self, obs=None) -> np.ndarray:
        return bot_actions(self.core, self.bot, np.arange(self.core.n_envs)).astype(np.float32)
