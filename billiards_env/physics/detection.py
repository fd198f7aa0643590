"""Contact-time detection for both solvers (numba kernels).

Event solver: within a motion state a ball's position is quadratic in time,
r(t) = r0 + v t + a t^2 / 2, so the gap function of a ball pair is a quartic,
of a ball and a cushion line a quadratic, of a ball and a jaw tip or pocket
circle a quartic (Leckie & Greenspan 2006, "An event-based pool physics
simulator"). Step solver: straight-line motion within a step, as in the
write-up's stage 3, so every gap function is at most quadratic.

Gap functions are signed so that contact is f(t) = 0 and f > 0 is apart.
"""
import math

from ._jit import njit
from . import constants as C
from .motion import acceleration
from .roots import first_entry, first_entry_quadratic


@njit
def _moving(s):
    return s == C.SLIDING or s == C.ROLLING


@njit
def pair_time(pos, vel, om, st, e, i, j, H, p):
    """Time from now until balls i and j meet (inf if not within H)."""
    si, sj = st[e, i], st[e, j]
    if si == C.POCKETED or sj == C.POCKETED or not (_moving(si) or _moving(sj)):
        return math.inf
    R2 = 2.0 * p[C.P_R]
    dx = pos[e, i, 0] - pos[e, j, 0]
    dy = pos[e, i, 1] - pos[e, j, 1]
    dvx = vel[e, i, 0] - vel[e, j, 0]
    dvy = vel[e, i, 1] - vel[e, j, 1]
    aix, aiy = acceleration(vel, om, st, e, i, p)
    ajx, ajy = acceleration(vel, om, st, e, j, p)
    dax, day = aix - ajx, aiy - ajy
    # broad phase: the gap cannot close within H
    gap = math.hypot(dx, dy) - R2
    if gap > C.CONTACT_TOL and gap > math.hypot(dvx, dvy) * H + 0.5 * math.hypot(dax, day) * H * H:
        return math.inf
    c4 = 0.25 * (dax * dax + day * day)
    c3 = dvx * dax + dvy * day
    c2 = dvx * dvx + dvy * dvy + dx * dax + dy * day
    c1 = 2.0 * (dx * dvx + dy * dvy)
    c0 = dx * dx + dy * dy - R2 * R2
    return first_entry(c4, c3, c2, c1, c0, H, 2.0 * R2 * C.CONTACT_TOL, -math.inf)


@njit
def _circle_time(px, py, vx, vy, ax, ay, cx, cy, r, H, f_tol, f_floor):
    """Time until a point moving as p + v t + a t^2/2 enters the circle (c, r)."""
    dx, dy = px - cx, py - cy
    gap = math.hypot(dx, dy) - r
    if gap > math.hypot(vx, vy) * H + 0.5 * math.hypot(ax, ay) * H * H + f_tol:
        return math.inf
    c4 = 0.25 * (ax * ax + ay * ay)
    c3 = vx * ax + vy * ay
    c2 = vx * vx + vy * vy + dx * ax + dy * ay
    c1 = 2.0 * (dx * vx + dy * vy)
    c0 = dx * dx + dy * dy - r * r
    return first_entry(c4, c3, c2, c1, c0, H, f_tol, f_floor)


@njit
def boundary_time(pos, vel, om, st, e, i, H, p, segs, norms, tips, pockets, quadratic):
    """Earliest contact of ball i with a cushion segment, a jaw tip or a
    pocket within H. Returns (time, kind, index). With ``quadratic`` the
    ball moves in a straight line (step solver)."""
    best = math.inf
    kind = -1
    idx = -1
    if not _moving(st[e, i]):
        return best, kind, idx
    R = p[C.P_R]
    x, y = pos[e, i, 0], pos[e, i, 1]
    vx, vy = vel[e, i, 0], vel[e, i, 1]
    if quadratic:
        ax, ay = 0.0, 0.0
    else:
        ax, ay = acceleration(vel, om, st, e, i, p)
    reach = math.hypot(vx, vy) * H + 0.5 * math.hypot(ax, ay) * H * H
    for s in range(segs.shape[0]):
        nx, ny = norms[s, 0], norms[s, 1]
        c0 = (x - segs[s, 0]) * nx + (y - segs[s, 1]) * ny - R
        if c0 > reach + C.CONTACT_TOL:
            continue
        c1 = vx * nx + vy * ny
        c2 = 0.5 * (ax * nx + ay * ny)
        if quadratic:
            t = first_entry_quadratic(0.0, c1, c0, min(H, best), C.CONTACT_TOL, -R)
        else:
            t = first_entry(0.0, 0.0, c2, c1, c0, min(H, best), C.CONTACT_TOL, -R)
        if t < best:
            # the contact point must lie on the segment (tips handle its ends)
            qx = x + vx * t + 0.5 * ax * t * t - segs[s, 0]
            qy = y + vy * t + 0.5 * ay * t * t - segs[s, 1]
            ex, ey = segs[s, 2] - segs[s, 0], segs[s, 3] - segs[s, 1]
            lam = (qx * ex + qy * ey) / (ex * ex + ey * ey)
            if 0.0 <= lam <= 1.0:
                best = t; kind = C.EV_CUSHION; idx = s
    for v in range(tips.shape[0]):
        if quadratic:
            dx, dy = x - tips[v, 0], y - tips[v, 1]
            c0 = dx * dx + dy * dy - R * R
            t = first_entry_quadratic(vx * vx + vy * vy, 2.0 * (dx * vx + dy * vy), c0,
                                      min(H, best), 2.0 * R * C.CONTACT_TOL, -math.inf)
        else:
            t = _circle_time(x, y, vx, vy, ax, ay, tips[v, 0], tips[v, 1], R, min(H, best),
                             2.0 * R * C.CONTACT_TOL, -math.inf)
        if t < best:
            best = t; kind = C.EV_JAW_TIP; idx = v
    for k in range(pockets.shape[0]):
        cx, cy, r = pockets[k, 0], pockets[k, 1], pockets[k, 2]
        if quadratic:
            dx, dy = x - cx, y - cy
            t = first_entry_quadratic(vx * vx + vy * vy, 2.0 * (dx * vx + dy * vy),
                                      dx * dx + dy * dy - r * r, min(H, best), 0.0, -math.inf)
        else:
            t = _circle_time(x, y, vx, vy, ax, ay, cx, cy, r, min(H, best), 0.0, -math.inf)
        if t < best:
            best = t; kind = C.EV_POCKET; idx = k
    return best, kind, idx


@njit
def pair_time_linear(pos, vel, st, e, i, j, H, p):
    """Straight-line version of ``pair_time`` for the step solver."""
    si, sj = st[e, i], st[e, j]
    if si == C.POCKETED or sj == C.POCKETED or not (_moving(si) or _moving(sj)):
        return math.inf
    R2 = 2.0 * p[C.P_R]
    dx = pos[e, i, 0] - pos[e, j, 0]
    dy = pos[e, i, 1] - pos[e, j, 1]
    dvx = vel[e, i, 0] - vel[e, j, 0]
    dvy = vel[e, i, 1] - vel[e, j, 1]
    c1 = 2.0 * (dx * dvx + dy * dvy)
    if c1 >= 0.0:
        return math.inf
    c0 = dx * dx + dy * dy - R2 * R2
    if c0 > 0.0 and math.sqrt(c0 + R2 * R2) - R2 > math.hypot(dvx, dvy) * H:
        return math.inf
    return first_entry_quadratic(dvx * dvx + dvy * dvy, c1, c0, H, 2.0 * R2 * C.CONTACT_TOL, -math.inf)
