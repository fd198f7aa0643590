"""Ball-cushion impact integrated through the impulse (numba kernel).

Source: S. Mathavan, M. R. Jackson and R. M. Parkin (2010), "A theoretical
analysis of billiard ball dynamics under cushion impacts", Proc. IMechE
Part C 224(9), 1863-1873. pooltool implements the same paper as its
"mathavan_2010" ball-cushion model.

Model. The cushion is rigid; its nose touches the ball at I, above the
equator at the angle theta with sin(theta) = h/R - 1 (h the nose height),
and the felt touches it at C, straight below the centre. The ball stays on
the felt (no vertical velocity), so the felt's normal impulse is whatever
balances the vertical part of the cushion's. Both contacts slide with
Coulomb friction against their own slip (mu_w at the cushion, mu_s at the
felt). With the cushion's accumulated normal impulse P_I as the independent
variable, in the paper's frame (X along the cushion, Y horizontal into it,
Z up):

- eqs. 12a-b: slip at I, along X and along the tangent Y' of the cushion
  contact: x_I = vx + R (wy sin(theta) - wz cos(theta)),
  y_I = -vy sin(theta) + R wx; speed s, direction phi;
- eqs. 13a-b: slip at C: x_C = vx - R wy, y_C = vy + R wx; speed s', phi';
- the felt's normal impulse per unit P_I: sin(theta) + mu_w sin(phi) cos(theta)
  (vertical balance);
- eqs. 17a-b and 14d-f: dv/dP_I and dw/dP_I, linear in the friction terms;
- eq. 16a: the work of the cushion's normal force, dW = z_I dP_I with
  z_I = vy cos(theta) the normal approach speed at I;
- compression ends when z_I = 0; restitution then releases e_c^2 times the
  compression work (eq. 16b: W_final = (1 - e_c^2) W_compression).

Numerics (where this implementation departs from the paper's scheme, which
takes explicit Euler steps of a fixed impulse increment, N = 5000):
- midpoint steps of a fixed impulse increment, IMPULSE_STEPS per
  compression of a frictionless ball (so the step count, and the relative
  accuracy, do not depend on the speed); within one step the rates are
  constant, so the normal velocity is linear in the impulse and the
  trapezoidal work of eq. 16a is exact; the last step of each phase is
  shortened to land exactly on z_I = 0 (compression) or on the target work
  (restitution: a quadratic in the step);
- eqs. 15a-b (a contact that rolls has no friction) become a sticking rule
  applied per step: if a contact's slip ends within the step, its friction
  is the step's mean of mu until the slip ends and then either the friction
  that holds the slip at zero against the normal impulse's drive (if mu
  allows: sticking) or mu the other way (the slip reverses). The mean is
  exact for a contact whose slip keeps its line, and friction never
  reverses a slip on its own; the paper's scheme (friction always along the
  slip at the step's start) chatters around zero slip instead. The
  midpoint rule is second order while both contacts slide and first order
  across a stick or reversal;
- the felt's normal impulse is clamped at zero: a cushion friction that
  would lift the ball off the felt is cut there (only possible for
  mu_w > tan(theta), about 0.44 for h = 7R/5);
- guards: no approach (or a non-finite one) returns the state unchanged;
  each phase stops after MAX_PHASE_FACTOR times the step count; a normal
  velocity left into the cushion is removed; if rounding or discretisation
  left the ball with more kinetic energy than it came in with, its
  velocities are scaled down to the incoming energy. None of the guards
  acts on an ordinary impact.

Conventions: right-handed axes, spin in rad/s, as in motion.py; the
caller's normal points from the cushion to the ball's centre, the paper's
Y axis is its opposite.
"""
import math

from .._jit import njit
from .. import constants as C

# Impulse steps in the compression of a frictionless ball: at 200 the
# outgoing velocities (and R x spins) differ from a 100x finer integration
# by at most ~0.1% of the incoming speed over speeds to 12 m/s and spins to
# 400 rad/s (median ~1e-6 m/s; tests/physics/test_new_models.py checks 0.2%), far
# below the spread of measured restitution and friction; cost is linear in it.
IMPULSE_STEPS = 200
# Bound on the steps of one phase, in units of IMPULSE_STEPS: with both
# frictions <= 0.5 and h = 7R/5 the normal velocity still falls at >= 0.28 / m
# per unit impulse (0.92 / m without friction), so a phase takes under 3.5
# units; only larger frictions (which can stall the normal velocity) reach
# the bound.
MAX_PHASE_FACTOR = 20


@njit
def _friction(x, y, drive_y, kx, ky, mu, dp, M):
    """Mean friction per unit P_I over a step dp at one contact whose slip
    is (x, y), whose Y slip the normal impulses drive at drive_y per unit
    P_I, and whose slip compliances (times M) are kx along X, ky along Y.
    Returns the size f and the direction (c, n) it opposes. While the
    contact slides, f = mu against the slip (eqs. 14, 17); if the slip ends
    within the step (after the fraction tau of it), the rest of the step
    either sticks (eq. 15: the friction that holds the slip at zero against
    the drive, if mu allows) or slides back along the drive with mu. The
    mean is exact for a contact whose slip keeps its line, and it never
    reverses the slip that friction alone acts on."""
    s = math.sqrt(x * x + y * y)
    tau = 0.0
    c, n = 0.0, 0.0
    if s > 0.0:
        c, n = x / s, y / s
        closing = mu * (kx * c * c + ky * n * n) - M * drive_y * n  # -M ds/dP while sliding
        if closing * dp <= M * s:
            return mu, c, n  # slides throughout the step
        tau = M * s / (closing * dp)
    # after the slip ends: hold it against the drive, or slide along the drive
    g = min(max(M * drive_y / ky, -mu), mu)
    gx = tau * mu * c
    gy = tau * mu * n + (1.0 - tau) * g
    f = math.sqrt(gx * gx + gy * gy)
    if not (f > 0.0):
        return 0.0, 0.0, 0.0
    return f, gx / f, gy / f


@njit
def _rates(vx, vy, wx, wy, wz, R, M, st, ct, mu_w, mu_s, dp):
    """Rates d(vx, vy, wx, wy, wz)/dP_I in the cushion frame (eqs. 12-14,
    17) for a step of impulse dp."""
    # eq. 12: slip of the ball at the cushion contact I (X and Y'); the
    # normal impulse drives its Y' part at st ct / M; slip compliances
    # 7/(2M) along X and (5/2 + st^2)/M along Y'
    fw, cw, sw = _friction(vx + R * (wy * st - wz * ct), -vy * st + R * wx,
                           st * ct / M, 3.5, 2.5 + st * st, mu_w, dp, M)
    # felt's normal impulse per unit P_I (vertical balance), never pulling
    nc = st + fw * sw * ct
    if nc < 0.0:
        nc = 0.0
    # eq. 13: slip at the felt contact C; the normal impulse drives its Y
    # part at -ct / M; compliance 7/(2M) both ways
    fs, cc, sc = _friction(vx - R * wy, vy + R * wx, -ct / M, 3.5, 3.5, mu_s * nc, dp, M)
    k = 1.0 / M
    q = 2.5 / (M * R)  # R / I for a solid sphere
    ax = -k * (fw * cw + fs * cc)
    ay = -k * (ct - fw * sw * st + fs * sc)
    awx = -q * (fw * sw + fs * sc)
    awy = -q * (fw * cw * st - fs * cc)
    awz = q * fw * cw * ct
    return ax, ay, awx, awy, awz


@njit
def _mid_rates(vx, vy, wx, wy, wz, R, M, st, ct, mu_w, mu_s, dp, h):
    """Midpoint-rule rates for a step of impulse h: the rates of eqs. 14, 17
    evaluated at the state half a step ahead (frictions as means over a
    step dp, see ``_friction``)."""
    ax, ay, awx, awy, awz = _rates(vx, vy, wx, wy, wz, R, M, st, ct, mu_w, mu_s, dp)
    g = 0.5 * h
    return _rates(vx + g * ax, vy + g * ay, wx + g * awx, wy + g * awy, wz + g * awz,
                  R, M, st, ct, mu_w, mu_s, dp)


@njit
def _landing(vy, ay, ct, rem):
    """Impulse h at which the restitution releases the work rem, with vy
    linear in h at rate ay < 0: ct (-vy h - ay h^2 / 2) = rem (the root
    written without cancellation). Returns -1 if there is none."""
    q = rem / ct
    den = -vy + math.sqrt(vy * vy - 2.0 * ay * q)
    return 2.0 * q / den if den > 0.0 else -1.0


@njit
def _integrate(vx, vy, wx, wy, wz, R, M, st, ct, mu_w, mu_s, e, steps):
    """Compression and restitution in the cushion frame (vy > 0 into the
    cushion). Returns the outgoing (vx, vy, wx, wy, wz)."""
    dp = M * vy / (ct * steps)
    max_steps = MAX_PHASE_FACTOR * steps
    # compression: until the normal approach at I, vy cos(theta), is zero
    work_c = 0.0
    for _ in range(max_steps):
        if vy <= 0.0:
            break
        ax, ay, awx, awy, awz = _mid_rates(vx, vy, wx, wy, wz, R, M, st, ct, mu_w, mu_s, dp, dp)
        h = dp
        last = False
        if ay < 0.0 and vy + ay * dp <= 0.0:  # compression ends within this step
            ax, ay, awx, awy, awz = _mid_rates(vx, vy, wx, wy, wz, R, M, st, ct, mu_w, mu_s, dp, -vy / ay)
            if ay < 0.0 and vy + ay * dp <= 0.0:
                h = -vy / ay  # lands on vy = 0
                last = True
        vy_next = 0.0 if last else vy + ay * h
        work_c += 0.5 * ct * (vy + vy_next) * h  # eq. 16a, exact for vy linear in the step
        vx += ax * h; vy = vy_next
        wx += awx * h; wy += awy * h; wz += awz * h
        if last:
            break
    if vy > 0.0:  # guard: phase bound reached
        vy = 0.0
    # restitution: until the cushion gives back e^2 of the compression work
    target = e * e * work_c
    released = 0.0
    for _ in range(max_steps):
        rem = target - released
        if rem <= 0.0:
            break
        ax, ay, awx, awy, awz = _mid_rates(vx, vy, wx, wy, wz, R, M, st, ct, mu_w, mu_s, dp, dp)
        h = dp
        last = -0.5 * ct * (2.0 * vy + ay * dp) * dp >= rem
        if last and ay < 0.0:  # the target is reached within this step
            hl = _landing(vy, ay, ct, rem)
            if hl > 0.0:
                ax, ay, awx, awy, awz = _mid_rates(vx, vy, wx, wy, wz, R, M, st, ct, mu_w, mu_s, dp, hl)
                last = -0.5 * ct * (2.0 * vy + ay * dp) * dp >= rem
                if last and ay < 0.0:
                    hl = _landing(vy, ay, ct, rem)
                    if hl > 0.0:
                        h = min(dp, hl)
        released += -0.5 * ct * (2.0 * vy + ay * h) * h
        vx += ax * h; vy += ay * h
        wx += awx * h; wy += awy * h; wz += awz * h
        if last:
            break
    if vy > 0.0:  # guard: never leave moving into the cushion
        vy = 0.0
    return vx, vy, wx, wy, wz


@njit
def _resolve_steps(vx, vy, wx, wy, wz, nx, ny, e_c, p, steps):
    """``resolve`` with the number of impulse steps as an argument (the
    tests use it to measure the discretisation error)."""
    M, R = p[C.P_M], p[C.P_R]
    st = p[C.P_H_C] / R - 1.0
    if not (0.0 <= st < 1.0):  # cushion nose outside [R, 2R): no model
        return vx, vy, wx, wy, wz
    ct = math.sqrt(1.0 - st * st)
    # cushion frame: X along the cushion, Y = -n into it, Z up (X x Y = Z)
    Xx, Xy = -ny, nx
    Yx, Yy = -nx, -ny
    u = vx * Xx + vy * Xy
    w = vx * Yx + vy * Yy  # approach speed
    if not (w > 0.0):  # no approach (or not finite): no impulse
        return vx, vy, wx, wy, wz
    ox = wx * Xx + wy * Xy
    oy = wx * Yx + wy * Yy
    e = min(max(e_c, 0.0), 1.0)
    e_in = vx * vx + vy * vy + 0.4 * R * R * (wx * wx + wy * wy + wz * wz)  # 2 E / m
    u, w, ox, oy, oz = _integrate(u, w, ox, oy, wz, R, M, st, ct, p[C.P_F_C], p[C.P_MU_S], e, steps)
    e_out = u * u + w * w + 0.4 * R * R * (ox * ox + oy * oy + oz * oz)
    if e_out > e_in:  # guard: never gain energy (rounding / discretisation)
        s = math.sqrt(e_in / e_out)
        u *= s; w *= s; ox *= s; oy *= s; oz *= s
    return (u * Xx + w * Yx, u * Xy + w * Yy,
            ox * Xx + oy * Yx, ox * Xy + oy * Yy, oz)


@njit
def resolve(vx, vy, wx, wy, wz, nx, ny, approach, e_c, p):
    """Outgoing (vx, vy, wx, wy, wz), world frame, of a ball hitting a
    cushion whose unit normal (nx, ny) points from the cushion to the ball's
    centre, with restitution e_c (0 for a resting contact). Reads m, R,
    h_c, mu_s and f_c from the parameter vector p. The integration starts
    from the ball's own velocity; ``approach`` (the interface's measured
    approach speed) is not needed."""
    return _resolve_steps(vx, vy, wx, wy, wz, nx, ny, e_c, p, IMPULSE_STEPS)
