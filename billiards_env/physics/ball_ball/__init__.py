"""Ball-ball impact models.

A model is ``resolve(pos, vel, om, e, i, j, p) -> w``: it applies the impulses
of an impact of touching balls i and j of table e and returns the normal
approach speed w (m/s) before it (resting contacts below ZENO_SPEED are
handled by the shared ``contact.rest_contact``). ``frictionless`` is used
when ``Effects.ball_friction`` is off, else ``coulomb`` with the friction law
``Models.ball_ball_friction`` names in ``FRICTION_LAWS``: a module with a
jitted ``friction_coefficient(slip_speed, p) -> mu``.
"""
import importlib

from . import coulomb, frictionless

# name -> module ball_ball/<name>.py; a new law is one more line here
FRICTION_LAWS = {name: importlib.import_module(f"{__name__}.{name}") for name in (
    "constant",
    "alciatore",
)}

_coulomb = {}


def resolver(friction: bool, law: str):
    """The ball-ball model: frictionless, or Coulomb friction with the named
    law (one compiled function per law)."""
    if not friction:
        return frictionless.resolve
    if law not in _coulomb:
        _coulomb[law] = coulomb.make_resolve(FRICTION_LAWS[law].friction_coefficient)
    return _coulomb[law]
