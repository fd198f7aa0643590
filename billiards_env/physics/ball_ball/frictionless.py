"""Frictionless ball-ball impact: the normal impulse alone (restitution e_b
along the line of centres); tangential velocities and spins are unchanged.

Source: the textbook impulse of two equal smooth spheres (e.g. Alciatore,
"The Illustrated Principles of Pool and Billiards", technical proofs on
ball-ball collisions, without the throw term).
"""
from .._jit import njit
from . import contact


@njit
def resolve(pos, vel, om, e, i, j, p):
    """Impulses of an impact of touching balls i and j. Returns the normal
    approach speed (m/s) before the impact."""
    nx, ny, d = contact.line_of_centres(pos, e, i, j)
    w = contact.approach(pos, vel, e, i, j) / d  # > 0 when closing
    if w > 0.0:
        contact.push_apart(vel, e, i, j, nx, ny, contact.normal_impulse(w, p))
    return w
