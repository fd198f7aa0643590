"""The one-player agent machinery on the two-player games.

The agent wrappers of ``agents.interface.features`` (the ghost-ball features, the
choice menu, residual actions) read a one-player native env: its
``state``, ``shot_context()``, ``legal_target()``, ``aim_origin()`` and
``shots_to_actions`` (4 action components). ``GameView`` shows a game env
against an opponent (``billiards_env.envs.games.versus``) the same way and
completes the 4 components to the game's 8 by rules a player follows
rather than learns; the policy still chooses every shot:

- **ball in hand**: the cue ball goes where the ghost-ball game policy puts
  it (``bots.ghost.GhostBot.placements``: behind a legal ball for a short
  straight-in pot, else the head spot or the table's centre, made legal),
  and the view shows the table with the cue ball there;
- **the target** the menu and features are about: the legal ball with the
  easiest ghost-ball pot from there (``GhostBot.best_pots``; in
  9-ball the lowest ball, the only legal one), else the lowest legal ball;
- **the break**: the game policies' standard break (the policy's action is
  not used on break shots);
- **no push-out and no pass**;
- **the called pocket** (8-ball, on the 8): the chosen menu item's pocket
  (``action_mode: choice``), else that of the easiest pot.

``agents.evaluation.policies.GamePolicy`` plays a named game policy as the agent on
such an env (the baselines of an evaluation or of a held-seed curve).
"""
from __future__ import annotations

import dataclasses
import weakref

import numpy as np
from gymnasium import spaces

from billiards_env.envs.core import ShotContext
from billiards_env.envs.unwrap import env_chain
from billiards_env.envs.games import GameCore
from billiards_env.envs.games.core import ACTION_DIM, N_POCKETS
from billiards_env.rules import records as R
from billiards_env.bots.ghost import GhostBot, PotGeometry
from billiards_env.envs.games.play import bot_actions

AGENT_ACTION_DIM = 4  # the policy's part of a game action: aim, draw, side, height (a0..a3)


def is_game(env) -> bool:
    """Whether ``env`` is a two-player game env with a ``GameCore`` (``core``)."""
    return isinstance(getattr(env, "core", None), GameCore)


class GameView:
    """A game env seen as a one-player native env: see the module docstring."""

    def __init__(self, env, seed: int = 0):
        self.env, self.core = env, (env if isinstance(env, GameCore) else env.core)
        self.placer = GhostBot(seed=seed)
        self.geo = PotGeometry(self.core.table, self.core.params)
        self.table, self.params, self.config = self.core.table, self.core.params, self.core.config
        self.n_envs = self.core.n_envs
        self._key = None  # the core's ShotContext the view was built from

    def _refresh(self) -> None:
        core = self.core
        key = core.shot_context()
        if self._key is key:
            return
        c, s = core.constraints(), core.state
        E = self.n_envs
        pos, pocket = s.pos.copy(), s.pocket.copy()
        hand = (c.ball_in_hand != R.IN_HAND_NONE) & ~c.is_break & ~c.over
        placement = np.full((E, 2), np.nan)
        h = np.nonzero(hand)[0]
        origin = key.aim_origin.copy()
        if len(h):
            want = self.placer.placements(self.geo, pos[h], pocket[h] < 0, c.targets[h], c.ball_in_hand[h] == R.IN_HAND_KITCHEN)
            spots, _ = core.legal_placement(want, h)
            pos[h, 0], pocket[h, 0], placement[h] = spots, -1, spots
            origin[h] = core._origin_from(spots, h)
        pots = self.placer.best_pots(self.geo, pos, pocket < 0, c.targets)
        has = np.isfinite(pots["cost"])
        target = np.where(has, pots["ball"], c.nominal_target()).astype(np.int64)
        self._state = dataclasses.replace(s, pos=pos, pocket=pocket)
        self._context = ShotContext(target, origin, np.zeros(E))
        self._placement, self._pocket, self._break = placement, pots["pocket"].copy(), c.is_break.copy()
        self._key = key

    # --- what the one-player agent machinery reads --------------------------------
    @property
    def state(self):
        self._refresh()
        return self._state

    def shot_context(self) -> ShotContext:
        self._refresh()
        return self._context

    def legal_target(self) -> np.ndarray:
        return self.shot_context().target

    def aim_origin(self) -> np.ndarray:
        return self.shot_context().aim_origin

    def shots_to_actions(self, shots) -> np.ndarray:
        """``Shots`` [E] played from the view's cue ball -> the game's a0..a3 [E, 4]."""
        self._refresh()
        return self.core.actions_for(shots, np.arange(self.n_envs), self._placement)[:, :AGENT_ACTION_DIM]

    # --- the game's remaining components --------------------------------------------
    def complete_actions(self, a4: np.ndarray, items: np.ndarray | None = None) -> np.ndarray:
        """The policy's a0..a3 [E, 4] -> game actions [E, 8]: the placement,
        no declaration, the called pocket (menu ``items`` below the pocket
        count name one), and the standard break on break shots."""
        self._refresh()
        E = self.n_envs
        out = np.zeros((E, ACTION_DIM), dtype=np.float32)
        out[:, :AGENT_ACTION_DIM] = a4
        out[:, 4:6] = self.core.placement_to_actions(np.nan_to_num(self._placement, nan=0.0))
        out[:, 6] = -1.0
        pocket = self._pocket
        if items is not None:
            items = np.asarray(items, dtype=np.int64)
            pocket = np.where(items < N_POCKETS, items, pocket)
        out[:, 7] = -1.0 + (2.0 * pocket + 1.0) / N_POCKETS
        brk = np.nonzero(self._break)[0]
        if len(brk):
            out[brk] = bot_actions(self.core, self.placer, brk)
        return out


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
