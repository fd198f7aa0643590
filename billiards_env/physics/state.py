"""Ball state as a struct of arrays batched over environments, and racks.

``pos [E, B, 2]`` and ``vel [E, B, 2]`` (m, m/s), ``omega [E, B, 3]`` (rad/s,
about the table's x, y, z axes), ``pocket [E, B]`` (-1 on the table, else the
pocket id). Ball 0 is the cue ball.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from .table import Table


@dataclasses.dataclass(frozen=True, eq=False)
class BallState:
    pos: np.ndarray
    vel: np.ndarray
    omega: np.ndarray
    pocket: np.ndarray

    @property
    def n_envs(self) -> int:
        return self.pos.shape[0]

    @property
    def n_balls(self) -> int:
        return self.pos.shape[1]

    @property
    def on_table(self) -> np.ndarray:
        return self.pocket < 0

    def copy(self) -> "BallState":
        return BallState(self.pos.copy(), self.vel.copy(), self.omega.copy(), self.pocket.copy())

    def take(self, envs) -> "BallState":
        """The sub-batch of the given environment indices."""
        return BallState(self.pos[envs], self.vel[envs], self.omega[envs], self.pocket[envs])

    @classmethod
    def from_positions(cls, pos, pocket=None) -> "BallState":
        """Balls at rest at ``pos [E, B, 2]`` (or ``[B, 2]`` for one table)."""
        pos = np.array(pos, dtype=np.float64)
        if pos.ndim == 2:
            pos = pos[None]
        if pos.ndim != 3 or pos.shape[2] != 2:
            raise ValueError(f"positions must have shape [E, B, 2] or [B, 2], got {pos.shape}")
        E, B, _ = pos.shape
        pk = np.full((E, B), -1, dtype=np.int64) if pocket is None else np.array(pocket, dtype=np.int64).reshape(E, B)
        return cls(pos, np.zeros((E, B, 2)), np.zeros((E, B, 3)), pk)

    @classmethod
    def stack(cls, states) -> "BallState":
        states = list(states)
        return cls(*(np.concatenate([getattr(s, f) for s in states]) for f in ("pos", "vel", "omega", "pocket")))


def _rng(seed):
    return seed if isinstance(seed, np.random.Generator) else np.random.default_rng(seed)


def _triangle(n_rows: int, apex, R: float, gap: float, order) -> np.ndarray:
    """Centres of a triangle rack pointing towards -y with its apex at ``apex``."""
    d = 2 * R + gap
    pts = []
    for row in range(n_rows):
        for k in range(row + 1):
            pts.append((apex[0] + (k - row / 2) * d, apex[1] + row * d * math.sqrt(3) / 2))
    return np.array(pts)[order]


def diamond_slots(table: Table, R: float, gap: float = 0.0) -> np.ndarray:
    """The 9 centres [9, 2] of a 9-ball diamond on the foot spot, row by row
    from the apex: slot 0 is the apex (the 1-ball), slot 4 the centre (the
    9-ball). ``gap=0`` freezes neighbours (centres exactly 2R apart)."""
    fx, fy = table.width / 2, 0.75 * table.length
    d = 2 * R + gap
    return np.array([(fx + (k - (n - 1) / 2) * d, fy + r * d * math.sqrt(3) / 2)
                     for r, n in enumerate((1, 2, 3, 2, 1)) for k in range(n)])


def _rack(table: Table, R: float, layout: str, gap: float, rng, jitter: float) -> np.ndarray:
    w, l = table.width, table.length
    foot_spot = (w / 2, 0.75 * l)
    head = (w / 2, 0.25 * l)
    if layout == "nine":
        # diamond: 1 at the apex on the foot spot, 9 in the centre
        pts = diamond_slots(table, R, gap)
        # ball numbers: apex = 1, centre (row 2, middle) = 9, others shuffled
        others = [i for i in range(9) if i not in (0, 4)]
        nums = [2, 3, 4, 5, 6, 7, 8]
        rng.shuffle(nums)
        order = np.empty(9, dtype=int)
        order[0], order[4] = 1, 9
        for i, n in zip(others, nums):
            order[i] = n
        balls = np.zeros((10, 2))
        balls[order] = pts
    elif layout == "eight":
        pts = _triangle(5, foot_spot, R, gap, slice(None))
        nums = list(range(1, 16))
        nums.remove(8)
        rng.shuffle(nums)
        order = np.array(nums[:4] + [8] + nums[4:])  # 8 in the centre of the third row
        balls = np.zeros((16, 2))
        balls[order] = pts
    else:
        raise ValueError(f"unknown rack layout {layout!r}")
    if jitter:
        balls[1:] += rng.uniform(-jitter, jitter, size=balls[1:].shape)
    balls[0] = head
    return balls


def rack(table: Table, params, layout: str = "nine", n_envs: int = 1, *, gap: float = 0.0,
         jitter: float = 0.0, seed=None) -> BallState:
    """A 9-ball diamond (``layout="nine"``, 10 balls) or 8-ball triangle
    (``"eight"``, 16 balls) on the foot spot, cue ball on the head spot.
    ``gap=0`` freezes every ball to its neighbours (centres exactly 2R apart);
    the numbered balls are shuffled as the rules allow, seeded."""
    rng = _rng(seed)
    pos = np.stack([_rack(table, params.R, layout, gap, rng, jitter) for _ in range(n_envs)])
    return BallState.from_positions(pos)


def random_placement(table: Table, params, n_balls: int, n_envs: int = 1, *, seed=None,
                     margin: float = 0.0, max_tries: int = 10_000) -> BallState:
    """``n_balls`` balls at uniformly random positions without overlap, at
    least ``margin`` clear of each other and of the cushions; seeded."""
    rng = _rng(seed)
    R = params.R
    lo = np.array([R + margin, R + margin])
    hi = np.array([table.width - R - margin, table.length - R - margin])
    pos = np.empty((n_envs, n_balls, 2))
    for e in range(n_envs):
        placed = 0
        tries = 0
        while placed < n_balls:
            tries += 1
            if tries > max_tries:
                raise ValueError(f"could not place {n_balls} balls without overlap on {table.name}")
            p = rng.uniform(lo, hi)
            if placed and np.min(np.hypot(*(pos[e, :placed] - p).T)) < 2 * R + margin:
                continue
            if not table.contains(p[None], R + margin, 0.0)[0]:
                continue
            pos[e, placed] = p
            placed += 1
    return BallState.from_positions(pos)
