"""Plain reflection: the normal velocity reverses with restitution e_c,
v' = v - (1 + e_c) (v . n) n; tangential velocity and spin unchanged (a
frictionless cushion).

Source: Newton's law of restitution for a smooth wall (any mechanics text).
"""
from .._jit import njit


@njit
def resolve(vx, vy, wx, wy, wz, nx, ny, approach, e_c, p):
    """Cushion model (``contact`` describes the interface); v . n is the
    measured approach, negated."""
    vn = -approach
    return vx - (1.0 + e_c) * vn * nx, vy - (1.0 + e_c) * vn * ny, wx, wy, wz
