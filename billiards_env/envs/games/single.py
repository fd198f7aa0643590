"""A single-agent Gymnasium env per game: the agent plays one side of a
two-player game against a fixed opponent policy."""
from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np

from ...rules import DEFAULT_GAME, GAMES, get_game
from .core import GameCore
from .spaces import OBSERVATION_DOC, action_space, game_doc, info_row, make_config, observation_space
from .versus import AGENT, check_opponent, make_opponent, new_games, opponent_turns


class GameEnv(gym.Env):
    __doc__ = """One table of ``game``; the agent is player 0 and the opponent
    (``opponent=``: a bot name of ``bots.make_bot``, default ``"ghost"``,
    a ``module:factory`` or a bot object; docs/bots.md) plays player 1.
    Who breaks is drawn per game from the table's stream (``options=
    {"breaker": 0 or 1}`` fixes it; a seeded reset also reseeds the opponent
    with ``opponent_seed + seed``). ``step`` plays the agent's shot, then
    the opponent's shots until the agent is to move again or the game ends,
    so each observation is one the agent acts on (a game the opponent ends
    before the agent's first shot is replaced by the next rack,
    ``info["skipped_games"]``).

    **Reward**: +1 when the agent wins, -1 when it loses, 0 otherwise (a
    game cut at ``max_shots`` shots is a draw, truncated). **Info**: the
    agent's shot record (see ``GameVectorEnv``; ``foul`` is a code,
    ``rules.FOUL_*``, 0 none), ``opponent_shots`` (how many the opponent
    played since), ``winner`` and, on the step the game ends,
    ``final_score`` (the game's score, agent first: points in games to a
    score; ``score`` is the agent's own shot's, before the opponent replied).

    **Rendering**: ``render_mode="rgb_array"`` keeps each shot's event log
    (``rendering.RecordReplay`` records whole games from it) and
    ``render()`` draws the table with the game's status panel
    (``rendering.game.render_game``).
    """ + OBSERVATION_DOC

    metadata = {"render_modes": ["rgb_array"], "render_fps": 4}
    game = DEFAULT_GAME
    AGENT = AGENT

    def __init__(self, opponent="ghost", config=None, opponent_seed: int = 0, render_mode: str | None = None,
                 **overrides: Any):
        check_opponent(opponent)
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise ValueError(f"render_mode must be one of {self.metadata['render_modes']} or None, got {render_mode!r}")
        self.render_mode = render_mode
        self.config = make_config(config, overrides, self.game)
        self.core = GameCore(self.config, 1, record=render_mode is not None)
        self.observation_space = observation_space(self.core)
        self.action_space = action_space(self.core)
        self._opponent_spec, self._opponent_seed = opponent, opponent_seed
        self.opponent = None
        self._done = True
        self._seeded = False

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        super().reset(seed=seed)
        if seed is not None:
            self.core.streams.seed([0], [seed])
        elif not self._seeded:
            self.core.streams.seed([0], [int(self.np_random.integers(2 ** 63))])
        self._seeded = True
        if self.opponent is None or seed is not None:  # a seeded reset reseeds the opponent too
            self.opponent = make_opponent(self._opponent_spec, self._opponent_seed + (seed or 0))
        breaker = (options or {}).get("breaker")
        skipped, shots = new_games(self.core, self.opponent, [0], None if breaker is None else [int(breaker)])
        self._done = False
        return self.core.observe()[0], {"opponent_shots": int(shots[0]), "skipped_games": int(skipped[0])}

    def step(self, action):
        if self._done:
            raise RuntimeError("the game has ended (or never started): call reset() before step()")
        d = self.core.action_dim
        if np.shape(action) != (d,):
            raise ValueError(f"action must have shape ({d},), got {np.shape(action)}")
        out = self.core.step(self.core.validate_actions(np.reshape(action, (1, d)), 1), [0])
        info = info_row(out["info"], 0)
        reward = float(out["reward"][0])
        terminated, truncated = bool(out["terminated"][0]), bool(out["truncated"][0])
        n = 0
        if not (terminated or truncated):
            out = opponent_turns(self.core, self.opponent, [0])
            reward, terminated, truncated = (float(out["reward"][0]), bool(out["terminated"][0]),
                                             bool(out["truncated"][0]))
            n = int(out["shots"][0])
        info["opponent_shots"] = n
        info["winner"] = int(self.core.game.winner[0])
        self._done = terminated or truncated
        if self._done:  # the game's final score, agent first (``score`` is the agent's shot's, before the replies)
            info["final_score"] = self.core.game.score[0].astype(int).tolist()
        return self.core.observe()[0], reward, terminated, truncated, info

    def render(self):
        if self.render_mode is None:
            gym.logger.warn("render() called without a render_mode; pass render_mode='rgb_array' to gymnasium.make")
            return None
        if self.core.state is None:
            raise RuntimeError("call reset() before render()")
        from ...rendering.game import render_game
        return render_game(self.core, 0)


_CLASSES: dict = {}  # game -> (its spec, its generated single-agent class)


def single_class(name: str) -> type:
    """The single-agent env class of a registered game, ``<id_stem>Env`` (a ``GameEnv`` whose default opponent
    is the game's ``default_bot``), generated from its registry entry on first use."""
    spec = get_game(name)
    made = _CLASSES.get(name)
    if made is None or made[0] is not spec:
        default = spec.default_bot

        def __init__(self, opponent=default, config=None, opponent_seed: int = 0, render_mode: str | None = None,
                     **overrides: Any):
            GameEnv.__init__(self, opponent, config, opponent_seed, render_mode, **overrides)

        cls = type(f"{spec.id_stem}Env", (GameEnv,), {
            "__init__": __init__, "game": spec.name, "__module__": __name__,
            "__doc__": game_doc(spec, f"against a fixed opponent (default ``{default}``)", GameEnv.__doc__)})
        cls.__init__.__qualname__ = f"{cls.__name__}.__init__"
        made = _CLASSES[name] = (spec, cls)
    return made[1]


def __getattr__(attr: str):
    """``NineBall2PEnv``, ``SnookerEnv``, ...: a registered game's single-agent class (``single_class``)."""
    for name, spec in GAMES.items():
        if attr == f"{spec.id_stem}Env":
            return single_class(name)
    raise AttributeError(f"module {__name__!r} has no attribute {attr!r}")
