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
mu = f_c, the regime follows from v0 alone (eqs. 5.29-5.33 of the book):

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

The end of a stick phase (|u| = mu eta^2 F, a transcendental equation) is
found by bracketing on STICK_SAMPLES points and bisection. The
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
def final_slip(v0, mu, e, kt_kn):
    """Tangential slip at the end of the impact, in units of the normal
    approach speed, for an initial slip v0 >= 0 (same units) along a fixed
    line: positive along the initial slip, negative if it reversed."""
    r = math.sqrt(BETA_T / BETA_N * kt_kn)
    eta2 = 1.0 / kt_kn
    tf = (1.0 + e) * 0.5 * math.pi
    B = BETA_T / BETA_N
    if mu <= 0.0:
        return v0
    if e <= 0.0:  # a resting contact (no restitution phase): the rigid limit
        return max(v0 - mu * B, 0.0)
    if v0 > mu * ((1.0 + e) * B - eta2 / e):  # gross slip
        return v0 - mu * B * (1.0 + e)
    lim = mu * eta2
    if v0 < lim:  # initial stick: the spring starts unloaded
        t0, u0, w0 = 0.0, 0.0, v0
    else:  # slip, then stick at theta_s
        if v0 <= mu * B:
            t0 = math.acos(min(max((v0 / mu - B) / (eta2 - B), -1.0), 1.0))
        else:
            x = (B - v0 / mu) / (eta2 / e - e * B)
            t0 = 0.5 * math.pi + e * math.asin(min(max(x, -1.0), 1.0))
        u0 = lim * _force(t0, e)
        w0 = v0 - mu * B * _impulse(t0, e)
    ts = _stick_end(u0, w0, t0, tf, r, lim, e)
    tau = ts - t0
    u = u0 * math.cos(r * tau) + w0 / r * math.sin(r * tau)
    v = -r * u0 * math.sin(r * tau) + w0 * math.cos(r * tau)
    if ts >= tf:
        return v
    # slides the rest, its friction along the spring's force (against u)
    return v - math.copysign(mu * B * (_impulse(tf, e) - _impulse(ts, e)), u)


@njit
def resolve(vx, vy, wx, wy, wz, nx, ny, approach, e_c, p):
    """Cushion model (``contact`` describes the interface)."""
    k = nose.contact(vx, vy, wx, wy, wz, nx, ny, approach, p)
    Nx, Ny, Nz = k.N
    jn = (1.0 + e_c) * k.w
    slip = math.sqrt(k.tx * k.tx + k.ty * k.ty + k.tz * k.tz)
    jt = 0.0
    if slip > SLIP_EPS and k.w > 0.0:
        vf = final_slip(slip / k.w, p[C.P_F_C], e_c, p[C.P_KT_KN]) * k.w
        jt = (vf - slip) / BETA_T / slip  # per unit slip, along the slip
    return nose.apply(k, jn * Nx + jt * k.tx, jn * Ny + jt * k.ty, jn * Nz + jt * k.tz, p[C.P_R])
