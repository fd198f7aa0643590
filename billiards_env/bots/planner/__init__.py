"""``champion``: a game bot searching window-aimed, throw-corrected pots, safeties and kicks, judged by
successive halving under noise (one module per job: ``windows``, ``aim``, ``candidates``, ``halving``,
``breaks``, ``bot``)."""
from .bot import Champion, champion

__all__ = ["Champion", "champion"]
