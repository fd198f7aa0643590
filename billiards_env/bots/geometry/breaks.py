"""Seeded 9-ball break shots: the one-player NineBall task's break and the
ghost bot's standard break."""
from __future__ import annotations

import numpy as np


def break_shots(table, apex: np.ndarray, break_speed: float, u: np.ndarray, z: np.ndarray):
    """Seeded break shots from uniforms ``u`` [n, 5] and normals ``z`` [n]:
    the cue ball within +-0.15 m across and +-0.03 m along the head string's
    centre, aimed at ``apex`` [n, 2] (0.3 deg standard deviation), at
    ``break_speed`` +-5 %, side offset in [-0.05, 0.05] R, height in [-0.1,
    0.05] R. Returns (cue position [n, 2], phi, speed, a, b)."""
    cue = np.column_stack([table.width / 2 + (-0.15 + 0.3 * u[:, 0]), 0.25 * table.length + (-0.03 + 0.06 * u[:, 1])])
    d = apex - cue
    phi = np.arctan2(d[:, 1], d[:, 0]) + np.radians(0.3 * z)
    speed = break_speed * (1.0 + (-0.05 + 0.1 * u[:, 2]))
    return cue, phi, speed, -0.05 + 0.1 * u[:, 3], -0.1 + 0.15 * u[:, 4]
