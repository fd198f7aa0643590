"""First-contact times: the earliest t in [0, H] where a polynomial gap
function f(t) (degree <= 4) goes from positive to non-positive.

Root isolation by derivatives rather than closed-form Ferrari: the real roots
of f' split [0, H] into intervals on which f is monotone, and those of f''
split it for f'. Each monotone bracket with a sign change is solved by
Newton's method guarded by bisection, so a root is never missed and every
returned root lies inside its bracket. Degenerate polynomials (leading
coefficients zero, e.g. two balls with equal accelerations) need no special
case: the same isolation applies to any degree.
"""
import math

from ._jit import njit
from . import constants as C


@njit
def _poly(c4, c3, c2, c1, c0, t):
    return (((c4 * t + c3) * t + c2) * t + c1) * t + c0


@njit
def _solve_bracket(c4, c3, c2, c1, c0, a, b, fa):
    """Root of a polynomial that is monotone on [a, b] with a sign change:
    Newton steps, falling back to bisection when a step leaves the bracket."""
    t = 0.5 * (a + b)
    for _ in range(200):
        f = _poly(c4, c3, c2, c1, c0, t)
        if f == 0.0:
            return t
        if (f > 0.0) == (fa > 0.0):
            a = t
        else:
            b = t
        if b - a <= C.ROOT_TIME_TOL * max(1.0, abs(a)):
            break
        d = ((4.0 * c4 * t + 3.0 * c3) * t + 2.0 * c2) * t + c1
        tn = t - f / d if d != 0.0 else a - 1.0
        if tn <= a or tn >= b:
            tn = 0.5 * (a + b)
        t = tn
    # return the end of the bracket on the non-positive side for f decreasing
    # through zero (fa > 0): contact is reached, never overshot by rounding.
    return b if fa > 0.0 else a


@njit
def _quadratic_roots(a, b, c):
    """Real roots of a t^2 + b t + c (any degree <= 2), sorted; nan if absent.
    Uses the cancellation-free form of the quadratic formula."""
    if a == 0.0:
        if b == 0.0:
            return math.nan, math.nan
        return -c / b, math.nan
    disc = b * b - 4.0 * a * c
    if disc < 0.0:
        return math.nan, math.nan
    sq = math.sqrt(disc)
    q = -0.5 * (b + math.copysign(sq, b))
    r1 = q / a
    r2 = c / q if q != 0.0 else r1
    if r1 > r2:
        r1, r2 = r2, r1
    return r1, r2


@njit
def _critical_points(c4, c3, c2, c1, H):
    """Real roots in (0, H) of f'(t) = 4c4 t^3 + 3c3 t^2 + 2c2 t + c1, sorted:
    returns (count, r0, r1, r2)."""
    d3, d2, d1, d0 = 4.0 * c4, 3.0 * c3, 2.0 * c2, c1
    x0 = x1 = x2 = math.inf
    n = 0
    if d3 == 0.0:
        q1, q2 = _quadratic_roots(d2, d1, d0)
        if q1 == q1 and 0.0 < q1 < H:
            x0 = q1; n = 1
        if q2 == q2 and 0.0 < q2 < H:
            if n == 0:
                x0 = q2
            else:
                x1 = q2
            n += 1
        return n, x0, x1, x2
    # the roots of f'' split [0, H] into pieces on which f' is monotone
    s1, s2 = _quadratic_roots(3.0 * d3, 2.0 * d2, d1)
    a = 0.0
    fa = d0
    for k in range(3):
        b = s1 if k == 0 else (s2 if k == 1 else H)
        if not (b == b and a < b <= H):
            continue
        fb = ((d3 * b + d2) * b + d1) * b + d0
        if (fa > 0.0 and fb < 0.0) or (fa < 0.0 and fb > 0.0):
            x = _solve_bracket(0.0, d3, d2, d1, d0, a, b, fa)
            if 0.0 < x < H:
                if n == 0:
                    x0 = x
                elif n == 1:
                    x1 = x
                else:
                    x2 = x
                n += 1
        a, fa = b, fb
    return n, x0, x1, x2


@njit
def first_entry(c4, c3, c2, c1, c0, H, f_tol, f_floor):
    """Earliest t in [0, H] at which f goes from > 0 to <= 0; inf if none.

    At t = 0, a gap within ``f_tol`` of zero counts as contact if it is
    closing (f' < 0) or held closed by the accelerations (f' = 0 within
    rounding, f'' < 0); a touching pair that is opening is not a contact,
    and its next contact is when the gap returns to its current level.
    Below ``f_floor`` the gap is not a contact at all (a ball far behind a
    cushion line).
    """
    if not H > 0.0:
        H = 0.0
    if f_floor <= c0 <= f_tol:
        # closing means faster than SPEED_EPS: a rate below it is rounding
        # (an impulse that small cannot even change a velocity's last bit)
        c1_tol = f_tol * (C.SPEED_EPS / C.CONTACT_TOL)
        # held closed: likewise only by more than rounding of accelerations
        c2_tol = f_tol * (C.ACCEL_EPS / C.CONTACT_TOL)
        if c1 < -c1_tol or (c1 <= c1_tol and c2 < -c2_tol):
            return 0.0
        if H > 0.0:
            # Touching and not closing: the gap may open by less than
            # rounding can resolve and close again (a pair pressed by the
            # felt after a slow impact; two balls sliding past each other
            # whose decelerations turn them into each other, a cubic term).
            # c0 itself may be a rounding below zero, so f need never rise
            # above zero first. Contact is when f returns to its current
            # level: the first root of (f - c0) / t = c4 t^3 + c3 t^2 +
            # c2 t + c1. Rates within rounding of zero are zero, in this and
            # in f itself: taken as real they close a pair that moves
            # together a few nanoseconds later, again and again.
            g1 = c1 if c1 > c1_tol else 0.0
            g2 = c2 if abs(c2) > c2_tol else 0.0
            t_back = _entry(0.0, c4, c3, g2, g1, H)
            return min(t_back, _entry(c4, c3, g2, g1, c0, H))
    if H == 0.0:
        return math.inf
    return _entry(c4, c3, c2, c1, c0, H)


# Relative rounding allowance of the Bernstein exclusion test: its
# coefficients are sums of five terms, each exact to an ulp (2.2e-16).
BERNSTEIN_ROUNDING = 1e-14
# Pieces [0, H] is cut into when the hull of the whole interval is not
# positive: a pair whose paths cross at different times is then settled
# without root isolation.
BERNSTEIN_PIECES = 4


@njit
def _hull_positive(c4, c3, c2, c1, c0, w):
    """True if the Bernstein coefficients of f on [0, w] are all positive:
    f then lies above their minimum (convex-hull property; Farouki & Rajan
    1987, "Algorithms for polynomials in Bernstein form")."""
    a1 = c1 * w
    a2 = c2 * w * w
    a3 = c3 * w * w * w
    a4 = c4 * w * w * w * w
    scale = abs(c0) + abs(a1) + abs(a2) + abs(a3) + abs(a4)
    b = min(c0, c0 + 0.25 * a1, c0 + 0.5 * a1 + a2 / 6.0,
            c0 + 0.75 * a1 + 0.5 * a2 + 0.25 * a3, c0 + a1 + a2 + a3 + a4)
    return b > BERNSTEIN_ROUNDING * scale


@njit
def _positive_on(c4, c3, c2, c1, c0, H):
    """True if f > 0 on all of [0, H] by the Bernstein hull of the whole
    interval or else of each of BERNSTEIN_PIECES pieces (coefficients moved
    to a piece's start by a Taylor shift). A dozen flops per piece, never
    wrong, and it settles most pairs the broad phase lets through, which
    never meet, without root isolation."""
    if _hull_positive(c4, c3, c2, c1, c0, H):
        return True
    w = H / BERNSTEIN_PIECES
    for k in range(BERNSTEIN_PIECES):
        s = k * w
        # Taylor coefficients of f(s + u) in u
        d0 = (((c4 * s + c3) * s + c2) * s + c1) * s + c0
        d1 = ((4.0 * c4 * s + 3.0 * c3) * s + 2.0 * c2) * s + c1
        d2 = (6.0 * c4 * s + 3.0 * c3) * s + c2
        d3 = 4.0 * c4 * s + c3
        if not _hull_positive(c4, d3, d2, d1, d0, w):
            return False
    return True


@njit
def _entry(c4, c3, c2, c1, c0, H):
    """First t in (0, H] where f goes from > 0 to <= 0 (inf if none)."""
    if not H > 0.0:
        return math.inf
    if H < math.inf and _positive_on(c4, c3, c2, c1, c0, H):
        return math.inf
    n, r0, r1, r2 = _critical_points(c4, c3, c2, c1, H)
    a = 0.0
    fa = c0
    for k in range(n + 1):
        b = H if k == n else (r0 if k == 0 else (r1 if k == 1 else r2))
        if b <= a:
            continue
        fb = _poly(c4, c3, c2, c1, c0, b)
        if fa > 0.0 and fb <= 0.0:
            return _solve_bracket(c4, c3, c2, c1, c0, a, b, fa)
        a, fa = b, fb
    return math.inf


@njit
def first_entry_quadratic(c2, c1, c0, H, f_tol, f_floor):
    """``first_entry`` for straight-line motion (the step solver): f is convex
    or linear (c2 >= 0), so the first closing root has a closed form, taken in
    its cancellation-free version."""
    if c0 <= f_tol:
        closing = c1 < -f_tol * (C.SPEED_EPS / C.CONTACT_TOL)  # as in first_entry
        return 0.0 if (closing and c0 >= f_floor) else math.inf
    if c1 >= 0.0:
        return math.inf
    if c2 == 0.0:
        t = -c0 / c1
    else:
        disc = c1 * c1 - 4.0 * c2 * c0
        if disc < 0.0:
            return math.inf
        t = 2.0 * c0 / (-c1 + math.sqrt(disc))
    return t if t <= H else math.inf
