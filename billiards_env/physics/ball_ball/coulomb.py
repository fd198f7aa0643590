"""Ball-ball impact with Coulomb friction (throw and spin transfer).

Source: Alciatore's technical proofs on throw (the model of pooltool's
"frictional inelastic" resolver, with consistent signs). The normal impulse
jn gives restitution e_b along the line of centres
(``contact.normal_impulse``). Friction acts against the slip u_t of the two
contact points, u = v + omega x r with r = +R n on ball i and -R n on
ball j, with impulse

    J_t = -min(mu jn, |u_t| / 7) u_t / |u_t|        (per unit mass),

where mu = friction_coefficient(|u_t|, p) is the friction law and |u_t| / 7
the impulse that ends the slip of two equal solid spheres: friction never
reverses the slip and never adds energy. Both balls turn by
d omega = (r x J) / I, I = 2/5 m R^2. The friction's vertical component turns
the balls but is taken up by the table, not by their linear velocity.

``make_resolve(friction_coefficient)`` builds the model for one friction
law: a jitted ``friction_coefficient(slip_speed, p) -> mu`` (``constant``:
mu_b).
"""
import math

from .. import constants as C
from .._jit import name_of, variant_njit
from . import contact


def make_resolve(friction_coefficient):
    """Coulomb-friction impact resolver for the friction law
    ``friction_coefficient(slip_speed, p)``."""
    njit = variant_njit("coulomb", name_of(friction_coefficient))

    @njit
    def friction(vel, om, e, i, j, nx, ny, jn, p):
        """Friction impulse between touching balls i and j, for a normal
        impulse jn (/ m) along (nx, ny)."""
        R = p[C.P_R]
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
            jt = min(friction_coefficient(slip, p) * jn, slip / 7.0)  # friction impulse / m
            fx, fy, fz = -jt * tx / slip, -jt * ty / slip, -jt * tz / slip  # on ball i
            vel[e, i, 0] += fx; vel[e, i, 1] += fy
            vel[e, j, 0] -= fx; vel[e, j, 1] -= fy
            # r_i = R n, r_j = -R n, J_j = -J_i: both balls turn the same way
            k = 2.5 / R
            cx = ny * fz
            cy = -nx * fz
            cz = nx * fy - ny * fx
            om[e, i, 0] += k * cx; om[e, i, 1] += k * cy; om[e, i, 2] += k * cz
            om[e, j, 0] += k * cx; om[e, j, 1] += k * cy; om[e, j, 2] += k * cz

    @njit
    def resolve(pos, vel, om, e, i, j, p):
        """Impulses of an impact of touching balls i and j. Returns the
        normal approach speed (m/s) before the impact."""
        nx, ny, d = contact.line_of_centres(pos, e, i, j)
        w = contact.approach(pos, vel, e, i, j) / d  # > 0 when closing
        if w > 0.0:
            jn = contact.normal_impulse(w, p)
            friction(vel, om, e, i, j, nx, ny, jn, p)
            contact.push_apart(vel, e, i, j, nx, ny, jn)
        return w

    return resolve
