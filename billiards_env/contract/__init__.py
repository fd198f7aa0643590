"""The bot contract: what a player is handed and what it hands back, below
both the bots and the envs (``docs/bots.md``).

- ``GameView`` / ``TaskView`` (``contract.view``): a read-only picture of a
  batch of tables where a player is to move;
- ``ShotPlan`` (``contract.plan``): one shot per table;
- ``preview`` (``contract.preview``): candidate shots tried in the
  simulator and judged by the rules, exactly as the env plays them;
- ``play_turn`` (``contract.turn``): one turn of a two-player game, the
  function the env's step and the preview share;
- ``ActionCodec`` (``contract.codec``): the games' action convention,
  plans to actions and back;
- ``ShotOutcome`` (``contract.outcome``): what a one-player task judges.

Layers: ``physics`` and ``rules`` below, ``bots`` and ``envs`` above; no
module here imports either of them.
"""
from .codec import ActionCodec
from .outcome import ShotOutcome
from .plan import ShotPlan
from .preview import Preview, TaskPreview, common_draws, preview
from .turn import Equipment, Turn, play_turn
from .view import GameView, TableMarks, TaskView

__all__ = ["ActionCodec", "ShotOutcome", "ShotPlan", "Preview", "TaskPreview", "common_draws", "preview",
           "Equipment", "Turn", "play_turn", "GameView", "TableMarks", "TaskView"]
