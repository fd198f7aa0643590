"""A two-player game seen as a one-player native env: what learned shot
policies read (``bots.learned.features``), in training and as bots.

The agent wrappers of ``bots.learned.features`` (the ghost-ball features, the
choice menu, residual actions) read a one-player native env: its
``state``, ``shot_context()``, ``legal_target()``, ``aim_origin()`` and
``shots_to_actions`` (4 action components). ``OnePlayerView`` shows a game env
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

It follows a game env (the training wrappers, ``agents.interface.game_view``)
or shows one bot view (the ladder's bots, ``bots.learned.ladder``, and
trained models entered as bots).
"""
from __future__ import annotations

import types

import numpy as np

from ...contract.codec import ShotContext
from ...contract.codec import N_POCKETS
from ...rules import records as R
from ..ghost import GhostBot, PotGeometry
from ...contract.preview import rest_state

AGENT_ACTION_DIM = 4  # the policy's part of a game action: aim, draw, side, height (a0..a3)


class OnePlayerView:
    """A game seen as a one-player native env: see the module docstring.

    It reads the bot API's view of the tables only (``billiards_env.bots.GameView``):
    ``OnePlayerView(env)`` follows a game env (the agent wrappers of training;
    the env's view of every table, taken anew whenever the env's state
    changes), ``OnePlayerView.of_view(view)`` shows one bot view (a learned bot,
    ``bots.learned.policy.ViewPolicy``)."""

    def __init__(self, env=None, seed: int = 0, view=None, placer: GhostBot | None = None):
        self.placer = placer or GhostBot(seed=seed)
        self.env = env
        self.core = None if env is None else getattr(env, "core", env)  # a game env, or its GameCore
        self._key = None  # what the shown view was taken from: the core's ShotContext, or the view itself
        source = view if view is not None else self.core
        self.table, self.params = source.table, source.params
        self.geo = PotGeometry(self.table, self.params)
        # what the features read of the env's options: its shortest draw (``config.min_draw``)
        self.config = self.core.config if view is None else types.SimpleNamespace(min_draw=view.min_draw)
        if view is not None:
            self._load(view)
            self._key = view

    @classmethod
    def of_view(cls, view, placer: GhostBot) -> "OnePlayerView":
        """The tables of one bot view (``billiards_env.bots.GameView``);
        ``placer``: the ghost bot that places the cue ball and breaks (kept
        across views, so its random stream runs on)."""
        return cls(view=view, placer=placer)

    @property
    def n_envs(self) -> int:
        return self.core.n_envs if self.core is not None else self._view.n

    def _refresh(self) -> None:
        if self.core is None:
            return
        key = self.core.shot_context()
        if self._key is key:
            return
        self._load(self.core.view(np.arange(self.core.n_envs)))
        self._key = key

    def _load(self, view) -> None:
        """Show ``view``'s tables: the cue ball placed where a player with ball in hand would put it."""
        n, codec = view.n, view.codec
        pos, pocket = view.pos.copy(), view.pocket.copy()
        hand = view.in_hand & ~view.is_break & ~view.state.over
        placement = np.full((n, 2), np.nan)
        h = np.nonzero(hand)[0]
        origin = codec.origin.copy()
        if len(h):
            want = self.placer.placements(self.geo, pos[h], pocket[h] < 0, view.targets[h],
                                          view.ball_in_hand[h] == R.IN_HAND_KITCHEN)
            spots, _ = view.legal_placement(want, h)
            pos[h, 0], pocket[h, 0], placement[h] = spots, -1, spots
            origin[h] = codec.origin_from(spots, h)
        pots = self.placer.best_pots(self.geo, pos, pocket < 0, view.targets)
        has = np.isfinite(pots["cost"])
        target = np.where(has, pots["ball"], view.nominal_target()).astype(np.int64)
        self._view = view
        self._state = rest_state(view)
        self._state.pos[:], self._state.pocket[:] = pos, pocket
        self._context = ShotContext(target, origin, np.zeros(n))
        self._placement, self._pocket, self._break = placement, pots["pocket"].copy(), view.is_break.copy()

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
        return self._view.codec.encode(shots, self._placement)[:, :AGENT_ACTION_DIM]

    # --- the game's remaining components --------------------------------------------
    def complete_actions(self, a4: np.ndarray, items: np.ndarray | None = None) -> np.ndarray:
        """The policy's a0..a3 [E, 4] -> game actions [E, codec.action_dim]: the placement,
        no declaration, the called pocket (menu ``items`` below the pocket
        count name one), the game's nominal ball where it calls or nominates one
        (10-ball, snooker: the codec's ``encode``), and the standard break on break shots."""
        self._refresh()
        codec = self._view.codec
        pocket = self._pocket
        if items is not None:
            items = np.asarray(items, dtype=np.int64)
            pocket = np.where(items < N_POCKETS, items, pocket)
        out = np.zeros((self.n_envs, codec.action_dim), dtype=np.float32)
        out[:, 4:6] = codec.placement_to_actions(np.nan_to_num(self._placement, nan=0.0))
        out[:, 6] = -1.0
        out[:, 7] = -1.0 + (2.0 * pocket + 1.0) / N_POCKETS
        if codec.ball_dim:   # the called / nominated ball: the codec's nominal (its ``encode`` with ball=None)
            out[:, 8] = -1.0 + (2.0 * codec.nominal + 1.0) / codec.n_balls
        if codec.max_elevation:  # the airborne option's elevation: the level cue
            out[:, codec.elevation_index] = -1.0
        out[:, :AGENT_ACTION_DIM] = a4
        brk = np.nonzero(self._break)[0]
        if len(brk):
            out[brk] = self._view.codec.take(brk).encode_plan(self.placer.act(self._view.take(brk)))
        return out
