"""Where the cue ball may be placed with ball in hand, and the table's marks
the rules name (WPA World Standardized Rules, 8.1 and 8.2: the head string,
the foot spot; "behind the head string" is the kitchen).

Coordinates: x across the table (0 .. width), y along it from the head rail
(y = 0) to the foot rail (y = length); the head string is the line
y = HEAD_STRING * length, the foot spot (width / 2, FOOT_SPOT * length).
A legal spot keeps the cue ball's centre R + SPOT_EDGE inside the cushions,
clear of every ball by SPOT_CLEAR beyond 2R and outside every pocket's
capture circle (``physics.state.spot_free``), and, in the kitchen, behind
the head string by KITCHEN_GAP. Snooker's ball in hand is in the D
(``place_cue_in_d``).
"""
from __future__ import annotations

import math

import numba
import numpy as np

from ..physics.state import SPOT_CLEAR, SPOT_EDGE, spot_free

HEAD_STRING = 0.25   # the head string's distance from the head rail, as a fraction of the table's length
FOOT_SPOT = 0.75     # the foot spot's, likewise
CENTRE_SPOT = 0.5    # the centre spot's, likewise (three-cushion's spot for a jumped ball)
OPENING_OFFSET = 0.182  # m: three-cushion's opening: the starting player's ball on the head string beside the head spot
KITCHEN_GAP = 1e-6   # m: a cue ball placed behind the head string keeps its centre this far behind the line
PLACE_RINGS = 400    # rings of the nearest-legal-spot search (radius step R/4: covers any table)
D_ARC_TOL = 1e-9     # m: a spot this little outside the D's arc counts as in the D, so a placed spot placed again stays
                     # put (a point projected onto the arc, then kept behind the line, lands within 1e-11 m of it)

_jit = numba.njit(cache=True, nogil=True)


@_jit
def _legal_spot(x, y, pos, on, width, y_hi, R, pockets):
    """The nearest point to (x, y) where a cue ball may be placed: clamped into
    the allowed rectangle (centre R + SPOT_EDGE inside the cushions, y at most
    ``y_hi``), then, if it overlaps a ball or a pocket, the first free point
    of rings of radius k R / 4 (k = 1, 2, ...; 8 k points each, nearest ring
    first). Returns (x, y, found)."""
    edge = R + SPOT_EDGE
    md = 2 * R + SPOT_CLEAR
    x = min(max(x, edge), width - edge)
    y = min(max(y, edge), y_hi)
    if spot_free(x, y, pos, on, width, y_hi + edge, edge, pockets, md):
        return x, y, True
    for k in range(1, PLACE_RINGS):
        r = 0.25 * R * k
        m = 8 * k
        for j in range(m):
            a = 2.0 * math.pi * j / m
            cx, cy = x + r * math.cos(a), y + r * math.sin(a)
            if cy <= y_hi and spot_free(cx, cy, pos, on, width, y_hi + edge, edge, pockets, md):
                return cx, cy, True
    return x, y, False


@_jit
def place_cue(want, pos, pocket, kitchen, width, length, R, pockets, out, moved):
    """Per table: the cue ball (ball 0) placed at the legal spot nearest to
    ``want`` [n, 2]; ``kitchen[e]`` limits it to behind the head string.
    Writes ``out`` [n, 2] and ``moved`` [n] (the spot differs from ``want``);
    returns False if some table has no free spot."""
    ok = True
    for e in range(want.shape[0]):
        on = pocket[e] < 0
        on[0] = False  # the cue ball is in hand
        y_hi = HEAD_STRING * length - KITCHEN_GAP if kitchen[e] else length - R - SPOT_EDGE
        x, y, found = _legal_spot(want[e, 0], want[e, 1], pos[e], on, width, y_hi, R, pockets)
        ok &= found
        out[e, 0], out[e, 1] = x, y
        moved[e] = x != want[e, 0] or y != want[e, 1]
    return ok


def legal_spots(xy, pos, pocket, kitchen, width: float, length: float, R: float, pockets, d=None):
    """``place_cue`` for arrays from Python: the legal cue-ball spots nearest
    to ``xy`` [n, 2] on tables ``pos`` [n, B, 2] / ``pocket`` [n, B], behind
    the head string where ``kitchen`` [n]; on a snooker table (``d``, the
    D's centre and radius: ``d_of``) in the D (``place_cue_in_d``):
    (spots [n, 2], moved [n]). Raises RuntimeError if some table has no free spot."""
    xy = np.ascontiguousarray(np.asarray(xy, dtype=np.float64).reshape(len(kitchen), 2))
    out, moved = np.empty((len(kitchen), 2)), np.zeros(len(kitchen), dtype=bool)
    pos, pocket = np.ascontiguousarray(pos), np.ascontiguousarray(pocket)
    if d is not None:
        ok = place_cue_in_d(xy, pos, pocket, np.asarray(d, dtype=np.float64), width, length, R, pockets, out, moved)
    else:
        ok = place_cue(xy, pos, pocket, np.ascontiguousarray(kitchen), width, length, R, pockets, out, moved)
    if not ok:
        raise RuntimeError("no free spot for the cue ball")
    return out, moved


def d_of(table):
    """A snooker table's D as (cx, cy, r) for ``legal_spots``; None on a table without one."""
    m = getattr(table, "marks", None)
    return None if m is None else np.array([m.d_centre[0], m.d_centre[1], m.d_radius])


@_jit
def _in_d(x, y, cx, cy, r):
    return y <= cy - KITCHEN_GAP and math.hypot(x - cx, y - cy) <= r


@_jit
def place_cue_in_d(want, pos, pocket, d, width, length, R, pockets, out, moved):
    """Snooker's ball in hand (WPBSA Section 2: "in-hand" means in the D):
    per table the cue ball at the point of the D nearest to ``want`` [n, 2]
    (the D's line and arc count, its centre kept KITCHEN_GAP behind the
    baulk line), then, if that overlaps a ball, the first free point of the
    rings of ``_legal_spot`` that lies in the D. ``d``: the D's centre and
    radius (cx, cy, r). Writes ``out``, ``moved``; returns False if some
    table has no free spot."""
    cx, cy = d[0], d[1]
    r = d[2] - SPOT_EDGE
    md = 2 * R + SPOT_CLEAR
    edge = R + SPOT_EDGE
    ok = True
    for e in range(want.shape[0]):
        on = pocket[e] < 0
        on[0] = False
        x, y = want[e, 0], min(want[e, 1], cy - KITCHEN_GAP)
        dist = math.hypot(x - cx, y - cy)
        if dist > r + D_ARC_TOL:  # onto the arc, then behind the line again (the projection moves a point near the
            # line towards the centre's y, past the KITCHEN_GAP margin)
            x, y = cx + (x - cx) * r / dist, min(cy + (y - cy) * r / dist, cy - KITCHEN_GAP)
        found = spot_free(x, y, pos[e], on, width, length, edge, pockets, md)
        if not found:
            for k in range(1, PLACE_RINGS):
                rr = 0.25 * R * k
                m = 8 * k
                for j in range(m):
                    a = 2.0 * math.pi * j / m
                    qx, qy = x + rr * math.cos(a), y + rr * math.sin(a)
                    if _in_d(qx, qy, cx, cy, r) and spot_free(qx, qy, pos[e], on, width, length, edge, pockets, md):
                        x, y, found = qx, qy, True
                        break
                if found or rr > 2 * r:
                    break
        ok &= found
        out[e, 0], out[e, 1] = x, y
        moved[e] = x != want[e, 0] or y != want[e, 1]
    return ok
