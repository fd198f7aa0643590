"""Where the rules put balls back after a shot, in place on position arrays:
object balls respotted on the foot spot (``respot``), and in the games
where each player has a cue ball (three-cushion) the incoming player's ball
to slot 0 (``hand_over``) and the starting position (``three_cushion_spots``,
``restart_position``: the equal-innings last inning, and balls in contact
the shooter had replaced). Snooker's colours go back by
``rules.snooker.respot_colours``. ``contract.turn.play_turn`` applies them
after every ruling."""
from __future__ import annotations

import numpy as np

from ..physics.state import free_spot
from .placement import FOOT_SPOT, HEAD_STRING


def three_cushion_spots(table, R: float, u: np.ndarray) -> np.ndarray:
    """Positions [n, 3, 2] of three-cushion's opening (UMB; the rules'
    frame: the starting player's ball, the opponent's, the red): the red on
    the foot spot, the opponent's ball on the head spot, the starting
    player's on the head string ``OPENING_OFFSET`` to its left or right
    (``u`` [n, 1] < 0.5: left)."""
    from .three_cushion import OPENING_OFFSET
    n, w, l = len(u), table.width, table.length
    pos = np.zeros((n, 3, 2))
    side = np.where(u[:, 0] < 0.5, -1.0, 1.0)
    pos[:, 0, 0], pos[:, 0, 1] = w / 2 + side * OPENING_OFFSET, HEAD_STRING * l
    pos[:, 1] = (w / 2, HEAD_STRING * l)
    pos[:, 2] = (w / 2, FOOT_SPOT * l)
    return pos


def hand_over(pos: np.ndarray, rows: np.ndarray) -> None:
    """Games where each player has their own cue ball: on the tables of
    ``rows`` [n] (bool) the incoming player's ball (slot 1) and the outgoing
    player's (slot 0) change slots, in place, so slot 0 is always the ball
    of the player to move."""
    r = np.nonzero(rows)[0]
    pos[r, 0], pos[r, 1] = pos[r, 1].copy(), pos[r, 0].copy()


RESTART_SIDE = 1.0  # the side of the head spot (+x) of the mover's ball when the balls go back to the start


def restart_position(pos: np.ndarray, rows: np.ndarray, table, R: float) -> None:
    """Three-cushion: on the tables of ``rows`` [n] (bool; ``ShotRecord.restart``:
    the equal-innings last inning, or balls in contact the shooter had
    replaced, UMB Art. 27) the balls go back to the starting position,
    in place, in the frame of the player to move (call it after ``hand_over``:
    slot 0 the mover's ball): the red on the foot spot, the other player's ball
    on the head spot, the mover's own ball on the head string ``OPENING_OFFSET``
    beside it, always on the same side (``RESTART_SIDE``; UMB lets the player
    choose; the table is symmetric, so the side changes nothing but the mirror
    image)."""
    r = np.nonzero(rows)[0]
    if len(r):
        pos[r] = three_cushion_spots(table, R, np.full((len(r), 1), 0.5 + 0.5 * RESTART_SIDE))


def respot(pos: np.ndarray, pocket: np.ndarray, balls: np.ndarray, table, R: float, pockets: np.ndarray) -> None:
    """Put the balls marked in ``balls`` [n, B] back on the table in place:
    on the foot spot or the nearest free point behind it (``free_spot``)."""
    for e, b in zip(*np.nonzero(balls)):
        x, y, found = free_spot(pos[e], pocket[e] < 0, table.width / 2, FOOT_SPOT * table.length, 0.0, 1.0,
                                table.width, table.length, R, pockets)
        if not found:
            raise RuntimeError("no free spot on the table to respot a ball")
        pos[e, b] = (x, y)
        pocket[e, b] = -1
