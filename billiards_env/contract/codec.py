"""``ActionCodec``: the game envs' action convention for a batch of tables,
in one place.

A game action is 8 numbers in [-1, 1] (see ``envs.games.spaces``): the aim
relative to the table's aim origin (a0, in units of pi), the cue's draw
(a1, over the env's draw range), the tip's side and height offsets (a2, a3,
over the miscue limit), the cue ball's placement with ball in hand (a4, a5,
over the free span of the bed), a declaration (a6 > 0; in the games whose
rules replace balls on a declaration, ``Rules.replaces``, 0 < a6 <=
``PASS_LEVEL`` has the balls replaced: snooker's after a foul and a miss,
three-cushion's when the cue ball touches a ball; a6 > ``PASS_LEVEL``
there is a pass, snooker's offender put back in), the called
pocket (a7, six equal bins), in 10-ball only, the called ball (a8,
``n_balls`` equal bins; 0 a safety), and, only where the equipment
simulates balls in flight (``Effects(airborne=True)``), the cue's elevation
as the last component (a8, 10-ball a9): theta = (a + 1) / 2 *
``MAX_ACTION_ELEVATION`` (60 degrees), a = -1 the level cue. The aim origin is the direction from the cue
ball to the table's nominal target (the lowest legal ball; on the break, the
foot spot), so it moves with a placed cue ball.

The env encodes a bot's ``ShotPlan`` with it (``GameCore.actions_of``), and a
learned bot that acts in the env's action space encodes its shots with the
one its ``GameView`` carries (``view.codec``): the same arithmetic either way.
"""
from __future__ import annotations

import dataclasses
import math
from typing import Callable

import numba
import numpy as np

from ..physics import PhysicsParams, Table
from ..physics.noise import clip_offset as _clip_offset
from ..physics.strike import Shots, draw_to_speed, speed_to_draw
from .plan import ShotPlan

ACTION_DIM = 8
N_POCKETS = 6
# Where the rules replace balls on a declaration (snooker, three-cushion) a6 carries two: above this a pass
# (snooker's offender put back in, as a6 > 0 means in the other games, so a bot's encoded pass, a6 = 1, keeps
# its meaning), in (0, this] the balls replaced; the midpoint of (0, 1] leaves each an equal share of the
# positive half.
PASS_LEVEL = 0.5
REPLACE_ACTION = 0.25  # the a6 a replace declaration is encoded as (the middle of its share; float32-exact)
# The steepest cue an env's action can elevate (the last component, where the effects have airborne on): 60
# degrees spans the jump strokes (a jump cue at 30-50 degrees) and the half massés; a full massé's near-vertical
# cue (physics.strike.MAX_ELEVATION, 90 degrees) is a plan's (``ShotPlan.theta``), not an action's.
MAX_ACTION_ELEVATION_DEG = 60.0
MAX_ACTION_ELEVATION = math.radians(MAX_ACTION_ELEVATION_DEG)

# The shot mapping's per-table passes, fused (numpy would take one pass, and a temporary, per operation).
_jit = numba.njit(cache=True, nogil=True)


@_jit
def _context(pos, tgt, pockets, diag, aim, phi, ang):
    """Per table with legal target ``tgt`` (-1 none): Phi = -(its distance to
    the nearest pocket centre) / diag (0 without target or pockets) into
    ``phi`` and, if ``aim``, the direction cue ball -> target (rad, 0 without
    target) into ``ang``."""
    for e in range(pos.shape[0]):
        t = tgt[e]
        phi[e] = 0.0
        ang[e] = 0.0
        if t < 0:
            continue
        if aim:
            ang[e] = math.atan2(pos[e, t, 1] - pos[e, 0, 1], pos[e, t, 0] - pos[e, 0, 0])
        if pockets.shape[0] == 0:
            continue
        d2 = math.inf
        for p in range(pockets.shape[0]):
            dx, dy = pos[e, t, 0] - pockets[p, 0], pos[e, t, 1] - pockets[p, 1]
            d2 = min(d2, dx * dx + dy * dy)
        phi[e] = -math.sqrt(d2) / diag


@_jit
def _action_to_shot(actions, base, lo, hi, limit, out):
    """Actions [n, 4] -> rows (phi, draw, a, b) of ``out`` [4, n]: clipped to
    [-1, 1]; phi = base + pi * a0 wrapped to [-pi, pi); (a, b) scaled
    radially just inside the miscue limit (``_clip_offset``)."""
    for e in range(actions.shape[0]):
        a0 = min(max(actions[e, 0], -1.0), 1.0)
        a1 = min(max(actions[e, 1], -1.0), 1.0)
        a2 = min(max(actions[e, 2], -1.0), 1.0)
        a3 = min(max(actions[e, 3], -1.0), 1.0)
        out[0, e] = (base[e] + math.pi * a0 + math.pi) % (2 * math.pi) - math.pi
        out[1, e] = lo + (a1 + 1.0) * 0.5 * (hi - lo)
        out[2, e], out[3, e] = _clip_offset(a2 * limit, a3 * limit, limit)


def shot_actions(shots, origin, min_draw: float, params, log_speed: bool = False) -> np.ndarray:
    """The inverse of ``_action_to_shot`` on the unclipped range: ``Shots``
    (absolute aim phi, speed, tip offsets a, b; arrays [n] or scalars) ->
    actions a0..a3 [n, 4], not yet clipped: a0 the aim relative to
    ``origin`` [n] over pi, wrapped to [-1, 1); a1 the cue draw between
    ``min_draw`` and ``params.max_draw`` (linear, or geometric with
    ``log_speed``); a2, a3 the offsets over the miscue limit. The one
    mapping of the one-player tasks and the games' ``ActionCodec``."""
    n = len(origin)
    phi, speed, a, b = (np.broadcast_to(np.asarray(v, dtype=np.float64), (n,)) for v in shots)
    rel = (phi - origin) / math.pi
    rel = (rel + 1.0) % 2.0 - 1.0
    lo, hi, lim = min_draw, params.max_draw, params.miscue_limit
    draw = speed_to_draw(speed, params)
    if log_speed:
        a1 = 2.0 * np.log(np.maximum(draw, lo) / lo) / math.log(hi / lo) - 1.0
    else:
        a1 = 2.0 * (draw - lo) / (hi - lo) - 1.0
    return np.stack([rel, a1, a / lim, b / lim], axis=1)



@dataclasses.dataclass(frozen=True, eq=False)
class ShotContext:
    """What every shot of the current tables is relative to, arrays [N]:
    ``target`` the legal target ball (int, -1 if none), ``aim_origin`` the
    direction (rad) that action a0 = 0 aims at (cue ball -> target for
    ``aim="relative"``, 0 for ``"absolute"`` or without target) and
    ``potential`` Phi = -(distance of the target to its nearest pocket) /
    table diagonal (0 without target), the shaping potential."""

    target: np.ndarray
    aim_origin: np.ndarray
    potential: np.ndarray




def placement_to_actions(xy: np.ndarray, table: Table, params: PhysicsParams) -> np.ndarray:
    """Cue-ball positions [k, 2] (m) -> action components a4, a5 [k, 2]: the
    ball centre's free span of the bed mapped onto [-1, 1]."""
    R_ = params.R
    span = np.array([table.width - 2 * R_, table.length - 2 * R_])
    return np.clip(2.0 * (np.asarray(xy) - R_) / span - 1.0, -1.0, 1.0)


@_jit
def _aims(cue, aim, out):
    """The direction (rad) from each cue ball ``cue`` [k, 2] to ``aim`` [k, 2]
    into ``out`` [k]: ``_context``'s arithmetic, so an origin recomputed for a
    placed cue ball is the one the env's shot context gives."""
    for e in range(cue.shape[0]):
        out[e] = math.atan2(aim[e, 1] - cue[e, 1], aim[e, 0] - cue[e, 0])


def aim_origins(cue: np.ndarray, aim: np.ndarray, is_break: np.ndarray) -> np.ndarray:
    """The aim origins [k] of cue balls ``cue`` [k, 2] looking at ``aim``
    [k, 2]: the nominal target's centre (``_context``), or on the break the
    foot spot (numpy's arctan2, as ``GameCore.shot_context`` computes it)."""
    out = np.empty(len(cue))
    _aims(np.ascontiguousarray(cue, dtype=np.float64), np.ascontiguousarray(aim, dtype=np.float64), out)
    b = np.nonzero(is_break)[0]
    if len(b):
        out[b] = np.arctan2(aim[b, 1] - cue[b, 1], aim[b, 0] - cue[b, 0])
    return out


@dataclasses.dataclass(frozen=True, eq=False)
class ActionCodec:
    """The action convention of ``n`` tables. ``origin`` [n]: the aim origin
    with the cue ball where it lies; ``aim_point`` [n, 2]: the point the
    origin looks at (the nominal target's centre, or the foot spot on the
    break); ``in_hand`` [n]: the shooter places the cue ball; ``place``:
    ``(xy [k, 2], rows [k]) -> (spots, moved)``, the legal ball-in-hand spots
    nearest to ``xy`` on rows ``rows``; the table, the physics and the env's
    shortest draw (``min_draw``); ``nominal`` [n] the nominal target;
    ``ball_dim``: the action's size where it carries a called ball (10-ball;
    0 elsewhere), the elevation not counted; ``n_balls``; ``cue`` [n, 2]
    where the cue ball lies; ``is_break`` [n]; ``max_elevation``: the cue's
    elevation at the last component's +1 (rad; 0, the default: the action
    has no elevation component, the planar envs')."""

    origin: np.ndarray
    aim_point: np.ndarray
    in_hand: np.ndarray
    place: Callable
    table: Table
    params: PhysicsParams
    min_draw: float
    nominal: np.ndarray
    ball_dim: int
    n_balls: int
    cue: np.ndarray
    is_break: np.ndarray
    replaces: bool = False  # a6 carries a replace declaration below PASS_LEVEL (snooker, three-cushion)
    max_elevation: float = 0.0  # > 0: the last component is the cue's elevation (Effects(airborne=True))

    @property
    def n(self) -> int:
        return len(self.origin)

    def origin_from(self, cue: np.ndarray, rows: np.ndarray) -> np.ndarray:
        """The aim origin of rows ``rows`` with the cue ball at ``cue`` [k, 2]."""
        return aim_origins(cue, self.aim_point[rows], self.is_break[rows])

    def placement_of(self, a: np.ndarray) -> np.ndarray:
        """Action components a4, a5 of actions [k, >= 6] -> cue-ball positions [k, 2] (m)."""
        R_, t = self.params.R, self.table
        return R_ + (a[:, 4:6] + 1.0) / 2.0 * np.array([t.width - 2 * R_, t.length - 2 * R_])

    def called_pocket(self, a: np.ndarray) -> np.ndarray:
        """a7 -> the called pocket (six equal bins, in ``Table.pockets`` order)."""
        return np.minimum(np.floor((a[:, 7] + 1.0) / 2.0 * N_POCKETS), N_POCKETS - 1).astype(np.int64)

    def called_ball(self, a: np.ndarray) -> np.ndarray:
        """a8 -> the called ball (0: a called safety; 10-ball)."""
        k = self.n_balls  # calls: 0 (safety) and the object balls 1 .. n_balls - 1
        return np.minimum(np.floor((a[:, 8] + 1.0) / 2.0 * k), k - 1).astype(np.int64)

    def shots_of(self, actions: np.ndarray, origin: np.ndarray | None = None) -> Shots:
        """a0..a3 of actions [n, >= 4] (clipped to [-1, 1]) -> ``Shots``, the aim relative to ``origin`` [n]
        (default the codec's: the cue ball where it lies)."""
        actions = np.asarray(actions, dtype=np.float64)
        a = np.ascontiguousarray(actions[:, :4])
        out = np.empty((4, len(a)))
        _action_to_shot(a, self.origin if origin is None else origin, self.min_draw, self.params.max_draw,
                        self.params.miscue_limit, out)
        theta = self.elevation_of(actions) if self.max_elevation else None
        return Shots.of_arrays(out[0], draw_to_speed(out[1], self.params), out[2], out[3], theta)

    @property
    def elevation_index(self) -> int:
        """The action component that carries the cue's elevation (the last; meaningful where ``max_elevation``)."""
        return self.ball_dim or ACTION_DIM

    def elevation_of(self, a: np.ndarray) -> np.ndarray:
        """The elevation component of actions [k, action_dim] (clipped to [-1, 1]) -> theta [k] (rad):
        (a + 1) / 2 * ``max_elevation``, -1 the level cue."""
        return (np.clip(a[:, self.elevation_index], -1.0, 1.0) + 1.0) * 0.5 * self.max_elevation

    def elevation_to_actions(self, theta) -> np.ndarray:
        """``elevation_of``'s inverse: elevations [k] (rad, 0 .. ``max_elevation``) -> the component [k]."""
        return 2.0 * np.asarray(theta, dtype=np.float64) / self.max_elevation - 1.0

    def actions_of_shots(self, shots: Shots) -> np.ndarray:
        """``shots_of``'s inverse on the unclipped range: ``Shots`` -> a0..a3 [n, 4] (float64, clipped)."""
        return np.clip(shot_actions(shots, self.origin, self.min_draw, self.params), -1.0, 1.0)

    def decode(self, actions: np.ndarray) -> tuple[ShotPlan, np.ndarray]:
        """The ``ShotPlan`` the env plays for actions [n, action_dim] (clipped
        to [-1, 1] first): placements made legal (NaN without ball in hand),
        the aim absolute (relative to the origin seen from the placed cue
        ball), the declaration, the called pocket and ball; and ``moved``
        [n], where a placement had to move to be legal. ``encode``'s inverse
        on the unclipped range; what ``GameCore.step`` plays."""
        a = np.clip(np.asarray(actions, dtype=np.float64), -1.0, 1.0)
        n = self.n
        placement, moved = np.full((n, 2), np.nan), np.zeros(n, dtype=bool)
        origin = self.origin.copy()
        h = np.nonzero(self.in_hand)[0]
        if len(h):
            placement[h], moved[h] = self.place(self.placement_of(a[h]), h)
            origin[h] = self.origin_from(placement[h], h)
        shots = self.shots_of(a, origin)
        ball = self.called_ball(a) if self.ball_dim else None
        if not self.replaces:
            return ShotPlan.of(shots, placement, a[:, 6] > 0, self.called_pocket(a), ball), moved
        declare, replace = a[:, 6] > PASS_LEVEL, (a[:, 6] > 0) & (a[:, 6] <= PASS_LEVEL)
        return ShotPlan.of(shots, placement, declare, self.called_pocket(a), ball, replace), moved

    def placement_to_actions(self, xy: np.ndarray) -> np.ndarray:
        """Cue-ball positions [k, 2] (m) -> action components a4, a5 [k, 2]."""
        return placement_to_actions(xy, self.table, self.params)

    @property
    def action_dim(self) -> int:
        return (self.ball_dim or ACTION_DIM) + (self.max_elevation > 0)

    def encode(self, shots, placement=None, declare=None, pocket=None, ball=None, replace=None) -> np.ndarray:
        """Actions [n, action_dim] (float64) that play ``shots`` (absolute aim) with the
        cue ball at ``placement`` [n, 2] (rows without ball in hand are
        ignored; NaN rows: where it lies; an illegal spot is moved to the
        nearest legal one first, so the aim stays absolute), ``declare`` [n]
        (push-out or pass), the called ``pocket`` [n] and, in 10-ball, the
        called ``ball`` [n] (0 a safety; -1 or None: the lowest legal ball)
        and, in snooker and three-cushion, ``replace`` [n] (the balls
        replaced; it wins over ``declare``, as ``play_turn`` plays them).
        The cue's elevation is the shots' (``Shots.theta``), in [0,
        ``max_elevation``]; an elevated shot on a codec without the component
        (the planar envs) is a ValueError."""
        n = self.n
        theta = np.broadcast_to(np.asarray(getattr(shots, "theta", 0.0), dtype=np.float64), (n,))
        self._check_elevation(theta)
        out = np.zeros((n, self.action_dim))
        out[:, 4:6] = self.placement_to_actions(self.cue)
        origin = self.origin.copy()
        if placement is not None:
            placement = np.array(placement, dtype=np.float64)
            has = ~np.isnan(placement[:, 0]) & self.in_hand
            rows = np.nonzero(has)[0]
            if len(rows):
                placement[has], _ = self.place(placement[has], rows)
            out[:, 4:6] = self.placement_to_actions(np.where(has[:, None], placement, self.cue))
            if len(rows):
                origin[has] = self.origin_from(placement[has], rows)
        out[:, :4] = shot_actions(shots, origin, self.min_draw, self.params)
        out[:, 6] = -1.0 if declare is None else np.where(declare, 1.0, -1.0)
        if self.replaces and replace is not None:
            out[:, 6] = np.where(replace, REPLACE_ACTION, out[:, 6])
        if pocket is not None:
            out[:, 7] = -1.0 + (2.0 * np.asarray(pocket) + 1.0) / N_POCKETS
        if self.ball_dim:
            ball = self.nominal if ball is None else np.where(np.asarray(ball) < 0, self.nominal, ball)
            out[:, 8] = -1.0 + (2.0 * ball + 1.0) / self.n_balls
        if self.max_elevation:
            out[:, self.elevation_index] = self.elevation_to_actions(theta)
        return np.clip(out, -1.0, 1.0)

    def _check_elevation(self, theta: np.ndarray) -> None:
        """A ValueError naming an elevation the action cannot carry: any on a codec without the component,
        or one outside [0, ``max_elevation``]."""
        nonzero = theta != 0
        if not nonzero.any():
            return
        r = int(np.argmax(nonzero))
        if not self.max_elevation:
            raise ValueError(f"shot {r} elevates the cue (theta {theta[r]} rad) but this env's action has no "
                             "elevation: make the env with effects={'airborne': True}")
        bad = ~np.isfinite(theta) | (theta < 0) | (theta > self.max_elevation * (1 + 1e-12))
        if bad.any():
            r = int(np.argmax(bad))
            raise ValueError(f"the cue's elevation must lie in [0, {self.max_elevation:.6g}] rad (the action's "
                             f"{math.degrees(self.max_elevation):g} degrees), got {theta[r]} at shot {r}")

    def encode_plan(self, plan) -> np.ndarray:
        """The actions [n, 8] of a bot's ``ShotPlan`` (checked first), rounded
        through float32, the action space's dtype, as a policy's actions are.
        A plan that strikes another ball than the cue ball (``ShotPlan.struck``)
        has no action: a ValueError."""
        plan.check(self.n, self.params, self.n_balls)
        if (plan.struck != 0).any():
            raise ValueError("ShotPlan.struck: the env's actions always strike the shooter's own cue ball; a shot "
                             "with another ball is played through contract.turn.play_turn (a preview), not encoded")
        a = self.encode(plan.shots, plan.placement, plan.declare, plan.pocket, plan.ball, plan.replace)
        return a.astype(np.float32).astype(np.float64)

    def take(self, rows) -> "ActionCodec":
        """The codec of some of the rows."""
        rows = np.asarray(rows, dtype=np.int64)
        place = self.place
        return dataclasses.replace(self, origin=self.origin[rows], aim_point=self.aim_point[rows],
                                   in_hand=self.in_hand[rows], nominal=self.nominal[rows], cue=self.cue[rows],
                                   is_break=self.is_break[rows],
                                   place=lambda xy, r: place(xy, rows[r]))
