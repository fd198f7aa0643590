"""The target-frame observation (``observation: target_frame``).

The table seen from the legal target ball: origin at the target's centre,
x-axis along the line cue ball -> target, y-axis 90 degrees counter-clockwise
from it. Every length is divided by the table diagonal. A shot's outcome
depends on the layout only through these relative positions, so the policy
does not have to learn the same shot again for every rotation of it; with
``aim: impact`` the pocket's direction from the target maps almost linearly
to the action that pots into it (a0 ~ sin of the pocket's angle).

Layout (B balls, P pockets, size 4B + 2 + 5P; every entry in [-1, 1]):

==================  =========================================================
index               meaning
==================  =========================================================
0                   cue ball -> target centre distance / diagonal
1 + 3*i, 2 + 3*i    ball i (x, y) in the frame / diagonal (0, 0 if pocketed)
3 + 3*i             1 if ball i is on the table, 0 if pocketed
1 + 3*B + i         1 if ball i is the legal target ball, else 0
1 + 4*B             shots taken this episode / max_shots
2 + 4*B + 5*k ...   k-th pocket: unit direction (ux, uy) from the target in
                    the frame, distance target -> pocket centre / diagonal,
                    and the pocket's axis (ax, ay) in the frame: the unit
                    vector from the pocket into the table along which a ball
                    enters it head-on (``pocket_axes``); a pot needs the
                    object ball's path within some angle of it, narrower for
                    side pockets than for corners
==================  =========================================================

Pockets are listed by increasing angle |atan2(uy, ux)| from the x-axis
(the straightest pot first; ties by the pocket index), those the target
ball cannot enter on a straight line listed after all the others: a
pocket's jaws turn away a ball that comes in more than ``SIDE_ACCEPT_DEG``
(side) or ``CORNER_ACCEPT_DEG`` (corner) off its axis. The order does not
depend on the pockets' index on the table: the observation depends on the
layout only, and a layout rotated by 180 degrees (the table's symmetry)
gives the same observation, a mirrored one the same with every y and uy
negated. Without a legal target the frame is the table's own (x-axis +x)
centred on the cue ball, with distance 0.
"""
from __future__ import annotations

import math

import numba
import numpy as np


_jit = numba.njit(cache=True, nogil=True)

SORT_LAST = 4.0  # > pi: added to the sort key of a pocket the ball cannot enter


def obs_size(n_balls: int, n_pockets: int) -> int:
    """Length of the observation for ``n_balls`` balls (cue ball included)."""
    return 4 * n_balls + 2 + 5 * n_pockets


@_jit
def _clip1(v):
    return min(max(v, -1.0), 1.0)


@_jit
def observe_target_frame(pos, pocket, tgt, shots, max_shots, pockets, axes, accept_cos, diag, obs):
    """Fill the zeroed observations ``obs`` [N, obs_size] (layout: module docstring)."""
    B = pos.shape[1]
    P = pockets.shape[0]
    key = np.empty(P)
    order = np.empty(P, dtype=np.int64)
    for e in range(pos.shape[0]):
        t = tgt[e]
        if t >= 0:
            ox, oy = pos[e, t, 0], pos[e, t, 1]
            dx, dy = ox - pos[e, 0, 0], oy - pos[e, 0, 1]
            d = math.hypot(dx, dy)
            c, s = dx / d, dy / d
        else:
            ox, oy, d, c, s = pos[e, 0, 0], pos[e, 0, 1], 0.0, 1.0, 0.0
        obs[e, 0] = _clip1(d / diag)
        for b in range(B):
            if pocket[e, b] < 0:
                rx, ry = pos[e, b, 0] - ox, pos[e, b, 1] - oy
                obs[e, 1 + 3 * b] = _clip1((c * rx + s * ry) / diag)
                obs[e, 2 + 3 * b] = _clip1((-s * rx + c * ry) / diag)
                obs[e, 3 + 3 * b] = 1.0
        if t >= 0:
            obs[e, 1 + 3 * B + t] = 1.0
        obs[e, 1 + 4 * B] = min(shots[e] / max_shots, 1.0)
        for k in range(P):  # insertion sort of the pockets by |angle| from the x-axis, unreachable last
            rx, ry = pockets[k, 0] - ox, pockets[k, 1] - oy
            key[k] = abs(math.atan2(-s * rx + c * ry, c * rx + s * ry))
            r = math.hypot(rx, ry)
            if r > 0.0 and -(rx * axes[k, 0] + ry * axes[k, 1]) / r < accept_cos[k]:
                key[k] += SORT_LAST
            j = k
            while j > 0 and key[order[j - 1]] > key[k]:
                order[j] = order[j - 1]
                j -= 1
            order[j] = k
        base = 2 + 4 * B
        for j in range(P):
            k = order[j]
            rx, ry = pockets[k, 0] - ox, pockets[k, 1] - oy
            u, v = c * rx + s * ry, -s * rx + c * ry
            r = math.hypot(u, v)
            if r > 0.0:
                obs[e, base + 5 * j] = u / r
                obs[e, base + 5 * j + 1] = v / r
            obs[e, base + 5 * j + 2] = _clip1(r / diag)
            obs[e, base + 5 * j + 3] = c * axes[k, 0] + s * axes[k, 1]
            obs[e, base + 5 * j + 4] = -s * axes[k, 0] + c * axes[k, 1]
