"""The reference integration of tests/physics/test_mathavan_convergence.py:
billiards_env/physics/cushion/mathavan2010.py as it was at df93ffd, before its
Dormand-Prince integration (commit d229a82), kept unchanged but for its
imports. It integrates the same equations with independent numerics
(midpoint steps of a fixed impulse, its own stick landing), and converges
as its step count grows (64 against 128 times its 200 steps: within 2e-7
of the speed scale); the tests run it at 64 times. Its docstring below
describes it as the library's model, as it then was.

Ball-cushion impact integrated through the impulse (numba kernel).

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
impulse); both contacts may stick (a 2 x 2 solve per axis). Otherwise it
slides, from zero, along the friction that would have held it, cut to the
cone. (The version before this one held a stuck contact against the normal
impulse's drive only: the held slip then chattered around zero with an
amplitude proportional to the step, first order across every stick while
the ball slid on the felt.)

Numerics: the midpoint rule in steps of a fixed impulse increment,
IMPULSE_STEPS per compression of a frictionless ball (so the step count,
and the relative accuracy, do not depend on the speed), with the right-hand
side's non-smooth points landed on:

- compression's end (z_I = 0) and restitution's end (the released work, a
  quadratic in the step: within a step the rates are constant, so the
  normal velocity is linear in the impulse and the trapezoidal work of
  eq. 16a is exact);
- the end of a stickable contact's slip (``_closing``): with the other
  contact's friction frozen, the slip obeys p' = q - lim A p / |A p| (an
  affine map of the contact's own friction), whose impulse to p = 0 is an
  integral over ln |p| (``_end_impulse``, classical Runge-Kutta in the slip's
  direction angle, closed-form tail); one step of that impulse with the
  mean friction that ends the slip exactly then lands on zero;
- a non-stickable slip's closest approach to zero (it reverses), found with
  the rates at the step's start (the midpoint's rates may already have
  overshot); a slip passing near zero is resolved with steps that move it
  by at most TURN of its size;
- a contact at zero that cannot stick, and one released from a stick,
  slides along the friction that would have held it (the direction its
  slip leaves zero in) until its slip exceeds ``_zero_slip``: below that
  the slip's direction relaxes faster than a step, where the explicit rule
  is unstable and chatters.

Why this and not an adaptive embedded pair: the non-smooth points are
known, so landing on them keeps a fixed, cheap step without rejected
steps; an error estimate would only find them by shrinking the step around
each one, and the stiff relaxation of a small slip's direction would keep
it small. Measured by tests/physics/test_mathavan_convergence.py against
64 x the steps (itself within 2e-7 of 128 x), over speeds to 12 m/s and
spins to 400 rad/s, in units of the speed scale V = |v| + R |w|: median
error ~3e-8 V (the version before: the same), 96% of impacts within 1e-5 V,
the worst ~8e-5 V (before: 4e-4 V); 200 against 400 steps differ by a
median ~2e-8 V. The impacts left above 1e-5 V have a contact whose friction
barely fails to hold it (drive ~ friction limit), so that its slip hovers
within one step's change of zero for several steps: the explicit rule is
first order there. The paper's own scheme takes explicit Euler steps of a
fixed impulse increment (N = 5000) with the friction along the slip at the
step's start, which chatters around zero slip.

Guards: the felt's normal impulse is clamped at zero (a cushion friction
that would lift the ball off the felt, only possible for mu_w > tan(theta),
about 0.44 for h_c = 0.04 m); no approach (or a non-finite one) returns the
state unchanged; each phase stops after MAX_PHASE_FACTOR times the step
count; a normal velocity left into the cushion is removed; if rounding or
discretisation left the ball with more kinetic energy than it came in
with, its velocities are scaled down to the incoming energy. None of the
guards acts on an ordinary impact.

Conventions: right-handed axes, spin in rad/s, as in motion.py; the
caller's normal points from the cushion to the ball's centre, the paper's
Y axis is its opposite.
"""
import collections
import math

from billiards_env.physics._jit import njit
from billiards_env.physics import constants as C

# A contact released from zero slip (it stuck, or its slip reversed) keeps
# sliding along the friction that would have held it until its slip
# exceeds RELEASE_STEPS steps of its change: before that its direction is
# set by the last step's rounding and the midpoint's overshoot, not by the
# physics.
RELEASE_STEPS = 4.0
# A step moves a sliding contact's slip by at most TURN of its size (so its
# direction turns by at most ~TURN rad), but is never shorter than MIN_STEP
# of the full step (a bound on the work near a slip that passes very close
# to zero, which the closest-approach landing then takes).
TURN = 0.1
MIN_STEP = 1e-3
# Impulse steps in the compression of a frictionless ball: at 200 every
# impact of tests/physics/test_mathavan_convergence.py (speeds to 12 m/s,
# spins to 400 rad/s) is within 1e-5 of its speed scale |v| + R |w| of a
# 64 x finer integration, and 400 steps change it by less than 1e-6 of it;
# the cost is linear in the count.
IMPULSE_STEPS = 200
# Bound on the steps of one phase, in units of IMPULSE_STEPS: with both
# frictions <= 0.5 and h_c = 0.04 m the normal velocity still falls at
# >= 0.28 / m per unit impulse (0.92 / m without friction), so a phase takes
# under 3.5 units, plus one landing step per stick or reversal; only larger
# frictions (which can stall the normal velocity) reach the bound.
MAX_PHASE_FACTOR = 20
# A sliding contact whose slip's closest approach within a step is below
# this fraction of its slip at the step's start ends the step there: the
# slip's direction turns through most of a half-turn around such a point
# within a fraction of a step, which the midpoint rule would not resolve.
NEAR_ZERO = 0.25

# The ball in the cushion frame: velocity (m/s) and spin (rad/s); also the
# rates d/dP_I of the same five values.
Ball = collections.namedtuple("Ball", "vx vy wx wy wz")
# The impact's constants: ball radius (m) and mass (kg), sin and cos of the
# contact angle theta, cushion and felt friction coefficients.
Contact = collections.namedtuple("Contact", "R M st ct mu_w mu_s")
# Friction per unit P_I at the cushion (FIx, FIy along X and Y') and at the
# felt (FCx, FCy); hold_i, hold_c: whether each contact sticks.
Friction = collections.namedtuple("Friction", "FIx FIy FCx FCy hold_i hold_c")


@njit
def _advance(b, k, h):
    """The state b + h k."""
    return Ball(b.vx + h * k.vx, b.vy + h * k.vy, b.wx + h * k.wx, b.wy + h * k.wy, b.wz + h * k.wz)


@njit
def _slip_i(b, c):
    """Slip at the cushion contact I (eqs. 12a-b): along X and along Y'."""
    return b.vx + c.R * (b.wy * c.st - b.wz * c.ct), -b.vy * c.st + c.R * b.wx


@njit
def _slip_c(b, c):
    """Slip at the felt contact C (eqs. 13a-b)."""
    return b.vx - c.R * b.wy, b.vy + c.R * b.wx


@njit
def _unit(x, y):
    """(x, y) / |(x, y)| and |(x, y)| (zeros for a zero vector)."""
    s = math.sqrt(x * x + y * y)
    if s > 0.0:
        return x / s, y / s, s
    return 0.0, 0.0, 0.0


@njit
def _felt_normal(c, FIy):
    """Felt's normal impulse per unit P_I (vertical balance), never pulling."""
    return max(c.st - c.ct * FIy, 0.0)


@njit
def _hold_cushion(c, ux, uy):
    """Friction (FIx, FIy) holding the cushion slip at zero while the felt
    slides with friction mu_s N_C (ux, uy), N_C depending on FIy (module
    docstring). Returns a value outside the cone when none holds it."""
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
    """Friction (FCx, FCy) holding the felt slip at zero against the normal
    impulse and the cushion friction (FIx, FIy)."""
    return -(1.0 - 2.5 * c.st) * FIx / 3.5, (c.ct - (2.5 - c.st) * FIy) / 3.5


@njit
def _cut(x, y, limit):
    """(x, y) cut to length limit; and whether it was within it."""
    f = math.sqrt(x * x + y * y)
    if f <= limit:
        return x, y, True
    return limit * x / f, limit * y / f, False


# How the frictions are chosen in one evaluation: zi, zc, whether each
# contact's slip is at zero (the sticking rule decides its friction); fix:
# 0, or the contact (1 cushion, 2 felt) whose friction is held at (Fx, Fy)
# through a step that ends its slip (``_closing``).
Mode = collections.namedtuple("Mode", "zi zc fix Fx Fy")


@njit
def _friction(b, c, m):
    """Frictions of both contacts (module docstring) in mode m. A contact
    slides against its slip unless the slip is zero or ``m`` says it is at
    zero; then the sticking rule decides."""
    xi, yi = _slip_i(b, c)
    xc, yc = _slip_c(b, c)
    ix, iy, si = _unit(xi, yi)
    cx, cy, sc = _unit(xc, yc)
    zi = m.zi or si == 0.0
    zc = m.zc or sc == 0.0
    if m.fix == 1:  # the cushion's friction is given
        FIx, FIy = m.Fx, m.Fy
        lim_c = c.mu_s * _felt_normal(c, FIy)
        if not zc:
            return Friction(FIx, FIy, -lim_c * cx, -lim_c * cy, False, False)
        hx, hy = _hold_felt(c, FIx, FIy)
        FCx, FCy, held = _cut(hx, hy, lim_c)
        return Friction(FIx, FIy, FCx, FCy, False, held)
    if m.fix == 2:  # the felt's friction is given; the cushion slides
        return Friction(-c.mu_w * ix, -c.mu_w * iy, m.Fx, m.Fy, False, False)
    if not zi and not zc:
        FIx, FIy = -c.mu_w * ix, -c.mu_w * iy
        n = c.mu_s * _felt_normal(c, FIy)
        return Friction(FIx, FIy, -n * cx, -n * cy, False, False)
    if zi and not zc:
        FIx, FIy = _hold_cushion(c, -cx, -cy)
        FIx, FIy, held = _cut(FIx, FIy, c.mu_w)
        n = c.mu_s * _felt_normal(c, FIy)
        return Friction(FIx, FIy, -n * cx, -n * cy, held, False)
    if zc and not zi:
        FIx, FIy = -c.mu_w * ix, -c.mu_w * iy
        hx, hy = _hold_felt(c, FIx, FIy)
        FCx, FCy, held = _cut(hx, hy, c.mu_s * _felt_normal(c, FIy))
        return Friction(FIx, FIy, FCx, FCy, False, held)
    # both at zero: both held (x: no drive, no friction; y: a 2 x 2 solve)
    s, k = c.st, c.ct
    g = 2.5 - s
    det = 3.5 * (2.5 + s * s) - g * g
    FIy = -k * (3.5 * s + g) / det
    FCy = k * (2.5 + s * s + g * s) / det
    lim_c = c.mu_s * _felt_normal(c, FIy)
    if abs(FIy) <= c.mu_w and abs(FCy) <= lim_c:
        return Friction(0.0, FIy, 0.0, FCy, True, True)
    if abs(FCy) > lim_c:  # the felt slides, along the friction that would have held it
        ux, uy, _ = _unit(0.0, FCy)
        FIx, FIy = _hold_cushion(c, ux, uy)
        FIx, FIy, held = _cut(FIx, FIy, c.mu_w)
        n = c.mu_s * _felt_normal(c, FIy)
        return Friction(FIx, FIy, n * ux, n * uy, held, False)
    FIx, FIy, _ = _cut(0.0, FIy, c.mu_w)  # the cushion slides, the felt may hold
    hx, hy = _hold_felt(c, FIx, FIy)
    FCx, FCy, held = _cut(hx, hy, c.mu_s * _felt_normal(c, FIy))
    return Friction(FIx, FIy, FCx, FCy, False, held)


# The slip's final approach to zero (``_end_impulse``): the direction's
# equation is integrated in u = ln |p| with classical Runge-Kutta steps of
# END_DU until the direction has settled (its rate below END_SETTLED) or u
# has fallen by END_SPAN (|p| by e^-40); the rest of the impulse is then a
# closed-form tail.
END_DU = 0.125
END_SETTLED = 1e-12
END_SPAN = 40.0

# A stickable contact's slip on its way to zero, in the coordinates
# p = A^-1 m s (s the slip): p' = q - lim A p / |A p| per unit P_I, where
# lim is the friction limit, q = A^-1 r0 and r0 + A F the slip rate (times
# m) as an affine function of the contact's friction F (A = [[a11, a12],
# [a21, a22]]; the other contact's friction held as it is).
Approach = collections.namedtuple("Approach", "px py qx qy a11 a12 a21 a22 lim")


@njit
def _approach_rate(ap, phi):
    """(e . G, e_perp . G), G = dp/dP, for p along e = (cos phi, sin phi)."""
    ex, ey = math.cos(phi), math.sin(phi)
    sx, sy = ap.a11 * ex + ap.a12 * ey, ap.a21 * ex + ap.a22 * ey
    n = math.sqrt(sx * sx + sy * sy)
    gx, gy = ap.qx - ap.lim * sx / n, ap.qy - ap.lim * sy / n
    return ex * gx + ey * gy, -ey * gx + ex * gy


@njit
def _end_impulse(ap, h):
    """Impulse T at which the slip reaches zero, p(T) = 0, from p0 =
    (px, py), if T < h; else -1 (also if it does not close: |q| >= lim).
    With u = ln |p|: dphi/du = (e_perp . G) / (e . G) and dT/du =
    |p| / (-e . G); T is the integral over u from -inf to ln |p0|."""
    qq = ap.qx * ap.qx + ap.qy * ap.qy
    if qq >= ap.lim * ap.lim:
        return -1.0
    rho = math.sqrt(ap.px * ap.px + ap.py * ap.py)
    if not (rho > 0.0) or rho >= h * (math.sqrt(qq) + ap.lim):  # |p'| <= |q| + lim: T >= rho / (|q| + lim)
        return -1.0
    phi = math.atan2(ap.py, ap.px)
    a, b = _approach_rate(ap, phi)
    if not (a < 0.0) or rho / -a >= 2.0 * h:  # far from zero: not within this step
        return -1.0
    du = -END_DU
    total = 0.0
    gu, gh = math.exp(du), math.exp(0.5 * du)
    for _ in range(int(END_SPAN / END_DU)):
        if abs(b / a) < END_SETTLED:
            break
        # RK4 on phi(u), and on T with dT/du = e^u / -a(phi)
        k1, t1 = b / a, rho / -a
        a2, b2 = _approach_rate(ap, phi + 0.5 * du * k1)
        a3, b3 = _approach_rate(ap, phi + 0.5 * du * (b2 / a2))
        a4, b4 = _approach_rate(ap, phi + du * (b3 / a3))
        if not (a2 < 0.0 and a3 < 0.0 and a4 < 0.0):
            return -1.0
        phi += du * (k1 + 2.0 * b2 / a2 + 2.0 * b3 / a3 + b4 / a4) / 6.0
        total += -du * (t1 + 2.0 * rho * gh / -a2 + 2.0 * rho * gh / -a3 + rho * gu / -a4) / 6.0
        rho *= gu
        a, b = _approach_rate(ap, phi)
        if not (a < 0.0):
            return -1.0
    t = total + rho / -a  # the tail: the direction has settled, |p| falls at -a
    return t if t < h else -1.0


@njit
def _may_end(px, py, qx, qy, lim, h):
    """Whether a slip at p can reach zero within h: |p'| <= |q| + lim, so it
    takes at least |p| / (|q| + lim) (checked without roots)."""
    bound = h * (abs(qx) + abs(qy) + lim)  # >= h (|q| + lim)
    return px * px + py * py < bound * bound


@njit
def _closing(b, c, f, zi, zc, h):
    """A step that ends a stickable sliding contact's slip within h: the
    impulse T at which it reaches zero (``_end_impulse``) and the mean
    friction over it, (Fx, Fy) = -(p0 / T + q) (from s(T) = 0), which
    brings the slip exactly to zero at T while the other contact slides as
    in f (its friction affine in this one's, module docstring). Returns
    (contact, T, Fx, Fy, stick_i, stick_c) for the contact whose slip ends
    first (contact 0 if none does within h); stick_* say per contact
    whether it could stick (|q| < lim: its slip, while it slides, keeps
    shrinking)."""
    s, k, M = c.st, c.ct, c.M
    g = 2.5 - s
    a = 1.0 - 2.5 * s
    best, tb, bx, by = 0, -1.0, 0.0, 0.0
    stick_i = stick_c = False
    if not zi and not zc and not f.hold_i:  # cushion, the felt sliding along u
        xi, yi = _slip_i(b, c)
        ms = c.mu_s
        lim_c = ms * _felt_normal(c, f.FIy)
        ux = uy = 0.0
        if lim_c > 0.0:  # the felt friction's direction, f.FC / (mu_s N_C)
            ux, uy = f.FCx / lim_c, f.FCy / lim_c
        else:  # clamped felt (or no felt friction)
            ms = 0.0
        # r0 = (a ms s ux, s k + g ms s uy); A = [[3.5, e], [0, d]]
        d = 2.5 + s * s - g * ms * k * uy
        if d > 0.0:
            e = -a * ms * k * ux
            # A^-1 (x, y) = ((x - e y / d) / 3.5, y / d)
            r0x, r0y = a * ms * s * ux, s * k + g * ms * s * uy
            px, py = (M * xi - e * M * yi / d) / 3.5, M * yi / d
            qx, qy = (r0x - e * r0y / d) / 3.5, r0y / d
            stick_i = qx * qx + qy * qy < c.mu_w * c.mu_w
            if stick_i and _may_end(px, py, qx, qy, c.mu_w, h):
                t = _end_impulse(Approach(px, py, qx, qy, 3.5, e, 0.0, d, c.mu_w), h)
                if t > 0.0:
                    best, tb, bx, by = 1, t, -(px / t + qx), -(py / t + qy)
    if not zc and not zi and not f.hold_c:  # felt, the cushion sliding as in f
        xc, yc = _slip_c(b, c)
        px, py = M * xc / 3.5, M * yc / 3.5
        qx, qy = a * f.FIx / 3.5, (-k + g * f.FIy) / 3.5
        lim = c.mu_s * _felt_normal(c, f.FIy)
        stick_c = qx * qx + qy * qy < lim * lim
        if stick_c and _may_end(px, py, qx, qy, lim, h):
            t = _end_impulse(Approach(px, py, qx, qy, 3.5, 0.0, 0.0, 3.5, lim), h)
            if t > 0.0 and (best == 0 or t < tb):
                best, tb, bx, by = 2, t, -(px / t + qx), -(py / t + qy)
    return best, tb, bx, by, stick_i, stick_c


@njit
def _rates_of(c, f):
    """d(vx, vy, wx, wy, wz)/dP_I of the frictions f (eqs. 14, 17)."""
    q = 2.5 / (c.M * c.R)  # R / I for a solid sphere
    return Ball((f.FIx + f.FCx) / c.M, (-c.ct - c.st * f.FIy + f.FCy) / c.M,
                q * (f.FIy + f.FCy), q * (c.st * f.FIx - f.FCx), -q * c.ct * f.FIx)


@njit
def _closest(sx, sy, rx, ry, h, zero):
    """How far a step of at most h may go for a sliding contact whose slip
    (sx, sy) changes at (rx, ry): to the slip's closest approach to zero if
    that lies within the step and within NEAR_ZERO of zero (and whether the
    slip left there, below ``zero``, counts as zero); else at most TURN of
    the slip's own size (the slip's direction turns by at most ~TURN rad:
    the midpoint rule resolves a slip passing near zero). Not used for a
    contact that can stick, whose slip ends by ``_closing``."""
    rr = rx * rx + ry * ry
    ss = sx * sx + sy * sy
    t = -(sx * rx + sy * ry) / rr if rr > 0.0 else -1.0
    if 0.0 < t < h:
        px, py = sx + t * rx, sy + t * ry
        left = px * px + py * py
        if left <= NEAR_ZERO * NEAR_ZERO * ss:
            return t, left <= zero * zero
    if TURN * TURN * ss < h * h * rr:
        return max(TURN * math.sqrt(ss / rr), MIN_STEP * h), False
    return h, False


@njit
def _zero_slip(c, Fx, Fy, h):
    """The slip (m/s) below which a contact with friction (Fx, Fy) counts
    as at zero for steps h: RELEASE_STEPS steps of the slip change its
    friction alone makes (3.5 |F| / m per unit P_I, the stiffest
    compliance). Below it the slip's direction relaxes faster than a
    step resolves (the explicit rule would be unstable there)."""
    return RELEASE_STEPS * h * 3.5 * math.sqrt(Fx * Fx + Fy * Fy) / c.M


@njit
def _slip_events(b, k, c, f, h, stick_i, stick_c):
    """The first impulse in (0, h] where a sliding contact's slip comes
    closest to zero under the rates k, and which contacts' slips end there."""
    ti = tc = h
    zi = zc = False
    if not f.hold_i and not stick_i:
        xi, yi = _slip_i(b, c)
        ri = _slip_i(k, c)
        ti, zi = _closest(xi, yi, ri[0], ri[1], h, _zero_slip(c, f.FIx, f.FIy, h))
    if not f.hold_c and not stick_c:
        xc, yc = _slip_c(b, c)
        rc = _slip_c(k, c)
        tc, zc = _closest(xc, yc, rc[0], rc[1], h, _zero_slip(c, f.FCx, f.FCy, h))
    t = min(ti, tc)
    return t, zi and ti <= t, zc and tc <= t, ti, tc


@njit
def _midpoint(b, c, m, k1, h):
    """The midpoint rule's rates for a step h from b in mode m, where the
    rates are k1: the frictions evaluated again, in the same mode, at
    b + h/2 k1."""
    f2 = _friction(_advance(b, k1, 0.5 * h), c, m)
    return _rates_of(c, f2)


# One step: its impulse h, its rates k, which contacts' slips it ended
# (land_i, land_c), which held at its start (held_i, held_c), and its mode,
# frictions and rates at its start (m, f1, k1: ``_midpoint`` again for a
# shortened step).
Step = collections.namedtuple("Step", "h k land_i land_c held_i held_c m f1 k1")


@njit
def _step(b, c, zi, zc, h):
    """One midpoint step of at most h, shortened to end where a sliding
    contact's slip ends (``_closing``: the contact can stick) or comes
    closest to zero (``_slip_events``, found with the rates at the step's
    start, then again with the midpoint rates of the shortened step: near
    zero the midpoint's slip can have overshot and reversed, so the
    midpoint rates alone would miss it)."""
    m = Mode(zi, zc, 0, 0.0, 0.0)
    f1 = _friction(b, c, m)
    k1 = _rates_of(c, f1)
    which, tc, Fx, Fy, stick_i, stick_c = _closing(b, c, f1, zi, zc, h)
    t, li, lc, ti, tk = _slip_events(b, k1, c, f1, h, stick_i, stick_c)
    # the slip of contact `which` ends at tc, before the other's event
    if which > 0 and tc <= (tk if which == 1 else ti):
        m = Mode(zi, zc, which, Fx, Fy)
        f1 = _friction(b, c, m)
        k1 = _rates_of(c, f1)
        k = _midpoint(b, c, m, k1, tc)
        return Step(tc, k, which == 1, which == 2, f1.hold_i, f1.hold_c, m, f1, k1)
    k = _midpoint(b, c, m, k1, t)
    if t < h:
        t2, li, lc, _, _ = _slip_events(b, k, c, f1, h, stick_i, stick_c)
        if t2 != t:
            t = t2
            k = _midpoint(b, c, m, k1, t)
    return Step(t, k, li, lc, f1.hold_i, f1.hold_c, m, f1, k1)


@njit
def _landing(vy, ay, ct, rem):
    """Impulse h at which the restitution releases the work rem, with vy
    linear in h at rate ay < 0: ct (-vy h - ay h^2 / 2) = rem (the root
    written without cancellation). Returns -1 if there is none."""
    q = rem / ct
    den = -vy + math.sqrt(vy * vy - 2.0 * ay * q)
    return 2.0 * q / den if den > 0.0 else -1.0


@njit
def _compress(b, c, dp, max_steps):
    """Compression: until the normal approach at I, vy cos(theta), is zero.
    Returns the state, the compression work (eq. 16a) and the contacts'
    at-zero flags."""
    work = 0.0
    zi = zc = False
    for _ in range(max_steps):
        if b.vy <= 0.0:
            break
        s = _step(b, c, zi, zc, dp)
        h, k = s.h, s.k
        last = False
        if k.vy < 0.0 and b.vy + k.vy * h <= 0.0:  # compression ends within this step
            k = _midpoint(b, c, s.m, s.k1, -b.vy / k.vy)
            if k.vy < 0.0 and b.vy + k.vy * h <= 0.0:
                h = -b.vy / k.vy  # lands on vy = 0
                last = True
        vy_next = 0.0 if last else b.vy + k.vy * h
        work += 0.5 * c.ct * (b.vy + vy_next) * h  # eq. 16a, exact for vy linear in the step
        b = _advance(b, k, h)
        b = Ball(b.vx, vy_next, b.wx, b.wy, b.wz)
        if last:
            break
        zi, zc = _at_zero(b, c, s, dp)
    if b.vy > 0.0:  # guard: phase bound reached
        b = Ball(b.vx, 0.0, b.wx, b.wy, b.wz)
    return b, work, zi, zc


@njit
def _at_zero(b, c, s, h):
    """At-zero flags after step s (of at most h), b the state after it: a
    contact whose slip the step ended, or one at zero at its start that
    held or whose slip is still below ``_zero_slip``; until it leaves, it
    slides along the friction that would have held it (``_friction``),
    the direction its slip takes as it leaves zero."""
    zi = s.land_i
    if s.m.zi and not zi:
        xi, yi = _slip_i(b, c)
        zi = s.held_i or math.sqrt(xi * xi + yi * yi) <= _zero_slip(c, s.f1.FIx, s.f1.FIy, h)
    zc = s.land_c
    if s.m.zc and not zc:
        xc, yc = _slip_c(b, c)
        zc = s.held_c or math.sqrt(xc * xc + yc * yc) <= _zero_slip(c, s.f1.FCx, s.f1.FCy, h)
    return zi, zc


@njit
def _restitute(b, c, dp, max_steps, target, zi, zc):
    """Restitution: until the cushion gives back the work target."""
    released = 0.0
    for _ in range(max_steps):
        rem = target - released
        if rem <= 0.0:
            break
        s = _step(b, c, zi, zc, dp)
        h, k = s.h, s.k
        last = -0.5 * c.ct * (2.0 * b.vy + k.vy * h) * h >= rem
        if last and k.vy < 0.0:  # the target is reached within this step
            hl = _landing(b.vy, k.vy, c.ct, rem)
            if hl > 0.0:
                k = _midpoint(b, c, s.m, s.k1, hl)
                last = -0.5 * c.ct * (2.0 * b.vy + k.vy * h) * h >= rem
                if last and k.vy < 0.0:
                    hl = _landing(b.vy, k.vy, c.ct, rem)
                    if hl > 0.0:
                        h = min(h, hl)
        released += -0.5 * c.ct * (2.0 * b.vy + k.vy * h) * h
        b = _advance(b, k, h)
        if last:
            break
        zi, zc = _at_zero(b, c, s, dp)
    return b


@njit
def _integrate(b, c, e, steps):
    """Compression and restitution in the cushion frame (b.vy > 0 into the
    cushion), restitution e. Returns the outgoing state."""
    dp = c.M * b.vy / (c.ct * steps)
    max_steps = MAX_PHASE_FACTOR * steps
    b, work_c, zi, zc = _compress(b, c, dp, max_steps)
    b = _restitute(b, c, dp, max_steps, e * e * work_c, zi, zc)
    if b.vy > 0.0:  # guard: never leave moving into the cushion
        b = Ball(b.vx, 0.0, b.wx, b.wy, b.wz)
    return b


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
    b = _integrate(Ball(u, w, ox, oy, wz), Contact(R, M, st, ct, p[C.P_F_C], p[C.P_MU_S]), e, steps)
    u, w, ox, oy, oz = b.vx, b.vy, b.wx, b.wy, b.wz
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
