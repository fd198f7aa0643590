"""Compliant frictional cushion impact after Stronge, *Impact Mechanics*,
2nd ed. (2018), ch. 5 (collinear impact of a sphere with tangential
compliance: slip, stick and reverse slip), at the cushion nose (``nose``
describes the contact: normal through the contact point and the centre,
the ball free during the impact, its vertical velocity dropped after).
pooltool 0.6.0 makes the same model ("stronge_compliant") its default
cushion.

The contact has a normal spring k_n and a tangential spring k_t in series
with Coulomb friction f_c. With beta_n = 1, beta_t = 7/2 the contact
point's mobilities (times m), the normal and tangential frequencies are
omega_n^2 = beta_n k_n / m and omega_t^2 = beta_t k_t / m; their ratio
r = omega_t / omega_n = sqrt(beta_t kt_kn) (kt_kn = k_t / k_n, the
parameter) must lie in (1, 2), where the book's three regimes are the only
ones. Restitution is energetic: the normal spring unloads at stiffness
k_n / e_c^2. In the phase theta = omega_n t the normal force is
F ~ sin(theta) in compression (0 <= theta <= pi/2) and
cos((theta - pi/2) / e_c) in restitution (to theta_f = (1 + e_c) pi / 2),
and the normal impulse per unit mass, in units of the approach speed w,
p(theta) = 1 - cos(theta), then 1 + e_c sin((theta - pi/2) / e_c).

With eta^2 = k_n / k_t = beta_t / r^2, v0 = the initial slip / w and
mu = f_c, the regime follows from v0 alone (the book, ch. 5):

- gross slip, v0 > mu ((1 + e_c) beta_t - eta^2 / e_c): the slip never
  ends; v_f = v0 - mu beta_t (1 + e_c);
- initial stick, v0 < mu eta^2: the contact sticks from the start; the
  tangential spring oscillates at omega_t, u(theta) = (v0 / r) sin(r theta),
  until its force reaches the friction limit, |u| = mu eta^2 F(theta),
  then slides (along the spring's force) to the end;
- slip, stick, reverse slip otherwise: the slip ends at theta_s, where the
  slip rate v - du/dtheta vanishes, in closed form: cos(theta_s) =
  (v0 / mu - beta_t) / (eta^2 - beta_t) if v0 <= mu beta_t (in
  compression), else sin((theta_s - pi/2) / e_c) =
  (beta_t - v0 / mu) / (eta^2 / e_c - e_c beta_t) (in restitution); the
  spring, loaded to u = mu eta^2 F(theta_s), then oscillates until its
  force reaches the limit again and the contact slides the rest.

The code follows the phases from the start with the same equations, each
phase's end (a slip's, where its slip rate vanishes; a stick's, where
|u| = mu eta^2 F, a transcendental equation) bracketed on STICK_SAMPLES
points and bisected: in the book's regimes that gives the closed forms
above (tests/physics/test_cushion_models.py checks them), and outside them
(a low restitution with a high friction, where a "gross" slip would in fact
stop and reverse before the end) it stays consistent and never gains
energy. The
tangential impulse per unit mass is (v_f - v0) w / beta_t along the
initial slip's direction, the normal one (1 + e_c) w along the normal.
"""
import math

from .. import constants as C
from .._jit import njit
from . import nose

# Tangential and normal mobilities (times m) of a solid sphere's contact point.
BETA_T = 3.5
BETA_N = 1.0
# The end of a stick phase is bracketed on this many points of the rest of
# the impact (a stick lasts a good part of a half-period of omega_t, more
# than a tenth of the impact for r < 2), then bisected to ROOT_PHASE_TOL.
STICK_SAMPLES = 64
# Bisection stops when the bracket is below this (in the phase, rad): far
# below any effect on v_f (|dv/dtheta| <= r v0 + mu beta_t).
ROOT_PHASE_TOL = 1e-13
# Phases (slip or stick) followed in one impact: the book's regimes have at
# most three; a bound against a root that rounding puts back at its start.
MAX_PHASES = 8
# Slips below this (m/s) count as zero: no direction to resolve along, so
# the contact keeps no tangential impulse (float64 rounding of ~1 m/s).
SLIP_EPS = 1e-14


@njit
def _force(theta, e):
    """Normal force shape F(theta) (compression, then restitution)."""
    half = 0.5 * math.pi
    if theta <= half:
        return math.sin(theta)
    return math.cos((theta - half) / e)


@njit
def _impulse(theta, e):
    """Normal impulse per unit mass, in units of the approach speed."""
    half = 0.5 * math.pi
    if theta <= half:
        return 1.0 - math.cos(theta)
    return 1.0 + e * math.sin((theta - half) / e)


@njit
def _stick_end(u0, v0, t0, tf, r, lim, e):
    """The first phase in (t0, tf] at which the stuck spring's force
    reaches the friction limit: |u(theta)| = lim F(theta), with u(theta) =
    u0 cos(r tau) + (v0 / r) sin(r tau), tau = theta - t0. Returns tf if
    the stick lasts to the end."""
    prev = t0
    for i in range(1, STICK_SAMPLES + 1):
        t = t0 + (tf - t0) * i / STICK_SAMPLES
        tau = t - t0
        u = u0 * math.cos(r * tau) + v0 / r * math.sin(r * tau)
        if abs(u) > lim * _force(t, e):
            lo, hi = prev, t
            while hi - lo > ROOT_PHASE_TOL:
                mid = 0.5 * (lo + hi)
                tau = mid - t0
                u = u0 * math.cos(r * tau) + v0 / r * math.sin(r * tau)
                if abs(u) > lim * _force(mid, e):
                    hi = mid
                else:
                    lo = mid
            return hi
        prev = t
    return tf


@njit
def _rate(theta, e):
    """dF/dtheta of the normal force shape."""
    half = 0.5 * math.pi
    if theta <= half:
        return math.cos(theta)
    return -math.sin((theta - half) / e) / e


@njit
def _slip_end(v, sg, t0, tf, mu, eta2, e):
    """The first phase in (t0, tf] at which a slip along sg (+1 or -1),
    contact velocity v at t0, stops: the slip rate sg (v(theta) -
    du/dtheta) = sg v(theta) - mu eta^2 F'(theta) reaches zero, with
    v(theta) = v - sg mu beta_t (p(theta) - p(t0)). tf if it never does."""
    B = BETA_T / BETA_N
    p0 = _impulse(t0, e)
    prev = t0
    for i in range(1, STICK_SAMPLES + 1):
        t = t0 + (tf - t0) * i / STICK_SAMPLES
        if sg * v - mu * B * (_impulse(t, e) - p0) - mu * eta2 * _rate(t, e) <= 0.0:
            lo, hi = prev, t
            while hi - lo > ROOT_PHASE_TOL:
                mid = 0.5 * (lo + hi)
                if sg * v - mu * B * (_impulse(mid, e) - p0) - mu * eta2 * _rate(mid, e) <= 0.0:
                    hi = mid
                else:
                    lo = mid
            return hi
        prev = t
    return tf


@njit
def final_slip(v0, mu, e, kt_kn):
    """Tangential contact velocity at the end of the impact, in units of
    the normal approach speed, for an initial slip v0 >= 0 (same units)
    along a fixed line: positive along the initial slip, negative if it
    reversed. The phases (module docstring) follow each other from the
    start: a slip ends where its slip rate vanishes (``_slip_end``; in the
    book's regimes the closed forms of the docstring), a stick where the
    spring's force reaches the friction limit (``_stick_end``), then the
    contact slides along the spring's force; at most MAX_PHASES phases."""
    if mu <= 0.0:
        return v0
    if e <= 0.0:  # a resting contact (no restitution phase): the rigid limit
        return max(v0 - mu * BETA_T / BETA_N, 0.0)
    r = math.sqrt(BETA_T / BETA_N * kt_kn)
    eta2 = 1.0 / kt_kn
    B = BETA_T / BETA_N
    tf = (1.0 + e) * 0.5 * math.pi
    lim = mu * eta2
    t, v, u = 0.0, v0, 0.0
    sliding = v0 - lim > 0.0  # slip rate at the start: v0 - mu eta^2 F'(0)
    sg = 1.0
    for _ in range(MAX_PHASES):
        if sliding:
            ts = _slip_end(v, sg, t, tf, mu, eta2, e)
            v = v - sg * mu * B * (_impulse(ts, e) - _impulse(t, e))
            if ts >= tf:
                return v
            t, u, sliding = ts, sg * lim * _force(ts, e), False
        else:
            ts = _stick_end(u, v, t, tf, r, lim, e)
            tau = ts - t
            u, v = (u * math.cos(r * tau) + v / r * math.sin(r * tau),
                    -r * u * math.sin(r * tau) + v * math.cos(r * tau))
            if ts >= tf:
                return v
            t, sg, sliding = ts, math.copysign(1.0, u), True
    return v


@njit
def _final_speed(slip, w, mu, e, kt_kn):
    """``final_slip`` in m/s, for a slip and an approach w in m/s. An
    approach of a few ulps overflows slip / w: then the slip is gross (or,
    without friction or restitution, the limits of ``final_slip``),
    computed without the division."""
    v0 = slip / w
    if math.isfinite(v0):
        return final_slip(v0, mu, e, kt_kn) * w
    B = BETA_T / BETA_N
    if mu <= 0.0:
        return slip
    if e <= 0.0:
        return max(slip - mu * B * w, 0.0)
    return slip - mu * B * (1.0 + e) * w


@njit
def resolve(vx, vy, wx, wy, wz, nx, ny, approach, e_c, p):
    """Cushion model (``contact`` describes the interface)."""
    k = nose.contact(vx, vy, wx, wy, wz, nx, ny, approach, p)
    Nx, Ny, Nz = k.N
    jn = (1.0 + e_c) * k.w
    slip = math.sqrt(k.tx * k.tx + k.ty * k.ty + k.tz * k.tz)
    jt = 0.0
    if slip > SLIP_EPS and k.w > 0.0:
        jt = (_final_speed(slip, k.w, p[C.P_F_C], e_c, p[C.P_KT_KN]) - slip) / BETA_T / slip  # along the slip
    return nose.apply(k, jn * Nx + jt * k.tx, jn * Ny + jt * k.ty, jn * Nz + jt * k.tz, p[C.P_R])
