"""The lookahead's geometric part, numba kernels over batches of tables: the
ghost-ball pot of a ball into a pocket (``_pot``: open when both paths clear
the other balls by 2R + ``BLOCK_CLEAR``, the cut below ``MAX_CUT`` and the
approach within the pocket's mouth; its success probability
``erf(tol / (sqrt(2) sigma))`` from the pocket's angular tolerance and the
object ball's direction error), every legal pot of a table
(``_pot_table``), the ease of the shooter's best pot (``_leave_ease``) and
the value of a table from it (``position_value``)."""
from __future__ import annotations

import math
from typing import NamedTuple

import numba
import numpy as np

from ...contract.pockets import CORNER_ACCEPT_DEG, SIDE_ACCEPT_DEG
from ...rules import get_game
from ..geometry.lines import blocked, ghost_ball

_jit = numba.njit(cache=True, nogil=True)

BLOCK_CLEAR = 0.004                # m: a pot's paths keep this clear of other balls beyond 2R (execution noise)
MAX_CUT = math.radians(75)         # a pot cut more than this is not tried
CORNER_APPROACH = math.radians(CORNER_ACCEPT_DEG)  # steepest approach to a corner pocket, from its axis, a pot accepts
SIDE_APPROACH = math.radians(SIDE_ACCEPT_DEG)      # and to a side pocket (its mouth faces straight across the table)
CORNER_INSET = 0.5                 # corner aim point: this fraction of the capture radius into the table
POCKET_TOL = 0.6                   # a pot's accepted half-width: this fraction of the pocket's capture radius
SIGMA_MODEL = 0.012                # rad: object-ball direction error the ghost-ball model makes beyond the aim noise
MIN_AIM_SIGMA = math.radians(0.125)  # rad: the aim noise the leave is judged with at least (tournament level)
HAND_DCG = 0.3                     # m: cue-to-ghost distance assumed for a shooter with ball in hand
ROLL_MIN = 0.35                    # m/s: speed the object ball should still have at the pocket's line
V_NONE = 0.5                       # value of a table whose shooter has no pot (a safety battle: even)
V_FULL = 0.9                       # value of a table whose shooter has a sure pot (the run may still end)


class PocketModel:
    """The pockets as the kernels take them: aim points [P, 2], outward axes [P, 2], steepest approach [P] (rad)
    and accepted half-widths [P] (m)."""

    def __init__(self, view):
        pk = view.pockets
        W, L = view.table.width, view.table.length
        cx, cy = pk[:, 0] - W / 2, pk[:, 1] - L / 2
        ax = np.stack([np.sign(cx) * (np.abs(cx) > W / 4), np.sign(cy) * (np.abs(cy) > L / 4)], axis=1)
        ax = ax / np.linalg.norm(ax, axis=1, keepdims=True)
        corner = np.abs(ax[:, 0] * ax[:, 1]) > 0
        self.aims = np.ascontiguousarray(pk[:, :2] - (corner * CORNER_INSET * pk[:, 2])[:, None] * ax)
        self.axes = np.ascontiguousarray(ax)
        self.approach = np.where(corner, CORNER_APPROACH, SIDE_APPROACH).astype(np.float64)
        self.half = np.ascontiguousarray(POCKET_TOL * pk[:, 2])
        self.table, self.params = view.table, view.params

    def arrays(self):
        return self.aims, self.axes, self.approach, self.half


# --- geometry kernels (the ghost ball and the blocked-path test come from bots.geometry.lines) ------------------
@_jit
def _pot(pos, on, b, p, cx, cy, hand, pockets, lim):
    """The ghost-ball pot of ball ``b`` into pocket ``p`` with the cue ball at (cx, cy) (``hand``: placed at will):
    (success probability, aim phi, cue-ghost distance, ball-pocket distance, cut); probability 0 if it is not open.
    ``pockets``: ``PocketModel.arrays()``; ``lim``: (R, clear, max cut, sigma aim, sigma model, hand distance)."""
    aims, axes, approach, half = pockets
    R, clear, max_cut, sig_aim, sig_model, hand_dcg = lim
    ox, oy = pos[b, 0], pos[b, 1]
    dop = math.hypot(aims[p, 0] - ox, aims[p, 1] - oy)
    if dop < 1e-9:
        return 0.0, 0.0, 0.0, 0.0, 0.0
    ux, uy, gx, gy = ghost_ball(ox, oy, aims[p, 0], aims[p, 1], R, dop)
    app = math.acos(min(max(ux * axes[p, 0] + uy * axes[p, 1], -1.0), 1.0))
    if app > approach[p]:
        return 0.0, 0.0, 0.0, 0.0, 0.0
    d2 = (2 * R + clear) ** 2
    if hand:
        dcg, cut, phi = hand_dcg, 0.0, math.atan2(uy, ux)
    else:
        vx, vy = gx - cx, gy - cy
        dcg = math.hypot(vx, vy)
        if dcg < 1e-9:
            return 0.0, 0.0, 0.0, 0.0, 0.0
        cut = math.acos(min(max((vx * ux + vy * uy) / dcg, -1.0), 1.0))
        if cut > max_cut or blocked(pos, on, b, -1, cx, cy, gx, gy, d2):
            return 0.0, 0.0, 0.0, 0.0, 0.0
        phi = math.atan2(vy, vx)
    if blocked(pos, on, b, -1, ox, oy, aims[p, 0], aims[p, 1], d2):
        return 0.0, 0.0, 0.0, 0.0, 0.0
    sig = math.hypot(sig_aim * dcg / (2 * R * max(math.cos(cut), 0.2)), sig_model)
    tol = half[p] * (0.5 + 0.5 * math.cos(app)) / dop
    return math.erf(tol / (math.sqrt(2.0) * sig)), phi, dcg, dop, cut


@_jit
def _pot_table(pos, on, targets, cue, hand, pockets, lim, out):
    """Every legal ball's pot into every pocket, per table e (cue ball at ``cue[e]``): ``out``, ``PotArrays`` [n, B, P]."""
    prob, phi, dcg, dop, cut = out
    for e in range(pos.shape[0]):
        for b in range(1, pos.shape[1]):
            for p in range(pockets[0].shape[0]):
                prob[e, b, p] = 0.0
                if targets[e, b] and on[e, b]:
                    r = _pot(pos[e], on[e], b, p, cue[e, 0], cue[e, 1], hand[e], pockets, lim)
                    prob[e, b, p], phi[e, b, p], dcg[e, b, p], dop[e, b, p], cut[e, b, p] = r


@_jit
def _leave_ease(pos, on, targets, hand, pockets, lim, out):
    """The success probability of the shooter's easiest pot, per table [n] (0: none open, or no cue ball)."""
    for e in range(pos.shape[0]):
        best = 0.0
        if hand[e] or on[e, 0]:
            for b in range(1, pos.shape[1]):
                if targets[e, b] and on[e, b]:
                    for p in range(pockets[0].shape[0]):
                        q = _pot(pos[e], on[e], b, p, pos[e, 0, 0], pos[e, 0, 1], hand[e], pockets, lim)[0]
                        best = max(best, q)
        out[e] = best


def position_value(ease: np.ndarray, v_none: float = V_NONE, v_full: float = V_FULL) -> np.ndarray:
    """The chance the shooter of a table wins, from the ease of their best pot: ``v_none`` with no pot
    (a safety battle), ``v_full`` with a sure one (the run may still end)."""
    return v_none + (v_full - v_none) * ease


def balls_left(game: str, on: np.ndarray, targets: np.ndarray) -> np.ndarray:
    """[n] the object balls the next shooter still has to pocket, the game's ball included: every object ball
    on the table in rotation games; in a game of groups (8-ball) the legal targets on the table, plus the game's
    ball while it is not one."""
    rules = get_game(game).rules
    if not rules.groups:
        return on[:, 1:].sum(axis=1)
    tg = (targets & on)[:, 1:]
    return tg.sum(axis=1) + ~tg[:, rules.game_ball - 1]


class PotArrays(NamedTuple):
    """A pot table's outputs, each [n, B, P]: success probability, aim, cue-ghost and ball-pocket distances, cut."""
    prob: np.ndarray
    phi: np.ndarray
    dcg: np.ndarray
    dop: np.ndarray
    cut: np.ndarray
