"""Cushion impact with friction and spin after Han (2005), "Dynamics in
carom and three cushion billiards", J. Mech. Sci. Tech. 19(4), eqs. 12-22.

The cushion nose touches the ball above its equator, at height h_c, so the
contact normal is tilted by theta = asin(h_c / R - 1) from the horizontal.
In the cushion frame (X into the cushion, Y along it, Z up) the slip of the
contact point is (eq. 14)

    s_x = v_X sin(theta) + R w_Y,
    s_y = -v_Y - R w_Z cos(theta) + R w_X sin(theta),

and the normal velocity of approach c = -v_X cos(theta). The impulse along
the contact normal is P_z = -(1 + e_c) c m (eq. 17); the friction impulse is
the one that ends the slip, s / A with A = 7 / (2m), if it lies within the
cone f_c P_z (sticking, eqs. 18, 20), else f_c P_z along the slip (eq. 19).
Eqs. 21-22 turn the impulse back into the cushion frame; it changes v by P/m
and omega by (r x P) / I with I = 2/5 m R^2. The vertical impulse on the
ball's centre is taken up by the table (the ball is kept on the felt), as in
pooltool's implementation of the same paper.
"""
import math

from .. import constants as C
from .._jit import njit
from ..vec import norm


@njit
def resolve(vx, vy, wx, wy, wz, nx, ny, approach, e_c, p):
    """Cushion model (``contact`` describes the interface)."""
    R, m = p[C.P_R], p[C.P_M]
    # cushion frame: X into the cushion (-n), Y = Z x X, Z up
    Xx, Xy = -nx, -ny
    Yx, Yy = -Xy, Xx
    cvx = vx * Xx + vy * Xy
    cvy = vx * Yx + vy * Yy
    cwx = wx * Xx + wy * Xy
    cwy = wx * Yx + wy * Yy
    cwz = wz
    sin_t = p[C.P_H_C] / R - 1.0
    cos_t = math.sqrt(1.0 - sin_t * sin_t)
    # eq. 14: slip at the contact point (no vertical velocity)
    sx = cvx * sin_t + R * cwy
    sy = -cvy - R * cwz * cos_t + R * cwx * sin_t
    c = -cvx * cos_t
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
    cvx += PX / m
    cvy += PY / m
    k = R / (0.4 * m * R * R)
    cwx += -k * PY * sin_t
    cwy += k * (PX * sin_t - PZ * cos_t)
    cwz += k * PY * cos_t
    return (cvx * Xx + cvy * Yx, cvx * Xy + cvy * Yy,
            cwx * Xx + cwy * Yx, cwx * Xy + cwy * Yy, cwz)
