"""Pocket acceptance windows, measured in the simulator once per table and physics.

For each pocket and each approach angle of a grid (the direction a ball travels into the pocket, turned from the
pocket's own axis), a lone ball is struck at the pocket from ``SHOT_DISTANCE`` along a fan of parallel lines
(lateral offsets ``OFFSETS`` from the pocket's centre) at ``SPEEDS``; the offsets where it drops at every speed
form the window. The aim line for a pocket and approach is the window's centre, its half-width the tolerance.
The side pockets' capture circles lie outside the cushion line, so an angled side pot aimed at the centre
misses: the window centre moves the aim into the mouth.
"""
from __future__ import annotations

import math

import numpy as np

from ...physics import BallState, simulate, strike_velocity

ANGLES = np.radians(np.arange(-72.0, 72.1, 4.0))  # approach angles from the pocket's axis (a 4-degree grid)
OFFSETS = np.arange(-0.09, 0.0901, 0.0025)         # m: lateral offsets of the fan (the window's resolution)
SHOT_DISTANCE = 0.5                                # m: the lone ball starts this far from the pocket's centre
SPEEDS = (0.9, 2.6)                                # m/s: a soft and a firm pot (both must drop)
MIN_RUN = 0.25                                     # a window needs this fraction of SHOT_DISTANCE of track left
EDGE_MARGIN = 0.002                                # m: a start kept this far inside the cushion line

_CACHE: dict = {}


class Windows:
    """The windows of one table: ``axes`` [P, 2] (unit, into the pocket), ``centre`` and ``half`` [P, A] (m,
    lateral offsets along the left normal of the approach direction; half 0: no window), ``ANGLES`` [A]."""

    def __init__(self, axes, centre, half, ref):
        self.axes, self.centre, self.half, self.ref = axes, centre, half, ref
        self.base = np.arctan2(axes[:, 1], axes[:, 0])

    def lookup(self, p, theta):
        """(centre [k], half-width [k]) of pockets ``p`` [k] for travel directions ``theta`` [k] (rad),
        linearly interpolated on the angle grid; half 0 outside it."""
        rel = (theta - self.base[p] + np.pi) % (2 * np.pi) - np.pi
        x = (rel - ANGLES[0]) / (ANGLES[1] - ANGLES[0])
        i = np.minimum(np.maximum(np.floor(x).astype(np.int64), 0), len(ANGLES) - 2)   # np.clip, without its
        f = np.minimum(np.maximum(x - i, 0.0), 1.0)                                     # wrapper's overhead
        c = (1 - f) * self.centre[p, i] + f * self.centre[p, i + 1]
        h = np.minimum(self.half[p, i], self.half[p, i + 1])
        h = np.where((x < 0) | (x > len(ANGLES) - 1), 0.0, h)
        return c, h

    def aim(self, p, obj):
        """For object balls at ``obj`` [k, 2] into pockets ``p`` [k]: (travel direction [k] (rad), the window's
        half-width [k] (m), the aim point [k, 2], the distance to it [k]); two fixed-point steps on the angle."""
        ref = self.ref[p]
        d = ref - obj
        th = np.arctan2(d[:, 1], d[:, 0])
        for _ in range(2):
            c, h = self.lookup(p, th)
            tgt = ref + c[:, None] * np.column_stack([-np.sin(th), np.cos(th)])
            d = tgt - obj
            th = np.arctan2(d[:, 1], d[:, 0])
        c, h = self.lookup(p, th)
        return th, h, tgt, np.linalg.norm(d, axis=1)


def pocket_axes(table) -> np.ndarray:
    """[P, 2] each pocket's axis: the unit direction a ball travels straight into it."""
    pk = np.asarray(table.geometry(True)[3], dtype=np.float64)
    W, L = table.width, table.length
    cx, cy = pk[:, 0] - W / 2, pk[:, 1] - L / 2
    ax = np.stack([np.sign(cx) * (np.abs(cx) > W / 4), np.sign(cy) * (np.abs(cy) > L / 4)], axis=1)
    return ax / np.linalg.norm(ax, axis=1, keepdims=True)


def windows_of(view) -> Windows:
    """The view's table's windows, measured on first use and cached per (table, params, effects, models)."""
    key = (id(view.table), id(view.params), id(view.effects), id(view.models))
    hit = _CACHE.get(key)
    if hit is not None and hit[0] is view.table and hit[1] is view.params:
        return hit[2]
    w = measure(view)
    _CACHE[key] = (view.table, view.params, w)
    return w


def measure(view) -> Windows:
    """Shoot the fans (see the module docstring) in one batched simulation."""
    table, params = view.table, view.params
    R = params.R
    pk = np.asarray(table.geometry(True)[3], dtype=np.float64)
    ref = pk[:, :2].copy()
    axes = pocket_axes(table)
    P, A, O, S = len(pk), len(ANGLES), len(OFFSETS), len(SPEEDS)
    th = np.arctan2(axes[:, 1], axes[:, 0])[:, None] + ANGLES[None, :]          # [P, A]
    u = np.stack([np.cos(th), np.sin(th)], axis=-1)                             # [P, A, 2]
    nrm = np.stack([-u[..., 1], u[..., 0]], axis=-1)
    through = ref[:, None, None] + OFFSETS[None, None, :, None] * nrm[:, :, None]   # [P, A, O, 2]
    # walk the start back from the pocket along the line, but keep it on the table
    dist = np.full((P, A, O), SHOT_DISTANCE)
    lo = np.array([R + EDGE_MARGIN, R + EDGE_MARGIN])
    hi = np.array([table.width - R - EDGE_MARGIN, table.length - R - EDGE_MARGIN])
    ub = np.broadcast_to(u[:, :, None], (P, A, O, 2))
    for ax_ in range(2):
        with np.errstate(divide="ignore", invalid="ignore"):
            # through - t u within [lo, hi] on this axis: the largest t that stays inside
            t_lo = (through[..., ax_] - lo[ax_]) / ub[..., ax_]
            t_hi = (through[..., ax_] - hi[ax_]) / ub[..., ax_]
        tmax = np.where(ub[..., ax_] > 0, t_lo, np.where(ub[..., ax_] < 0, t_hi, np.inf))
        dist = np.minimum(dist, tmax)
    start = through - dist[..., None] * ub
    ok = dist > MIN_RUN * SHOT_DISTANCE
    ok &= table.contains(start.reshape(-1, 2), R + EDGE_MARGIN, 0.0, True).reshape(ok.shape)
    k = P * A * O
    pos = np.repeat(start.reshape(k, 1, 2), S, axis=0)
    phi = np.repeat(th[:, :, None].repeat(O, axis=2).reshape(k), S)
    speed = np.tile(np.asarray(SPEEDS, dtype=np.float64), k)
    safe = np.repeat(ok.reshape(k), S)
    pos[~safe] = [[table.width / 2, table.length / 2]]                        # unused lines: a harmless shot
    state = BallState(pos, np.zeros((k * S, 1, 2)), np.zeros((k * S, 1, 3)), np.full((k * S, 1), -1, np.int64))
    struck = strike_velocity(state, phi, speed, 0.0, 0.0, params)
    res = simulate(struck, table, params, solver=view.solver, dt=view.dt, effects=view.effects, models=view.models)
    drop = (res.state.pocket[:, 0] >= 0) & safe
    drop = drop.reshape(P, A, O, S).all(axis=3)
    centre, half = np.zeros((P, A)), np.zeros((P, A))
    step = OFFSETS[1] - OFFSETS[0]
    for p in range(P):
        for a in range(A):
            run = _longest_run(drop[p, a])
            if run is not None:
                i0, i1 = run
                centre[p, a] = 0.5 * (OFFSETS[i0] + OFFSETS[i1])
                half[p, a] = 0.5 * (OFFSETS[i1] - OFFSETS[i0]) + 0.5 * step
    return Windows(axes, centre, half, ref)


def _longest_run(mask):
    """(first, last) index of the longest run of True in ``mask``, or None."""
    best, cur0, out = 0, None, None
    for i, m in enumerate(list(mask) + [False]):
        if m and cur0 is None:
            cur0 = i
        elif not m and cur0 is not None:
            if i - cur0 > best:
                best, out = i - cur0, (cur0, i - 1)
            cur0 = None
    return out


def angle_tolerance(half, dist):
    """The angular tolerance (rad) of a window of half-width ``half`` seen from ``dist``."""
    return np.arctan2(half, np.maximum(dist, 1e-6))


__all__ = ["Windows", "windows_of", "measure", "pocket_axes", "angle_tolerance", "ANGLES", "math"]
