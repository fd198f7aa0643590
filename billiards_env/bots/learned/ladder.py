"""The shipped ladder: frozen learned agents per game, weak to strong,
loadable by name as opponents (``make_bot("ladder-3")``, the game envs'
``opponent="ladder-3"``, ``scripts/match.py --policies ladder-3``).

Each agent is two files in ``bots/learned/ladder/<game>/`` (package data):

- ``ladder-<k>.npz``: the actor network's weights and the observation
  statistics as plain arrays (``bots.learned.mlp.MLPPolicy.arrays``; no
  pickle: ``numpy.load`` runs with ``allow_pickle=False``);
- ``ladder-<k>.json``: its card: ``format`` / ``format_version`` of these
  files, the agent's ``version``, ``game``, ``env_id``, the architecture
  (hidden sizes, activation, the menu's ``nvec``), the observation
  normalisation (clip, eps), the agent-side options (features, aim scale,
  action mode), ``training_steps``, the training wall time, whom it trained
  against and the run's resolved config (``source_config``).

``scripts/export_ladder.py`` writes them from a trained run's checkpoint.
Rung k of a game is the k-th agent of that game from the weakest; the same
name plays the game of whatever view it is handed, so ``ladder-2`` in an
8-ball match is the 8-ball agent.
"""
from __future__ import annotations

import json
import re
from functools import lru_cache
from pathlib import Path

import numpy as np

from .mlp import MLPPolicy
from .policy import ViewPolicy

LADDER_DIR = Path(__file__).with_name("ladder")
FORMAT = "billiards_env ladder agent"
FORMAT_VERSION = 1
_NAME = re.compile(r"^ladder-(\d+)$")


def is_ladder_name(name) -> bool:
    return isinstance(name, str) and _NAME.match(name) is not None


def ladder_names(game: str, root: Path = LADDER_DIR) -> list[str]:
    """The rungs shipped for ``game``, weakest first."""
    folder = Path(root) / game
    found = [p.stem for p in folder.glob("ladder-*.json") if is_ladder_name(p.stem)] if folder.is_dir() else []
    return sorted(found, key=lambda s: int(s.split("-")[1]))


def card(game: str, name: str, root: Path = LADDER_DIR) -> dict:
    """The JSON card of rung ``name`` of ``game``."""
    path = Path(root) / game / f"{name}.json"
    if not path.exists():
        have = ladder_names(game, root)
        raise ValueError(f"no ladder agent {name!r} for {game}; shipped: {', '.join(have) or 'none'}")
    doc = json.loads(path.read_text())
    if doc.get("format") != FORMAT or int(doc.get("format_version", -1)) > FORMAT_VERSION:
        raise ValueError(f"{path}: not a ladder card of format {FORMAT!r} version <= {FORMAT_VERSION}")
    if doc.get("game") != game:
        raise ValueError(f"{path}: the card is for {doc.get('game')!r}, not {game!r}")
    return doc


@lru_cache(maxsize=None)
def load_network(game: str, name: str, root: Path = LADDER_DIR) -> tuple[MLPPolicy, dict]:
    """(network, card) of rung ``name`` of ``game`` (read once per process)."""
    doc = card(game, name, root)
    arch, norm = doc["architecture"], doc.get("obs_norm") or {}
    with np.load(Path(root) / game / f"{name}.npz", allow_pickle=False) as z:
        net = MLPPolicy.from_arrays({k: z[k] for k in z.files}, arch["activation"], arch["nvec"],
                                    clip=float(norm.get("clip", 10.0)), eps=float(norm.get("eps", 1e-8)))
    hidden = [w.shape[0] for w in net.weights[:-1]]
    if hidden != list(arch["hidden"]):
        raise ValueError(f"{game}/{name}: the weights have hidden sizes {hidden}, the card says {arch['hidden']}")
    return net, doc


class LadderBot:
    """Rung ``name`` of the ladder as a bot: on each view it plays the
    agent of the view's game (``ViewPolicy``); ``seed`` seeds its
    placements' and breaks' ghost bot."""

    def __init__(self, name: str, seed: int = 0, root: Path = LADDER_DIR):
        if not is_ladder_name(name):
            raise ValueError(f"a ladder agent is named ladder-<k>, got {name!r}")
        self.name, self.seed, self.root = name, int(seed), Path(root)
        self._players: dict = {}

    def player(self, game: str) -> ViewPolicy:
        p = self._players.get(game)
        if p is None:
            net, doc = load_network(game, self.name, self.root)
            agent = doc["agent"]
            p = self._players[game] = ViewPolicy(net, self.name, agent["features"], agent["aim_scale"],
                                                 agent["action_mode"], placer_seed=self.seed)
        return p

    def act(self, view) -> np.ndarray:
        return self.player(view.game).act(view)
