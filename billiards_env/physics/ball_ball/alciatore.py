"""Ball-ball friction that falls with the sliding speed (numba kernel).

Source: D. G. Alciatore, technical proof TP A-14 ("the effects of cut angle,
speed and spin on object ball throw"), which fits measured throw of pool
balls with a Coulomb coefficient that decays exponentially with the
relative sliding speed of the two balls at the contact point:

    mu(v_rel) = a + b exp(-c v_rel),    a = 9.951e-3, b = 0.108, c = 1.088 s/m

(v_rel in m/s). pooltool uses the same fit, with the same constants, as the
default friction of its frictional inelastic ball-ball resolver.

v_rel is the speed of the relative tangential velocity of the two contact
points at the moment of impact (the normal part, which the normal impulse
removes, is left out): for a stun cut shot at speed v and cut angle phi it is
v sin(phi). The coefficient is evaluated once, from the slip before the
impulse, and then used as a constant Coulomb coefficient for the whole
(instantaneous) impact. The impulse that uses it must still be capped by the
one that ends the slip (m |u_t| / 7 for two equal solid balls): at slow
slips mu approaches a + b = 0.118, and without the cap a slow, thin cut
would reverse the slip and gain energy.
"""
import math

from .._jit import njit

# Fit constants of TP A-14 (dimensionless, dimensionless, s/m).
ALCIATORE_A = 9.951e-3   # limit at fast sliding
ALCIATORE_B = 0.108      # extra friction at vanishing slip: mu(0) = a + b = 0.118
ALCIATORE_C = 1.088      # decay rate per m/s of sliding speed


@njit
def friction_coefficient(slip_speed, p):
    """Ball-ball Coulomb coefficient for an impact whose contact points
    slide past each other at slip_speed (m/s, >= 0; a negative value is
    taken as 0, so mu never exceeds a + b). ``p`` (the parameter vector) is
    not read: the fit has its own constants."""
    v = slip_speed if slip_speed > 0.0 else 0.0
    return ALCIATORE_A + ALCIATORE_B * math.exp(-ALCIATORE_C * v)
