"""Racks, the cue-ball placement of ball in hand, and respotting, for the
two-player games (numba kernels over the placement helpers of
``physics.state``)."""
from __future__ import annotations

import math

import numba
import numpy as np

from ...physics.state import SPOT_CLEAR, SPOT_EDGE, _triangle, free_spot, spot_free
from ..tasks.nine_ball import nine_ball_rack

HEAD_STRING = 0.25   # the head string's distance from the head rail, as a fraction of the table's length
FOOT_SPOT = 0.75     # the foot spot's, likewise
KITCHEN_GAP = 1e-6   # m: a cue ball placed behind the head string keeps its centre this far behind the line
PLACE_RINGS = 400    # rings of the nearest-legal-spot search (radius step R/4: covers any table)

_jit = numba.njit(cache=True, nogil=True)


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


def rack(game: str, table, R: float, u: np.ndarray) -> np.ndarray:
    """The rack of ``game`` from uniforms ``u`` [n, >= 14] (9-ball takes the first 7)."""
    return nine_ball_rack(table, R, u[:, :7]) if game == "nine_ball" else eight_ball_rack(table, R, u[:, :14])


@_jit
def _legal_spot(x, y, pos, on, width, y_hi, R, pockets):
    """The nearest point to (x, y) where a cue ball may be placed: clamped into
    the allowed rectangle (centre R + SPOT_EDGE inside the cushions, y at most
    ``y_hi``), then, if it overlaps a ball or a pocket, the first free point
    of rings of radius k R / 4 (k = 1, 2, ...; 8 k points each, nearest ring
    first). Returns (x, y, found)."""
    edge = R + SPOT_EDGE
    md = 2 * R + SPOT_CLEAR
    x = min(max(x, edge), width - edge)
    y = min(max(y, edge), y_hi)
    if spot_free(x, y, pos, on, width, y_hi + edge, edge, pockets, md):
        return x, y, True
    for k in range(1, PLACE_RINGS):
        r = 0.25 * R * k
        m = 8 * k
        for j in range(m):
            a = 2.0 * math.pi * j / m
            cx, cy = x + r * math.cos(a), y + r * math.sin(a)
            if cy <= y_hi and spot_free(cx, cy, pos, on, width, y_hi + edge, edge, pockets, md):
                return cx, cy, True
    return x, y, False


@_jit
def place_cue(want, pos, pocket, kitchen, width, length, R, pockets, out, moved):
    """Per table: the cue ball (ball 0) placed at the legal spot nearest to
    ``want`` [n, 2]; ``kitchen[e]`` limits it to behind the head string.
    Writes ``out`` [n, 2] and ``moved`` [n] (the spot differs from ``want``);
    returns False if some table has no free spot."""
    ok = True
    for e in range(want.shape[0]):
        on = pocket[e] < 0
        on[0] = False  # the cue ball is in hand
        y_hi = HEAD_STRING * length - KITCHEN_GAP if kitchen[e] else length - R - SPOT_EDGE
        x, y, found = _legal_spot(want[e, 0], want[e, 1], pos[e], on, width, y_hi, R, pockets)
        ok &= found
        out[e, 0], out[e, 1] = x, y
        moved[e] = x != want[e, 0] or y != want[e, 1]
    return ok


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
