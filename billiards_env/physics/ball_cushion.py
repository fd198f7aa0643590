"""Ball-cushion impact response (numba kernels).

With cushion friction: Han (2005), "Dynamics in carom and three cushion
billiards", J. Mech. Sci. Tech. 19(4), eqs. 12-22: the cushion nose touches
the ball above its equator (height h, contact angle theta = asin(h/R - 1));
the normal impulse gives restitution e_c along the contact normal, friction
f_c acts against the contact slip and is capped by sticking (eqs. 17-20).
The vertical impulse on the ball's centre is taken up by the table (the ball
is kept on the felt), as in pooltool's implementation of the same paper.

Without cushion friction: a plain reflection of the normal velocity with
restitution e_c; tangential velocity and spin unchanged.

Impacts slower than ZENO_SPEED, and contacts reported without approach (the
felt pressing the ball into the cushion), are resting contacts: restitution
0, the slide ends at once, no normal velocity into the cushion remains.
"""
import math

from ._jit import njit
from . import constants as C
from .vec import norm
from .motion import end_slide


@njit
def resolve_cushion(vel, om, st, e, i, rx, ry, p, friction_on, spin_on):
    """Resolve ball i's impact with a cushion. (rx, ry) is the contact normal,
    pointing into the table, exactly as the detector formed it (the unit
    normal of a cushion segment, or ball centre minus jaw tip): the approach
    test below uses the detector's own expression, so the two never disagree
    by rounding about whether the ball is closing. Returns the approach speed
    before the impact."""
    d = norm(rx, ry)
    nx, ny = rx / d, ry / d
    w = -(vel[e, i, 0] * rx + vel[e, i, 1] * ry) / d
    vn = -w
    resting = w < C.ZENO_SPEED
    if w <= 0.0:
        # reported without approach: the felt presses the ball into the
        # cushion (a slide whose friction points into it); end the slide
        if spin_on:  # a no-op unless the ball slips on the felt
            end_slide(vel, om, e, i, p[C.P_R])
        _unpress(vel, e, i, rx, ry)
        return w
    e_c = 0.0 if resting else p[C.P_E_C]
    if not friction_on:
        vel[e, i, 0] -= (1.0 + e_c) * vn * nx
        vel[e, i, 1] -= (1.0 + e_c) * vn * ny
    else:
        R, m = p[C.P_R], p[C.P_M]
        # cushion frame: X into the cushion (-n), Y = Z x X, Z up
        Xx, Xy = -nx, -ny
        Yx, Yy = -Xy, Xx
        vx = vel[e, i, 0] * Xx + vel[e, i, 1] * Xy
        vy = vel[e, i, 0] * Yx + vel[e, i, 1] * Yy
        wx = om[e, i, 0] * Xx + om[e, i, 1] * Xy
        wy = om[e, i, 0] * Yx + om[e, i, 1] * Yy
        wz = om[e, i, 2]
        sin_t = p[C.P_H_C] / R - 1.0
        cos_t = math.sqrt(1.0 - sin_t * sin_t)
        # Han eq. 14: slip at the contact point (no vertical velocity)
        sx = vx * sin_t + R * wy
        sy = -vy - R * wz * cos_t + R * wx * sin_t
        c = -vx * cos_t
        A = 3.5 / m
        B = 1.0 / m
        pz = -(1.0 + e_c) * c / B           # eq. 17
        s_abs = norm(sx, sy)
        if s_abs / A <= p[C.P_F_C] * pz:    # eqs. 18, 20: sticking
            px = sx / A
            py = sy / A
        else:                               # eq. 19: sliding throughout
            px = p[C.P_F_C] * pz * sx / s_abs
            py = p[C.P_F_C] * pz * sy / s_abs
        # eqs. 21-22: contact frame -> cushion frame
        PX = -px * sin_t - pz * cos_t
        PY = py
        PZ = px * cos_t - pz * sin_t
        vx += PX / m
        vy += PY / m
        k = R / (0.4 * m * R * R)
        wx += -k * PY * sin_t
        wy += k * (PX * sin_t - PZ * cos_t)
        wz += k * PY * cos_t
        vel[e, i, 0] = vx * Xx + vy * Yx
        vel[e, i, 1] = vx * Xy + vy * Yy
        om[e, i, 0] = wx * Xx + wy * Yx
        om[e, i, 1] = wx * Xy + wy * Yy
        om[e, i, 2] = wz
    if resting:
        if spin_on:  # by the slip after the impulse, not the stale st
            end_slide(vel, om, e, i, p[C.P_R])
        _unpress(vel, e, i, rx, ry)
    return w


@njit
def _unpress(vel, e, i, rx, ry):
    """After a resting contact, remove any velocity left into the cushion
    along the detector's normal (rx, ry) (rounding, or a slide's end), so the
    detector cannot see the ball closing again at the same instant. Removing
    it only lowers the energy."""
    r2 = rx * rx + ry * ry
    for _ in range(4):
        vr = vel[e, i, 0] * rx + vel[e, i, 1] * ry
        if vr >= 0.0:
            break
        vel[e, i, 0] -= vr / r2 * rx
        vel[e, i, 1] -= vr / r2 * ry
    if vel[e, i, 0] * rx + vel[e, i, 1] * ry < 0.0:  # rounding: stop the normal motion outright
        t = vel[e, i, 0] * (-ry) + vel[e, i, 1] * rx
        vel[e, i, 0] = -t * ry / r2
        vel[e, i, 1] = t * rx / r2
