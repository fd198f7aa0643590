"""What every ball-ball model shares (numba kernels): the line of centres,
the normal approach speed, the normal impulse with restitution e_b, and the
resting-contact treatment of impacts slower than ZENO_SPEED.

Instantaneous impulses between equal solid balls: the normal impulse
exchanges velocity along the line of centres with restitution e_b (0 below
ZENO_SPEED); a model may add a tangential (friction) impulse. Momentum in the
table plane is conserved exactly (equal and opposite impulses).

Impacts slower than ZENO_SPEED, and contacts with no approach that the felt
presses together, are resting contacts: restitution 0, the balls' slides end
at once, and a pair still pressed together moves on at its mean velocity
(see constants.ZENO_SPEED and ``rest_contact``).
"""
from .. import constants as C
from .._jit import njit
from ..motion import end_slide, rolling_acceleration
from ..vec import norm


@njit
def approach(pos, vel, e, i, j):
    """d * (normal approach speed): the same expression, up to the factor -2,
    as the detection's c1, so a pair the detectors call closing (c1 < 0) is
    always approaching here (> 0): no rounding disagreement can stall time."""
    dx = pos[e, i, 0] - pos[e, j, 0]
    dy = pos[e, i, 1] - pos[e, j, 1]
    return -(dx * (vel[e, i, 0] - vel[e, j, 0]) + dy * (vel[e, i, 1] - vel[e, j, 1]))


@njit
def line_of_centres(pos, e, i, j):
    """Unit vector (nx, ny) from ball i to ball j, and their distance d."""
    nx = pos[e, j, 0] - pos[e, i, 0]
    ny = pos[e, j, 1] - pos[e, i, 1]
    d = norm(nx, ny)
    return nx / d, ny / d, d


@njit
def normal_impulse(w, p):
    """Normal impulse / m of an impact approaching at w > 0 (m/s): half the
    change of the approach speed, (1 + e) w / 2, with e = e_b, or 0 for an
    impact slower than ZENO_SPEED."""
    restitution = 0.0 if w < C.ZENO_SPEED else p[C.P_E_B]
    return 0.5 * (1.0 + restitution) * w


@njit
def push_apart(vel, e, i, j, nx, ny, jn):
    """Apply the normal impulse jn (/ m) along (nx, ny), from i towards j."""
    vel[e, i, 0] -= jn * nx; vel[e, i, 1] -= jn * ny
    vel[e, j, 0] += jn * nx; vel[e, j, 1] += jn * ny


@njit
def _rolling_or_rest(vel, e, i, p):
    """Felt acceleration of ball i after a resting contact: rolling, or
    none if it moves slower than SPEED_EPS (at rest, as ``classify`` will
    find it)."""
    if norm(vel[e, i, 0], vel[e, i, 1]) <= C.SPEED_EPS:
        return 0.0, 0.0
    return rolling_acceleration(vel[e, i, 0], vel[e, i, 1], p)


@njit
def rest_contact(pos, vel, om, e, i, j, p, spin_on):
    """Resting contact after an impact slower than ZENO_SPEED (or a contact
    without approach, pressed by the felt): end both slides; if the rolling
    balls are still pressed together (the gap's second derivative negative at
    zero approach), they move on together at their mean velocity. Each step
    conserves momentum in the plane (slide ends are felt impulses) and never
    adds energy (rolling energy 7/10 m v^2 is convex in v). Kept apart from
    the impulse so that the impulse alone can be checked for momentum."""
    nx, ny, d = line_of_centres(pos, e, i, j)
    R = p[C.P_R]
    if spin_on:
        # by the actual slip, not st: st still holds the state before the
        # impulse (a ball at rest that was just hit slides but says STATIONARY)
        end_slide(vel, om, e, i, R)
        end_slide(vel, om, e, j, R)
    # make the normal approach non-positive exactly as the detectors see it
    k = 1.0
    for _ in range(8):
        wr = approach(pos, vel, e, i, j)
        if wr <= 0.0:
            break
        jn = 0.5 * k * wr / d
        push_apart(vel, e, i, j, nx, ny, jn)
        k *= 2.0
    # both balls now roll, or rest: the felt's rolling law
    aix, aiy = _rolling_or_rest(vel, e, i, p)
    ajx, ajy = _rolling_or_rest(vel, e, j, p)
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
