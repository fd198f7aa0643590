"""8-ball for two agents, as a PettingZoo game: ``env()``, ``raw_env()``, ``parallel_env()`` (``factories``)."""
from ..aec import EightBallAECEnv
from .factories import factories

env, raw_env, parallel_env = factories(EightBallAECEnv)

__all__ = ["env", "raw_env", "parallel_env"]
