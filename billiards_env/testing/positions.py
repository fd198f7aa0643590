"""Constructed positions for tests and bot experiments: a one-table game core
with chosen balls on the table, in a chosen phase."""
from __future__ import annotations

from ..envs.games import GameConfig, GameCore
from ..rules import records as R


def game_table(game: str, balls: dict, phase: int = R.PHASE_PLAY, hand: int = R.IN_HAND_NONE) -> GameCore:
    """A ``GameCore`` of one table of ``game`` (racked from seed 0, player 0
    to shoot) with the balls of ``balls`` (ball -> (x, y), m) on the table
    and every other ball pocketed, in game ``phase`` (``rules.PHASE_*``;
    default open play) with ball-in-hand state ``hand`` (``rules.IN_HAND_*``).
    ``core.view([0])`` is the table as a bot sees it."""
    core = GameCore(GameConfig(game=game), 1)
    core.streams.seed([0], [0])
    core.reset_tables([0], [0])
    core.state.pocket[0] = 0
    for b, xy in balls.items():
        core.state.pos[0, b] = xy
        core.state.pocket[0, b] = -1
    core.game.phase[0] = phase
    core.game.ball_in_hand[0] = hand
    core._changed()
    return core
