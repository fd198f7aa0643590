"""Ball-ball impact response (numba kernels).

Instantaneous impulse model for equal balls (Alciatore TP A.14, the model of
pooltool's "frictional inelastic" resolver; the write-up's stage 4 with its
signs made consistent): the normal impulse exchanges velocity along the line
of centres with restitution e_b; Coulomb friction mu_b acts against the slip
of the two contact points, bounded by the impulse that ends the slip
(m |u_t| / 7 for two equal solid spheres), so it never reverses the slip and
never adds energy. The friction's vertical component turns the balls but is
taken up by the table, not by their linear velocity. Momentum in the table
plane is conserved exactly (equal and opposite impulses).

Impacts slower than ZENO_SPEED are resting contacts: restitution 0 and the
balls' slides end at once (see constants.ZENO_SPEED).
"""
import math

from ._jit import njit
from . import constants as C
from .motion import end_slide


@njit
def resolve_ball_ball(pos, vel, om, st, e, i, j, p, friction_on, spin_on):
    """Resolve an impact of balls i and j, which touch. Returns the normal
    approach speed (m/s) before the impact."""
    R, m = p[C.P_R], p[C.P_M]
    nx = pos[e, j, 0] - pos[e, i, 0]
    ny = pos[e, j, 1] - pos[e, i, 1]
    d = math.hypot(nx, ny)
    nx /= d; ny /= d
    # approach speed along the line of centres (> 0 when closing)
    w = (vel[e, i, 0] - vel[e, j, 0]) * nx + (vel[e, i, 1] - vel[e, j, 1]) * ny
    if w <= 0.0:
        return w
    resting = w < C.ZENO_SPEED
    restitution = 0.0 if resting else p[C.P_E_B]
    jn = 0.5 * (1.0 + restitution) * w  # normal impulse / m
    if friction_on:
        # contact-point velocities: ball i at +R n, ball j at -R n
        # u = v + omega x r, r = (rx, ry, 0)
        uix = vel[e, i, 0] - om[e, i, 2] * (R * ny)
        uiy = vel[e, i, 1] + om[e, i, 2] * (R * nx)
        uiz = om[e, i, 0] * (R * ny) - om[e, i, 1] * (R * nx)
        ujx = vel[e, j, 0] + om[e, j, 2] * (R * ny)
        ujy = vel[e, j, 1] - om[e, j, 2] * (R * nx)
        ujz = -om[e, j, 0] * (R * ny) + om[e, j, 1] * (R * nx)
        ux, uy, uz = uix - ujx, uiy - ujy, uiz - ujz
        un = ux * nx + uy * ny
        tx, ty, tz = ux - un * nx, uy - un * ny, uz
        slip = math.sqrt(tx * tx + ty * ty + tz * tz)
        if slip > C.SPEED_EPS:
            jt = min(p[C.P_MU_B] * jn, slip / 7.0)  # friction impulse / m
            fx, fy, fz = -jt * tx / slip, -jt * ty / slip, -jt * tz / slip  # on ball i
            vel[e, i, 0] += fx; vel[e, i, 1] += fy
            vel[e, j, 0] -= fx; vel[e, j, 1] -= fy
            # d omega = (r x J) / I, I = 2/5 m R^2; r_i = R n, r_j = -R n,
            # J_j = -J_i: both balls turn the same way
            k = 2.5 / R
            cx = ny * fz
            cy = -nx * fz
            cz = nx * fy - ny * fx
            om[e, i, 0] += k * cx; om[e, i, 1] += k * cy; om[e, i, 2] += k * cz
            om[e, j, 0] += k * cx; om[e, j, 1] += k * cy; om[e, j, 2] += k * cz
    vel[e, i, 0] -= jn * nx; vel[e, i, 1] -= jn * ny
    vel[e, j, 0] += jn * nx; vel[e, j, 1] += jn * ny
    if resting and spin_on:
        if st[e, i] == C.SLIDING:
            end_slide(vel, om, e, i, R)
        if st[e, j] == C.SLIDING:
            end_slide(vel, om, e, j, R)
    return w
