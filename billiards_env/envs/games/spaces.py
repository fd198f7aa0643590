"""Spaces, the observation table and the info layout shared by the game envs."""
from __future__ import annotations

import dataclasses
import os

import numpy as np
from gymnasium import spaces

from .core import GameConfig

OBSERVATION_DOC = """
    **Observation** (``Box(0, 1, (4*B + 14,), float32)``, B = 10 balls in
    9-ball, 16 in 8-ball, 11 in 10-ball; snooker ``(4*B + 20,)``, B = 22;
    ball 0 the cue ball):

    ==============  ===========================================================
    index           meaning
    ==============  ===========================================================
    3*i, 3*i + 1    ball i x / table width, y / table length (0 if pocketed)
    3*i + 2         1 if ball i is on the table
    3*B + i         1 if ball i is a legal first contact for the shooter
    4*B             shots played in this game / max_shots
    4*B + 1         the player to move (0 or 1)
    4*B + 2..4      ball in hand: none, anywhere, behind the head string
    4*B + 5..8      push-out allowed, may pass (after a push-out; 10-ball
                    also after an illegal pot), call needed (8-ball, on
                    the 8; 10-ball, every shot but the break), break shot
    4*B + 9..11     the shooter's group: open (9-ball, 10-ball always),
                    solids, stripes
    4*B + 12, 13    consecutive fouls of the shooter, of the opponent, / 3
    4*B + 14..17    snooker only (B = 22): the shooter's score, the
                    opponent's, the points of the balls on the table (each
                    / 147, clipped to 1), 1 if a free ball may be nominated
    4*B + 18, 19    snooker only: 1 if the balls may be replaced (after
                    the opponent's foul and a miss: a6 in (0, 0.5]), 1 if
                    the cue ball lies touching a ball
    ==============  ===========================================================

    Snooker reads "behind the head string" as "in the D" and its "call
    needed" as a nomination (a colour after a red, or a free ball).
"""


def make_config(config, overrides: dict, game: str | None = None) -> GameConfig:
    """The env's ``GameConfig``: ``config`` (None: the game's defaults; a
    ``GameConfig``; or the path of a YAML file) with ``overrides`` (keywords:
    any key, the equipment's flat) over it."""
    if config is None:
        return GameConfig(**({"game": game} if game else {}), **overrides)
    if isinstance(config, (str, os.PathLike)):
        config, overrides = GameConfig.from_yaml(config, **overrides), {}
    if not isinstance(config, GameConfig):
        raise TypeError(f"config must be a GameConfig or the path of a YAML file, got {type(config).__name__}")
    if game is not None and config.game != game:
        raise ValueError(f"config is for {config.game!r}, this env plays {game!r}")
    if overrides:
        return dataclasses.replace(config, **overrides)
    return config


def observation_space(core) -> spaces.Box:
    return spaces.Box(0.0, 1.0, shape=(core.obs_dim,), dtype=np.float32)


def action_space(core) -> spaces.Box:
    """``Box(-1, 1, (core.action_dim,))``: 8 components, 9 in 10-ball (the called ball)."""
    return spaces.Box(-1.0, 1.0, shape=(core.action_dim,), dtype=np.float32)


def info_row(info: dict, k: int) -> dict:
    """Table ``k``'s entries of a batched step info, as Python scalars or small arrays."""
    return {key: (v[k].item() if np.ndim(v) == 1 else np.array(v[k])) for key, v in info.items()}


def game_doc(spec, what: str, base: str) -> str:
    """A generated env class's docstring: the game's summary and ``what`` it is, the shared ``base`` docstring and
    what the game's ruleset adds (``Rules.env_doc``)."""
    from ...rules import get_rules
    return f"{spec.summary[:1].upper()}{spec.summary[1:]} {what}.\n\n    " + base + get_rules(spec.name).env_doc
