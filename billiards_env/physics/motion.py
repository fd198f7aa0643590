"""Ball motion on the felt between events (numba kernels).

Model (Alciatore, "The Illustrated Principles of Pool and Billiards",
technical proofs on sliding and rolling; the same equations as pooltool's evolve module, Kiefl 2024):
- sliding: the contact-point velocity u = v + omega x (-R z) keeps its
  direction; v' = -mu_s g u_hat, omega_xy' = 5 mu_s g / (2R) (z x u_hat), so
  |u| falls at 7/2 mu_s g and sliding lasts 2|u0| / (7 mu_s g);
- rolling: v' = -mu_r g v_hat with omega_xy locked to v (u = 0), lasting
  |v0| / (mu_r g);
- spin about the vertical axis decays at the constant rate 5 mu_sp g / (2R)
  in every state (clamped at zero; no event, since it does not move the ball)
  and, for a ball otherwise at rest, ends with a spin-stop event.

The friction torque is r x F with r the radius from the centre to the
contact point; u above is the velocity of that contact point (the ball's
"perimeter velocity" at the cloth).
"""
import math

from ._jit import njit
from . import constants as C
from .vec import norm


@njit
def slip(vx, vy, wx, wy, R):
    """Contact-point velocity with the felt, (ux, uy)."""
    return vx - R * wy, vy + R * wx


@njit
def classify(vel, om, st, e, i, R, spin_on):
    """Set the motion state of ball i from its velocities; snaps near-rolling
    spins to exact rolling so no spurious slide events follow."""
    vx, vy = vel[e, i, 0], vel[e, i, 1]
    speed = norm(vx, vy)
    if not spin_on:
        om[e, i, 0] = 0.0; om[e, i, 1] = 0.0; om[e, i, 2] = 0.0
        if speed <= C.SPEED_EPS:
            vel[e, i, 0] = 0.0; vel[e, i, 1] = 0.0
            st[e, i] = C.STATIONARY
        else:
            st[e, i] = C.ROLLING
        return
    ux, uy = slip(vx, vy, om[e, i, 0], om[e, i, 1], R)
    if norm(ux, uy) > C.SPEED_EPS:
        st[e, i] = C.SLIDING
    elif speed > C.SPEED_EPS:
        om[e, i, 0] = -vy / R
        om[e, i, 1] = vx / R
        st[e, i] = C.ROLLING
    else:
        vel[e, i, 0] = 0.0; vel[e, i, 1] = 0.0
        om[e, i, 0] = 0.0; om[e, i, 1] = 0.0
        st[e, i] = C.SPINNING if abs(om[e, i, 2]) > C.SPIN_EPS else C.STATIONARY
        if st[e, i] == C.STATIONARY:
            om[e, i, 2] = 0.0


@njit
def end_slide(vel, om, e, i, R):
    """The rolling state a slide ends in, at once: u decays along its own
    direction, so v_end = v - (2/7) u (angular momentum about the contact
    point is conserved)."""
    ux, uy = slip(vel[e, i, 0], vel[e, i, 1], om[e, i, 0], om[e, i, 1], R)
    vx = vel[e, i, 0] - 2.0 / 7.0 * ux
    vy = vel[e, i, 1] - 2.0 / 7.0 * uy
    vel[e, i, 0] = vx; vel[e, i, 1] = vy
    om[e, i, 0] = -vy / R; om[e, i, 1] = vx / R


@njit
def acceleration(vel, om, st, e, i, p):
    """Constant linear acceleration (ax, ay) of ball i in its current state."""
    R, g = p[C.P_R], p[C.P_G]
    s = st[e, i]
    if s == C.SLIDING:
        ux, uy = slip(vel[e, i, 0], vel[e, i, 1], om[e, i, 0], om[e, i, 1], R)
        n = norm(ux, uy)
        if n == 0.0:  # reached its slide end by rounding, a hair early
            return 0.0, 0.0
        a = p[C.P_MU_S] * g / n
        return -a * ux, -a * uy
    if s == C.ROLLING:
        return rolling_acceleration(vel[e, i, 0], vel[e, i, 1], p)
    return 0.0, 0.0


@njit
def rolling_acceleration(vx, vy, p):
    """Acceleration of a ball rolling at (vx, vy): -mu_r g v / |v|."""
    n = norm(vx, vy)
    if n == 0.0:  # reached its stop by rounding, a hair early
        return 0.0, 0.0
    a = p[C.P_MU_R] * p[C.P_G] / n
    return -a * vx, -a * vy


@njit
def transition_time(vel, om, st, e, i, p):
    """Time from now to ball i's next motion transition (inf if none)."""
    R, g = p[C.P_R], p[C.P_G]
    s = st[e, i]
    if s == C.SLIDING:
        ux, uy = slip(vel[e, i, 0], vel[e, i, 1], om[e, i, 0], om[e, i, 1], R)
        return 2.0 * norm(ux, uy) / (7.0 * p[C.P_MU_S] * g)
    if s == C.ROLLING:
        return norm(vel[e, i, 0], vel[e, i, 1]) / (p[C.P_MU_R] * g)
    if s == C.SPINNING:
        rate = 2.5 * p[C.P_MU_SP] * g / R
        if rate <= 0.0:
            return math.inf
        return abs(om[e, i, 2]) / rate
    return math.inf


@njit
def _decay_vertical_spin(om, e, i, dt, rate):
    w = om[e, i, 2]
    if w > 0.0:
        om[e, i, 2] = max(w - rate * dt, 0.0)
    elif w < 0.0:
        om[e, i, 2] = min(w + rate * dt, 0.0)


@njit
def evolve(pos, vel, om, st, e, i, dt, p, zspin_on, spin_on):
    """Advance ball i exactly by dt (dt no later than its next transition).
    Without spin (point masses) a rolling ball carries no angular velocity,
    so none is given to it here (it would count as energy it never had)."""
    if dt <= 0.0:
        return
    R, g = p[C.P_R], p[C.P_G]
    s = st[e, i]
    if s == C.SLIDING or s == C.ROLLING:
        ax, ay = acceleration(vel, om, st, e, i, p)
        pos[e, i, 0] += vel[e, i, 0] * dt + 0.5 * ax * dt * dt
        pos[e, i, 1] += vel[e, i, 1] * dt + 0.5 * ay * dt * dt
        if s == C.SLIDING:
            ux, uy = slip(vel[e, i, 0], vel[e, i, 1], om[e, i, 0], om[e, i, 1], R)
            n = norm(ux, uy)
            k = 2.5 * p[C.P_MU_S] * g / R * dt / n if n > 0.0 else 0.0
            om[e, i, 0] -= k * uy
            om[e, i, 1] += k * ux
            vel[e, i, 0] += ax * dt
            vel[e, i, 1] += ay * dt
        else:
            vel[e, i, 0] += ax * dt
            vel[e, i, 1] += ay * dt
            if spin_on:
                om[e, i, 0] = -vel[e, i, 1] / R
                om[e, i, 1] = vel[e, i, 0] / R
    if zspin_on and s != C.STATIONARY and s != C.POCKETED:
        _decay_vertical_spin(om, e, i, dt, 2.5 * p[C.P_MU_SP] * g / R)


@njit
def apply_transition(vel, om, st, e, i, p):
    """Ball i has reached its transition time: enter the next state exactly.
    Returns the event kind."""
    R = p[C.P_R]
    s = st[e, i]
    if s == C.SLIDING:
        # u = 0 exactly: lock the spin to the velocity
        om[e, i, 0] = -vel[e, i, 1] / R
        om[e, i, 1] = vel[e, i, 0] / R
        if norm(vel[e, i, 0], vel[e, i, 1]) > C.SPEED_EPS:
            st[e, i] = C.ROLLING
        else:
            vel[e, i, 0] = 0.0; vel[e, i, 1] = 0.0; om[e, i, 0] = 0.0; om[e, i, 1] = 0.0
            st[e, i] = C.SPINNING if abs(om[e, i, 2]) > C.SPIN_EPS else C.STATIONARY
        return C.EV_SLIDE_ROLL
    if s == C.ROLLING:
        vel[e, i, 0] = 0.0; vel[e, i, 1] = 0.0; om[e, i, 0] = 0.0; om[e, i, 1] = 0.0
        st[e, i] = C.SPINNING if abs(om[e, i, 2]) > C.SPIN_EPS else C.STATIONARY
        if st[e, i] == C.STATIONARY:
            om[e, i, 2] = 0.0
        return C.EV_ROLL_STOP
    om[e, i, 2] = 0.0
    st[e, i] = C.STATIONARY
    return C.EV_SPIN_STOP


@njit
def friction_step(vel, om, st, e, i, dt, p, zspin_on, spin_on):
    """Explicit (Euler) friction update over one fixed step, of the
    fixed-step scheme, clamped so that friction never reverses a velocity:
    a slide that would end within the step ends in its rolling state, a roll
    that would end stops. Returns True if the ball's state changed kind."""
    R, g = p[C.P_R], p[C.P_G]
    s = st[e, i]
    changed = False
    if s == C.SLIDING:
        ux, uy = slip(vel[e, i, 0], vel[e, i, 1], om[e, i, 0], om[e, i, 1], R)
        n = norm(ux, uy)
        if n <= 3.5 * p[C.P_MU_S] * g * dt:
            end_slide(vel, om, e, i, R)
            classify(vel, om, st, e, i, R, True)
            changed = True
        else:
            a = p[C.P_MU_S] * g * dt / n
            k = 2.5 * p[C.P_MU_S] * g / R * dt / n
            vel[e, i, 0] -= a * ux; vel[e, i, 1] -= a * uy
            om[e, i, 0] -= k * uy; om[e, i, 1] += k * ux
    elif s == C.ROLLING:
        vx, vy = vel[e, i, 0], vel[e, i, 1]
        n = norm(vx, vy)
        dv = p[C.P_MU_R] * g * dt
        if n <= dv:
            vel[e, i, 0] = 0.0; vel[e, i, 1] = 0.0; om[e, i, 0] = 0.0; om[e, i, 1] = 0.0
            st[e, i] = C.SPINNING if abs(om[e, i, 2]) > C.SPIN_EPS else C.STATIONARY
            changed = True
        else:
            f = 1.0 - dv / n
            vel[e, i, 0] = vx * f; vel[e, i, 1] = vy * f
            if spin_on:  # point masses (spin off) carry no angular velocity
                om[e, i, 0] = -vel[e, i, 1] / R; om[e, i, 1] = vel[e, i, 0] / R
    if zspin_on and s != C.STATIONARY and s != C.POCKETED:
        _decay_vertical_spin(om, e, i, dt, 2.5 * p[C.P_MU_SP] * g / R)
        if st[e, i] == C.SPINNING and om[e, i, 2] == 0.0:
            st[e, i] = C.STATIONARY
            changed = True
    return changed


@njit
def energy(vel, om, st, e, i, p):
    """Kinetic plus rotational energy of ball i (J)."""
    if st[e, i] == C.POCKETED:
        return 0.0
    return kinetic_energy(vel[e, i, 0], vel[e, i, 1], om[e, i, 0], om[e, i, 1], om[e, i, 2], p)


@njit
def kinetic_energy(vx, vy, wx, wy, wz, p):
    """Translational plus rotational energy of a solid ball (J),
    1/2 m |v|^2 + 1/2 (2/5 m R^2) |omega|^2. Plain arithmetic: its
    ``py_func`` works on numpy arrays too (testing.initial_energy)."""
    m, R = p[C.P_M], p[C.P_R]
    I = 0.4 * m * R * R
    return 0.5 * m * (vx ** 2 + vy ** 2) + 0.5 * I * (wx ** 2 + wy ** 2 + wz ** 2)
