"""Racks for the two-player games (where the rules put balls back after a
shot is ``rules.respot``; the cue-ball placement of ball in hand,
``rules.placement``).

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

from ...physics.state import _triangle, snooker_rack
from ...rules.placement import FOOT_SPOT
from ...rules.respot import three_cushion_spots
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
