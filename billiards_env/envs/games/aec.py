"""PettingZoo AEC environments of the two-player games (``pettingzoo`` is
an optional dependency: the ``games`` extra)."""
from __future__ import annotations

from typing import Any

import numpy as np
from pettingzoo import AECEnv

from ...rules import DEFAULT_GAME, GAMES, get_game
from .core import GameCore
from .spaces import OBSERVATION_DOC, action_space, game_doc, info_row, make_config, observation_space

AGENTS = ("player_0", "player_1")


class GameAECEnv(AECEnv):
    __doc__ = """A two-player game on one table as a PettingZoo AEC environment:
    agents ``player_0`` and ``player_1``; ``agent_selection`` is the player
    to move as the rules say (a player who pockets a ball legally shoots
    again, so turns do not simply alternate). Both agents observe the same
    table (the observation says whose turn it is). Rewards: +1 to the
    winner and -1 to the loser when the game ends; a game cut at
    ``max_shots`` shots is a draw (truncated). ``infos[agent]`` holds the
    last shot's record (see ``GameVectorEnv``). ``reset(seed=s)`` seeds the
    table like the vector env's table seeded with ``s``; ``options=
    {"breaker": 0 or 1}`` fixes who breaks.
    """ + OBSERVATION_DOC

    metadata = {"render_modes": [], "name": "billiards_game_v0", "is_parallelizable": False}
    render_mode = None  # no render modes (PettingZoo's wrappers read the attribute)
    game = DEFAULT_GAME

    def __init__(self, config=None, **overrides: Any):
        super().__init__()
        self.config = make_config(config, overrides, self.game)
        self.core = GameCore(self.config, 1)
        self.possible_agents = list(AGENTS)
        self.agents = list(AGENTS)
        obs, act = observation_space(self.core), action_space(self.core)
        self.observation_spaces = {a: obs for a in AGENTS}
        self.action_spaces = {a: act for a in AGENTS}
        self._seeded = False

    def observation_space(self, agent):
        return self.observation_spaces[agent]

    def action_space(self, agent):
        return self.action_spaces[agent]

    def observe(self, agent):
        return self._obs.copy()

    def reset(self, seed=None, options=None):
        if seed is not None:
            self.core.streams.seed([0], [seed])
        elif not self._seeded:
            self.core.streams.seed([0], [int(np.random.default_rng().integers(2 ** 63))])
        self._seeded = True
        breaker = (options or {}).get("breaker")
        self.core.reset_tables([0], None if breaker is None else [int(breaker)])
        self.agents = list(AGENTS)
        self.rewards = {a: 0.0 for a in AGENTS}
        self._cumulative_rewards = {a: 0.0 for a in AGENTS}
        self.terminations = {a: False for a in AGENTS}
        self.truncations = {a: False for a in AGENTS}
        self.infos = {a: {} for a in AGENTS}
        self._obs = self.core.observe()[0]
        self.agent_selection = AGENTS[int(self.core.constraints().shooter[0])]

    def step(self, action):
        agent = self.agent_selection
        if self.terminations[agent] or self.truncations[agent]:
            return self._was_dead_step(action)
        d = self.core.action_dim
        if np.shape(action) != (d,):
            raise ValueError(f"action must have shape ({d},), got {np.shape(action)}")
        self._cumulative_rewards[agent] = 0.0
        out = self.core.step(self.core.validate_actions(np.reshape(action, (1, d)), 1), [0])
        info = info_row(out["info"], 0)
        self.rewards = {a: 0.0 for a in AGENTS}
        winner = int(out["record"].winner[0])
        if winner >= 0:
            self.rewards[AGENTS[winner]] = 1.0
            self.rewards[AGENTS[1 - winner]] = -1.0
        if out["terminated"][0]:
            self.terminations = {a: True for a in AGENTS}
        elif out["truncated"][0]:
            self.truncations = {a: True for a in AGENTS}
        self.infos = {a: dict(info) for a in AGENTS}
        self._obs = self.core.observe()[0]
        if not (out["terminated"][0] or out["truncated"][0]):
            self.agent_selection = AGENTS[int(self.core.constraints().shooter[0])]
        self._accumulate_rewards()

    # --- bots (docs/bots.md) ---------------------------------------------------
    def bot_view(self):
        """The ``GameView`` of the table for the agent to move (``agent_selection``)."""
        return self.core.view([0])

    def bot_action(self, plan) -> np.ndarray:
        """The action [action_dim] that plays a bot's ``ShotPlan`` (one row) here."""
        return self.core.actions_of(plan, [0])[0].astype(np.float32)

    def render(self):
        return None

    def close(self):
        pass


_CLASSES: dict = {}  # game -> (its spec, its generated AEC class)


def aec_class(name: str) -> type:
    """The PettingZoo AEC class of a registered game, ``<class_prefix>AECEnv``, generated from its registry
    entry on first use."""
    spec = get_game(name)
    made = _CLASSES.get(name)
    if made is None or made[0] is not spec:
        cls = type(f"{spec.class_prefix}AECEnv", (GameAECEnv,), {
            "game": spec.name, "__module__": __name__,
            "metadata": {**GameAECEnv.metadata, "name": f"billiards_{spec.name}_v0"},
            "__doc__": game_doc(spec, "for two agents", GameAECEnv.__doc__)})
        made = _CLASSES[name] = (spec, cls)
    return made[1]


def __getattr__(attr: str):
    """``NineBallAECEnv``, ``SnookerAECEnv``, ...: a registered game's AEC class (``aec_class``)."""
    for name, spec in GAMES.items():
        if attr == f"{spec.class_prefix}AECEnv":
            return aec_class(name)
    raise AttributeError(f"module {__name__!r} has no attribute {attr!r}")
