"""Policies by name: the baselines of ``agents.baselines``, the lookahead
search of ``agents.lookahead`` and saved models (what ``scripts/evaluate.py
--policy`` and the training's final evaluation accept)."""
from __future__ import annotations

from .baselines import GhostBallPolicy, Policy, RandomPolicy, SB3Policy, SearchPolicy
from .lookahead import LookaheadPolicy

BASELINE_NAMES = ("random", "ghost", "lookahead")  # besides search<K>


def make_policy(name: str, env, seed: int = 0, k: int = 256) -> Policy:
    """A baseline by name: ``random``, ``ghost``, ``search`` (``search<K>``
    sets K, e.g. ``search64``), ``lookahead`` (``agents.lookahead``), or a
    path to a saved model / run directory."""
    if name == "random":
        return RandomPolicy(env, seed=seed)
    if name == "ghost":
        return GhostBallPolicy(env)
    if name == "lookahead":
        return LookaheadPolicy(env, seed=seed)
    if name.startswith("search"):
        kk = int(name[6:]) if name[6:] else k
        return SearchPolicy(env, k=kk, seed=seed)
    return SB3Policy.load(name, env=env)
