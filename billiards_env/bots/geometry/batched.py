"""The ghost-ball shots of a batch of tables (arrays over tables and
pockets): what the one-player bots, the lookahead and the agents' features
and shot menu build on.

``ghost_shots`` gives every pocket's ghost-ball shot (aim, cut, distances,
approach, blocked), ``choose_pocket`` / ``open_pots`` the easiest or the
open ones, ``ghost_ball_shot`` the shot played; ``contact_shots`` and
``kick_shots`` straight and one-rail hits on a ball. The lines are
``geometry.lines``' kernels; arccos and arctan2 are numpy's (vectorised).
"""
from __future__ import annotations

import math

import numba
import numpy as np

from ...contract.pockets import CORNER_ACCEPT_DEG, SIDE_ACCEPT_DEG
from ...physics import PhysicsParams, Table
from ...physics.strike import Shots
from .lines import (MIN_CUE_PATH, MIN_LINE, approach_cos, as_bool, blocked, cut_cos_of_units, ghost_ball,
                    line_length, paths_blocked, sqrt_test_d2)
from .pockets import pocket_aim_points, pocket_axes, side_pocket_mask
from .speed import required_speed

_jit = numba.njit(cache=True, nogil=True)


@_jit
def _ghost_lines(pos, on, target, pockets, R, d2, out):
    """Per table e and pocket p, the ghost-ball line of ``ghost_shots``
    before its arccos / arctan2 (which numpy takes): ``out`` = (d_op,
    ghost [E, P, 2], cue -> ghost vector cg [E, P, 2], d_cg, cos of the cut,
    cos of the approach, blocked). ``pockets``: (aims, axes)."""
    aims, axes = pockets
    d_op, ghost, cg, d_cg, cos_cut, cos_app, blk = out
    for e in range(pos.shape[0]):
        t = target[e]
        cx, cy, ox, oy = pos[e, 0, 0], pos[e, 0, 1], pos[e, t, 0], pos[e, t, 1]
        for p in range(aims.shape[0]):
            px, py = aims[p, 0], aims[p, 1]
            d = line_length(px - ox, py - oy)
            ux, uy, gx, gy = ghost_ball(ox, oy, px, py, R, max(d, MIN_LINE))
            vx, vy = gx - cx, gy - cy
            dcg = line_length(vx, vy)
            m = max(dcg, MIN_LINE)
            d_op[e, p], d_cg[e, p] = d, dcg
            ghost[e, p, 0], ghost[e, p, 1], cg[e, p, 0], cg[e, p, 1] = gx, gy, vx, vy
            cos_cut[e, p] = min(max(cut_cos_of_units(vx, vy, m, ux, uy), -1.0), 1.0)
            cos_app[e, p] = min(max(approach_cos(ux, uy, axes[p, 0], axes[p, 1]), -1.0), 1.0)
            blk[e, p] = blocked(pos[e], on[e], t, -1, cx, cy, gx, gy, d2) or \
                blocked(pos[e], on[e], t, -1, ox, oy, px, py, d2)


def ghost_shots(pos: np.ndarray, on_table: np.ndarray, target: np.ndarray, table: Table,
                params: PhysicsParams, inset: float = 0.02):
    """Every pocket's ghost-ball shot for each table.

    ``pos [E, B, 2]``, ``on_table [E, B]``, ``target [E]`` (object ball index).
    Returns a dict of arrays [E, P]: ``phi`` (cue aim angle), ``cut`` (cut
    angle, rad), ``d_cg`` (cue to ghost), ``d_op`` (object to pocket),
    ``approach`` (angle between the object ball's path and the pocket axis),
    ``blocked`` (another ball on the table lies within 2R of either path),
    ``valid`` (the cut is below 88 degrees, so the cue ball need not pass
    through the object ball to reach the ghost) and ``ghost`` [E, P, 2].
    """
    pos = np.ascontiguousarray(pos, dtype=np.float64)
    E = len(pos)
    R = params.R
    aims = np.ascontiguousarray(pocket_aim_points(table, inset))   # [P, 2]
    axes = np.ascontiguousarray(pocket_axes(table))
    P = len(aims)
    d_op, d_cg, cos_cut, cos_app = (np.empty((E, P)) for _ in range(4))
    ghost, cg = np.empty((E, P, 2)), np.empty((E, P, 2))
    blocked_ = np.empty((E, P), dtype=bool)
    _ghost_lines(pos, as_bool(on_table), np.ascontiguousarray(target, dtype=np.int64), (aims, axes), R,
                 sqrt_test_d2(2 * R), (d_op, ghost, cg, d_cg, cos_cut, cos_app, blocked_))
    cut = np.arccos(cos_cut)
    phi = np.arctan2(cg[..., 1], cg[..., 0])
    approach = np.arccos(cos_app)
    valid = (cut < math.radians(88.0)) & (d_cg > MIN_CUE_PATH)
    return dict(phi=phi, cut=cut, d_cg=d_cg, d_op=d_op, approach=approach, blocked=blocked_,
                valid=valid, ghost=ghost)


def contact_shots(pos: np.ndarray, on_table: np.ndarray, target: np.ndarray, fullness: np.ndarray, R: float,
                  width: float, length: float):
    """Straight shots that hit each table's ``target`` ball with impact
    parameter ``2R * fullness`` [F] (0 full, +-1 thinnest; the object ball
    leaves at asin(fullness) left (+) or right (-) of the cue ball's path, as
    in ``billiards_env.envs.impact``).

    Returns aims ``phi`` [E, F], the cue ball's ``path`` length to contact
    [E, F] and ``blocked`` [E, F]: another ball lies within 2R of that path,
    or the cue ball would touch a cushion line (closer than R to the edge of
    the ``width`` x ``length`` bed) where it meets the target.
    """
    E = len(pos)
    ar = np.arange(E)
    cue, obj = pos[:, 0], pos[ar, target]
    d_vec = obj - cue
    d = np.maximum(np.linalg.norm(d_vec, axis=1), 2 * R)
    b = 2 * R * np.asarray(fullness, dtype=np.float64)[None]          # [1, F]
    phi = np.arctan2(d_vec[:, 1], d_vec[:, 0])[:, None] - np.arcsin(np.clip(b / d[:, None], -1.0, 1.0))
    u = np.stack([np.cos(phi), np.sin(phi)], axis=-1)                  # [E, F, 2]
    along = np.sum(d_vec[:, None] * u, axis=-1)                        # target centre's projection on the path
    path = np.maximum(along - np.sqrt(np.maximum(4 * R * R - b * b, 0.0)), 0.0)
    end = cue[:, None] + path[..., None] * u
    blocked = ((end[..., 0] < R) | (end[..., 0] > width - R) | (end[..., 1] < R) | (end[..., 1] > length - R))
    _paths_blocked(pos, on_table, target, np.broadcast_to(cue[:, None], end.shape), end, R, blocked)
    return phi, path, blocked


def pot_cost(shots: dict, dist_weight: float, cut_weight: float = 1.0) -> np.ndarray:
    """How hard each pot of ``ghost_shots`` is [E, P]: ``cut_weight`` x the cut
    angle (rad) + ``dist_weight`` x the total distance (m), cue to ghost ball
    and object ball to pocket (the game kernels' ``best_pots`` rank pots the same way)."""
    return cut_weight * shots["cut"] + dist_weight * (shots["d_cg"] + shots["d_op"])


def choose_pocket(shots: dict, cut_weight: float = 1.0, dist_weight: float = 0.35,
                  approach_limit_corner: float = math.radians(CORNER_ACCEPT_DEG),
                  approach_limit_side: float = math.radians(SIDE_ACCEPT_DEG),
                  side_mask: np.ndarray | None = None) -> np.ndarray:
    """Index [E] of the easiest pocket: smallest cut angle (rad) plus
    ``dist_weight`` x total distance (m), skipping blocked lines and pockets
    approached too steeply; if every pocket is excluded, the smallest cut."""
    cost = pot_cost(shots, dist_weight, cut_weight)
    bad = ~open_pots(shots, side_mask, approach_limit_corner, approach_limit_side)
    cost_ok = np.where(bad, np.inf, cost)
    best = np.argmin(cost_ok, axis=1)
    none = ~np.isfinite(cost_ok.min(axis=1))
    if none.any():
        fallback = np.argmin(np.where(shots["valid"], shots["cut"], np.inf), axis=1)
        best = np.where(none, fallback, best)
    return best


def open_pots(shots: dict, side_mask: np.ndarray | None = None,
              approach_limit_corner: float = math.radians(CORNER_ACCEPT_DEG),
              approach_limit_side: float = math.radians(SIDE_ACCEPT_DEG)) -> np.ndarray:
    """[E, P]: the ghost-ball shot (``ghost_shots``) into each pocket is
    possible (cut below 88 degrees), its paths are clear of other balls, and
    (with ``side_mask``, ``side_pocket_mask``) the object ball comes in within
    the pocket's acceptance angle."""
    ok = shots["valid"] & ~shots["blocked"]
    if side_mask is not None:
        ok &= shots["approach"] <= np.where(side_mask[None], approach_limit_side, approach_limit_corner)
    return ok


def ghost_ball_shot(pos: np.ndarray, on_table: np.ndarray, target: np.ndarray, table: Table,
                    params: PhysicsParams, b: float = 0.0, margin: float = 1.0, dist_weight: float = 0.5,
                    inset: float = 0.0) -> Shots:
    """The ghost-ball shot of each table: aim at the ghost ball of the easiest
    pocket (``choose_pocket``), ``required_speed`` times ``margin``, no side
    spin, height offset ``b``."""
    sh = ghost_shots(pos, on_table, target, table, params, inset)
    k = choose_pocket(sh, dist_weight=dist_weight, side_mask=side_pocket_mask(table))
    ar = np.arange(len(pos))
    phi = sh["phi"][ar, k]
    speed = required_speed(sh["d_cg"][ar, k], sh["d_op"][ar, k], sh["cut"][ar, k], params, b=b, margin=margin)
    return Shots(phi, speed, np.zeros_like(phi), np.full_like(phi, b))


# m beyond a pocket's capture circle: a rebound point closer than this may meet
# the pocket's jaw (whose cushion turns into the pocket), not straight rail.
KICK_POCKET_CLEAR = 0.08


def kick_shots(pos: np.ndarray, on_table: np.ndarray, target: np.ndarray, R: float, width: float, length: float,
               pockets: np.ndarray):
    """One-rail kicks at each table's ``target`` ball, one per rail (x = R,
    x = width - R, y = R, y = length - R: the lines the ball's centre
    reaches on each cushion): the cue ball aims at the target's mirror image
    across the rail and, reflected like light, rolls on to a full hit.
    Spin and cushion friction bend real rebounds (the policy learns which
    kicks work); geometry only says which are possible.

    Returns aims ``phi`` [E, 4], the cue ball's ``path`` length to contact
    (both legs) [E, 4] and ``blocked`` [E, 4]: another ball within 2R of
    either leg, the rebound point off the rail or within ``KICK_POCKET_CLEAR``
    of a pocket's capture circle (``pockets`` [P, 3]: x, y, r).
    """
    E = len(pos)
    ar = np.arange(E)
    cue, obj = pos[:, 0], pos[ar, target]
    lines = ((0, R), (0, width - R), (1, R), (1, length - R))
    pk = np.asarray(pockets, dtype=np.float64)
    phi = np.empty((E, 4))
    path = np.empty((E, 4))
    blocked = np.zeros((E, 4), dtype=bool)
    hits, ends = np.empty((E, 4, 2)), np.empty((E, 4, 2))
    for k, (axis, c) in enumerate(lines):
        image = obj.copy()
        image[:, axis] = 2 * c - obj[:, axis]
        d = image - cue
        phi[:, k] = np.arctan2(d[:, 1], d[:, 0])
        # where the path crosses the rail line (the cue and the target lie on the table side of it)
        den = d[:, axis]
        lam = np.where(np.abs(den) > 1e-12, (c - cue[:, axis]) / np.where(den == 0, 1.0, den), -1.0)
        hit = cue + np.clip(lam, 0.0, 1.0)[:, None] * d
        total = np.linalg.norm(d, axis=1)
        path[:, k] = np.maximum(total - 2 * R, 0.0)
        other_axis = 1 - axis
        span = width if other_axis == 0 else length
        bad = (lam <= 0.0) | (lam >= 1.0) | (hit[:, other_axis] < R) | (hit[:, other_axis] > span - R)
        if len(pk):   # near a pocket's capture circle
            bad |= (np.hypot(hit[:, 0, None] - pk[:, 0], hit[:, 1, None] - pk[:, 1])
                    < pk[:, 2] + KICK_POCKET_CLEAR).any(axis=1)
        # the second leg ends 2R short of the target's centre
        leg2 = obj - hit
        n2 = np.maximum(np.linalg.norm(leg2, axis=1), 1e-12)
        hits[:, k], ends[:, k] = hit, obj - 2 * R * leg2 / n2[:, None]
        blocked[:, k] = bad
    # both legs of the four kicks in two calls (a leg already bad is not tested again)
    _paths_blocked(pos, on_table, target, np.broadcast_to(cue[:, None], hits.shape), hits, R, blocked)
    _paths_blocked(pos, on_table, target, hits, ends, R, blocked)
    return phi, path, blocked


def _paths_blocked(pos, on_table, target, a, b, R: float, out: np.ndarray) -> None:
    """``out`` [E, K] |= another ball on the table (not the cue ball, not
    ``target``) lies within 2R of the path a-b [E, K, 2] (``lines.paths_blocked``)."""
    paths_blocked(np.ascontiguousarray(pos, dtype=np.float64), as_bool(on_table),
                  np.ascontiguousarray(target, dtype=np.int64), np.ascontiguousarray(a, dtype=np.float64),
                  np.ascontiguousarray(b, dtype=np.float64), sqrt_test_d2(2 * R), out)
