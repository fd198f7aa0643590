"""Ghost-ball geometry on batched states (numpy, vectorised over tables).

The ghost-ball construction (Alciatore, "The Illustrated Principles of Pool
and Billiards", ghost-ball aiming): to send the object ball at O towards an aim point P,
the cue ball must arrive at the *ghost ball* G = O - 2R * unit(P - O), so the
cue aims at G. The cut angle theta is the angle between the cue's path
(C -> G) and the object ball's path (O -> P); the object ball leaves with
about v_c * cos(theta) * (1 + e_b) / 2 of the cue ball's speed v_c.

Speed model (used to pick a stroke speed from distances): a ball rolling a
distance d with rolling resistance mu_r loses v^2 by 2 mu_r g d; an object
ball leaves the collision sliding without spin and reaches rolling at 5/7 of
its launch speed; a cue ball struck with height offset b ends its slide at
5/7 (1 + b) of its strike speed (conservation of angular momentum about the
contact point, Alciatore's technical proofs on stun and roll).
"""
from __future__ import annotations

import math

import numpy as np

from ..envs.target_frame import CORNER_ACCEPT_DEG, SIDE_ACCEPT_DEG, side_pockets
from ..envs.target_frame import pocket_axes as _pocket_axes
from ..physics import PhysicsParams, Table
from ..physics.strike import Shots


def pocket_aim_points(table: Table, inset: float = 0.02) -> np.ndarray:
    """Aim points [P, 2], one per pocket, in the order of ``table.pockets``:
    the centre of each pocket's mouth pushed ``inset`` metres into the pocket
    (corner pockets along the diagonal, side pockets across the rail)."""
    w, l = table.width, table.length
    pts = []
    for (cx, cy, _), side in zip(table.pockets, side_pocket_mask(table)):
        if side:  # side pocket: the mouth centre is on the rail line
            x = 0.0 if cx < w / 2 else w
            pts.append((x + (-inset if x == 0.0 else inset), l / 2))
        else:  # corner pocket: on the diagonal, `inset` in from the corner point
            sx = 1.0 if cx < w / 2 else -1.0
            sy = 1.0 if cy < l / 2 else -1.0
            d = inset / math.sqrt(2.0)
            pts.append((cx + sx * d, cy + sy * d))
    return np.array(pts, dtype=np.float64)


def pocket_axes(table: Table) -> np.ndarray:
    """Unit vectors [P, 2] pointing from each pocket into the table (the
    direction a ball must come from to enter the pocket head-on)."""
    return _pocket_axes(table.pockets, table.width, table.length)  # the one the env's target frame shows


def _seg_point_dist(a: np.ndarray, b: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Distance from points p [..., 2] to segments a-b [..., 2] (broadcast)."""
    d = b - a
    L2 = np.maximum(np.sum(d * d, axis=-1), 1e-18)
    lam = np.clip(np.sum((p - a) * d, axis=-1) / L2, 0.0, 1.0)
    near = a + lam[..., None] * d
    return np.linalg.norm(p - near, axis=-1)


def ghost_shots(pos: np.ndarray, on_table: np.ndarray, target: np.ndarray, table: Table,
                params: PhysicsParams, inset: float = 0.02):
    """Every pocket's ghost-ball shot for each table.

    ``pos [E, B, 2]``, ``on_table [E, B]``, ``target [E]`` (object ball index).
    Returns a dict of arrays [E, P]: ``phi`` (cue aim angle), ``cut`` (cut
    angle, rad), ``d_cg`` (cue to ghost), ``d_op`` (object to pocket),
    ``approach`` (angle between the object ball's path and the pocket axis),
    ``blocked`` (another ball lies on either path) and ``valid``.
    """
    E, B, _ = pos.shape
    R = params.R
    ar = np.arange(E)
    cue = pos[:, 0]                       # [E, 2]
    obj = pos[ar, target]                 # [E, 2]
    P = pocket_aim_points(table, inset)   # [P, 2]
    axes = pocket_axes(table)
    op = P[None] - obj[:, None]           # [E, P, 2]
    d_op = np.linalg.norm(op, axis=-1)
    u_op = op / np.maximum(d_op, 1e-12)[..., None]
    ghost = obj[:, None] - 2 * R * u_op   # [E, P, 2]
    cg = ghost - cue[:, None]
    d_cg = np.linalg.norm(cg, axis=-1)
    u_cg = cg / np.maximum(d_cg, 1e-12)[..., None]
    cos_cut = np.clip(np.sum(u_cg * u_op, axis=-1), -1.0, 1.0)
    cut = np.arccos(cos_cut)
    phi = np.arctan2(cg[..., 1], cg[..., 0])
    approach = np.arccos(np.clip(np.sum(-u_op * axes[None], axis=-1), -1.0, 1.0))
    # Blocking: any other ball on the table within 2R of the cue->ghost path
    # or of the object->pocket path.
    blocked = np.zeros((E, len(P)), dtype=bool)
    for j in range(B):
        other = on_table[:, j] & (j != 0) & (j != target)
        if not other.any():
            continue
        pj = pos[:, j][:, None]  # [E, 1, 2]
        d1 = _seg_point_dist(cue[:, None], ghost, pj)
        d2 = _seg_point_dist(obj[:, None], P[None], pj)
        blocked |= other[:, None] & ((d1 < 2 * R) | (d2 < 2 * R))
    # The cue ball must not have to pass through the object ball itself: the
    # ghost must be reachable (cut < 90 deg).
    valid = (cut < math.radians(88.0)) & (d_cg > 1e-9)
    return dict(phi=phi, cut=cut, d_cg=d_cg, d_op=d_op, approach=approach, blocked=blocked,
                valid=valid, ghost=ghost)


def required_speed(d_cg, d_op, cut, params: PhysicsParams, b: float = 0.0, margin: float = 1.25,
                   v_arrive: float = 0.35) -> np.ndarray:
    """Cue-ball strike speed (m/s) that carries the object ball ``d_op`` metres
    to the pocket and still arriving at ``v_arrive`` m/s, times ``margin``.

    Object ball: launch speed v_o slides to 5/7 v_o, then rolls with
    deceleration mu_r g: v_o = 7/5 sqrt(v_arrive^2 + 2 mu_r g d_op). Cut
    transfer: v_c = v_o / (cos(cut) (1 + e_b) / 2). Cue ball to the ghost:
    strike speed v0 = sqrt(v_c^2 + 2 mu_r g d_cg) / f where f = 5/7 (1 + b)
    (capped to [5/7, 1]) is the slide loss of a centre/draw hit.
    """
    v_o = 1.4 * np.sqrt(v_arrive ** 2 + 2 * params.mu_r * params.g * d_op)
    v_c = v_o / (np.maximum(np.cos(cut), 0.15) * (1 + params.e_b) / 2)
    return np.minimum(margin * rolling_strike_speed(d_cg, v_c, params, b), params.max_speed)


def rolling_strike_speed(distance, v_arrive, params: PhysicsParams, b: float = 0.0) -> np.ndarray:
    """Strike speed (m/s) with which the cue ball, struck at height offset
    ``b``, arrives ``distance`` metres away at ``v_arrive``: the slide ends at
    f = 5/7 (1 + b) of the strike speed (capped to [5/7, 1]), then rolling
    resistance takes 2 mu_r g d of v^2 (not capped to the max speed)."""
    f = min(max(5.0 / 7.0 * (1 + b), 5.0 / 7.0), 1.0)
    return np.sqrt(np.square(v_arrive) + 2 * params.mu_r * params.g * np.asarray(distance)) / f


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
    E, B, _ = pos.shape
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
    for j in range(1, B):
        other = on_table[:, j] & (j != target)
        if other.any():
            blocked |= other[:, None] & (_seg_point_dist(cue[:, None], end, pos[:, j][:, None]) < 2 * R)
    return phi, path, blocked


def choose_pocket(shots: dict, cut_weight: float = 1.0, dist_weight: float = 0.35,
                  approach_limit_corner: float = math.radians(CORNER_ACCEPT_DEG),
                  approach_limit_side: float = math.radians(SIDE_ACCEPT_DEG),
                  side_mask: np.ndarray | None = None) -> np.ndarray:
    """Index [E] of the easiest pocket: smallest cut angle (rad) plus
    ``dist_weight`` x total distance (m), skipping blocked lines and pockets
    approached too steeply; if every pocket is excluded, the smallest cut."""
    cost = cut_weight * shots["cut"] + dist_weight * (shots["d_cg"] + shots["d_op"])
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


def side_pocket_mask(table: Table) -> np.ndarray:
    return side_pockets(table.pockets, table.length)


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
    E, B, _ = pos.shape
    ar = np.arange(E)
    cue, obj = pos[:, 0], pos[ar, target]
    lines = ((0, R), (0, width - R), (1, R), (1, length - R))
    phi = np.empty((E, 4))
    path = np.empty((E, 4))
    blocked = np.zeros((E, 4), dtype=bool)
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
        for cx, cy, r in np.asarray(pockets, dtype=np.float64):
            bad |= np.hypot(hit[:, 0] - cx, hit[:, 1] - cy) < r + KICK_POCKET_CLEAR
        # the second leg ends 2R short of the target's centre
        leg2 = obj - hit
        n2 = np.maximum(np.linalg.norm(leg2, axis=1), 1e-12)
        end = obj - 2 * R * leg2 / n2[:, None]
        for j in range(1, B):
            other = on_table[:, j] & (j != target)
            if other.any():
                pj = pos[:, j]
                bad |= other & ((_seg_point_dist(cue, hit, pj) < 2 * R) | (_seg_point_dist(hit, end, pj) < 2 * R))
        blocked[:, k] = bad
    return phi, path, blocked
