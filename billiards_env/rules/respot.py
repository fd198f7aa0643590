"""Where the rules put balls back after a shot, in place on position arrays:
object balls respotted on the foot spot (``respot``), and in the games
where each player has a cue ball (three-cushion) the incoming player's ball
to slot 0 (``hand_over``) and the starting position (``three_cushion_spots``,
``restart_position``: the equal-innings last inning, and balls in contact
the shooter had replaced), and three-cushion's balls that left the table
(``carom_spots``). Snooker's colours go back by
``rules.snooker.respot_colours``. ``contract.turn.play_turn`` applies them
after every ruling, through the game's ``Rules.respot``."""
from __future__ import annotations

import numpy as np

from ..physics.state import SPOT_CLEAR, free_spot
from .placement import CENTRE_SPOT, FOOT_SPOT, HEAD_STRING, OPENING_OFFSET


def three_cushion_spots(table, R: float, u: np.ndarray) -> np.ndarray:
    """Positions [n, 3, 2] of three-cushion's opening (UMB; the rules'
    frame: the starting player's ball, the opponent's, the red): the red on
    the foot spot, the opponent's ball on the head spot, the starting
    player's on the head string ``OPENING_OFFSET`` to its left or right
    (``u`` [n, 1] < 0.5: left)."""
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


# Three-cushion's spots for balls put back (shooter's frame: slot 0 the shooter's ball, 1 the opponent's, 2 the
# red), as fractions of the table's length on the long string: the red on the foot (top) spot, the opponent's
# ball, whose inning comes next, on the head (starting) spot, the shooter's on the centre spot.
CAROM_SPOTS = (CENTRE_SPOT, HEAD_STRING, FOOT_SPOT)


def carom_spots(pos: np.ndarray, pocket: np.ndarray, balls: np.ndarray, table, R: float) -> None:
    """Three-cushion: put the balls marked in ``balls`` [n, 3] (the balls that
    left the table, ``ShotRecord.respot``, in the shooter's frame) back on
    the table, in place (``pos`` [n, 3, 2], ``pocket`` [n, 3] set to -1).

    The rule (UMB; the KNBB's text of it: balls that jump off the table are
    placed as balls in contact are, the red on the top spot, the cue ball on
    the lower spot, the other ball on the centre spot; a ball whose spot is
    occupied goes to the spot of the ball occupying it): each ball goes to
    its own spot (``CAROM_SPOTS``: the red on the foot spot; the cue ball of
    the next stroke, which after a jumped ball is the opponent's, the inning
    having ended, on the head spot; the other, the shooter's, on the centre
    spot); if a ball lies on it (centres nearer than 2R + ``SPOT_CLEAR``), to
    the spot of that ball, and so on (three balls, three spots: a free one
    is always found). Balls put back earlier in the same call count as lying
    there; the red is placed first, then the head spot's ball."""
    n, B = np.shape(balls)
    w, L = table.width, table.length
    spots = np.array([[w / 2, f * L] for f in CAROM_SPOTS])       # [3, 2], indexed by ball slot
    for e in range(n):
        for b in (2, 1, 0):
            if not balls[e, b]:
                continue
            on = pocket[e] < 0
            on[b] = False
            k = b
            for _ in range(B):
                d = np.hypot(*(pos[e] - spots[k]).T)
                blocker = np.nonzero(on & (d < 2 * R + SPOT_CLEAR))[0]
                if not len(blocker):
                    break
                k = int(blocker[0])
            else:
                raise RuntimeError("no free spot on the carom table to put back a ball")
            pos[e, b] = spots[k]
            pocket[e, b] = -1
