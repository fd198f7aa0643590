"""Impulse-based frictional inelastic cushion impact: one instantaneous
impulse at the cushion nose, Newton's restitution along the contact normal
and Coulomb friction across it, the ball free during the impulse and its
vertical velocity dropped afterwards (``nose`` describes the contact).

Source: the rigid-body impulse with Coulomb friction of Stronge, *Impact
Mechanics*, 2nd ed. (2018), ch. 3 (a sphere on a half-space: normal
mobility 1/m, tangential 1 / m + R^2 / I = 7 / (2m)); pooltool 0.6.0
offers the same model as "impulse_frictional_inelastic" for its cushions
(resolve_sphere_half_space_collision, 2D variant).

Normal impulse per unit mass j_n = (1 + e_c) w (w the normal approach at
the contact). Friction: the impulse that ends the tangential slip u_t,
-(2/7) u_t, if it lies in the cone f_c j_n (the slip ends: sticking), else
f_c j_n against the slip (sliding throughout). With f_c = 0 and the nose
at the equator (h_c = R) this is the reflection with restitution; above it
the normal velocity becomes v_n (1 - (1 + e_c) cos^2(theta)), as in
han2005, since the vertical part of the impulse is dropped.
"""
import math

from .. import constants as C
from .._jit import njit
from . import nose


@njit
def resolve(vx, vy, wx, wy, wz, nx, ny, approach, e_c, p):
    """Cushion model (``contact`` describes the interface)."""
    k = nose.contact(vx, vy, wx, wy, wz, nx, ny, approach, p)
    jn = (1.0 + e_c) * k.w
    Nx, Ny, Nz = k.N
    slip = math.sqrt(k.tx * k.tx + k.ty * k.ty + k.tz * k.tz)
    stick = 2.0 / 7.0
    if stick * slip <= p[C.P_F_C] * jn:  # the slip ends within the impulse
        f = stick
    else:  # sliding throughout: f_c j_n against the slip
        f = p[C.P_F_C] * jn / slip
    return nose.apply(k, jn * Nx - f * k.tx, jn * Ny - f * k.ty, jn * Nz - f * k.tz, p[C.P_R])
