"""Expert Iteration for the proposal network (docs/expert_iteration.md): self-play by the search over the network's
proposals (``selfplay``), the torch network and its losses (``model``), the resumable fit (``fit``), the rounds,
the distillation of the fast player and shipping (``loop``), its settings (``config``).
``scripts/expert_iteration.py`` is its command line. Importing this package loads neither torch nor ray."""
from .config import QUICK, ExItConfig, NetConfig

__all__ = ["QUICK", "ExItConfig", "NetConfig"]
