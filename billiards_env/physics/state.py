"""Ball state as a struct of arrays batched over environments, racks and
random placement.

``pos [E, B, 2]`` and ``vel [E, B, 2]`` (m, m/s), ``omega [E, B, 3]`` (rad/s,
about the table's x, y, z axes), ``pocket [E, B]`` (-1 on the table, else the
pocket id, or an off-table code from ``constants.OFF_TABLE`` on: the ball
left the table). Ball 0 is the cue ball. ``air [E, B, 2]`` (optional; None:
every ball on the slate, not moving vertically): the height of each ball's
lowest point above the slate (m) and its vertical velocity (m/s), which
only ``Effects(airborne=True)`` simulates (an elevated cue's strike into
the slate, a ball in flight).

Placement and respotting are written once here, as numba kernels that take
their random numbers from the caller (``place_from_candidates``: rejection
sampling over a sequence of uniform candidates; ``free_spot``: the respot
search), so each caller keeps its own random stream: ``random_placement``
(a ``numpy.random.Generator``) and the environments (per-table counter-based
streams, ``envs/streams.py``).
"""
from __future__ import annotations

import dataclasses
import math

import numba
import numpy as np

from .table import Table


@dataclasses.dataclass(frozen=True, eq=False)
class BallState:
    pos: np.ndarray
    vel: np.ndarray
    omega: np.ndarray
    pocket: np.ndarray
    air: np.ndarray | None = None

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
        return BallState(self.pos.copy(), self.vel.copy(), self.omega.copy(), self.pocket.copy(),
                         None if self.air is None else self.air.copy())

    def take(self, envs) -> "BallState":
        """The sub-batch of the given environment indices."""
        return BallState(self.pos[envs], self.vel[envs], self.omega[envs], self.pocket[envs],
                         None if self.air is None else self.air[envs])

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
        planar = [np.concatenate([getattr(s, f) for s in states]) for f in ("pos", "vel", "omega", "pocket")]
        if all(s.air is None for s in states):
            return cls(*planar)
        return cls(*planar, np.concatenate([s.vertical() for s in states]))

    def vertical(self) -> np.ndarray:
        """``air``, or zeros [E, B, 2] (every ball on the slate) where it is None."""
        return np.zeros(self.pos.shape[:2] + (2,)) if self.air is None else self.air


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
    elif layout == "snooker":
        balls = snooker_rack(table, R, gap)
    else:
        raise ValueError(f"unknown rack layout {layout!r}")
    if jitter:
        balls[1:] += rng.uniform(-jitter, jitter, size=balls[1:].shape)
    balls[0] = head if layout != "snooker" else snooker_break_spot(table)
    return balls


SNOOKER_REDS = 15
PINK_GAP = 1e-3      # m between the pink and the apex red: "as near to the pink as possible without touching" (WPBSA)
BREAK_SPOT_D = 0.5   # the default break-off spot: this fraction of the D's radius from its centre, towards the yellow


def snooker_rack(table: Table, R: float, gap: float = 0.0) -> np.ndarray:
    """Positions [22, 2] of a snooker frame's opening (WPBSA Section 3, rule 2):
    the 15 reds (balls 1..15) in a triangle with its apex on the table's long
    axis PINK_GAP behind the pink and its base towards the top cushion; the
    colours (16..21: yellow, green, brown, blue, pink, black) on their spots;
    the cue ball (0) in the D (``snooker_break_spot``). ``gap=0``: the reds frozen."""
    m = table.marks
    if m is None:
        raise ValueError("a snooker rack needs a snooker table (Table.snooker())")
    pink = m.spots[4]
    balls = np.zeros((1 + SNOOKER_REDS + 6, 2))
    balls[1:1 + SNOOKER_REDS] = _triangle(5, (pink[0], pink[1] + 2 * R + PINK_GAP), R, gap, slice(None))
    balls[1 + SNOOKER_REDS:] = m.spots
    balls[0] = snooker_break_spot(table)
    return balls


def snooker_break_spot(table: Table) -> tuple:
    """A cue-ball spot in the D for the break-off: on the baulk line, BREAK_SPOT_D of the radius towards the yellow."""
    m = table.marks
    return (m.d_centre[0] + BREAK_SPOT_D * m.d_radius, m.d_centre[1] - 1e-6)


def rack(table: Table, params, layout: str = "nine", n_envs: int = 1, *, gap: float = 0.0,
         jitter: float = 0.0, seed=None) -> BallState:
    """A 9-ball diamond (``layout="nine"``, 10 balls) or 8-ball triangle
    (``"eight"``, 16 balls) on the foot spot, cue ball on the head spot; or
    a snooker frame's 22 balls (``"snooker"``, ``snooker_rack``: a snooker table).
    ``gap=0`` freezes every ball to its neighbours (centres exactly 2R apart);
    the numbered balls are shuffled as the rules allow, seeded."""
    rng = _rng(seed)
    pos = np.stack([_rack(table, params.R, layout, gap, rng, jitter) for _ in range(n_envs)])
    return BallState.from_positions(pos)


# ------------------------------------------------------------ placement --
_jit = numba.njit(cache=True, nogil=True)

SPOT_EDGE = 1e-4      # m: a respotted ball keeps this clear of the R-inset rectangle's edge
SPOT_GAP = 1e-3       # m: step of the respot search beyond 2R (neighbouring candidates do not touch)
SPOT_CLEAR = 1e-6     # m: a respotted ball's least gap to any ball (no exact contact)


@_jit
def in_pocket(x, y, pockets):
    """True if (x, y) lies in a pocket capture circle (squared distance <= r**2)."""
    for p in range(pockets.shape[0]):
        dx, dy = x - pockets[p, 0], y - pockets[p, 1]
        if dx * dx + dy * dy <= pockets[p, 2] * pockets[p, 2]:
            return True
    return False


@_jit
def place_from_candidates(u, B, lo_x, lo_y, hi_x, hi_y, pockets, min_dist, out):
    """Rejection-sample ``B`` ball centres of one table into ``out`` [B, 2]
    from the candidate uniforms ``u`` [T, 2] (in [0, 1), taken in order).

    Candidate i is (lo + (hi - lo) * u[i]) in the box [lo, hi]; it is
    rejected inside a pocket capture circle (squared distance <= r**2) or
    closer than ``min_dist`` to a ball already placed. Returns how many
    candidates were used, or -1 if ``B`` balls were not placed from the T
    given (the caller draws more and tries again)."""
    d2min = min_dist * min_dist
    placed = 0
    for i in range(u.shape[0]):
        if placed == B:
            return i
        x = lo_x + (hi_x - lo_x) * u[i, 0]
        y = lo_y + (hi_y - lo_y) * u[i, 1]
        if in_pocket(x, y, pockets):
            continue
        good = True
        for q in range(placed):
            dx, dy = x - out[q, 0], y - out[q, 1]
            if dx * dx + dy * dy < d2min:
                good = False
                break
        if good:
            out[placed, 0] = x
            out[placed, 1] = y
            placed += 1
    return u.shape[0] if placed == B else -1


@_jit
def place_many(u, B, lo_x, lo_y, hi_x, hi_y, pockets, min_dist, out, used):
    """``place_from_candidates`` for many tables: table j from ``u[j]`` into
    ``out[j]``, candidates used (or -1) into ``used[j]``."""
    for j in range(u.shape[0]):
        used[j] = place_from_candidates(u[j], B, lo_x, lo_y, hi_x, hi_y, pockets, min_dist, out[j])


@_jit
def spot_free(x, y, pos, on, width, length, edge, pockets, min_dist):
    """Whether a ball centred at (x, y) fits: inside the rectangle inset by
    ``edge``, outside every pocket capture circle, and at least ``min_dist``
    from every ball with ``on`` set."""
    if x < edge or x > width - edge or y < edge or y > length - edge:
        return False
    if in_pocket(x, y, pockets):
        return False
    for q in range(pos.shape[0]):
        if on[q]:
            dx, dy = x - pos[q, 0], y - pos[q, 1]
            if math.sqrt(dx * dx + dy * dy) < min_dist:
                return False
    return True


@_jit
def free_spot(pos, on, px, py, dx, dy, width, length, R, pockets):
    """First free point in the respot search order: the preferred spot
    (px, py); then +-k steps along the unit direction (dx, dy), k = 1..59; then
    sideways offsets j = 1..19 steps (both sides) each walked k = 0..29 steps
    along (dx, dy). Step 2R + SPOT_GAP. Free: ``spot_free`` with edge
    R + SPOT_EDGE and min_dist 2R + SPOT_CLEAR. Returns (x, y, found)."""
    step = 2 * R + SPOT_GAP
    md = 2 * R + SPOT_CLEAR
    edge = R + SPOT_EDGE
    if spot_free(px, py, pos, on, width, length, edge, pockets, md):
        return px, py, True
    for k in range(1, 60):
        for s in (1.0, -1.0):
            x, y = px + s * k * step * dx, py + s * k * step * dy
            if spot_free(x, y, pos, on, width, length, edge, pockets, md):
                return x, y, True
    qx, qy = -dy, dx
    for j in range(1, 20):
        for k in range(0, 30):
            for s in (1.0, -1.0):
                x = px + s * j * step * qx + k * step * dx
                y = py + s * j * step * qy + k * step * dy
                if spot_free(x, y, pos, on, width, length, edge, pockets, md):
                    return x, y, True
    return px, py, False


def random_placement(table: Table, params, n_balls: int, n_envs: int = 1, *, seed=None,
                     margin: float = 0.0, max_tries: int = 10_000) -> BallState:
    """``n_balls`` balls at uniformly random positions without overlap, at
    least ``margin`` clear of each other and of the cushions and outside
    every pocket's capture circle; seeded (``place_from_candidates`` fed by
    the generator, which advances by exactly the candidates used)."""
    rng = _rng(seed)
    R = params.R
    lo = np.array([R + margin, R + margin])
    hi = np.array([table.width - R - margin, table.length - R - margin])
    pockets = np.ascontiguousarray(table.geometry(True)[3], dtype=np.float64)
    pos = np.empty((n_envs, n_balls, 2))
    for e in range(n_envs):
        chunk = 4 * n_balls + 16
        while True:
            saved = rng.bit_generator.state
            u = rng.random((min(chunk, max_tries), 2))
            used = place_from_candidates(u, n_balls, lo[0], lo[1], hi[0], hi[1], pockets, 2 * R + margin, pos[e])
            if used >= 0 or chunk >= max_tries:
                break
            rng.bit_generator.state = saved  # draw the same candidates again, and more
            chunk *= 4
        if used < 0:
            raise ValueError(f"could not place {n_balls} balls without overlap on {table.name}")
        rng.bit_generator.state = saved
        rng.random((used, 2))  # advance the generator by exactly the candidates used
    return BallState.from_positions(pos)
