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
ball, its centre never above the other's) is pressed into the slate: two
contacts at once, ball-ball and ball-slate. The cloth-covered slate is far
softer than the contact of two phenolic balls (its restitution is 0.5
against their 0.95), so the balls' impact is over before the slate's has
built up, and the two are resolved one after the other in that order (the
sequential impulses of multibody impact: Han and Gilmore 1993; Stronge,
*Impact Mechanics*, on impacts at several points; the order a Newton's
cradle resolves in):

1. the two balls' impact as if both were free, the lower ball driven into
   the slate at vz < 0;
2. the slate's impact on the lower ball, a landing (``airborne.land``: its
   restitution 0.5 and the felt's friction), which sends it up at -0.5 vz,
   or, if that rebound would rise less than ``SETTLE_HEIGHT``, stops it;
3. again from 1 while the balls still approach (the lower ball, rising or
   stopped, meeting the upper one again), at most ``MAX_PASSES`` times.

Each step is an impact with a restitution at most 1 (the friction capped
where the slip ends), so none adds energy. Struck from above at an angle,
the lower ball jumps (and may leave the table). Two blows are held by the
slate from the start instead: a gentle one, whose rebound would settle,
and one on the top (the line of centres within 30 deg of the vertical,
``TOP_ZONE``), where the passes would leave the upper ball at rest on the
lower one, a balance that only a continuous contact resolves (the ball
rolls off) and a sequence of impacts cannot. Held, and for what
approach is left after the passes, the slate takes the blow without
rebound: an impulsive constraint holding the lower
ball at vz = 0, only the horizontal part n_h of n moving it, so its change
of approach speed is P n_h^2 / m instead of P / m and

    P / m = (1 + e) w / (1 + n_h^2),

the upper ball getting -P n / m, the ball on the slate P n_h / m; the
constraint does no work. At n_z = 0 (both centres at one height) it is the
planar frictionless impact. pooltool's main branch detects 3D ball-ball
contacts with the same quartic; its resolution of a ball pressed into the
slate is not modelled there yet. A ball dropped exactly on top of another
is tipped off its balance (``STACK_TILT``).
"""
import math

from .. import constants as C
from .. import airborne
from .._jit import njit
from ..roots import first_entry
from .contact import normal_impulse

# A ball dropped exactly onto the top of another (the line of centres
# exactly vertical) would bounce there for ever, each bounce lower by e_b^2,
# an unstable balance no real table keeps (any offset grows from bounce to
# bounce until the ball falls off). Its impact normal is tilted by this
# angle (rad) towards +x, the smallest offset of a real stack: it then falls
# off as from an offset of 6e-11 m (R times this).
STACK_TILT = 1e-9
# Passes of the two contacts of a ball pressed into the slate (ball-ball,
# then slate) before the slate holds it for the rest: a pass that does not
# end the approach leaves at most half of it (0.5 s^2 with s = |n_z|, the
# inelastic case below ZENO_SPEED), so 8 leave under 0.4% of it; the count
# bounds the work, the held end finishes it exactly.
MAX_PASSES = 8
# A blow whose line of centres is within 30 deg of the vertical (its
# horizontal part |n_h| below this) is held by the slate from the start: the
# passes would stop the upper ball on top of the lower one, a balance that
# only a continuous contact (rolling off) resolves and a sequence of impacts
# cannot (it decays to rest there); held, the upper ball bounces off with
# e_b and the tilt grows from bounce to bounce until it falls off.
TOP_ZONE = 0.5


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
def flight_contact_time(dx, dy, dz, vx, vy, vz, R, g, H):
    """Earliest time in [0, H] at which a ball in flight touches a ball
    resting on the slate (their centres 2R apart; ``airborne``'s docstring
    writes its quartic out), inf if it does not. (dx, dy, dz): the flying
    ball's centre relative to the resting ball's, (vx, vy, vz) its velocity;
    H the horizon (its landing). The closed-form reference of the tests."""
    return touch_time((dx, dy, dz), (vx, vy, vz), (0.0, 0.0, -g), 2.0 * R, H)


@njit
def _approach(balls, e, i, j, n):
    """The normal approach speed of balls i and j along n (3D), > 0 closing."""
    vel, air = balls.vel, balls.air
    return -((vel[e, j, 0] - vel[e, i, 0]) * n[0] + (vel[e, j, 1] - vel[e, i, 1]) * n[1]
             + (air[e, j, 1] - air[e, i, 1]) * n[2])


@njit
def _push(balls, e, i, j, n, P, low):
    """Impulse P / m along n: -P n to ball i, +P n to ball j, but none
    vertically to ball ``low`` (held by the slate; -1: neither)."""
    vel, air = balls.vel, balls.air
    vel[e, i, 0] -= P * n[0]; vel[e, i, 1] -= P * n[1]
    vel[e, j, 0] += P * n[0]; vel[e, j, 1] += P * n[1]
    if low != i:
        air[e, i, 1] -= P * n[2]
    if low != j:
        air[e, j, 1] += P * n[2]


@njit
def resolve(balls, e, i, j, p):
    """The impact of touching balls i and j, one of them in flight (module
    docstring). Returns the normal approach speed (m/s) before it."""
    pos, air, st = balls.pos, balls.air, balls.st
    nx = pos[e, j, 0] - pos[e, i, 0]
    ny = pos[e, j, 1] - pos[e, i, 1]
    nz = air[e, j, 0] - air[e, i, 0]
    if nx == 0.0 and ny == 0.0:  # stacked exactly: tip the balance (STACK_TILT)
        nx = STACK_TILT * abs(nz)
    d = math.sqrt(nx * nx + ny * ny + nz * nz)
    n = (nx / d, ny / d, nz / d)
    w0 = _approach(balls, e, i, j, n)
    if w0 <= 0.0:
        return w0
    # the lower ball, if it lies on the slate, is pressed into it
    low = -1
    if st[e, i] != C.AIRBORNE and n[2] > 0.0:
        low = i
    elif st[e, j] != C.AIRBORNE and n[2] < 0.0:
        low = j
    if low < 0:
        _push(balls, e, i, j, n, normal_impulse(w0, p), -1)
        return w0
    g = p[C.P_G]
    for k in range(MAX_PASSES):
        w = _approach(balls, e, i, j, n)
        if w <= 0.0:
            return w0
        P = normal_impulse(w, p)
        if k == 0 and (n[0] * n[0] + n[1] * n[1] < TOP_ZONE * TOP_ZONE
                       or airborne.settles(airborne.SLATE_RESTITUTION * P * abs(n[2]), g, airborne.SETTLE_HEIGHT)):
            break  # a blow on the top, or a gentle one: the slate holds the ball from the start
        _push(balls, e, i, j, n, P, -1)
        if air[e, low, 1] < 0.0:
            airborne.land(balls, e, low, p)  # the slate's rebound, or it settles
    # held by the slate for the approach that is left
    air[e, low, 1] = 0.0
    w = _approach(balls, e, i, j, n)
    if w > 0.0:
        nh2 = n[0] * n[0] + n[1] * n[1]
        _push(balls, e, i, j, n, 2.0 * normal_impulse(w, p) / (1.0 + nh2), low)  # (1 + e) w / (1 + n_h^2)
    return w0
