"""Constant ball-ball friction coefficient: mu = mu_b whatever the slip speed.

Source: Alciatore's technical proofs on throw (constant-friction case);
mu_b = 0.06 from Alciatore's throw analysis and Marlow (params.py).
"""
from .. import constants as C
from .._jit import njit


@njit
def friction_coefficient(slip_speed, p):
    """Ball-ball friction coefficient at contact slip speed ``slip_speed``
    (m/s): the parameter mu_b."""
    return p[C.P_MU_B]
