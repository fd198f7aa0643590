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

Eqs. 15a-b (a contact that rolls has no friction) in full. With the
frictions per unit P_I as forces F_I = (F_Ix, F_Iy') and F_C = (F_Cx, F_Cy),
eqs. 12-14 and 17 give the slip rates (times m) as one linear map, the
contacts' Delassus operator, with s = sin(theta), c = cos(theta):

    m dx_I/dP = 3.5 F_Ix + (1 - 2.5 s) F_Cx,
    m dy_I/dP = s c + (2.5 + s^2) F_Iy + (2.5 - s) F_Cy,
    m dx_C/dP = (1 - 2.5 s) F_Ix + 3.5 F_Cx,
    m dy_C/dP = -c + (2.5 - s) F_Iy + 3.5 F_Cy.

Each contact's slip is driven by the normal impulse *and* by the other
contact's friction. A contact whose slip is zero sticks if the friction
that holds its slip at zero, against both drives, lies within its friction
cone (|F_I| <= mu_w, |F_C| <= mu_s N_C, N_C = s - c F_Iy the felt's normal
impulse); held, its slip's rate is zero whatever drives it, the felt's
friction included. Both contacts can be held only at v_y = 0 (y_I = y_C = 0
needs (1 + sin(theta)) v_y = 0), where y is a 2 x 2 solve. A hold that
leaves its cone lets the slip grow from zero. (The version at df93ffd held
a stuck cushion contact against the normal impulse's drive only: its held
slip chattered around zero with an amplitude proportional to the step,
first order across every stick while the ball slid on the felt.)

Integration: Dormand and Prince's embedded 5(4) Runge-Kutta pair with
the usual step control (local error per step below STEP_TOL V, V = |v| +
R |w| the impact's speed scale), on the five velocities and the work W of
eq. 16a (dW/dP_I = z_I), the regime switches located inside the steps:

- a sliding contact's slip that closes on zero limits the step to
  APPROACH of the impulse it needs to get there (no stage straddles the
  zero, where the friction's direction jumps), so the steps shrink
  geometrically onto the zero; once the slip is within SNAP STEP_TOL V
  of zero (or closes within that much velocity change) it is set to zero
  and the contact held;
- a held contact's friction is the holding one cut to its cone: while it
  lies inside, the slip's rate is exactly zero (the held slip cannot
  chatter); when it leaves the cone the slip grows from zero along the
  direction it leaves in, and the contact slides once its slip exceeds
  RELEASE times the snapping threshold (the cut friction and the sliding
  one agree as the slip leaves zero, so the switch costs no accuracy);
- compression's end (v_y = 0) and restitution's end (W back to
  (1 - e_c^2) of its maximum) are located by Newton's method on re-taken
  steps, the maximum of W being stationary there.

Why this: the right-hand side is smooth between the switches, which are
few (each contact's slip ends, or its hold breaks, once or twice per
impact), so a high-order pair takes large steps between them (on the 300
impacts below a median of 19 steps per impact, 95 at the 90th percentile,
652 at most, rejected and re-taken ones included); the switches
themselves are landed on rather than stepped over, so the order holds
across them. A fixed step cannot do both: the step that resolves a slip
closing on zero is far smaller than the one the rest of the impact needs
(the version before this one, midpoint steps landed on each event, stayed
first order where a contact's friction barely failed to hold it). An
error estimate also makes the step count independent of the speed.
Measured by tests/physics/test_mathavan_convergence.py (300 impacts to
12 m/s and 400 rad/s, ``errors(300, seed=2)``) against an independent
integration (tests/physics/mathavan_midpoint.py, the previous midpoint
scheme, at 64 x its 200 steps, itself within 2e-7 V of 128 x), in units of
V: median error 8e-11 V, the worst 3.5e-7 V (before: 96% within 1e-5 V,
the worst 8e-5 V); 32 times the tolerance (half the step of a fifth-order
pair) changes no impact by more than 3.5e-7 V. The paper's own scheme
takes explicit Euler steps of a fixed impulse increment (N = 5000) with
the friction along the slip at the step's start, which chatters around
zero slip.

Guards: the felt's normal impulse is clamped at zero (a cushion friction
that would lift the ball off the felt, only possible for mu_w > tan(theta),
about 0.44 for h_c = 0.04 m); no approach (or a non-finite one) returns the
state unchanged; an impact stops after MAX_STEPS steps; a normal velocity
left into the cushion is removed; if rounding left the ball with more
kinetic energy than it came in with, its velocities are scaled down to the
incoming energy. None of the guards acts on an ordinary impact.

Conventions: right-handed axes, spin in rad/s, as in motion.py; the
caller's normal points from the cushion to the ball's centre, the paper's
Y axis is its opposite.
"""
import collections
import math

from .._jit import njit
from .. import constants as C

# Local error allowed per step (the embedded pair's estimate), as a fraction
# of the impact's speed scale V = |v| + R |w|: at 1e-9 every impact of
# tests/physics/test_mathavan_convergence.py is within 1e-5 V of the
# reference and 32 times tighter (the step halved, for a fifth-order pair)
# changes it by less than 1e-6 V (module docstring).
STEP_TOL = 1e-9
# A sliding contact whose slip closes on zero steps at most APPROACH of the
# impulse its slip, at its present rate, needs to reach zero: the stages
# then never straddle the zero, where the friction's direction jumps.
APPROACH = 0.5
# A sliding contact's slip is taken as at zero (set to zero, the contact
# held) when it is below SNAP times the step tolerance (in units of V), or
# closes on zero within that much velocity change (the friction it would
# still spend, at most 2 lim, over the impulse to zero, times the largest
# compliance 3.5 / m): below it an explicit step would chatter around
# zero with about that amplitude. Setting it to zero moves the state by
# less than that.
SNAP = 30.0
# A slip closing within the threshold's velocity change is set to zero
# only if it is below CLOSE times the threshold (setting it to zero moves
# the state by the slip: a weak friction's slip may still be large).
CLOSE = 10.0
# A held contact whose friction is cut to its cone lets its slip grow; it
# slides once its slip exceeds RELEASE times the snapping threshold (a
# hysteresis, so that a slip just released is not snapped back).
RELEASE = 2.0
# Step controller: the step grows by at most GROW, shrinks by at least
# SHRINK per step, aiming at SAFETY of the allowed error.
GROW, SHRINK, SAFETY = 5.0, 0.2, 0.9
# Bound on accepted plus rejected steps of one impact (the convergence
# test's 300 impacts take a median of 19 steps, at most 652, re-taken ones
# included; only a wedged ball, whose normal velocity stalls, reaches it).
MAX_STEPS = 3000
# First step, as a fraction of the frictionless compression impulse.
FIRST_STEP = 0.05

# The ball in the cushion frame: velocity (m/s), spin (rad/s) and the work
# W of the cushion's normal force (J, eq. 16a); also their rates d/dP_I.
Ball = collections.namedtuple("Ball", "vx vy wx wy wz W")
# The impact's constants: ball radius (m) and mass (kg), sin and cos of the
# contact angle theta, cushion and felt friction coefficients.
Contact = collections.namedtuple("Contact", "R M st ct mu_w mu_s")
# The contacts' regime: whether each is held (its friction the one that
# holds its slip, cut to its cone) or slides.
Regime = collections.namedtuple("Regime", "stick_i stick_c")
# Friction per unit P_I at the cushion (FIx, FIy along X and Y') and at the
# felt (FCx, FCy); held_i, held_c: whether a held contact's holding
# friction lies within its cone (else it is cut to it).
Friction = collections.namedtuple("Friction", "FIx FIy FCx FCy held_i held_c")


@njit
def _acc(b, s, k):
    """b + s k, component by component."""
    return Ball(b.vx + s * k.vx, b.vy + s * k.vy, b.wx + s * k.wx, b.wy + s * k.wy, b.wz + s * k.wz,
                b.W + s * k.W)


@njit
def _slip_i(b, c):
    """Slip at the cushion contact I (eqs. 12a-b): along X and along Y'."""
    return b.vx + c.R * (b.wy * c.st - b.wz * c.ct), -b.vy * c.st + c.R * b.wx


@njit
def _slip_c(b, c):
    """Slip at the felt contact C (eqs. 13a-b)."""
    return b.vx - c.R * b.wy, b.vy + c.R * b.wx


@njit
def _direction(x, y):
    """(x, y) / |(x, y)| (zeros for a zero vector)."""
    s = math.sqrt(x * x + y * y)
    if s > 0.0:
        return x / s, y / s
    return 0.0, 0.0


@njit
def _felt_normal(c, FIy):
    """Felt's normal impulse per unit P_I (vertical balance), never pulling."""
    return max(c.st - c.ct * FIy, 0.0)


@njit
def _hold_cushion(c, ux, uy):
    """Friction (FIx, FIy) holding the cushion slip's rate at zero while the
    felt slides with friction mu_s N_C (ux, uy), N_C depending on FIy
    (module docstring). Returns a value outside the cone when none holds it."""
    s, k = c.st, c.ct
    g = 2.5 - s
    den = 2.5 + s * s - g * c.mu_s * k * uy
    if not (den > 0.0):
        return 2.0 * c.mu_w + 1.0, 0.0
    FIy = -s * (k + g * c.mu_s * uy) / den
    n = c.st - c.ct * FIy
    if n < 0.0:  # clamped felt: no felt friction
        n = 0.0
        FIy = -s * k / (2.5 + s * s)
    FIx = -(1.0 - 2.5 * s) * c.mu_s * n * ux / 3.5
    return FIx, FIy


@njit
def _hold_felt(c, FIx, FIy):
    """Friction (FCx, FCy) holding the felt slip's rate at zero against the
    normal impulse and the cushion friction (FIx, FIy)."""
    return -(1.0 - 2.5 * c.st) * FIx / 3.5, (c.ct - (2.5 - c.st) * FIy) / 3.5


@njit
def _cut(x, y, limit):
    """(x, y) cut to length limit; and whether it was within it."""
    f = math.sqrt(x * x + y * y)
    if f <= limit:
        return x, y, True
    return limit * x / f, limit * y / f, False


@njit
def _friction(b, c, g):
    """Frictions of both contacts in regime g: a sliding contact's friction
    is its limit against its slip (eq. 15); a sticking contact's is the one
    that holds its slip's rate at zero against everything that drives it
    (the normal impulse and the other contact's friction), cut to its cone."""
    xi, yi = _slip_i(b, c)
    xc, yc = _slip_c(b, c)
    ix, iy = _direction(xi, yi)
    cx, cy = _direction(xc, yc)
    if not g.stick_i and not g.stick_c:
        FIx, FIy = -c.mu_w * ix, -c.mu_w * iy
        n = c.mu_s * _felt_normal(c, FIy)
        return Friction(FIx, FIy, -n * cx, -n * cy, False, False)
    if g.stick_i and not g.stick_c:
        FIx, FIy = _hold_cushion(c, -cx, -cy)
        FIx, FIy, held = _cut(FIx, FIy, c.mu_w)
        n = c.mu_s * _felt_normal(c, FIy)
        return Friction(FIx, FIy, -n * cx, -n * cy, held, False)
    if g.stick_c and not g.stick_i:
        FIx, FIy = -c.mu_w * ix, -c.mu_w * iy
        hx, hy = _hold_felt(c, FIx, FIy)
        FCx, FCy, held = _cut(hx, hy, c.mu_s * _felt_normal(c, FIy))
        return Friction(FIx, FIy, FCx, FCy, False, held)
    # both held (possible only at v_y = 0: y_I = y_C = 0 needs (1 + sin) v_y = 0):
    # x has no drive, y is a 2 x 2 solve
    s, k = c.st, c.ct
    q = 2.5 - s
    det = 3.5 * (2.5 + s * s) - q * q
    FIy = -k * (3.5 * s + q) / det
    FCy = k * (2.5 + s * s + q * s) / det
    lim_c = c.mu_s * _felt_normal(c, FIy)
    hi, hc = abs(FIy) <= c.mu_w, abs(FCy) <= lim_c
    FIy = max(-c.mu_w, min(c.mu_w, FIy))
    lim_c = c.mu_s * _felt_normal(c, FIy)
    FCy = max(-lim_c, min(lim_c, FCy))
    return Friction(0.0, FIy, 0.0, FCy, hi, hc)


@njit
def _rates_of(b, c, f):
    """d(vx, vy, wx, wy, wz, W)/dP_I of the frictions f (eqs. 14, 17, 16a)."""
    q = 2.5 / (c.M * c.R)  # R / I for a solid sphere
    return Ball((f.FIx + f.FCx) / c.M, (-c.ct - c.st * f.FIy + f.FCy) / c.M,
                q * (f.FIy + f.FCy), q * (c.st * f.FIx - f.FCx), -q * c.ct * f.FIx, c.ct * b.vy)


@njit
def _rates(b, c, g):
    return _rates_of(b, c, _friction(b, c, g))


# Dormand and Prince's 5(4) pair (Hairer, Norsett, Wanner, Solving ODEs I,
# table 5.2): stage nodes, coefficients, fifth-order weights (the last stage
# is the fifth-order solution's rate, reused as the next step's first), and
# the fifth minus the fourth-order weights (the error estimate).
A21 = 1.0 / 5.0
A31, A32 = 3.0 / 40.0, 9.0 / 40.0
A41, A42, A43 = 44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0
A51, A52, A53, A54 = 19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0
A61, A62, A63, A64, A65 = 9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0
B1, B3, B4, B5, B6 = 35.0 / 384.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0
E1, E3, E4, E5, E6, E7 = (71.0 / 57600.0, -71.0 / 16695.0, 71.0 / 1920.0, -17253.0 / 339200.0, 22.0 / 525.0,
                          -1.0 / 40.0)

# The error's weights: velocities, R times the spins, and the work in units
# of (velocity) x (the incoming momentum m v_n), which is how a work error
# moves the end of restitution's outgoing velocity.
Scale = collections.namedtuple("Scale", "v w")


@njit
def _dp_step(b, c, g, h, k1):
    """One Dormand-Prince step of impulse h from b (rates k1 there):
    the fifth-order state, its rates, and the error estimate (per component)."""
    k2 = _rates(_acc(b, h * A21, k1), c, g)
    y = _acc(_acc(b, h * A31, k1), h * A32, k2)
    k3 = _rates(y, c, g)
    y = _acc(_acc(_acc(b, h * A41, k1), h * A42, k2), h * A43, k3)
    k4 = _rates(y, c, g)
    y = _acc(_acc(_acc(_acc(b, h * A51, k1), h * A52, k2), h * A53, k3), h * A54, k4)
    k5 = _rates(y, c, g)
    y = _acc(_acc(_acc(_acc(_acc(b, h * A61, k1), h * A62, k2), h * A63, k3), h * A64, k4), h * A65, k5)
    k6 = _rates(y, c, g)
    y = _acc(_acc(_acc(_acc(_acc(b, h * B1, k1), h * B3, k3), h * B4, k4), h * B5, k5), h * B6, k6)
    k7 = _rates(y, c, g)
    z = Ball(0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    err = _acc(_acc(_acc(_acc(_acc(_acc(z, h * E1, k1), h * E3, k3), h * E4, k4), h * E5, k5), h * E6, k6),
               h * E7, k7)
    return y, k7, err


@njit
def _err_norm(err, c, sc):
    """The error estimate in units of the allowed error (max norm)."""
    ev = max(abs(err.vx), abs(err.vy), c.R * max(abs(err.wx), abs(err.wy), abs(err.wz)))
    return max(ev / sc.v, abs(err.W) / sc.w)


@njit
def _zero_slip(b, c, j):
    """b with contact j's slip set to exactly zero through the spins (a
    change below the snapping threshold: only called for a slip that small)."""
    if j == 1:
        x, y = _slip_i(b, c)
        return Ball(b.vx, b.vy, b.wx - y / c.R, b.wy, b.wz + x / (c.R * c.ct), b.W)
    x, y = _slip_c(b, c)
    return Ball(b.vx, b.vy, b.wx - y / c.R, b.wy + x / c.R, b.wz, b.W)


@njit
def _closing(b, c, g, k, j, thr):
    """For a sliding contact j: the impulse its slip needs to reach zero at
    its present rate (inf if not closing), and whether it counts as at zero
    (``SNAP``; thr the threshold in m/s)."""
    if j == 1:
        if g.stick_i:
            return math.inf, False
        x, y = _slip_i(b, c)
        rx, ry = _slip_i(k, c)
        lim = c.mu_w
    else:
        if g.stick_c:
            return math.inf, False
        x, y = _slip_c(b, c)
        rx, ry = _slip_c(k, c)
        lim = c.mu_s * (c.st + c.ct * c.mu_w)  # the felt's largest limit
    ss = x * x + y * y
    if not (lim > 0.0):  # a frictionless contact: its slip does not matter
        return math.inf, False
    if ss <= thr * thr:
        return 0.0, True
    a = -(x * rx + y * ry)  # |s| times the rate at which |s| falls
    if not (a > 0.0):
        return math.inf, False
    tau = ss / a
    return tau, 7.0 * lim * tau / c.M <= thr and ss <= (CLOSE * thr) ** 2


@njit
def _released(b, c, g, thr):
    """Regime after a step: a held contact whose slip has grown beyond
    RELEASE thr (its holding friction left its cone) slides."""
    si, sc = g.stick_i, g.stick_c
    if si:
        x, y = _slip_i(b, c)
        si = x * x + y * y <= (RELEASE * thr) ** 2
    if sc:
        x, y = _slip_c(b, c)
        sc = x * x + y * y <= (RELEASE * thr) ** 2
    return Regime(si, sc)


@njit
def _prepare(b, c, g, thr, h):
    """Before a step: hold the contacts whose slip is at zero (``SNAP``),
    and limit the step to APPROACH of a closing slip's impulse to zero.
    Returns b, g, the rates at b, and the step."""
    k = _rates(b, c, g)
    for _ in range(3):
        ti, zi = _closing(b, c, g, k, 1, thr)
        tc, zc = _closing(b, c, g, k, 2, thr)
        if not (zi or zc):
            return b, g, k, min(h, APPROACH * ti, APPROACH * tc)
        if zi:
            b = _zero_slip(b, c, 1)
        if zc:
            b = _zero_slip(b, c, 2)
        g = Regime(g.stick_i or zi, g.stick_c or zc)
        k = _rates(b, c, g)
    return b, g, k, h


# Newton iterations locating the end of compression and of restitution
# within a step, and the relative change of the impulse that ends them.
LOCATE_ITERS, LOCATE_TOL = 12, 1e-14


@njit
def _locate(b, c, g, k1, t, hi, target, work):
    """The state where v_y (work False) or W (work True) reaches target
    within a step of at most hi from b: Newton's method from t on the
    impulse of re-taken steps, whose rates give the derivative."""
    y = b
    for _ in range(LOCATE_ITERS):
        t = min(max(t, 0.0), hi)
        y, _, _ = _dp_step(b, c, g, t, k1)
        k = _rates(y, c, g)
        f = (y.W if work else y.vy) - target
        d = k.W if work else k.vy
        if f == 0.0 or d == 0.0:
            break
        dt = f / d
        t -= dt
        if abs(dt) <= LOCATE_TOL * hi:
            break
    return y


@njit
def _integrate(b, c, e, tol):
    """Compression and restitution in the cushion frame (b.vy > 0 into the
    cushion), restitution e, local error tol (in units of V): the outgoing
    state (its W the work left, (1 - e^2) of the compression work)."""
    V = math.hypot(b.vx, b.vy) + c.R * math.sqrt(b.wx * b.wx + b.wy * b.wy + b.wz * b.wz)
    sc = Scale(tol * V, tol * V * c.M * b.vy)
    g = Regime(False, False)
    thr = SNAP * tol * V
    h = FIRST_STEP * c.M * b.vy / c.ct
    compressing = True
    target = 0.0
    for _ in range(MAX_STEPS):
        b, g, k1, hs = _prepare(b, c, g, thr, h)
        y, _, err = _dp_step(b, c, g, hs, k1)
        r = _err_norm(err, c, sc)
        if not (r <= 1.0):  # rejected (also a non-finite estimate)
            h = hs * max(SHRINK, SAFETY * r ** -0.2) if r == r else hs * SHRINK
            continue
        h = hs * min(GROW, SAFETY * r ** -0.2) if r > 0.0 else hs * GROW
        if compressing and y.vy <= 0.0:  # compression ends within the step (eq. 16a's W is at its maximum)
            yc = _locate(b, c, g, k1, hs * b.vy / (b.vy - y.vy), hs, 0.0, False)
            compressing = False
            target = (1.0 - e * e) * yc.W  # eq. 16b
            if e == 0.0:
                return Ball(yc.vx, 0.0, yc.wx, yc.wy, yc.wz, yc.W)
        if not compressing and y.W <= target:  # restitution ends within the step
            t = hs * (b.W - target) / (b.W - y.W) if b.W > y.W else hs
            return _locate(b, c, g, k1, t, hs, target, True)
        b = y
        g = _released(b, c, g, thr)
    return b  # guard: step bound reached


@njit
def _resolve_tol(vx, vy, wx, wy, wz, nx, ny, e_c, p, tol):
    """``resolve`` with the step tolerance as an argument (the tests use it
    to measure the integration error)."""
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
    b = _integrate(Ball(u, w, ox, oy, wz, 0.0), Contact(R, M, st, ct, p[C.P_F_C], p[C.P_MU_S]), e, tol)
    u, w, ox, oy, oz = b.vx, b.vy, b.wx, b.wy, b.wz
    if w > 0.0:  # guard: never leave moving into the cushion
        w = 0.0
    e_out = u * u + w * w + 0.4 * R * R * (ox * ox + oy * oy + oz * oz)
    if e_out > e_in:  # guard: never gain energy (rounding)
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
    return _resolve_tol(vx, vy, wx, wy, wz, nx, ny, e_c, p, STEP_TOL)
