"""How the games' racks are set: ``realistic`` or ``perfect`` (each game's
own rack is its registry entry's, ``rules.games``; where the rules put balls
back after a shot, ``rules.respot``).

Racks are ``realistic`` by default: real balls are not all the same size
(WPA equipment specifications: 2 1/4 in +- 0.005 in, so diameters differ
by up to 0.25 mm) and a racked set does not freeze every ball to every
neighbour. ``loosen`` spreads a frozen lattice about its apex so that
neighbouring centres sit ``2R + RACK_GAP`` apart and then moves every
object ball by a seeded offset uniform in a disc of radius ``RACK_JITTER``
(the idea of pooltool's racks: a spaced lattice plus a random offset in a
disc of the spacing, there 1e-3 R, about 0.03 mm; here sized to the gaps of
real racks, about 0.1-0.5 mm). Neighbours end between 0 and
``RACK_GAP + 2 RACK_JITTER`` = 0.4 mm apart and never overlap. The
``perfect`` rack (every ball frozen) is the one of earlier versions.
"""
from __future__ import annotations

import numpy as np

from ...rules.placement import FOOT_SPOT


RACKS = ("realistic", "perfect")  # GameConfig.rack: seeded gaps and offsets (default), or every ball frozen
RACK_GAP = 0.2e-3     # m: lattice gap between neighbouring centres beyond 2R (balls differ by up to 0.25 mm, WPA)
RACK_JITTER = 0.1e-3  # m: radius of each ball's offset disc; RACK_GAP >= 2 RACK_JITTER keeps neighbours apart


def loosen(pos: np.ndarray, table, R: float, u: np.ndarray, gap: float = RACK_GAP,
           jitter: float = RACK_JITTER) -> None:
    """Open the frozen racks ``pos`` [n, B, 2] (object balls 1..B-1) in
    place: their lattice stretched about the foot spot so neighbouring
    centres are ``2R + gap`` apart, then each ball moved by an offset
    uniform in a disc of radius ``jitter`` from uniforms ``u`` [n, 2(B-1)]
    (radius jitter * sqrt(u), angle 2 pi u')."""
    if gap < 2 * jitter:
        raise ValueError(f"rack gap {gap} m must be at least twice the jitter {jitter} m, or balls overlap")
    n, B = pos.shape[:2]
    u = np.asarray(u, dtype=np.float64).reshape(n, B - 1, 2)
    apex = np.array([table.width / 2, FOOT_SPOT * table.length])
    r, ang = jitter * np.sqrt(u[..., 0]), 2 * np.pi * u[..., 1]
    pos[:, 1:] = apex + (pos[:, 1:] - apex) * ((2 * R + gap) / (2 * R))
    pos[:, 1:, 0] += r * np.cos(ang)
    pos[:, 1:, 1] += r * np.sin(ang)
