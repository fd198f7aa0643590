"""``ActionCodec``: the game envs' action convention for a batch of tables,
in one place.

A game action is 8 numbers in [-1, 1] (see ``envs.games.spaces``): the aim
relative to the table's aim origin (a0, in units of pi), the cue's draw
(a1, over the env's draw range), the tip's side and height offsets (a2, a3,
over the miscue limit), the cue ball's placement with ball in hand (a4, a5,
over the free span of the bed), a declaration (a6 > 0), the called
pocket (a7, six equal bins) and, in 10-ball only, the called ball (a8,
``n_balls`` equal bins; 0 a safety). The aim origin is the direction from the cue
ball to the table's nominal target (the lowest legal ball; on the break, the
foot spot), so it moves with a placed cue ball.

The env encodes a bot's ``ShotPlan`` with it (``GameCore.actions_of``), and a
learned bot that acts in the env's action space encodes its shots with the
one its ``GameView`` carries (``view.codec``): the same arithmetic either way.
"""
from __future__ import annotations

import dataclasses
from typing import Callable

import numpy as np

from ...physics import PhysicsParams, Table
from ..core import shot_actions

ACTION_DIM = 8
N_POCKETS = 6


def placement_to_actions(xy: np.ndarray, table: Table, params: PhysicsParams) -> np.ndarray:
    """Cue-ball positions [k, 2] (m) -> action components a4, a5 [k, 2]: the
    ball centre's free span of the bed mapped onto [-1, 1]."""
    R_ = params.R
    span = np.array([table.width - 2 * R_, table.length - 2 * R_])
    return np.clip(2.0 * (np.asarray(xy) - R_) / span - 1.0, -1.0, 1.0)


@dataclasses.dataclass(frozen=True, eq=False)
class ActionCodec:
    """The action convention of ``n`` tables. ``origin`` [n]: the aim origin
    with the cue ball where it lies; ``aim_point`` [n, 2]: the point the
    origin looks at (the nominal target's centre, or the foot spot on the
    break); ``in_hand`` [n]: the shooter places the cue ball; ``place``:
    ``(xy [k, 2], rows [k]) -> (spots, moved)``, the legal ball-in-hand spots
    nearest to ``xy`` on rows ``rows``; the table, the physics and the env's
    shortest draw (``min_draw``)."""

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

    @property
    def n(self) -> int:
        return len(self.origin)

    def origin_from(self, cue: np.ndarray, rows: np.ndarray) -> np.ndarray:
        """The aim origin of rows ``rows`` with the cue ball at ``cue`` [k, 2]."""
        aim = self.aim_point[rows]
        return np.arctan2(aim[:, 1] - cue[:, 1], aim[:, 0] - cue[:, 0])

    def placement_to_actions(self, xy: np.ndarray) -> np.ndarray:
        """Cue-ball positions [k, 2] (m) -> action components a4, a5 [k, 2]."""
        return placement_to_actions(xy, self.table, self.params)

    @property
    def action_dim(self) -> int:
        return self.ball_dim or ACTION_DIM

    def encode(self, shots, placement=None, declare=None, pocket=None, ball=None) -> np.ndarray:
        """Actions [n, action_dim] (float64) that play ``shots`` (absolute aim) with the
        cue ball at ``placement`` [n, 2] (rows without ball in hand are
        ignored; NaN rows: where it lies; an illegal spot is moved to the
        nearest legal one first, so the aim stays absolute), ``declare`` [n]
        (push-out or pass), the called ``pocket`` [n] and, in 10-ball, the
        called ``ball`` [n] (0 a safety; -1 or None: the lowest legal ball)."""
        n = self.n
        out = np.zeros((n, self.action_dim))
        origin = self.origin.copy()
        if placement is not None:
            placement = np.array(placement, dtype=np.float64)
            has = ~np.isnan(placement[:, 0]) & self.in_hand
            rows = np.nonzero(has)[0]
            if len(rows):
                placement[has], _ = self.place(placement[has], rows)
            out[:, 4:6] = self.placement_to_actions(np.where(has[:, None], placement, 0.5))
            if len(rows):
                origin[has] = self.origin_from(placement[has], rows)
        out[:, :4] = shot_actions(shots, origin, self.min_draw, self.params)
        out[:, 6] = -1.0 if declare is None else np.where(declare, 1.0, -1.0)
        if pocket is not None:
            out[:, 7] = -1.0 + (2.0 * np.asarray(pocket) + 1.0) / N_POCKETS
        if self.ball_dim:
            ball = self.nominal if ball is None else np.where(np.asarray(ball) < 0, self.nominal, ball)
            out[:, 8] = -1.0 + (2.0 * ball + 1.0) / self.n_balls
        return np.clip(out, -1.0, 1.0)

    def encode_plan(self, plan) -> np.ndarray:
        """The actions [n, 8] of a bot's ``ShotPlan`` (checked first), rounded
        through float32, the action space's dtype, as a policy's actions are."""
        plan.check(self.n, self.params, self.n_balls)
        a = self.encode(plan.shots, plan.placement, plan.declare, plan.pocket, plan.ball)
        return a.astype(np.float32).astype(np.float64)

    def take(self, rows) -> "ActionCodec":
        """The codec of some of the rows."""
        rows = np.asarray(rows, dtype=np.int64)
        place = self.place
        return dataclasses.replace(self, origin=self.origin[rows], aim_point=self.aim_point[rows],
                                   in_hand=self.in_hand[rows], nominal=self.nominal[rows],
                                   place=lambda xy, r: place(xy, rows[r]))
