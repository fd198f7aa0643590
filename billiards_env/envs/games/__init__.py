"""Two-player pool by the rules (9-ball, 8-ball, 10-ball) over the batched simulator:
the batched game core, the self-play vector env, the single-agent env
against a fixed opponent (one table, and batched: ``versus``), the
PettingZoo AEC env (``aec``) and the PettingZoo modules of each game,
``env()``, ``raw_env()`` and ``parallel_env()`` (``pz``; docs/games.md)."""
from .core import ACTION_DIM, GAMES, GameConfig, GameCore

__all__ = ["ACTION_DIM", "GAMES", "GameConfig", "GameCore"]
