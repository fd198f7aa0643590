"""The ghost-ball construction's lines, as scalar numba kernels: written
once, called by the batched shots (``geometry.batched``) and by the game
bots' per-table searches (``geometry.game``).

- ``ghost_ball``: for the object ball at O and an aim point P at distance
  ``dop`` = |P - O|, the unit direction u = (P - O) / dop and the ghost
  ball's centre G = O - 2R u, where the cue ball must arrive (Alciatore,
  "The Illustrated Principles of Pool and Billiards", ghost-ball aiming);
- ``cut_cos``: the cosine of the cut angle, between the cue ball's path
  (to the ghost ball) and the object ball's;
- ``approach_cos``: the cosine of the angle between the object ball's path
  and a pocket's axis (pointing into the table), the pocket's acceptance test;
- ``seg_dist2`` and ``blocked``: a path (segment a-b) is blocked when some
  other ball on the table lies within a given distance of it.

The two callers round differently, and each keeps its rounding so that
its results stay bit-identical to what they were (the ``geometry``
docstring says by how much they differ): the batched shots measure a
length as ``line_length`` (numpy's norm), the cut as ``cut_cos_of_units``
and take numpy's vectorised arccos / arctan2 on the arrays; the game
kernels measure a length with ``math.hypot``, the cut as ``cut_cos`` and
take libm's acos / atan2.
"""
from __future__ import annotations

import math

import numba
import numpy as np

_jit = numba.njit(cache=True, nogil=True)
MIN_LINE = 1e-12     # m: a ball this close to its aim point has no direction to it
MIN_SEGMENT2 = 1e-18  # m^2: a shorter segment is measured as the point a (no direction to project on)
MIN_CUE_PATH = 1e-9   # m: a cue ball this close to the ghost ball has no path to aim along


@_jit
def line_length(x, y):
    """sqrt(x^2 + y^2) rounded as ``np.linalg.norm`` of (x, y) rounds it
    (``math.hypot`` may differ in the last bit)."""
    return math.sqrt(x * x + y * y)


@_jit
def ghost_ball(ox, oy, px, py, R, dop):
    """The unit direction (ux, uy) from the object ball at (ox, oy) to the
    aim point (px, py), ``dop`` away (> 0), and the ghost ball's centre
    (gx, gy), 2R behind the object ball on that line."""
    ux, uy = (px - ox) / dop, (py - oy) / dop
    return ux, uy, ox - 2 * R * ux, oy - 2 * R * uy


@_jit
def cut_cos(vx, vy, dcg, ux, uy):
    """cos of the cut angle: between the cue ball's path (vx, vy), of length
    ``dcg`` (> 0), and the object ball's (ux, uy), as v.u / dcg (the game
    kernels' rounding)."""
    return (vx * ux + vy * uy) / dcg


@_jit
def cut_cos_of_units(vx, vy, dcg, ux, uy):
    """``cut_cos`` as (v / dcg).u: the batched shots' rounding (they divide
    the path by its length first, as numpy array code does)."""
    return (vx / dcg) * ux + (vy / dcg) * uy


@_jit
def approach_cos(ux, uy, ax, ay):
    """cos of the angle between the object ball's path (ux, uy) and a pocket's
    axis (ax, ay) (pointing from the pocket into the table)."""
    return -(ux * ax + uy * ay)


@_jit
def seg_dist2(ax, ay, bx, by, px, py):
    """Squared distance from (px, py) to the segment a-b."""
    dx, dy = bx - ax, by - ay
    L2 = max(dx * dx + dy * dy, MIN_SEGMENT2)
    t = min(max(((px - ax) * dx + (py - ay) * dy) / L2, 0.0), 1.0)
    qx, qy = ax + t * dx - px, ay + t * dy - py
    return qx * qx + qy * qy


@_jit
def blocked(pos, on, skip1, skip2, ax, ay, bx, by, d2):
    """Some ball on the table (``pos`` [B, 2], ``on`` [B]) other than the cue
    ball and ``skip1``/``skip2`` lies closer than sqrt(d2) to the segment a-b."""
    for j in range(1, pos.shape[0]):
        if j == skip1 or j == skip2 or not on[j]:
            continue
        if seg_dist2(ax, ay, bx, by, pos[j, 0], pos[j, 1]) < d2:
            return True
    return False


@_jit
def paths_blocked(pos, on, skip, a, b, d2, out):
    """``out[e, k] |= blocked(pos[e], on[e], skip[e], -1, a[e, k], b[e, k], d2)``
    for paths a-b [E, K, 2] on tables ``pos`` [E, B, 2]."""
    for e in range(a.shape[0]):
        for k in range(a.shape[1]):
            if not out[e, k]:
                out[e, k] = blocked(pos[e], on[e], skip[e], -1, a[e, k, 0], a[e, k, 1], b[e, k, 0], b[e, k, 1], d2)


def sqrt_test_d2(r: float) -> float:
    """The least double s with sqrt(s) >= r: ``s < sqrt_test_d2(r)`` is exactly
    ``sqrt(s) < r`` (sqrt is correctly rounded, hence monotone), which
    ``r * r`` as the bound is not in the last bit. The batched shots test
    clearance as ``distance < 2R``; through this bound they share ``blocked``."""
    s = r * r
    while math.sqrt(s) < r:
        s = math.nextafter(s, math.inf)
    while s > 0.0 and math.sqrt(math.nextafter(s, 0.0)) >= r:
        s = math.nextafter(s, 0.0)
    return s


def as_bool(a) -> np.ndarray:
    """A C-contiguous bool copy-or-view of ``a`` (what the kernels take)."""
    return np.ascontiguousarray(a, dtype=np.bool_)
