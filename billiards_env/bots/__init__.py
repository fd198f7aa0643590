"""Bots: players that act on an explicit, read-only view of a batch of tables.

The two-player games' bot API (docs/bots.md):

- a bot has ``name`` and ``act(view: GameView) -> ShotPlan``: it is handed
  the tables where its player is to move and returns one shot per table;
- ``GameView`` (``contract.view``) holds the positions, the game state, the
  shooter's constraints, the equipment, the noise, and the helpers every
  bot needs: ``legal_placement``, ``marks`` and ``preview`` (``contract.preview``);
- ``ShotPlan`` (``contract.plan``): aim, speed, tip offsets, placement,
  declaration and called pocket per table;
- ``make_bot`` (``bots.registry``): built-in bots by name (``random``,
  ``ghost``, ``ghost-safety``, ``search<K>``) and ``module:factory`` bots.

The one-player tasks' baselines (``random``, ``ghost``, ``search<K>``,
``lookahead``) live in ``bots.one_player`` and ``bots.lookahead``.
"""
from ..contract import GameView, Preview, ShotPlan, TableMarks, preview  # the contract bots are written against
from .registry import BOT_NAMES, is_bot_name, make_bot

__all__ = ["ShotPlan", "Preview", "preview", "BOT_NAMES", "is_bot_name", "make_bot", "GameView",
           "TableMarks"]
