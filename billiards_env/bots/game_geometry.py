"""Ghost-ball geometry for the game policies as numba kernels over tables.

The same constructions as ``bots.geometry`` (ghost ball, cut angle,
approach to the pocket, blocked paths: see its docstring), written as loops
so that a policy can weigh every legal target and pocket of a thousand
tables in well under a millisecond per table: ``best_pots`` (the easiest
open pot per table), ``straight_in_spots`` (a ball-in-hand spot for a
straight-in pot) and ``open_lines`` (whether the cue ball sees a legal
target).
"""
from __future__ import annotations

import math
from typing import NamedTuple

import numba
import numpy as np

_jit = numba.njit(cache=True, nogil=True)
MIN_LINE = 1e-12  # m: a ball this close to a pocket's aim point has no direction to it


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


@_jit
def _ghost(ox, oy, px, py, R):
    """The ghost-ball construction for potting the ball at (ox, oy) towards
    the aim point (px, py): the unit direction (ux, uy) ball -> aim point,
    the distance ``dop`` and the ghost ball's centre (gx, gy), 2R behind the
    ball on that line. ``dop`` is 0 (and the rest meaningless) when the ball
    is within ``MIN_LINE`` of the aim point."""
    ux, uy = px - ox, py - oy
    dop = math.hypot(ux, uy)
    if dop < MIN_LINE:
        return 0.0, 0.0, 0.0, ox, oy
    ux /= dop
    uy /= dop
    return ux, uy, dop, ox - 2 * R * ux, oy - 2 * R * uy


@_jit
def _seg_dist2(ax, ay, bx, by, px, py):
    """Squared distance from (px, py) to the segment a-b."""
    dx, dy = bx - ax, by - ay
    L2 = max(dx * dx + dy * dy, 1e-18)
    t = min(max(((px - ax) * dx + (py - ay) * dy) / L2, 0.0), 1.0)
    qx, qy = ax + t * dx - px, ay + t * dy - py
    return qx * qx + qy * qy


@_jit
def _blocked(pos, on, skip1, skip2, ax, ay, bx, by, d2):
    """Some ball on the table other than ``skip1``/``skip2`` (and the cue ball)
    lies closer than sqrt(d2) to the segment a-b."""
    for j in range(1, pos.shape[0]):
        if j == skip1 or j == skip2 or not on[j]:
            continue
        if _seg_dist2(ax, ay, bx, by, pos[j, 0], pos[j, 1]) < d2:
            return True
    return False


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
                ux, uy, dop, gx, gy = _ghost(ox, oy, aims[p, 0], aims[p, 1], R)
                if dop == 0.0:
                    continue
                if math.acos(min(max(-(ux * axes[p, 0] + uy * axes[p, 1]), -1.0), 1.0)) > limits[p]:
                    continue
                vx, vy = gx - cx, gy - cy
                dcg = math.hypot(vx, vy)
                if dcg < 1e-9:
                    continue
                c = math.acos(min(max((vx * ux + vy * uy) / dcg, -1.0), 1.0))
                if c > max_cut:
                    continue
                k = c + dist_weight * (dcg + dop)
                if k >= cost[e]:
                    continue
                if _blocked(pos[e], on[e], b, -1, cx, cy, gx, gy, d2) or \
                        _blocked(pos[e], on[e], b, -1, ox, oy, aims[p, 0], aims[p, 1], d2):
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
                ux, uy, dop, gx, gy = _ghost(ox, oy, aims[p, 0], aims[p, 1], R)
                if dop == 0.0:
                    continue
                if _blocked(pos[e], on[e], b, -1, ox, oy, aims[p, 0], aims[p, 1], d2):
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
                    if not ok or _blocked(pos[e], on[e], b, -1, x, y, gx, gy, d2):
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
            if targets[e, b] and on[e, b] and not _blocked(pos[e], on[e], b, -1, pos[e, 0, 0], pos[e, 0, 1],
                                                             pos[e, b, 0], pos[e, b, 1], d2):
                out[e] = True
                break


def pocket_limits(table, corner: float, side: float) -> np.ndarray:
    """The steepest approach angle accepted for each pocket (side or corner)."""
    from .geometry import side_pocket_mask
    return np.where(side_pocket_mask(table), side, corner).astype(np.float64)


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
            if d < best_open and not _blocked(pos[e], on[e], b, -1, pos[e, 0, 0], pos[e, 0, 1], pos[e, b, 0],
                                              pos[e, b, 1], d2):
                best_open, out[e] = d, b
        seen[e] = out[e] >= 0
        if out[e] < 0:
            out[e] = any_b
