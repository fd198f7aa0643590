"""Three-cushion for two agents, as a PettingZoo game: ``env()``, ``raw_env()``, ``parallel_env()`` (``factories``)."""
from ..aec import ThreeCushionAECEnv
from .factories import factories

env, raw_env, parallel_env = factories(ThreeCushionAECEnv)

__all__ = ["env", "raw_env", "parallel_env"]
