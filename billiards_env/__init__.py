"""billiards_env: a Gymnasium pool environment over a batched numba simulator."""
__version__ = "0.1.0"

from .envs.registration import register_envs as _register_envs

_register_envs()
