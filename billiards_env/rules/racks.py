"""The games' racks: the opening position of each game from seeded
uniforms, every pool rack frozen (``envs.games.setup.loosen`` opens them
into realistic racks). Each game's registry entry (``rules.games``) names
its rack; three-cushion's opening is ``rules.respot.three_cushion_spots``."""
from __future__ import annotations

import numpy as np

from ..physics.state import _triangle, diamond_slots, snooker_rack
from .placement import FOOT_SPOT


def nine_ball_rack(table, R: float, u: np.ndarray) -> np.ndarray:
    """Positions [n, 10, 2] of 9-ball racks from uniforms ``u`` [n, 7]: the
    1 on the foot spot (apex), the 9 in the centre, balls 2..8 shuffled by
    the ranks of ``u``, frozen (``diamond_slots``); the cue ball (row 0) is
    left at the origin for the caller."""
    n = len(u)
    diamond = diamond_slots(table, R)  # slot 0 apex, 4 centre
    pos = np.zeros((n, 10, 2))
    pos[:, 1] = diamond[0]
    pos[:, 9] = diamond[4]
    others = diamond[[1, 2, 3, 5, 6, 7, 8]]
    pos[np.arange(n)[:, None], 2 + np.argsort(u, axis=1)] = others
    return pos


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


def snooker_opening(table, R: float, u: np.ndarray) -> np.ndarray:
    """Positions [n, 22, 2] of snooker's opening (``physics.state.snooker_rack``: the reds frozen, the colours on
    their spots, the cue ball in the D); nothing is drawn from ``u``."""
    return np.repeat(snooker_rack(table, R)[None], len(u), axis=0)
