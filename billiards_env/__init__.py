"""billiards_env: a Gymnasium pool environment over a batched numba simulator."""
__version__ = "0.1.0"
