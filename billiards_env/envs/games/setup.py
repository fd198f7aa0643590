"""Racks and respotting for the two-player games (the cue-ball placement of
ball in hand is a rule: ``rules.placement``).

Racks are ``realistic`` by default: real balls are not all the same size
(WPA equipment specifications: 2 1/4 in +- 0.005 in, so diameters differ
by up to 0.25 mm) and a racked set does not freeze every ball to every
neighbour. ``loosen`` spreads a frozen lattice about its apex so that
neighbouring centres sit ``2R + RACK_GAP`` apart and then moves every
object ball by a seeded offset uniform in a disc of radius ``RACK_JITTER``
(the idea of pooltool's racks: a spaced lattice plus a random offset in a
disc of the spacing, there 1e-3 R, about 0.03 mm; here sized to the gaps of
real racks, about 0.1-0.5 mm). Neighbours end between 0 and
``RACK_GAP + 2 RACK_JITTER`` = 0.4 mm apart and never overlap. The
``perfect`` rack (every ball frozen) is the one of earlier versions.
"""
from __future__ import annotations

import numpy as np

from ...physics.state import _triangle, free_spot, snooker_rack
from ...rules.placement import FOOT_SPOT, HEAD_STRING
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


def three_cushion_spots(table, R: float, u: np.ndarray) -> np.ndarray:
    """Positions [n, 3, 2] of three-cushion's opening (UMB; the rules'
    frame: the starting player's ball, the opponent's, the red): the red on
    the foot spot, the opponent's ball on the head spot, the starting
    player's on the head string ``OPENING_OFFSET`` to its left or right
    (``u`` [n, 1] < 0.5: left)."""
    from ...rules.three_cushion import OPENING_OFFSET
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
    the equal-innings last inning) the balls go back to the starting position,
    in place, in the frame of the player to move (call it after ``hand_over``:
    slot 0 the mover's ball): the red on the foot spot, the other player's ball
    on the head spot, the mover's own ball on the head string ``OPENING_OFFSET``
    beside it, always on the same side (``RESTART_SIDE``; UMB lets the player
    choose; the table is symmetric, so the side changes nothing but the mirror
    image)."""
    r = np.nonzero(rows)[0]
    if len(r):
        pos[r] = three_cushion_spots(table, R, np.full((len(r), 1), 0.5 + 0.5 * RESTART_SIDE))


def respot_frozen(pos: np.ndarray, table, R: float) -> None:
    """Three-cushion: where the cue ball of the player to move (slot 0) is
    frozen to a ball (closer than 2R + ``FROZEN_GAP``), the balls go to the
    opening spots, in place: the cue ball on the head spot, the red on the
    foot spot, the opponent's ball on the centre spot (docs/rules.md: UMB
    lets the player choose; this always respots)."""
    from ...rules.three_cushion import FROZEN_GAP
    gap = np.linalg.norm(pos[:, 1:] - pos[:, :1], axis=2).min(axis=1)
    r = np.nonzero(gap < 2 * R + FROZEN_GAP)[0]
    w, l = table.width, table.length
    pos[r, 0] = (w / 2, HEAD_STRING * l)
    pos[r, 1] = (w / 2, 0.5 * l)
    pos[r, 2] = (w / 2, FOOT_SPOT * l)


RACKS = ("realistic", "perfect")  # GameConfig.rack: seeded gaps and offsets (default), or every ball frozen
RACK_GAP = 0.2e-3     # m: lattice gap between neighbouring centres beyond 2R (balls differ by up to 0.25 mm, WPA)
RACK_JITTER = 0.1e-3  # m: radius of each ball's offset disc; RACK_GAP >= 2 RACK_JITTER keeps neighbours apart


def rack(game: str, table, R: float, u: np.ndarray) -> np.ndarray:
    """The rack of ``game`` from uniforms ``u`` [n, >= 14] (9-ball takes the
    first 7, 10-ball the first 8, three-cushion the first 1; snooker's opening has nothing to draw); the pool racks
    have every ball frozen (``loosen`` opens them)."""
    if game == "snooker":
        return np.repeat(snooker_rack(table, R)[None], len(u), axis=0)
    if game == "three_cushion":
        return three_cushion_spots(table, R, u[:, :1])
    if game == "ten_ball":
        return ten_ball_rack(table, R, u[:, :8])
    return nine_ball_rack(table, R, u[:, :7]) if game == "nine_ball" else eight_ball_rack(table, R, u[:, :14])


def loosen(pos: np.ndarray, table, R: float, u: np.ndarray, gap: float = RACK_GAP,
           jitter: float = RACK_JITTER) -> None:
    """Open the frozen racks ``pos`` [n, B, 2] (object balls 1..B-1) in
    place: their lattice stretched about the foot spot so neighbouring
    centres are ``2R + gap`` apart, then each ball moved by an offset
    uniform in a disc of radius ``jitter`` from uniforms ``u`` [n, 2(B-1)]
    (radius jitter * sqrt(u), angle 2 pi u')."""
    if gap < 2 * jitter:
        raise ValueError(f"rack gap {gap} m must be at least twice the jitter {jitter} m, or balls overlap")
    n, B = pos.shape[:2]
    u = np.asarray(u, dtype=np.float64).reshape(n, B - 1, 2)
    apex = np.array([table.width / 2, FOOT_SPOT * table.length])
    r, ang = jitter * np.sqrt(u[..., 0]), 2 * np.pi * u[..., 1]
    pos[:, 1:] = apex + (pos[:, 1:] - apex) * ((2 * R + gap) / (2 * R))
    pos[:, 1:, 0] += r * np.cos(ang)
    pos[:, 1:, 1] += r * np.sin(ang)


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
