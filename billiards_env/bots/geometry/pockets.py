"""The pockets as the ghost-ball construction sees them: one aim point, one
axis (the direction a ball must come from to enter head-on) and one
acceptance limit per pocket, in the order of ``Table.pockets``. The axes
and the side / corner split are the env's target frame's
(``envs.target_frame``)."""
from __future__ import annotations

import math

import numpy as np

from ...contract.pockets import pocket_axes as _pocket_axes
from ...contract.pockets import side_pockets
from ...physics import Table


def pocket_aim_points(table: Table, inset: float = 0.02) -> np.ndarray:
    """Aim points [P, 2], one per pocket, in the order of ``table.pockets``:
    the centre of each pocket's mouth pushed ``inset`` metres into the pocket
    (corner pockets along the diagonal, side pockets across the rail)."""
    w, l = table.width, table.length
    pts = []
    for (cx, cy, _), side in zip(table.pockets, side_pocket_mask(table)):
        if side:  # side pocket: the mouth centre is on the rail line
            x = 0.0 if cx < w / 2 else w
            pts.append((x + (-inset if x == 0.0 else inset), l / 2))
        else:  # corner pocket: on the diagonal, `inset` in from the corner point
            sx = 1.0 if cx < w / 2 else -1.0
            sy = 1.0 if cy < l / 2 else -1.0
            d = inset / math.sqrt(2.0)
            pts.append((cx + sx * d, cy + sy * d))
    return np.array(pts, dtype=np.float64)


def pocket_axes(table: Table) -> np.ndarray:
    """Unit vectors [P, 2] pointing from each pocket into the table (the
    direction a ball must come from to enter the pocket head-on)."""
    return _pocket_axes(table.pockets, table.width, table.length)  # the one the env's target frame shows


def side_pocket_mask(table: Table) -> np.ndarray:
    """bool [P]: the pocket is a side pocket (else a corner)."""
    return side_pockets(table.pockets, table.length)


def pocket_limits(table: Table, corner: float, side: float) -> np.ndarray:
    """The steepest approach angle (rad) accepted for each pocket [P]: ``side``
    for the side pockets, ``corner`` for the corners."""
    return np.where(side_pocket_mask(table), side, corner).astype(np.float64)
