"""Airborne motion: flight, ball-slate impacts and the bounces of a jumped
ball until it settles on the slate (issue 46, item 2).

The event solver simulates them with ``Effects(airborne=True)``
(``event_solver``: a ball in flight is in the motion state
``constants.AIRBORNE``, its height and vertical velocity in ``Balls.air``);
its contacts in flight are ``ball_ball.flight`` (with another ball) and
``cushion.rail`` (with a cushion, a pocket, and over the rail off the
table). Scalars in, tuples out for the closed forms, tested against them
(tests/physics/test_airborne.py); ``fly`` and ``land`` are the kernel's
evolve and resolve of a ball in flight.

Frame: x, y on the slate, z up; a ball's centre at height z (z = R: on the
slate). Velocity v = (vx, vy, vz), spin w = (wx, wy, wz), m the mass, R the
radius, I = 2/5 m R^2.

Flight (``flight``, ``landing_time``). Gravity alone: no felt, no air. The
centre follows the parabola

    x(t) = x0 + vx t,  y(t) = y0 + vy t,  z(t) = z0 + vz t - g t^2 / 2,

and the spin does not change (no torque). Air drag and the Magnus force on
a pool ball at 5 m/s with 100 rad/s of spin are below 1% of its weight and
are left out, as pooltool's main branch leaves them out. The ball meets the
slate when z(t) = R, descending:

    t_land = (vz + sqrt(vz^2 + 2 g (z0 - R))) / g,

evaluated as 2 (z0 - R) / (sqrt(vz^2 + 2 g (z0 - R)) - vz) when vz <= 0
(no cancellation). From the slate (z0 = R) with vz > 0: t = 2 vz / g, the
apex vz^2 / (2g) above it, the range 2 vz |v_xy| / g.

Ball-slate impact (``slate_impact``). An instantaneous impact at the
contact point r = -R z, with a restitution e along z and Coulomb friction
mu against the slip of the contact point u = v_xy + w x (-R z)
(``motion.slip``), capped where the slip ends (Alciatore's technical proof
TP A-14, the model pooltool's main branch resolves as its frictional
inelastic ball-table collision):

    vz' = -e vz                               (vz < 0 before)
    P_n = m (1 + e) |vz|                      normal impulse
    P_t = -min(mu P_n, 2/7 m |u|) u_hat       friction impulse
    v_xy' = v_xy + P_t / m
    w' = w + (r x P_t) / I = w + 5 / (2 m R) (P_ty, -P_tx, 0)

The slip changes by 7/2 P_t / m, so 2/7 m |u| is the impulse that ends it:
friction never reverses the slip and the impact never adds energy. Spin
about z is untouched (a point contact has no torque about the normal).
pooltool's main branch resolves the same impact with the same equations
while the ball slides through it; where the cap is reached (the ball
leaves rolling) it sets all of w to 2/7 w + 5/7 (z x v) / R, which agrees
here about x and y but also takes 5/7 of the spin about z away, a torque
its contact at -R z cannot exert; here w_z is kept in both cases.

Settling (``settles``, ``bounces``). Each bounce leaves at e times the
vertical speed it came in with, so the bounce heights fall by e^2 and the
flights by e: a geometric sequence with infinitely many bounces in a finite
time (a Zeno sequence). A rebound lower than ``SETTLE_HEIGHT`` ends it: the
vertical velocity is set to 0 and the ball is on the slate, rolling or
sliding by the felt's model. From a first rebound of height h_1 the ball
settles after n = ceil(log(SETTLE_HEIGHT / h_1) / log(e^2)) bounces at
most, and its centre is never below R (``landing_time`` ends every flight
at z = R exactly).

A ball in flight and a ball on the slate (``ball_ball.flight.flight_contact_time``). With
D the flying ball's centre relative to the resting ball's and a = -g z,
the squared distance of the centres is a quartic in t,

    |D + v t + a t^2 / 2|^2 = g^2/4 t^4 - g vz t^3 + (|v|^2 - g Dz) t^2
                              + 2 D.v t + |D|^2,

and the balls touch at its first entry below (2R)^2 (``roots.first_entry``,
the solver of every other contact): a jumped ball clears a ball it passes
over exactly when this has no root before it lands. Passing straight over
the resting ball at the apex of its flight, it clears it when the apex is
at least 2R above the resting ball's centre (if vh^2 > g h, the apex is the
nearest point of the pass). The kernels track the height of the ball's
lowest point, h = z - R (0 on the slate), so that a ball on the slate is at
h = 0 exactly; ``drop_time`` is ``landing_time`` in h.

Constants. e = ``SLATE_RESTITUTION`` = 0.5, Alciatore's ball-table
coefficient of restitution ("physical properties" of pool equipment, the
page pooltool's parameters follow); mu = the felt's sliding friction
``PhysicsParams.mu_s`` (0.2), as pooltool uses its u_s for this impact.
pooltool's main branch ends the bounces below 5 mm
(``min_bounce_height``); this module at 0.1 mm (``SETTLE_HEIGHT``): a 5 mm
hop lasts 64 ms, 19 cm of flight at 3 m/s that would be played on the
felt instead.
"""
import math

from . import constants as C
from ._jit import njit
from .motion import slip

# Alciatore's ball-table coefficient of restitution ("physical properties":
# e = 0.5), the vertical rebound of a ball dropped on the slate.
SLATE_RESTITUTION = 0.5
# Rebounds lower than this (m) end the bounces: a hop of 0.1 mm lasts 9 ms
# (2 sqrt(2h/g)), 3 cm of travel at 3 m/s, rises a fraction of the cloth's
# thickness and clears nothing.
SETTLE_HEIGHT = 1e-4


@njit
def flight(x, y, z, vx, vy, vz, t, g):
    """Position and vertical velocity after ``t`` seconds of flight:
    (x, y, z, vz). The horizontal velocity and the spin do not change."""
    z, vz = rise(z, vz, t, g)
    return x + vx * t, y + vy * t, z, vz


@njit
def rise(z, vz, t, g):
    """Height and vertical velocity ``t`` seconds on: (z + vz t - g t^2 / 2,
    vz - g t), the one closed form of the vertical motion (``flight``,
    ``fly``, ``cushion.rail``, the replays)."""
    return z + vz * t - 0.5 * g * t * t, vz - g * t


@njit
def landing_time(z, vz, R, g):
    """Time until a ball at height ``z`` >= R with vertical velocity ``vz``
    reaches the slate (its centre at R, descending); 0 for a ball on the
    slate moving into it (or resting on it: the caller settles such a
    ball instead of flying it)."""
    return drop_time(max(z - R, 0.0), vz, g)  # a ball is never below the slate


@njit
def drop_time(dz, vz, g):
    """Time until a body ``dz`` >= 0 above a level, moving up at ``vz``,
    comes down to that level (the later root of dz + vz t - g t^2 / 2 = 0;
    0 for dz = 0 and vz <= 0)."""
    root = math.sqrt(vz * vz + 2.0 * g * dz)
    if vz <= 0.0:
        den = root - vz
        return 0.0 if den == 0.0 else 2.0 * dz / den
    return (vz + root) / g


@njit
def fly(balls, e, i, dt, g):
    """Advance ball i of ``balls`` (layout.Balls), in flight, by dt: the
    parabola above, the spin unchanged; never below the slate (a flight
    ends at its landing time, where rounding may leave h a hair below 0)."""
    if dt <= 0.0:
        return
    pos, vel, air = balls.pos, balls.vel, balls.air
    pos[e, i, 0] += vel[e, i, 0] * dt
    pos[e, i, 1] += vel[e, i, 1] * dt
    h, vz = rise(air[e, i, 0], air[e, i, 1], dt, g)
    air[e, i, 0] = max(h, 0.0)
    air[e, i, 1] = vz


@njit
def land(balls, e, i, p):
    """The resolve of a slate event: ball i of ``balls`` meets the slate
    (h = 0, vz <= 0): ``slate_impact``, and the bounces end when the rebound
    would rise less than ``SETTLE_HEIGHT`` (vz = 0: the caller gives the
    ball its motion state on the felt). Returns True if it flies on."""
    vel, om, air = balls.vel, balls.om, balls.air
    R = p[C.P_R]
    air[e, i, 0] = 0.0
    vx, vy, vz, wx, wy, wz = slate_impact(vel[e, i, 0], vel[e, i, 1], min(air[e, i, 1], 0.0),
                                          om[e, i, 0], om[e, i, 1], om[e, i, 2], R, SLATE_RESTITUTION,
                                          p[C.P_MU_S])
    vel[e, i, 0] = vx; vel[e, i, 1] = vy
    om[e, i, 0] = wx; om[e, i, 1] = wy; om[e, i, 2] = wz
    if settles(vz, p[C.P_G], SETTLE_HEIGHT):
        air[e, i, 1] = 0.0
        return False
    air[e, i, 1] = vz
    return True


@njit
def leaves_slate(balls, e, i):
    """True if ball i (on the table) starts in flight or moving off or into
    the slate: it is given the motion state AIRBORNE (a ball struck into
    the slate meets it at once)."""
    return balls.air[e, i, 0] > 0.0 or balls.air[e, i, 1] != 0.0


@njit
def landing_now(balls, e, i, t_land, t):
    """True if ball i is in flight and meets the slate at this instant
    (``t_land``, its transition time, is now): its pairs wait for the
    bounce, which comes first and changes its vertical velocity."""
    return balls.st[e, i] == C.AIRBORNE and t_land <= t


@njit
def meets_slate(balls, e, i):
    """True if ball i is in flight on the slate and not rising (its
    landing is now), with its state current (the step solver's)."""
    return balls.st[e, i] == C.AIRBORNE and balls.air[e, i, 0] <= 0.0 and balls.air[e, i, 1] <= 0.0


@njit
def flight_energy(balls, e, i, p):
    """The energy of ball i's height and vertical motion (J), m g h +
    m vz^2 / 2, which the planar energy (``motion.energy``) leaves out."""
    h, vz = balls.air[e, i, 0], balls.air[e, i, 1]
    return p[C.P_M] * (p[C.P_G] * h + 0.5 * vz * vz)


@njit
def slate_impact(vx, vy, vz, wx, wy, wz, R, e, mu):
    """Velocity and spin after an impact with the slate (module docstring):
    (vx, vy, vz, wx, wy, wz). ``vz`` < 0 (into the slate); an impact with
    vz >= 0 changes nothing."""
    if vz >= 0.0:
        return vx, vy, vz, wx, wy, wz
    pn = (1.0 + e) * (-vz)  # normal impulse per unit mass
    ux, uy = slip(vx, vy, wx, wy, R)
    us = math.sqrt(ux * ux + uy * uy)
    if us == 0.0:
        return vx, vy, -e * vz, wx, wy, wz
    pt = min(mu * pn, us * (2.0 / 7.0))  # friction impulse per unit mass
    px, py = -pt * ux / us, -pt * uy / us
    k = 2.5 / R  # r x P / I per unit mass: 5 / (2 R)
    return vx + px, vy + py, -e * vz, wx + k * py, wy - k * px, wz


@njit
def settles(vz, g, settle_height):
    """True if a ball leaving the slate at ``vz`` rises less than
    ``settle_height``: its bounces end (vz^2 / (2 g) < settle_height)."""
    return vz * vz < 2.0 * g * settle_height


def bounces(pos, vel, spin, R, g, mu, e=SLATE_RESTITUTION, settle_height=SETTLE_HEIGHT):
    """Fly and bounce a ball until it settles on the slate. ``pos``, ``vel``
    and ``spin`` are 3-sequences (a ball at height pos[2] >= R; on the slate
    with vel[2] < 0: struck into it, the first impact is at once). Returns
    the impacts as a list of (t, pos, vel, spin) after each impact, the
    last with vel[2] = 0 (settled, at rest on the slate vertically), t from
    the start. e must lie in [0, 1): e = 1 would never settle."""
    if not 0.0 <= e < 1.0:
        raise ValueError(f"the slate's restitution must lie in [0, 1), got {e}")
    if settle_height <= 0.0:
        raise ValueError(f"settle_height must be > 0, got {settle_height}")
    x, y, z = map(float, pos)
    vx, vy, vz = map(float, vel)
    wx, wy, wz = map(float, spin)
    if z < R:
        raise ValueError(f"the ball's centre is below the slate (z = {z} < R = {R})")
    t = 0.0
    out = []
    # Each rebound is at most e times the last one, so the count is bounded:
    # a guard against a Zeno loop, never reached with e < 1.
    h0 = max(vz * vz / (2.0 * g) + (z - R), settle_height)
    limit = 2 + int(math.ceil(math.log(settle_height / h0) / math.log(e * e))) if e > 0.0 else 2
    for _ in range(limit):
        dt = landing_time(z, vz, R, g)
        x, y, _, vz = flight(x, y, z, vx, vy, vz, dt, g)
        z = R  # exactly on the slate: never below it
        t += dt
        vx, vy, vz, wx, wy, wz = slate_impact(vx, vy, vz, wx, wy, wz, R, e, mu)
        if settles(vz, g, settle_height):
            vz = 0.0
        out.append((t, (x, y, z), (vx, vy, vz), (wx, wy, wz)))
        if vz == 0.0:
            return out
    raise RuntimeError("the bounces did not settle within their bound")  # unreachable for e < 1
