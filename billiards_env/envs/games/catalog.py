"""The env classes of every registered game, generated from its registry
entry (``rules.games.GameSpec``) as tasks' are from theirs: the single-agent
env against a fixed opponent (``single.single_class``: ``<id_stem>Env``),
the vector entry point (``vector.vector_entry``: ``<name>_vector``) and the
PettingZoo AEC env (``aec.aec_class``: ``<class_prefix>AECEnv``; PettingZoo
is an optional dependency, so it is made on first use). Each module also
answers the classes by name (``single.NineBall2PEnv``, ...), looked up in
the registry, so a game registered after import has them too.
"""
from __future__ import annotations

import dataclasses
from typing import Callable

from ...rules import get_game
from .single import single_class
from .vector import vector_entry


@dataclasses.dataclass(frozen=True)
class GameClasses:
    """A game's generated env classes: ``single``, ``vector`` and ``aec()`` (made on first call)."""

    name: str
    single: type
    vector: Callable

    def aec(self) -> type:
        from .aec import aec_class
        return aec_class(self.name)


def game_classes(name: str) -> GameClasses:
    """The generated classes of a registered game."""
    get_game(name)  # an unknown game fails here, naming the registered ones
    return GameClasses(name, single_class(name), vector_entry(name))


def entry_points(name: str) -> tuple[str, str]:
    """The Gymnasium ``entry_point`` and ``vector_entry_point`` strings of a registered game's id."""
    spec = get_game(name)
    return (f"billiards_env.envs.games.single:{spec.id_stem}Env",
            f"billiards_env.envs.games.vector:{spec.name}_vector")
