"""Contact-time detection for both solvers (numba kernels).

Event solver: within a motion state a ball's position is quadratic in time,
r(t) = r0 + v t + a t^2 / 2, so the gap function of a ball pair is a quartic,
of a ball and a cushion line a quadratic, of a ball and a jaw tip or pocket
circle a quartic (Leckie & Greenspan 2006, "An event-based pool physics
simulator"). Step solver: straight-line motion within a step (a first-order
scheme), so every gap function is at most quadratic.

Gap functions are signed so that contact is f(t) = 0 and f > 0 is apart.
"""
import math

from ._jit import njit, njit_inline
from . import constants as C
from .layout import Motion
from .vec import norm
from .roots import first_entry, first_entry_quadratic


# Slack of the bounding-box broad phase (m): boxes are computed in the same
# float64 arithmetic as the roots, so 1 nm covers every rounding difference.
BOX_SLACK = 1e-9


@njit
def _moving(s):
    return s == C.SLIDING or s == C.ROLLING or s == C.AIRBORNE


@njit
def _extent(x, v, a, H):
    """Range of x + v t + a t^2 / 2 over t in [0, H]: the exact extent of a
    ball's path in one coordinate until its next transition."""
    x1 = x + v * H + 0.5 * a * H * H
    lo = min(x, x1)
    hi = max(x, x1)
    if a != 0.0:
        ts = -v / a
        if 0.0 < ts < H:
            xs = x + v * ts + 0.5 * a * ts * ts
            lo = min(lo, xs)
            hi = max(hi, xs)
    return lo, hi


@njit
def _apart(lo1, hi1, lo2, hi2, gap):
    """True if two intervals are more than ``gap`` apart."""
    return lo1 - hi2 > gap or lo2 - hi1 > gap


@njit_inline
def sweep_path(pos, vel, st, e, i, ax, ay, H, paths):
    """Store ball i's acceleration (ax, ay) and the box its path sweeps over
    [now, now + H] in paths[e, i] = (ax, ay, x_lo, x_hi, y_lo, y_hi)."""
    x, y = pos[e, i, 0], pos[e, i, 1]
    paths[e, i, 0] = ax; paths[e, i, 1] = ay
    if not _moving(st[e, i]):
        paths[e, i, 2] = x; paths[e, i, 3] = x; paths[e, i, 4] = y; paths[e, i, 5] = y
    elif H < math.inf:
        paths[e, i, 2], paths[e, i, 3] = _extent(x, vel[e, i, 0], ax, H)
        paths[e, i, 4], paths[e, i, 5] = _extent(y, vel[e, i, 1], ay, H)
    else:
        paths[e, i, 2] = -math.inf; paths[e, i, 3] = math.inf
        paths[e, i, 4] = -math.inf; paths[e, i, 5] = math.inf


@njit
def paths_apart(paths, e, i, j, gap):
    """The broad phase: the boxes swept by balls i and j (``sweep_path``)
    stay more than ``gap`` (+ BOX_SLACK) apart in x or in y."""
    return (_apart(paths[e, i, 2], paths[e, i, 3], paths[e, j, 2], paths[e, j, 3], gap + BOX_SLACK)
            or _apart(paths[e, i, 4], paths[e, i, 5], paths[e, j, 4], paths[e, j, 5], gap + BOX_SLACK))


@njit_inline
def pair_time(pos, vel, st, paths, e, i, j, H, p, lag):
    """Time from now until balls i and j meet (inf if not within H).
    ``paths`` holds each ball's acceleration and swept box (``sweep_path``).
    Ball i's state is at the current time, ball j's ``lag`` seconds earlier
    (the event solver evolves a ball only when an event involves it): j's
    quadratic path is shifted to now, the same arithmetic as
    ``motion.evolve``."""
    si, sj = st[e, i], st[e, j]
    if si == C.POCKETED or sj == C.POCKETED or not (_moving(si) or _moving(sj)):
        return math.inf
    R2 = 2.0 * p[C.P_R]
    # broad phase: the boxes swept by the two paths stay 2R apart
    if paths_apart(paths, e, i, j, R2):
        return math.inf
    xj, yj = pos[e, j, 0], pos[e, j, 1]
    vxj, vyj = vel[e, j, 0], vel[e, j, 1]
    if lag > 0.0 and _moving(sj):
        axj, ayj = paths[e, j, 0], paths[e, j, 1]
        xj += vxj * lag + 0.5 * axj * lag * lag
        yj += vyj * lag + 0.5 * ayj * lag * lag
        vxj += axj * lag
        vyj += ayj * lag
    dx = pos[e, i, 0] - xj
    dy = pos[e, i, 1] - yj
    dvx = vel[e, i, 0] - vxj
    dvy = vel[e, i, 1] - vyj
    dax = paths[e, i, 0] - paths[e, j, 0]
    day = paths[e, i, 1] - paths[e, j, 1]
    if si == C.ROLLING and sj == C.ROLLING and dvx * dvx + dvy * dvy <= C.SPEED_EPS * C.SPEED_EPS:
        # Two rolling balls moving together: a rolling ball's acceleration
        # is -mu_r g v/|v|, the same for equal velocities, so a difference
        # here comes from the rounding of v, amplified by 1/|v| in slow
        # balls (above ACCEL_EPS below ~0.1 m/s). Taken as real it makes
        # a touching pair that rolls side by side collide again every 1e-8 s.
        dax = 0.0
        day = 0.0
    c4 = 0.25 * (dax * dax + day * day)
    c3 = dvx * dax + dvy * day
    c2 = dvx * dvx + dvy * dvy + dx * dax + dy * day
    c1 = 2.0 * (dx * dvx + dy * dvy)
    c0 = dx * dx + dy * dy - R2 * R2
    return first_entry(c4, c3, c2, c1, c0, H, 2.0 * R2 * C.CONTACT_TOL, -math.inf)


@njit
def _circle_time(m, cx, cy, r, H, f_tol, f_floor):
    """Time until a point moving as ``m`` (layout.Motion: p + v t + a t^2/2)
    enters the circle (c, r) within H; ``f_tol``, ``f_floor`` as in
    roots.first_entry."""
    px, py, vx, vy, ax, ay = m
    dx, dy = px - cx, py - cy
    gap = norm(dx, dy) - r
    if gap > norm(vx, vy) * H + 0.5 * norm(ax, ay) * H * H + f_tol:
        return math.inf
    c4 = 0.25 * (ax * ax + ay * ay)
    c3 = vx * ax + vy * ay
    c2 = vx * vx + vy * vy + dx * ax + dy * ay
    c1 = 2.0 * (dx * vx + dy * vy)
    c0 = dx * dx + dy * dy - r * r
    return first_entry(c4, c3, c2, c1, c0, H, f_tol, f_floor)


@njit
def _segment_time(segs, norms, s, m, H, R, quadratic):
    """Time until the ball moving as ``m`` (layout.Motion) touches cushion
    segment s within H (inf if not); the contact point must lie on the
    segment (tips handle its ends)."""
    x, y, vx, vy, ax, ay = m
    nx, ny = norms[s, 0], norms[s, 1]
    c0 = (x - segs[s, 0]) * nx + (y - segs[s, 1]) * ny - R
    c1 = vx * nx + vy * ny
    c2 = 0.5 * (ax * nx + ay * ny)
    if quadratic:
        t = first_entry_quadratic(0.0, c1, c0, H, C.CONTACT_TOL, -R)
    else:
        t = first_entry(0.0, 0.0, c2, c1, c0, H, C.CONTACT_TOL, -R)
    if t < math.inf:
        qx = x + vx * t + 0.5 * ax * t * t - segs[s, 0]
        qy = y + vy * t + 0.5 * ay * t * t - segs[s, 1]
        ex, ey = segs[s, 2] - segs[s, 0], segs[s, 3] - segs[s, 1]
        lam = (qx * ex + qy * ey) / (ex * ex + ey * ey)
        if not 0.0 <= lam <= 1.0:
            return math.inf
    return t


@njit
def _segment_box_apart(segs, s, bx0, bx1, by0, by1, gap):
    return (_apart(bx0, bx1, min(segs[s, 0], segs[s, 2]), max(segs[s, 0], segs[s, 2]), gap)
            or _apart(by0, by1, min(segs[s, 1], segs[s, 3]), max(segs[s, 1], segs[s, 3]), gap))


@njit
def _tip_time(tips, v, m, H, R, quadratic):
    """Time until the ball moving as ``m`` (layout.Motion) touches jaw tip v
    within H (inf if not)."""
    if quadratic:
        x, y, vx, vy = m.x, m.y, m.vx, m.vy
        dx, dy = x - tips[v, 0], y - tips[v, 1]
        c0 = dx * dx + dy * dy - R * R
        return first_entry_quadratic(vx * vx + vy * vy, 2.0 * (dx * vx + dy * vy), c0,
                                     H, 2.0 * R * C.CONTACT_TOL, -math.inf)
    return _circle_time(m, tips[v, 0], tips[v, 1], R, H, 2.0 * R * C.CONTACT_TOL, -math.inf)


@njit
def _pocket_time(pockets, k, m, H, quadratic):
    """Time until the centre of the ball moving as ``m`` (layout.Motion)
    enters pocket k's capture circle within H."""
    cx, cy, r = pockets[k, 0], pockets[k, 1], pockets[k, 2]
    if quadratic:
        x, y, vx, vy = m.x, m.y, m.vx, m.vy
        dx, dy = x - cx, y - cy
        return first_entry_quadratic(vx * vx + vy * vy, 2.0 * (dx * vx + dy * vy),
                                     dx * dx + dy * dy - r * r, H, 0.0, -math.inf)
    return _circle_time(m, cx, cy, r, H, 0.0, -math.inf)


@njit_inline
def boundary_time(balls, e, i, ax, ay, H, p, geo, quadratic):
    """Earliest contact of ball i of ``balls`` (layout.Balls), moving with
    acceleration (ax, ay), with a cushion segment, a jaw tip or a pocket of
    ``geo`` (layout.Geometry) within H. Returns (time, kind, index). With
    ``quadratic`` the ball moves in a straight line (step solver; pass
    ax = ay = 0).

    Broad phase: the rails (and tips near no pocket) are tested first; a
    pocket's jaws, tips and capture circle only if the box the path sweeps
    until the earliest rail contact (or H) reaches the pocket's
    neighbourhood (``geo.near``, table.pocket_groups)."""
    pos, vel, st = balls.pos, balls.vel, balls.st
    segs, norms, tips, pockets = geo.segs, geo.norms, geo.tips, geo.pockets
    best = math.inf
    kind = -1
    idx = -1
    if not _moving(st[e, i]):
        return best, kind, idx
    R = p[C.P_R]
    x, y = pos[e, i, 0], pos[e, i, 1]
    vx, vy = vel[e, i, 0], vel[e, i, 1]
    m = Motion(x, y, vx, vy, ax, ay)
    # the box swept by the ball's path until its next transition
    bx0, bx1, by0, by1 = -math.inf, math.inf, -math.inf, math.inf
    if H < math.inf:  # (H is infinite only without sliding friction)
        bx0, bx1 = _extent(x, vx, ax, H)
        by0, by1 = _extent(y, vy, ay, H)
    rails = geo.rails
    for q in range(rails.shape[0]):
        s = rails[q]
        if _segment_box_apart(segs, s, bx0, bx1, by0, by1, R + BOX_SLACK):
            continue
        t = _segment_time(segs, norms, s, m, min(H, best), R, quadratic)
        if t < best:
            best = t; kind = C.EV_CUSHION; idx = s
    free_tips = geo.free_tips
    for q in range(free_tips.shape[0]):
        v = free_tips[q]
        if (_apart(bx0, bx1, tips[v, 0], tips[v, 0], R + BOX_SLACK)
                or _apart(by0, by1, tips[v, 1], tips[v, 1], R + BOX_SLACK)):
            continue
        t = _tip_time(tips, v, m, min(H, best), R, quadratic)
        if t < best:
            best = t; kind = C.EV_JAW_TIP; idx = v
    if pockets.shape[0] == 0:
        return best, kind, idx
    if best < H:  # nothing after the first rail contact matters
        bx0, bx1 = _extent(x, vx, ax, best)
        by0, by1 = _extent(y, vy, ay, best)
    near, gsegs, gtips = geo.near, geo.gsegs, geo.gtips
    gap = R + BOX_SLACK
    for k in range(pockets.shape[0]):
        if _apart(bx0, bx1, near[k, 0], near[k, 1], gap) or _apart(by0, by1, near[k, 2], near[k, 3], gap):
            continue
        for q in range(gsegs.shape[1]):
            s = gsegs[k, q]
            if s < 0:
                break
            if _segment_box_apart(segs, s, bx0, bx1, by0, by1, gap):
                continue
            t = _segment_time(segs, norms, s, m, min(H, best), R, quadratic)
            if t < best:
                best = t; kind = C.EV_CUSHION; idx = s
        for q in range(gtips.shape[1]):
            v = gtips[k, q]
            if v < 0:
                break
            if _apart(bx0, bx1, tips[v, 0], tips[v, 0], gap) or _apart(by0, by1, tips[v, 1], tips[v, 1], gap):
                continue
            t = _tip_time(tips, v, m, min(H, best), R, quadratic)
            if t < best:
                best = t; kind = C.EV_JAW_TIP; idx = v
        cx, cy, r = pockets[k, 0], pockets[k, 1], pockets[k, 2]
        if _apart(bx0, bx1, cx, cx, r + BOX_SLACK) or _apart(by0, by1, cy, cy, r + BOX_SLACK):
            continue
        t = _pocket_time(pockets, k, m, min(H, best), quadratic)
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
    if c0 > 0.0 and math.sqrt(c0 + R2 * R2) - R2 > norm(dvx, dvy) * H:
        return math.inf
    return first_entry_quadratic(dvx * dvx + dvy * dvy, c1, c0, H, 2.0 * R2 * C.CONTACT_TOL, -math.inf)
