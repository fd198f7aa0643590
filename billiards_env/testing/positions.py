"""Constructed positions for tests and bot experiments: a one-table game core
with chosen balls on the table, in a chosen phase."""
from __future__ import annotations

from ..envs.games import GameConfig, GameCore
from ..rules import records as R


def game_table(game: str, balls: dict, phase: int = R.PHASE_PLAY, hand: int = R.IN_HAND_NONE,
               **config) -> GameCore:
    """A ``GameCore`` of one table of ``game`` (racked from seed 0, player 0
    to shoot) with the balls of ``balls`` (ball -> (x, y), m) on the table
    and every other ball pocketed, in game ``phase`` (``rules.PHASE_*``;
    default open play) with ball-in-hand state ``hand`` (``rules.IN_HAND_*``).
    ``config``: ``GameConfig`` keys over the game's defaults (e.g.
    ``effects={"airborne": True}``). ``core.view([0])`` is the table as a
    bot sees it."""
    core = GameCore(GameConfig(game=game, **config), 1)
    core.streams.seed([0], [0])
    core.reset_tables([0], [0])
    return set_table(core, balls, phase, hand)


def set_table(core: GameCore, balls: dict, phase: int = R.PHASE_PLAY, hand: int = R.IN_HAND_NONE,
              row: int = 0) -> GameCore:
    """Table ``row`` of a reset ``core`` (a ``GameCore``, or an env's
    ``env.unwrapped.core``) with only the balls of ``balls`` on it, in game
    ``phase`` with ball-in-hand state ``hand``, its game otherwise as it
    is; returns ``core``."""
    core.state.pocket[row] = 0
    for b, xy in balls.items():
        core.state.pos[row, b] = xy
        core.state.pocket[row, b] = -1
    core.game.phase[row] = phase
    core.game.ball_in_hand[row] = hand
    core._changed()
    return core
