"""Ball-cushion impact models.

A model is ``resolve(vx, vy, wx, wy, wz, nx, ny, approach, e_c, p) -> (vx,
vy, wx, wy, wz)`` (``contact`` describes it; ``contact.make_resolve`` wraps it with the
approach test and resting contacts). ``reflection`` is used when
``Effects.cushion_friction`` is off, else the model ``Models.cushion`` names
in ``MODELS``.
"""
import importlib

from . import reflection

# name -> module cushion/<name>.py; a new model is one more line here
MODELS = {name: importlib.import_module(f"{__name__}.{name}") for name in (
    "han2005",
    "mathavan2010",
    "stronge",
    "impulse_frictional",
)}


def resolver(friction: bool, name: str):
    """The cushion model: plain reflection, or the named model with friction."""
    return MODELS[name].resolve if friction else reflection.resolve
