"""Ball-ball impact response (numba kernels).

Instantaneous impulse model for equal balls (Alciatore's technical proofs on throw, the model of
pooltool's "frictional inelastic" resolver; the write-up's stage 4 with its
signs made consistent): the normal impulse exchanges velocity along the line
of centres with restitution e_b; Coulomb friction mu_b acts against the slip
of the two contact points, bounded by the impulse that ends the slip
(m |u_t| / 7 for two equal solid spheres), so it never reverses the slip and
never adds energy. The friction's vertical component turns the balls but is
taken up by the table, not by their linear velocity. Momentum in the table
plane is conserved exactly (equal and opposite impulses).

Impacts slower than ZENO_SPEED, and contacts with no approach that the felt
presses together, are resting contacts: restitution 0, the balls' slides end
at once, and a pair still pressed together moves on at its mean velocity
(see constants.ZENO_SPEED and ``_rest``).
"""
import math

from ._jit import njit
from . import constants as C
from .vec import norm
from .motion import end_slide


@njit
def _approach(pos, vel, e, i, j):
    """d * (normal approach speed): the same expression, up to the factor -2,
    as the detection's c1, so a pair the detectors call closing (c1 < 0) is
    always approaching here (> 0): no rounding disagreement can stall time."""
    dx = pos[e, i, 0] - pos[e, j, 0]
    dy = pos[e, i, 1] - pos[e, j, 1]
    return -(dx * (vel[e, i, 0] - vel[e, j, 0]) + dy * (vel[e, i, 1] - vel[e, j, 1]))


@njit
def _rolling_accel(vel, e, i, mu_r_g):
    vx, vy = vel[e, i, 0], vel[e, i, 1]
    n = norm(vx, vy)
    if n <= C.SPEED_EPS:
        return 0.0, 0.0
    return -mu_r_g * vx / n, -mu_r_g * vy / n


@njit
def _rest(pos, vel, om, st, e, i, j, nx, ny, d, p, spin_on):
    """Resting contact (approach below ZENO_SPEED, or none but the felt
    presses the pair together): end both slides; if the rolling balls are
    still pressed together (the gap's second derivative negative at zero
    approach), they move on together at their mean velocity. Each step
    conserves momentum in the plane (slide ends are felt impulses) and never
    adds energy (rolling energy 7/10 m v^2 is convex in v)."""
    R = p[C.P_R]
    if spin_on:
        # by the actual slip, not st: st still holds the state before the
        # impulse (a ball at rest that was just hit slides but says STATIONARY)
        end_slide(vel, om, e, i, R)
        end_slide(vel, om, e, j, R)
    # make the normal approach non-positive exactly as the detectors see it
    k = 1.0
    for _ in range(8):
        wr = _approach(pos, vel, e, i, j)
        if wr <= 0.0:
            break
        jn = 0.5 * k * wr / d
        vel[e, i, 0] -= jn * nx; vel[e, i, 1] -= jn * ny
        vel[e, j, 0] += jn * nx; vel[e, j, 1] += jn * ny
        k *= 2.0
    mu_r_g = p[C.P_MU_R] * p[C.P_G]
    aix, aiy = _rolling_accel(vel, e, i, mu_r_g)
    ajx, ajy = _rolling_accel(vel, e, j, mu_r_g)
    dvx = vel[e, i, 0] - vel[e, j, 0]
    dvy = vel[e, i, 1] - vel[e, j, 1]
    # gap'' / 2 for |r_i - r_j|^2 with r_i - r_j = -d n
    c2 = dvx * dvx + dvy * dvy - d * ((aix - ajx) * nx + (aiy - ajy) * ny)
    if c2 < -2.0 * d * C.ACCEL_EPS:  # the detector's threshold (roots.first_entry)
        mx = 0.5 * (vel[e, i, 0] + vel[e, j, 0])
        my = 0.5 * (vel[e, i, 1] + vel[e, j, 1])
        for b in (i, j):
            vel[e, b, 0] = mx; vel[e, b, 1] = my
            if spin_on:
                om[e, b, 0] = -my / R; om[e, b, 1] = mx / R


@njit
def resolve_ball_ball(pos, vel, om, st, e, i, j, p, friction_on, spin_on):
    """Impulses of an impact of balls i and j, which touch. Returns the normal
    approach speed (m/s) before the impact; below ZENO_SPEED (including a
    contact the detector reported without approach, pressed by the felt) the
    caller follows with ``rest_contact``."""
    R, m = p[C.P_R], p[C.P_M]
    nx = pos[e, j, 0] - pos[e, i, 0]
    ny = pos[e, j, 1] - pos[e, i, 1]
    d = norm(nx, ny)
    nx /= d; ny /= d
    # approach speed along the line of centres (> 0 when closing)
    w = _approach(pos, vel, e, i, j) / d
    if w > 0.0:
        restitution = 0.0 if w < C.ZENO_SPEED else p[C.P_E_B]
        jn = 0.5 * (1.0 + restitution) * w  # normal impulse / m
        if friction_on:
            _friction(vel, om, e, i, j, nx, ny, R, p[C.P_MU_B] * jn)
        vel[e, i, 0] -= jn * nx; vel[e, i, 1] -= jn * ny
        vel[e, j, 0] += jn * nx; vel[e, j, 1] += jn * ny
    return w


@njit
def rest_contact(pos, vel, om, st, e, i, j, p, spin_on):
    """After an impact slower than ZENO_SPEED (or a pressed contact without
    approach): the resting-contact treatment of ``_rest``. Kept apart from
    the impulse so that the impulse alone can be checked for momentum."""
    nx = pos[e, j, 0] - pos[e, i, 0]
    ny = pos[e, j, 1] - pos[e, i, 1]
    d = norm(nx, ny)
    _rest(pos, vel, om, st, e, i, j, nx / d, ny / d, d, p, spin_on)


@njit
def _friction(vel, om, e, i, j, nx, ny, R, jt_max):
    """Coulomb friction impulse (bounded by jt_max / m and by the impulse
    that ends the contact slip) between touching balls i and j."""
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
        jt = min(jt_max, slip / 7.0)  # friction impulse / m
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
