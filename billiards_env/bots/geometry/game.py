"""The game bots' searches over tables, as numba kernels: the ghost-ball
lines (``geometry.lines``) of every legal target and pocket of a thousand
tables weighed in well under a millisecond per table. ``best_pots`` (the
easiest open pot per table), ``straight_in_spots`` (a ball-in-hand spot for
a straight-in pot), ``open_lines`` (whether the cue ball sees a legal
target) and ``nearest_open_target``. Lengths are ``math.hypot``, angles
libm's ``acos`` / ``atan2`` (the bots' choices were measured with them).
"""
from __future__ import annotations

import math
from typing import NamedTuple

import numba

from .lines import MIN_CUE_PATH, MIN_LINE, approach_cos, blocked, cut_cos, ghost_ball

_jit = numba.njit(cache=True, nogil=True)


class PotLimits(NamedTuple):
    """What makes a pot open in ``best_pots``: ball radius ``R`` (m), paths
    clear of other balls by 2R + ``clear`` (m), cut at most ``max_cut``
    (rad); cost = cut + ``dist_weight`` x (distances, m)."""

    R: float
    clear: float
    max_cut: float
    dist_weight: float


class SpotLimits(NamedTuple):
    """Where ``straight_in_spots`` may put the cue ball: inside a table
    ``width`` wide (m), ball radius ``R``, 2R + ``clear`` from every ball."""

    width: float
    R: float
    clear: float


def best_pots(pos, on, targets, aims, axes, limits, lim: PotLimits, out: dict) -> None:
    """``_best_pots`` writing into ``out``'s arrays ``cost``, ``phi``,
    ``d_cg``, ``d_op``, ``cut``, ``pocket``, ``ball`` [n]."""
    _best_pots(pos, on, targets, (aims, axes, limits), tuple(lim),
               (out["cost"], out["phi"], out["d_cg"], out["d_op"], out["cut"], out["pocket"], out["ball"]))


@_jit
def _best_pots(pos, on, targets, pockets, lim, out):
    """Per table e: among legal targets b (``targets[e, b]``) and pockets p,
    the open ghost-ball pot of least ``cut + dist_weight (d_cg + d_op)``:
    cut below ``max_cut``, approach to the pocket within ``limits[p]``, both
    paths (cue -> ghost, ball -> aim point) clear of other balls by 2R +
    ``clear``. Writes the cost (inf: none), aim ``phi``, distances, cut,
    pocket, ball. ``pockets``: (aims, axes, limits); ``lim``: a
    ``PotLimits``; ``out``: (cost, phi, d_cg, d_op, cut, pocket, ball)."""
    aims, axes, limits = pockets
    R, clear, max_cut, dist_weight = lim
    cost, phi, d_cg, d_op, cut, pocket, ball = out
    d2 = (2.0 * R + clear) ** 2
    for e in range(pos.shape[0]):
        cost[e] = math.inf
        ball[e] = -1
        cx, cy = pos[e, 0, 0], pos[e, 0, 1]
        for b in range(1, pos.shape[1]):
            if not (targets[e, b] and on[e, b]):
                continue
            ox, oy = pos[e, b, 0], pos[e, b, 1]
            for p in range(aims.shape[0]):
                dop = math.hypot(aims[p, 0] - ox, aims[p, 1] - oy)
                if dop < MIN_LINE:
                    continue
                ux, uy, gx, gy = ghost_ball(ox, oy, aims[p, 0], aims[p, 1], R, dop)
                if math.acos(min(max(approach_cos(ux, uy, axes[p, 0], axes[p, 1]), -1.0), 1.0)) > limits[p]:
                    continue
                vx, vy = gx - cx, gy - cy
                dcg = math.hypot(vx, vy)
                if dcg < MIN_CUE_PATH:
                    continue
                c = math.acos(min(max(cut_cos(vx, vy, dcg, ux, uy), -1.0), 1.0))
                if c > max_cut:
                    continue
                k = c + dist_weight * (dcg + dop)
                if k >= cost[e]:
                    continue
                if blocked(pos[e], on[e], b, -1, cx, cy, gx, gy, d2) or \
                        blocked(pos[e], on[e], b, -1, ox, oy, aims[p, 0], aims[p, 1], d2):
                    continue
                cost[e], phi[e], d_cg[e], d_op[e], cut[e], pocket[e], ball[e] = (k, math.atan2(vy, vx), dcg, dop, c,
                                                                                  p, b)


def straight_in_spots(pos, on, targets, y_hi, aims, backs, lim: SpotLimits, pockets, spot) -> int:
    """``_straight_in_spots`` (a ``SpotLimits`` for the table and clearance)."""
    return _straight_in_spots(pos, on, targets, y_hi, aims, backs, tuple(lim), pockets, spot)


@_jit
def _straight_in_spots(pos, on, targets, y_hi, aims, backs, lim, pockets, spot):
    """Per table e: a cue-ball spot for a straight-in pot of a legal target,
    ``backs[k]`` metres behind its ghost ball on the line pocket -> ball,
    inside the cushions, at most ``y_hi[e]`` along the table, more than 2R +
    ``clear`` from every other ball and off every pocket, with both paths
    clear; the least ``d_op + backs / 2`` wins. Leaves ``spot[e]`` unchanged
    if there is none; returns the number of tables that found one.
    ``lim``: (width, R, clear)."""
    width, R, clear = lim
    d2 = 4.0 * R * R
    md2 = (2.0 * R + clear) ** 2
    found = 0
    for e in range(pos.shape[0]):
        best = math.inf
        for b in range(1, pos.shape[1]):
            if not (targets[e, b] and on[e, b]):
                continue
            ox, oy = pos[e, b, 0], pos[e, b, 1]
            for p in range(aims.shape[0]):
                dop = math.hypot(aims[p, 0] - ox, aims[p, 1] - oy)
                if dop < MIN_LINE:
                    continue
                ux, uy, gx, gy = ghost_ball(ox, oy, aims[p, 0], aims[p, 1], R, dop)
                if blocked(pos[e], on[e], b, -1, ox, oy, aims[p, 0], aims[p, 1], d2):
                    continue
                for k in range(backs.shape[0]):
                    cost = dop + 0.5 * backs[k]
                    if cost >= best:
                        continue
                    x, y = gx - backs[k] * ux, gy - backs[k] * uy
                    if x < R + clear or x > width - R - clear or y < R + clear or y > y_hi[e]:
                        continue
                    ok = True
                    for j in range(1, pos.shape[1]):
                        if on[e, j]:
                            dx, dy = x - pos[e, j, 0], y - pos[e, j, 1]
                            if dx * dx + dy * dy < md2:
                                ok = False
                                break
                    for q in range(pockets.shape[0]):
                        if math.hypot(x - pockets[q, 0], y - pockets[q, 1]) < pockets[q, 2] + R:
                            ok = False
                    if not ok or blocked(pos[e], on[e], b, -1, x, y, gx, gy, d2):
                        continue
                    best = cost
                    spot[e, 0], spot[e, 1] = x, y
        if best < math.inf:
            found += 1
    return found


@_jit
def open_lines(pos, on, targets, R, out):
    """Per table: the cue ball has a straight line (clear of other balls by 2R)
    to the centre of some legal target on the table."""
    d2 = 4.0 * R * R
    for e in range(pos.shape[0]):
        out[e] = False
        for b in range(1, pos.shape[1]):
            if targets[e, b] and on[e, b] and not blocked(pos[e], on[e], b, -1, pos[e, 0, 0], pos[e, 0, 1],
                                                             pos[e, b, 0], pos[e, b, 1], d2):
                out[e] = True
                break


@_jit
def nearest_open_target(pos, on, targets, R, out, seen):
    """Per table: the nearest legal target the cue ball sees along a line
    clear of other balls by 2R (``seen`` True); if none, the nearest legal
    target (``seen`` False); -1 if there is no legal target on the table."""
    d2 = 4.0 * R * R
    for e in range(pos.shape[0]):
        best_open, best_any = math.inf, math.inf
        out[e] = -1
        any_b = -1
        for b in range(1, pos.shape[1]):
            if not (targets[e, b] and on[e, b]):
                continue
            d = math.hypot(pos[e, b, 0] - pos[e, 0, 0], pos[e, b, 1] - pos[e, 0, 1])
            if d < best_any:
                best_any, any_b = d, b
            if d < best_open and not blocked(pos[e], on[e], b, -1, pos[e, 0, 0], pos[e, 0, 1], pos[e, b, 0],
                                              pos[e, b, 1], d2):
                best_open, out[e] = d, b
        seen[e] = out[e] >= 0
        if out[e] < 0:
            out[e] = any_b
