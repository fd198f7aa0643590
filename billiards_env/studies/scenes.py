"""Seeded shot sets for accuracy/cost studies of the physics solvers.

Each builder returns a struck ``BallState`` batch (one shot per table) ready
for ``simulate``. All randomness comes from the given seed, so a scene is the
same set of shots on every run.
"""
from __future__ import annotations

import numpy as np

from billiards_env.physics import BallState, PhysicsParams, Table, rack, random_placement, simulate, strike_velocity
from billiards_env.physics.state import spot_free

MAX_OFFSET = 0.45  # |(a, b)| of random spin offsets, inside the 0.5 R miscue limit


def _offsets(rng, n):
    r = MAX_OFFSET * np.sqrt(rng.uniform(0.0, 1.0, n))
    th = rng.uniform(0.0, 2 * np.pi, n)
    return r * np.cos(th), r * np.sin(th)


def two_ball(table: Table, params: PhysicsParams, n: int, seed: int = 0, margin: float = 0.01,
             aim_noise_deg: float = 3.0, speed=(0.5, 4.0), spin: bool = True) -> BallState:
    """Cue ball + one object ball at random positions; cue aimed at the object
    ball +- ``aim_noise_deg`` at a uniform speed, with random spin offsets."""
    rng = np.random.default_rng(seed)
    s = random_placement(table, params, 2, n, seed=rng, margin=margin)
    d = s.pos[:, 1] - s.pos[:, 0]
    phi = np.arctan2(d[:, 1], d[:, 0]) + np.radians(rng.uniform(-aim_noise_deg, aim_noise_deg, n))
    v = rng.uniform(speed[0], speed[1], n)
    a, b = _offsets(rng, n) if spin else (np.zeros(n), np.zeros(n))
    return strike_velocity(s, phi, v, a, b, params)


def breaks(table: Table, params: PhysicsParams, n: int, seed: int = 1, speed: float = 8.0,
           speed_noise: float = 0.3, offset: float = 0.01, spin: float = 0.1) -> BallState:
    """9-ball breaks: frozen diamond rack, cue ball at the head spot +- ``offset``
    (m) across the table, aimed at the apex ball at ``speed`` +- noise (m/s),
    small random spin offsets (|a|, |b| <= ``spin``)."""
    rng = np.random.default_rng(seed)
    s = rack(table, params, "nine", n, seed=rng)
    s.pos[:, 0, 0] += rng.uniform(-offset, offset, n)
    d = s.pos[:, 1] - s.pos[:, 0]
    phi = np.arctan2(d[:, 1], d[:, 0]) + np.radians(rng.uniform(-0.2, 0.2, n))
    v = speed + rng.uniform(-speed_noise, speed_noise, n)
    a = rng.uniform(-spin, spin, n)
    b = rng.uniform(-spin, spin, n)
    return strike_velocity(s, phi, v, a, b, params)


def respot_cue(state: BallState, table: Table, params: PhysicsParams) -> BallState:
    """Put a pocketed cue ball back on the table: on the head spot if free,
    else the nearest free point found along the head string (then further up
    the table). Free: ``physics.state.spot_free`` (the respot rule the
    environments use) with a clearance of 1e-6 m from the cushions' R-inset
    rectangle and from every ball. Returns a new state at rest."""
    out = BallState(state.pos.copy(), np.zeros_like(state.vel), np.zeros_like(state.omega), state.pocket.copy())
    R = params.R
    w, l = table.width, table.length
    pockets = np.ascontiguousarray(table.geometry(True)[3], dtype=np.float64)
    cands = [(w / 2, l / 4)]
    for k in range(1, 200):
        for sgn in (1, -1):
            cands.append((w / 2 + sgn * k * 0.01, l / 4))
    for k in range(1, 200):
        cands.append((w / 2, l / 4 - k * 0.005))
    for e in np.nonzero(out.pocket[:, 0] >= 0)[0]:
        on = (out.pocket[e] < 0)
        on[0] = False
        for x, y in cands:
            if spot_free(x, y, out.pos[e], on, w, l, R + 1e-6, pockets, 2 * R + 1e-6):
                out.pos[e, 0] = (x, y)
                out.pocket[e, 0] = -1
                break
        else:
            raise RuntimeError(f"no free spot for the cue ball in env {e}")
    return out


def post_break(table: Table, params: PhysicsParams, n: int, seed: int = 2, speed=(0.5, 5.0),
               break_seed: int | None = None) -> BallState:
    """Random shots on the resting tables left by ``n`` 9-ball breaks (event
    solver): pocketed balls stay off the table, a pocketed cue ball is
    respotted; uniform random aim, uniform speed, random spin offsets."""
    rng = np.random.default_rng(seed)
    br = breaks(table, params, n, seed=seed + 1000 if break_seed is None else break_seed)
    res = simulate(br, table, params, solver="event")
    s = respot_cue(res.state, table, params)
    phi = rng.uniform(0.0, 2 * np.pi, n)
    v = rng.uniform(speed[0], speed[1], n)
    a, b = _offsets(rng, n)
    return strike_velocity(s, phi, v, a, b, params)


# The throughput benchmark's scenes (billiards_env.studies.bench.scenes names
# them): fixed shots with small noise. Their draws from ``seed`` (an int, or
# a Generator drawn from in place) are fixed: a change would change the
# benchmark's figures across commits.
def straight_break(table: Table, params: PhysicsParams, n: int, seed=0, layout: str = "nine",
                   speed=(8.0, 0.2), aim_sd: float = 0.01, height: float = 0.1) -> BallState:
    """A frozen ``layout`` rack (``"nine"`` or ``"eight"``), the cue ball on the
    head spot struck straight up the table (pi/2 + N(0, ``aim_sd``) rad) at
    N(``speed[0]``, ``speed[1]``) m/s, no side, height offset b uniform in
    +-``height``."""
    rng = np.random.default_rng(seed)
    s = rack(table, params, layout, n, seed=rng)
    return strike_velocity(s, np.pi / 2 + rng.normal(0, aim_sd, n), rng.normal(speed[0], speed[1], n),
                           0.0, rng.uniform(-height, height, n), params)


def elevated_break(table: Table, params: PhysicsParams, n: int, seed=0, theta_deg=(3.0, 12.0)) -> BallState:
    """``straight_break``'s 9-ball breaks with the cue elevated ``theta_deg``
    (uniform, degrees) as many players break: the cue ball is driven into
    the slate and hops on its way to the rack. The state carries ``air``
    (``Effects(airborne=True)`` simulates the hop; the planar simulator needs
    ``planar(state)``, which drops the vertical velocity)."""
    rng = np.random.default_rng(seed)
    s = rack(table, params, "nine", n, seed=rng)
    s = BallState(s.pos, s.vel, s.omega, s.pocket, np.zeros(s.pos.shape[:2] + (2,)))
    theta = np.radians(rng.uniform(theta_deg[0], theta_deg[1], n))
    return strike_velocity(s, np.pi / 2 + rng.normal(0, 0.01, n), rng.normal(8.0, 0.2, n), 0.0,
                           rng.uniform(-0.1, 0.1, n), params, theta=theta)


def jump_over(table: Table, params: PhysicsParams, n: int, seed=0) -> BallState:
    """Jump shots: the cue ball in x 0.3-0.9, y 0.4-0.8 m, a blocking ball
    0.15-0.3 m straight ahead, an object ball 0.4-0.6 m beyond it; the cue
    elevated 30-50 degrees at 3-6 m/s through the centre (a jump cue's
    stroke). With ``air``, as ``elevated_break``."""
    rng = np.random.default_rng(seed)
    cue = np.column_stack([rng.uniform(0.3, 0.9, n), rng.uniform(0.4, 0.8, n)])
    block = cue + np.column_stack([np.zeros(n), rng.uniform(0.15, 0.3, n)])
    obj = block + np.column_stack([rng.uniform(-0.05, 0.05, n), rng.uniform(0.4, 0.6, n)])
    s = BallState.from_positions(np.stack([cue, block, obj], axis=1))
    s = BallState(s.pos, s.vel, s.omega, s.pocket, np.zeros((n, 3, 2)))
    return strike_velocity(s, np.pi / 2, rng.uniform(3.0, 6.0, n), 0.0, 0.0, params,
                           theta=np.radians(rng.uniform(30.0, 50.0, n)))


def planar(state: BallState) -> BallState:
    """``state`` without its ``air``: every ball on the slate, the vertical
    velocity dropped (what the planar simulator plays of an elevated cue)."""
    return BallState(state.pos, state.vel, state.omega, state.pocket)


def half_ball_cut(table: Table, params: PhysicsParams, n: int, seed=0, speed=(2.0, 0.1),
                  side: float = 0.2, height: float = 0.3) -> BallState:
    """Cue ball in x 0.3-0.9, y 0.5-0.9 m, an object ball 0.5-0.8 m up the
    table and +-0.15 m across from it; the cue ball's path passes R beside
    the object ball's centre (a half-ball hit) at N(``speed[0]``,
    ``speed[1]``) m/s with offsets a = ``side``, b = ``height``. (The
    positions are fixed numbers: ``table`` is unused.)"""
    rng = np.random.default_rng(seed)
    cue = np.column_stack([rng.uniform(0.3, 0.9, n), rng.uniform(0.5, 0.9, n)])
    obj = cue + np.column_stack([rng.uniform(-0.15, 0.15, n), rng.uniform(0.5, 0.8, n)])
    s = BallState.from_positions(np.stack([cue, obj], axis=1))
    d = obj - cue
    phi = np.arctan2(d[:, 1], d[:, 0]) + np.arcsin(params.R / np.linalg.norm(d, axis=1))
    return strike_velocity(s, phi, rng.normal(speed[0], speed[1], n), side, height, params)


def one_ball_two_cushions(table: Table, params: PhysicsParams, n: int, seed=0, speed: float = 3.0,
                          height: float = 0.4) -> BallState:
    """One ball in x 0.5-0.8, y 1.5-1.8 m struck at 60 +- N(0, 0.02 rad) degrees
    at ``speed`` m/s with top spin b = ``height`` (off two cushions; ``table``
    is unused)."""
    rng = np.random.default_rng(seed)
    s = BallState.from_positions(np.column_stack([rng.uniform(0.5, 0.8, n), rng.uniform(1.5, 1.8, n)])[:, None])
    return strike_velocity(s, np.radians(60) + rng.normal(0, 0.02, n), speed, 0.0, height, params)


SCENES = {"two_ball": two_ball, "break": breaks, "post_break": post_break}


def build(name: str, table: Table, params: PhysicsParams, n: int, seed: int = 0) -> BallState:
    """Scene ``name`` (``two_ball``, ``break``, ``post_break``) with ``n`` shots."""
    if name not in SCENES:
        raise ValueError(f"unknown scene {name!r}; choose one of {sorted(SCENES)}")
    return SCENES[name](table, params, n, seed=seed)
