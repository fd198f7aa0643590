"""Ball-ball contact with a ball in flight (``Effects(airborne)``): the
contact time in 3D and the impact, frictionless, with the slate holding a
ball that lies on it.

Contact time. Each ball's centre moves on a quadratic path in 3D: on the
felt r(t) = r0 + v t + a t^2 / 2 with a the felt's (horizontal) deceleration
and no vertical motion; in flight a = (0, 0, -g). With D, V, A the
differences of the two balls' positions (heights h of the lowest points:
the radius cancels), velocities and accelerations, the squared distance of
the centres is the quartic

    |D + V t + A t^2 / 2|^2 = |A|^2/4 t^4 + V.A t^3 + (|V|^2 + D.A) t^2
                              + 2 D.V t + |D|^2,

the planar detector's (``detection.pair_time``) with the vertical terms
added, and the balls touch at its first entry below (2R)^2
(``roots.first_entry``). A jumped ball clears a ball it passes over exactly
when this has no root before the flight ends.

Impact. Smooth spheres (no friction between them: the throw models are
planar) exchange an impulse P along the unit line of centres n (from i to j,
in 3D), with the restitution e_b of the planar impacts (0 below ZENO_SPEED,
as ``contact.normal_impulse``). Two balls in flight:

    P / m = (1 + e) w / 2,   w = -(v_j - v_i).n > 0 the approach speed.

A ball on the slate struck from above (n_z < 0 towards it: it is the lower
ball, its centre never above the other's) is pressed into the slate, which
takes the vertical part of the impulse: an impulsive constraint with no
rebound, so that ball keeps vz = 0 and only the horizontal part n_h of n
moves it. Its change of approach speed is then P n_h^2 / m instead of
P / m, so

    P / m = (1 + e) w / (1 + n_h^2),

the flying ball gets -P n / m (its vertical part lifts it), the ball on the
slate P n_h / m. The constraint does no work (the ball does not move into
the slate), so with e <= 1 the impact never adds energy; horizontal momentum
is conserved, vertical momentum goes into the slate. At n_z = 0 (both
centres at one height) it is the planar frictionless impact. pooltool's main
branch detects 3D ball-ball contacts with the same quartic; its resolution
of a ball pressed into the slate is not modelled there yet, which is why
this one is the rigid-slate limit written out here. A ball dropped exactly
on top of another is tipped off its balance (``STACK_TILT``).
"""
import math

from .. import constants as C
from .._jit import njit
from ..roots import first_entry

# A ball dropped exactly onto the top of another (the line of centres
# exactly vertical) would bounce there for ever, each bounce lower by e_b^2,
# an unstable balance no real table keeps (any offset grows from bounce to
# bounce until the ball falls off). Its impact normal is tilted by this
# angle (rad) towards +x, the smallest offset of a real stack: it then falls
# off as from an offset of 6e-11 m (R times this).
STACK_TILT = 1e-9


@njit
def _lagged(balls, e, j, ax, ay, lag, g):
    """Ball j's centre offset (x, y, h), velocity and acceleration (3D), its
    horizontal acceleration (ax, ay) on the felt, its state ``lag`` seconds
    old shifted to now."""
    pos, vel, air, st = balls.pos, balls.vel, balls.air, balls.st
    x, y, h = pos[e, j, 0], pos[e, j, 1], air[e, j, 0]
    vx, vy, vz = vel[e, j, 0], vel[e, j, 1], air[e, j, 1]
    az = 0.0
    if st[e, j] == C.AIRBORNE:
        ax, ay, az = 0.0, 0.0, -g
    elif st[e, j] != C.SLIDING and st[e, j] != C.ROLLING:
        return x, y, h, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    if lag > 0.0:
        x += vx * lag + 0.5 * ax * lag * lag
        y += vy * lag + 0.5 * ay * lag * lag
        h += vz * lag + 0.5 * az * lag * lag
        vx += ax * lag; vy += ay * lag; vz += az * lag
    return x, y, h, vx, vy, vz, ax, ay, az


@njit
def contact_time(balls, e, i, j, acc, H, p, lag):
    """Time from now until balls i and j touch in 3D (inf if not within H):
    ball i's state is now, ball j's ``lag`` seconds old; ``acc`` = (axi,
    ayi, axj, ayj), the balls' horizontal accelerations on the felt (the
    event solver's ``paths``; zeros for the step solver's straight lines)."""
    g = p[C.P_G]
    xi, yi, hi, vxi, vyi, vzi, axi, ayi, azi = _lagged(balls, e, i, acc[0], acc[1], 0.0, g)
    xj, yj, hj, vxj, vyj, vzj, axj, ayj, azj = _lagged(balls, e, j, acc[2], acc[3], lag, g)
    return touch_time((xi - xj, yi - yj, hi - hj), (vxi - vxj, vyi - vyj, vzi - vzj), (axi - axj, ayi - ayj, azi - azj),
                      2.0 * p[C.P_R], H)


@njit
def touch_time(d, v, a, R2, H):
    """Earliest time in [0, H] at which two centres ``d`` apart (3-tuples:
    the first's minus the second's), with relative velocity ``v`` and
    acceleration ``a``, come within ``R2`` = 2R: the quartic of the module
    docstring (inf if they do not)."""
    dx, dy, dz = d
    vx, vy, vz = v
    ax, ay, az = a
    c4 = 0.25 * (ax * ax + ay * ay + az * az)
    c3 = vx * ax + vy * ay + vz * az
    c2 = vx * vx + vy * vy + vz * vz + dx * ax + dy * ay + dz * az
    c1 = 2.0 * (dx * vx + dy * vy + dz * vz)
    c0 = dx * dx + dy * dy + dz * dz - R2 * R2
    return first_entry(c4, c3, c2, c1, c0, H, 2.0 * R2 * C.CONTACT_TOL, -math.inf)


@njit
def resolve(balls, e, i, j, p):
    """The impact of touching balls i and j, one of them in flight (module
    docstring). Returns the normal approach speed (m/s) before it."""
    pos, vel, air, st = balls.pos, balls.vel, balls.air, balls.st
    nx = pos[e, j, 0] - pos[e, i, 0]
    ny = pos[e, j, 1] - pos[e, i, 1]
    nz = air[e, j, 0] - air[e, i, 0]
    if nx == 0.0 and ny == 0.0:  # stacked exactly: tip the balance (STACK_TILT)
        nx = STACK_TILT * abs(nz)
    d = math.sqrt(nx * nx + ny * ny + nz * nz)
    nx /= d; ny /= d; nz /= d
    w = -((vel[e, j, 0] - vel[e, i, 0]) * nx + (vel[e, j, 1] - vel[e, i, 1]) * ny
          + (air[e, j, 1] - air[e, i, 1]) * nz)
    if w <= 0.0:
        return w
    restitution = 0.0 if w < C.ZENO_SPEED else p[C.P_E_B]
    # the lower ball, if it lies on the slate, is held by it
    held_i = st[e, i] != C.AIRBORNE and nz > 0.0
    held_j = st[e, j] != C.AIRBORNE and nz < 0.0
    nh2 = nx * nx + ny * ny
    P = (1.0 + restitution) * w / (1.0 + nh2) if held_i or held_j else 0.5 * (1.0 + restitution) * w
    vel[e, i, 0] -= P * nx; vel[e, i, 1] -= P * ny
    vel[e, j, 0] += P * nx; vel[e, j, 1] += P * ny
    if not held_i:
        air[e, i, 1] -= P * nz
    if not held_j:
        air[e, j, 1] += P * nz
    return w
