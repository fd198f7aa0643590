"""What every cushion model shares (numba kernels): the approach test, the
choice of restitution, loading and storing the ball's values, and resting
contacts.

A cushion model is a jitted function

    resolve(vx, vy, wx, wy, wz, nx, ny, approach, e_c, p) -> (vx, vy, wx, wy, wz)

in the table's frame: the ball's velocity (m/s) and spin (rad/s) before and
after the impact, (nx, ny) the unit contact normal pointing into the table,
``approach`` the normal approach speed (m/s, > 0) exactly as the approach
test measured it (a model that uses it, rather than recomputing -v.n from
the unit normal, agrees with that test to the last bit), e_c the restitution
to use (0 for a resting contact) and p the parameter vector (constants.P_*).
``make_resolve`` wraps one.

Impacts slower than ZENO_SPEED, and contacts reported without approach (the
felt pressing the ball into the cushion), are resting contacts: restitution
0, the slide ends at once, no normal velocity into the cushion remains.
"""
from .. import constants as C
from .._jit import name_of, njit, variant_njit
from ..motion import end_slide
from ..vec import norm


def make_resolve(model, spin_on):
    """Resolve an impact of ball i with a cushion by ``model``."""
    variant = variant_njit("cushion", name_of(model), spin_on)

    @variant
    def resolve(vel, om, e, i, rx, ry, p):
        """Ball i of table e meets a cushion. (rx, ry) is the contact normal,
        pointing into the table, exactly as the detector formed it (the unit
        normal of a cushion segment, or ball centre minus jaw tip): the
        approach test below uses the detector's own expression, so the two
        never disagree by rounding about whether the ball is closing.
        Returns the approach speed before the impact."""
        d = norm(rx, ry)
        w = -(vel[e, i, 0] * rx + vel[e, i, 1] * ry) / d
        resting = w < C.ZENO_SPEED
        if w <= 0.0:
            # reported without approach: the felt presses the ball into the
            # cushion (a slide whose friction points into it); end the slide
            if spin_on:  # a no-op unless the ball slips on the felt
                end_slide(vel, om, e, i, p[C.P_R])
            unpress(vel, e, i, rx, ry)
            return w
        e_c = 0.0 if resting else p[C.P_E_C]
        vel[e, i, 0], vel[e, i, 1], om[e, i, 0], om[e, i, 1], om[e, i, 2] = model(
            vel[e, i, 0], vel[e, i, 1], om[e, i, 0], om[e, i, 1], om[e, i, 2], rx / d, ry / d, w, e_c, p)
        if resting:
            if spin_on:  # by the slip after the impulse, not the stale st
                end_slide(vel, om, e, i, p[C.P_R])
            unpress(vel, e, i, rx, ry)
        return w

    return resolve


@njit
def unpress(vel, e, i, rx, ry):
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
