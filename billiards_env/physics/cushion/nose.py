"""The cushion nose's contact, shared by the impulse cushion models
(``impulse_frictional``, ``stronge``): its geometry, the contact point's
velocity split along the contact normal, and an impulse applied there.

The nose touches the ball above its equator, at height h_c, so the contact
point sits at r = R (-c n, s) from the centre (n the cushion's unit normal
into the table, s = sin(theta) = h_c / R - 1, c = cos(theta)) and the unit
contact normal, from the contact point through the centre, is
N = (c n, -s). Both models treat the ball as free during the impulse (the
contact point's mobility 1/m along N and 7/(2m) across it, uncoupled) and
then drop the vertical velocity the impulse gave it (the felt takes it up),
as Han (2005) and pooltool's 2D cushion models do.
"""
import collections
import math

from .. import constants as C
from .._jit import njit

# The contact: the ball's velocity and spin, the contact point's offset r
# from the centre and the contact normal N (both 3-vectors, as tuples), the
# normal approach speed w = -v_c . N > 0, and the tangential slip of the
# contact point (tx, ty, tz).
Contact = collections.namedtuple("Contact", "vx vy wx wy wz r N w tx ty tz")


@njit
def contact(vx, vy, wx, wy, wz, nx, ny, approach, p):
    """The nose contact of a ball (velocity, spin) on a cushion of unit
    normal (nx, ny) into the table, with ``approach`` = -v . n the measured
    approach speed: w = cos(theta) approach (the spin adds nothing along N)."""
    R = p[C.P_R]
    s = p[C.P_H_C] / R - 1.0
    c = math.sqrt(1.0 - s * s)
    rx, ry, rz = -R * c * nx, -R * c * ny, R * s
    Nx, Ny, Nz = c * nx, c * ny, -s
    # contact point velocity v + w x r (no vertical velocity)
    ux = vx + wy * rz - wz * ry
    uy = vy + wz * rx - wx * rz
    uz = wx * ry - wy * rx
    un = ux * Nx + uy * Ny + uz * Nz
    return Contact(vx, vy, wx, wy, wz, (rx, ry, rz), (Nx, Ny, Nz), c * approach,
                   ux - un * Nx, uy - un * Ny, uz - un * Nz)


@njit
def apply(k, jx, jy, jz, R):
    """The ball after an impulse per unit mass (jx, jy, jz) at the contact
    point: v += j (its vertical part dropped), w += r x j / (2/5 R^2)."""
    rx, ry, rz = k.r
    q = 2.5 / (R * R)
    return (k.vx + jx, k.vy + jy,
            k.wx + q * (ry * jz - rz * jy),
            k.wy + q * (rz * jx - rx * jz),
            k.wz + q * (rx * jy - ry * jx))
