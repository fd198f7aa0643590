"""Racks and respotting for the two-player games (the cue-ball placement of
ball in hand is a rule: ``rules.placement``)."""
from __future__ import annotations

import numpy as np

from ...physics.state import _triangle, free_spot, snooker_rack
from ...rules.placement import FOOT_SPOT
from ..tasks.nine_ball import nine_ball_rack


def eight_ball_rack(table, R: float, u: np.ndarray) -> np.ndarray:
    """Positions [n, 16, 2] of 8-ball racks from uniforms ``u`` [n, 14]: a
    frozen triangle with its apex on the foot spot, the 8 in the centre of
    the third row, the other 14 balls shuffled by the ranks of ``u`` and
    then, if both back corners hold the same group, the second corner
    swapped with the first ball of the other group behind the apex (so the
    corners hold one solid and one stripe); cue ball left at the origin."""
    n = len(u)
    slots = _triangle(5, (table.width / 2, FOOT_SPOT * table.length), R, 0.0, slice(None))  # 15 slots
    others = np.array([b for b in range(1, 16) if b != 8])
    order = others[np.argsort(u, axis=1)]                                # [n, 14] balls in slot order
    balls = np.concatenate([order[:, :4], np.full((n, 1), 8), order[:, 4:]], axis=1)  # [n, 15]
    for e in range(n):
        c1, c2 = balls[e, 10], balls[e, 14]
        if (c1 < 8) == (c2 < 8):
            j = next(k for k in range(1, 10) if k != 4 and (balls[e, k] < 8) != (c1 < 8))
            balls[e, 14], balls[e, j] = balls[e, j], balls[e, 14]
    pos = np.zeros((n, 16, 2))
    pos[np.arange(n)[:, None], balls] = slots[None]
    return pos


TEN_BALL_CENTRE = 4  # the slot of the 10 in a four-row triangle: the middle of the third row (slots row by row)


def ten_ball_rack(table, R: float, u: np.ndarray) -> np.ndarray:
    """Positions [n, 11, 2] of 10-ball racks from uniforms ``u`` [n, 8]
    (WPA Ten Ball: a triangle of four rows, the 1 at the apex on the foot
    spot, the 10 in the centre, the other balls placed at random): a frozen
    triangle, balls 2..9 shuffled by the ranks of ``u``; cue ball left at
    the origin."""
    n = len(u)
    slots = _triangle(4, (table.width / 2, FOOT_SPOT * table.length), R, 0.0, slice(None))  # 10 slots
    others = np.array([k for k in range(1, 10) if k != TEN_BALL_CENTRE])                    # slots of balls 2..9
    pos = np.zeros((n, 11, 2))
    pos[:, 1] = slots[0]
    pos[:, 10] = slots[TEN_BALL_CENTRE]
    pos[np.arange(n)[:, None], 2 + np.argsort(u, axis=1)] = slots[others][None]
    return pos


def rack(game: str, table, R: float, u: np.ndarray) -> np.ndarray:
    """The rack of ``game`` from uniforms ``u`` [n, >= 14] (9-ball takes the
    first 7, 10-ball the first 8; snooker's opening has nothing to draw)."""
    if game == "snooker":
        return np.repeat(snooker_rack(table, R)[None], len(u), axis=0)
    if game == "ten_ball":
        return ten_ball_rack(table, R, u[:, :8])
    return nine_ball_rack(table, R, u[:, :7]) if game == "nine_ball" else eight_ball_rack(table, R, u[:, :14])


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
