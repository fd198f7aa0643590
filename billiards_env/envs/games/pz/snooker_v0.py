"""Snooker for two agents, as a PettingZoo game: ``env()``, ``raw_env()``, ``parallel_env()`` (``factories``)."""
from ..aec import SnookerAECEnv
from .factories import factories

env, raw_env, parallel_env = factories(SnookerAECEnv)

__all__ = ["env", "raw_env", "parallel_env"]
