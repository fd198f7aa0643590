"""10-ball for two agents, as a PettingZoo game: ``env()``, ``raw_env()``, ``parallel_env()`` (``factories``)."""
from ..aec import TenBallAECEnv
from .factories import factories

env, raw_env, parallel_env = factories(TenBallAECEnv)

__all__ = ["env", "raw_env", "parallel_env"]
