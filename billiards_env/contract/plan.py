"""``ShotPlan``: what a bot returns for a batch of tables, one row per table.

Every field is an array over the view's rows (n):

=============  ===========================================================
``phi``        aim: the cue ball's direction (rad, from +x, counter-clockwise)
``speed``      the cue ball's speed just after the strike (m/s, 0 .. max_speed)
``a``, ``b``   the tip's side and height offsets (units of R; inside the
               miscue disc ``hypot(a, b) < miscue_limit``)
``placement``  [n, 2] where the cue ball goes with ball in hand (m); NaN
               rows: leave it where it lies (tables without ball in hand
               ignore it). An illegal spot is moved to the nearest legal one
               before the shot and the aim is kept (absolute)
``declare``    bool: declare a push-out (9-ball, when the view allows it) or,
               right after the opponent's push-out, pass the shot back
               (``may_pass``: no shot is played)
``pocket``     the called pocket (index into ``Table.pockets``; -1: none), used
               where the view says a call is needed (8-ball, on the 8;
               10-ball, every shot but the break and a push-out)
``ball``       10-ball: the called ball (1..10; 0 calls a safety; -1, the
               default: the nominal target, the lowest legal one), used
               where the view says a call is needed; ignored elsewhere
``replace``    bool, where the constraints allow it (``may_replace``), have
               the balls replaced instead of a shot (it takes precedence over
               ``declare``): snooker, after the opponent's foul and a miss,
               where they were before the foul, the offender to play again;
               three-cushion, with the cue ball touching a ball, on the
               starting position, the shooter to play on; ignored elsewhere
``struck``     the ball the cue strikes (0, the default: the shooter's own
               cue ball). Three-cushion only: the opponent's ball (1) or the
               red (2) is a foul there (the wrong cue ball). The env's
               actions never strike another ball; a bot never plans it
``theta``      the cue's elevation above the horizontal (rad, 0 .. pi/2;
               0, the default, the level cue): a jump or massé stroke.
               Played only with the equipment's ``Effects(airborne=True)``
               (the envs' ``effects={"airborne": True}``); a plan that
               elevates the cue elsewhere is refused (``contract.turn``)
=============  ===========================================================
"""
from __future__ import annotations

import dataclasses

import numpy as np

from ..physics.strike import MAX_ELEVATION, Shots


@dataclasses.dataclass(eq=False)
class ShotPlan:
    phi: np.ndarray
    speed: np.ndarray
    a: np.ndarray
    b: np.ndarray
    placement: np.ndarray
    declare: np.ndarray
    pocket: np.ndarray
    ball: np.ndarray | None = None  # filled with -1 (none) when not given
    replace: np.ndarray | None = None  # filled with False when not given
    struck: np.ndarray | None = None   # filled with 0 (the shooter's own cue ball) when not given
    theta: np.ndarray | None = None    # filled with 0.0 (the level cue) when not given

    def __post_init__(self):
        if self.ball is None:
            self.ball = np.full(np.shape(self.phi)[:1] or (1,), -1, dtype=np.int64)
        if self.replace is None:
            self.replace = np.zeros(np.shape(self.phi)[:1] or (1,), dtype=bool)
        if self.struck is None:
            self.struck = np.zeros(np.shape(self.phi)[:1] or (1,), dtype=np.int64)
        if self.theta is None:
            self.theta = np.zeros(np.shape(self.phi)[:1] or (1,))

    @classmethod
    def of(cls, shots: Shots, placement=None, declare=None, pocket=None, ball=None, replace=None,
           struck=None) -> "ShotPlan":
        """A plan from ``Shots`` (arrays or scalars broadcast to the batch)
        and optional placements, declarations, called pockets, called balls,
        replace declarations and (three-cushion) the ball struck. The cue's
        elevation is the shots' (``Shots.theta``)."""
        given = [len(np.atleast_1d(v)) for v in (placement, declare, pocket, ball, replace, struck) if v is not None]
        n = max([np.size(v) for v in (shots.phi, shots.speed, shots.a, shots.b, shots.theta)] + given)
        vec = [np.broadcast_to(np.asarray(v, dtype=np.float64), (n,)).copy() for v in shots]
        th = np.broadcast_to(np.asarray(shots.theta, dtype=np.float64), (n,)).copy()
        place = np.full((n, 2), np.nan) if placement is None else np.asarray(placement, dtype=np.float64)
        decl = np.zeros(n, dtype=bool) if declare is None else np.asarray(declare, dtype=bool)
        pk = np.full(n, -1, dtype=np.int64) if pocket is None else np.asarray(pocket, dtype=np.int64)
        bl = np.full(n, -1, dtype=np.int64) if ball is None else np.asarray(ball, dtype=np.int64)
        rp = np.zeros(n, dtype=bool) if replace is None else np.asarray(replace, dtype=bool)
        st = np.zeros(n, dtype=np.int64) if struck is None else np.asarray(struck, dtype=np.int64)
        return cls(*vec, place, decl, pk, bl, rp, st, th)

    @property
    def n(self) -> int:
        return len(self.phi)

    @property
    def shots(self) -> Shots:
        return Shots(self.phi, self.speed, self.a, self.b, self.theta)

    @property
    def elevated(self) -> bool:
        """Some row elevates the cue (``theta`` > 0)."""
        return bool(np.any(self.theta != 0))

    def take(self, rows) -> "ShotPlan":
        return ShotPlan(*(getattr(self, f.name)[rows] for f in dataclasses.fields(self)))

    def check(self, n: int, params, n_balls: int | None = None) -> None:
        """Raise a ValueError naming the first problem: a field of the wrong
        shape, a NaN or infinite shot, a speed out of range, offsets outside
        the miscue disc, a bad pocket index, a called ball outside -1 ..
        ``n_balls - 1`` or a struck ball outside 0 .. ``n_balls - 1`` (when
        given), an elevation outside [0, pi/2]."""
        for f in ("phi", "speed", "a", "b", "declare", "pocket", "ball", "replace", "struck", "theta"):
            if np.shape(getattr(self, f)) != (n,):
                raise ValueError(f"ShotPlan.{f} must have shape ({n},), got {np.shape(getattr(self, f))}")
        if np.shape(self.placement) != (n, 2):
            raise ValueError(f"ShotPlan.placement must have shape ({n}, 2), got {np.shape(self.placement)}")
        # one pass over the rows; the messages below are only built when something is wrong
        ok = (np.isfinite(self.phi) & (self.speed >= 0) & (self.speed <= params.max_speed)
              & (np.hypot(self.a, self.b) < params.miscue_limit) & (self.pocket >= -1) & (self.pocket <= 5))
        if not ok.all():
            self._explain(params)
        if n_balls is not None and ((self.ball < -1) | (self.ball >= n_balls)).any():
            raise ValueError(f"ShotPlan.ball must be -1 (none), 0 (a safety) or a ball 1..{n_balls - 1}, "
                             f"got {self.ball}")
        if n_balls is not None and ((self.struck < 0) | (self.struck >= n_balls)).any():
            raise ValueError(f"ShotPlan.struck must be a ball 0..{n_balls - 1} (0: the shooter's cue ball), "
                             f"got {self.struck}")
        check_theta(self.theta)
        p = self.placement
        if not np.isfinite(p).all() and not (np.isfinite(p) | np.isnan(p[:, :1])).all():
            raise ValueError("ShotPlan.placement rows must be finite (or NaN in both coordinates)")

    def _explain(self, params) -> None:
        """Raise the ValueError that names the first problem ``check`` found."""
        for f in ("phi", "speed", "a", "b"):
            v = getattr(self, f)
            if not np.all(np.isfinite(v)):
                raise ValueError(f"ShotPlan.{f} has NaN or infinite values (first at row {int(np.argmin(np.isfinite(v)))})")
        bad = (self.speed < 0) | (self.speed > params.max_speed)
        if bad.any():
            r = int(np.argmax(bad))
            raise ValueError(f"ShotPlan.speed must lie in [0, {params.max_speed}] m/s, got {self.speed[r]} at row {r}")
        off = np.hypot(self.a, self.b) >= params.miscue_limit
        if off.any():
            r = int(np.argmax(off))
            raise ValueError(f"ShotPlan tip offset (a, b) = ({self.a[r]}, {self.b[r]}) at row {r} is outside the "
                             f"miscue disc (radius {params.miscue_limit} R)")
        if ((self.pocket < -1) | (self.pocket > 5)).any():
            raise ValueError(f"ShotPlan.pocket must be -1 (none) or a pocket index 0..5, got {self.pocket}")


def check_theta(theta) -> None:
    """Raise a ValueError naming the first elevation ``theta`` [n] that is not finite or outside [0, pi/2]."""
    theta = np.asarray(theta, dtype=np.float64)
    bad = ~np.isfinite(theta) | (theta < 0) | (theta > MAX_ELEVATION)
    if bad.any():
        r = int(np.argmax(bad))
        raise ValueError(f"ShotPlan.theta (the cue's elevation) must lie in [0, pi/2] rad, got {theta[r]} at row {r}")
