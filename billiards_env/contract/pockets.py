"""The pockets as every player sees them: which are side pockets, the axis
along which each takes a ball head-on, and the steepest approach each
accepts. Defined once, below the bots and the envs: the target-frame
observation (``envs.target_frame``), the ghost-ball bots and the search all
read these."""
from __future__ import annotations

import math

import numpy as np

# Largest angle between a ball's path and a pocket's axis at which the
# pocket still takes a ball rolling straight in: a side pocket's mouth faces
# straight across the table, so a shallow approach meets the far jaw; a
# corner's mouth spans both rails. Also the ghost-ball baseline's pocket
# limits (billiards_env.bots.geometry.choose_pocket): on PotOne its shot into the
# straightest pocket pots 0.837 of 1,000 held tables, 0.904 with these
# limits (docs/agents.md).
SIDE_ACCEPT_DEG = 50.0
CORNER_ACCEPT_DEG = 60.0


def side_pockets(pockets: np.ndarray, length: float) -> np.ndarray:
    """bool [P]: the pocket (centres ``pockets[:, :2]``) is a side pocket,
    its centre at half the table's ``length``; the others are corners."""
    return np.abs(np.asarray(pockets, dtype=np.float64)[:, 1] - length / 2) < 1e-9


def pocket_axes(pockets: np.ndarray, width: float, length: float) -> np.ndarray:
    """Unit vectors [P, 2] from each pocket (centres ``pockets[:, :2]``) into
    a ``width`` x ``length`` table: across the table for the side pockets
    (``side_pockets``), along the diagonal 45 degrees between the cushions
    for the corner pockets."""
    out = np.empty((len(pockets), 2))
    side = side_pockets(pockets, length)
    for k, (cx, cy) in enumerate(np.asarray(pockets, dtype=np.float64)[:, :2]):
        sx = 1.0 if cx < width / 2 else -1.0
        if side[k]:
            out[k] = (sx, 0.0)
        else:
            out[k] = np.array([sx, 1.0 if cy < length / 2 else -1.0]) / math.sqrt(2.0)
    return out


def pocket_accept_cos(pockets: np.ndarray, length: float) -> np.ndarray:
    """cos of each pocket's acceptance angle [P] (``SIDE_ACCEPT_DEG`` for the
    side pockets, ``CORNER_ACCEPT_DEG`` for the corners)."""
    return np.cos(np.radians(np.where(side_pockets(pockets, length), SIDE_ACCEPT_DEG, CORNER_ACCEPT_DEG)))
