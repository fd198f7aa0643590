"""The one-player agent machinery on the two-player games.

The game seen as a one-player native env is the library's
``billiards_env.bots.learned.game_view.OnePlayerView`` (re-exported here as
``GameView``: its module docstring says what the policy chooses and which
rules complete its actions); this module finds it under the training
wrappers (``agent_native``, ``game_view_of``, ``native_env``).

``agents.evaluation.policies.GamePolicy`` plays a named game policy as the agent on
such an env (the baselines of an evaluation or of a held-seed curve).
"""
from __future__ import annotations

import weakref

import numpy as np
from gymnasium import spaces

from billiards_env.bots.learned.game_view import AGENT_ACTION_DIM, OnePlayerView as GameView  # noqa: F401
from billiards_env.contract.unwrap import env_chain
from billiards_env.envs.games import GameCore


def is_game(env) -> bool:
    """Whether ``env`` is a two-player game env with a ``GameCore`` (``core``)."""
    return isinstance(getattr(env, "core", None), GameCore)


_VIEWS: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()


def agent_native(env):
    """What the agent wrappers read: ``env`` itself, or for a game env its
    ``GameView`` (one per env, so features and actions share its cache)."""
    if not is_game(env):
        return env
    v = _VIEWS.get(env)
    if v is None:
        v = _VIEWS[env] = GameView(env)
    return v


def game_view_of(env) -> GameView | None:
    """The ``GameView`` of the game env under ``env`` (SB3 adapters and
    wrappers are looked through), or None if there is no game env."""
    for e in env_chain(env):
        if is_game(e):
            return agent_native(e)
    return None


def native_env(env):
    """The native billiards vector env under an SB3 adapter / wrappers (a
    game env's ``GameView``)."""
    view = game_view_of(env)
    if view is not None:
        return view
    for env in env_chain(env):
        if hasattr(env, "legal_target") and hasattr(env, "shots_to_actions"):
            return env
    if hasattr(env, "legal_target"):
        return env
    raise TypeError("this policy needs the native billiards vector env (with .state, legal_target(), shots_to_actions())")


def policy_space() -> spaces.Box:
    """The policy's action space on a game env in the continuous modes: a0..a3."""
    return spaces.Box(-1.0, 1.0, shape=(AGENT_ACTION_DIM,), dtype=np.float32)
