"""A ball in flight at a cushion, a pocket and the rail (``Effects(airborne)``):
whether it strikes the cushion, drops into the pocket or leaves the table,
and where an off-table ball comes down.

Model. The cushion is a wall as high as its nose (``PhysicsParams.h_c``
above the slate) standing where the planar models put the contact: a ball
in flight meets a cushion when its centre comes within R of the cushion line
(a jaw tip: within R of the tip), as on the felt. If its lowest point is
then below the nose (h < h_c) it strikes the cushion: the table's cushion
model resolves the horizontal impact, and the vertical velocity is kept
(those models drop the vertical part of their impulse; the nose's downward
push on a ball in flight is left out). If its lowest point is above the
nose it passes over the cushion and leaves the table. It comes down on the
rail top (``constants.OFF_RAIL``) if it descends to the nose's height within
``RAIL_WIDTH`` beyond the cushion line, else on the floor (``OFF_FLOOR``):
the rail top is taken level with the nose and the ball is not followed
there (a ball that lands on the rail and rolls back is counted off the
table, where the rules of every game put a ball that leaves the bed). A
ball in flight entering a pocket's capture circle below the nose's height
drops in; above it, it drops in if it comes down to the nose's height still
over the circle, and otherwise carries over the pocket and off the table.

pooltool's main branch models the cushion's nose with a radius (a ball in
flight can glance off its rounded top) and has no off-table state yet; the
wall here is its limit of a sharp nose, which is why a ball that clears the
nose by less than the nose's rounding leaves the table here and would
rebound there.
"""
import math

from .. import constants as C
from .._jit import njit
from ..airborne import drop_time, rise
from ..detection import boundary_time as planar_boundary_time

# From the cushion line to the rail's outer edge (m): a pool table's
# cushion rubber (about 5 cm) and rail top (about 10 cm). A ball that comes
# down within it lands on the rail, beyond it on the floor.
RAIL_WIDTH = 0.15
# Index of an off-table event that crossed a pocket, not a cushion (its
# ``b``; a cushion's is its segment, a jaw tip's -2 - tip).
OVER_POCKET = -1


@njit
def boundary_time(balls, e, i, H, p, geo):
    """Earliest boundary event of ball i in flight within H (its landing):
    (time, kind, index), kind EV_CUSHION / EV_JAW_TIP (strikes it),
    EV_POCKET (drops in) or EV_OFF_TABLE (module docstring)."""
    t, kind, idx = planar_boundary_time(balls, e, i, 0.0, 0.0, H, p, geo, False)
    if kind < 0:
        return t, kind, idx
    g, hc = p[C.P_G], p[C.P_H_C]
    h, vz = rise(balls.air[e, i, 0], balls.air[e, i, 1], t, g)
    if kind == C.EV_POCKET:
        if h <= hc:
            return t, kind, idx
        td = drop_time(h - hc, vz, g)
        x = balls.pos[e, i, 0] + balls.vel[e, i, 0] * (t + td) - geo.pockets[idx, 0]
        y = balls.pos[e, i, 1] + balls.vel[e, i, 1] * (t + td) - geo.pockets[idx, 1]
        if x * x + y * y <= geo.pockets[idx, 2] ** 2:
            return t, kind, idx
        return t, C.EV_OFF_TABLE, OVER_POCKET
    if h < hc:
        return t, kind, idx
    return t, C.EV_OFF_TABLE, idx if kind == C.EV_CUSHION else -2 - idx


@njit
def landing_code(balls, geo, e, i, b, p):
    """Where ball i, passing over boundary b (``boundary_time``'s index of
    an off-table event) now, comes down: OFF_RAIL or OFF_FLOOR."""
    g, hc, R = p[C.P_G], p[C.P_H_C], p[C.P_R]
    vx, vy = balls.vel[e, i, 0], balls.vel[e, i, 1]
    td = drop_time(max(balls.air[e, i, 0] - hc, 0.0), balls.air[e, i, 1], g)
    if b >= 0:  # outwards across the cushion line (its normal points into the table)
        out = -(vx * geo.norms[b, 0] + vy * geo.norms[b, 1])
    else:
        out = math.sqrt(vx * vx + vy * vy)
    # the centre is R inside the line now
    return C.OFF_RAIL if out * td - R <= RAIL_WIDTH else C.OFF_FLOOR
