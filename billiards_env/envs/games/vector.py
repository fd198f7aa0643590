"""Batched self-play: a ``gymnasium.vector.VectorEnv`` of two-player games in
which each table's player to move acts."""
from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium.vector import AutoresetMode

from ...rules import DEFAULT_GAME, GAMES, get_game
from ..streams import seed_vector_env
from .batched import GameTables
from .spaces import OBSERVATION_DOC


class GameVectorEnv(GameTables):
    __doc__ = """``num_envs`` tables of one game (``game=``), self-play: on every table
    the player to move (observation entry 4*B + 1) plays the action of its
    row. One step is one shot (or one pass after a push-out) on every table,
    all shot with one batched simulator call.

    **Reward**: to the player who just played: +1 if the shot won the game,
    -1 if it lost it, else 0 (``info["rewards"]`` [N, 2] per player).
    **Episode**: one game; terminated when it is won or lost, truncated
    after ``max_shots`` shots (a draw). Autoreset: Gymnasium's next-step
    mode (the step after a game ends starts a new game on that table; its
    action is ignored; ``info["reset"]`` marks it).

    **Seeding**: ``reset(seed=s)`` seeds table k like a single game seeded
    with ``s + k`` (or pass a list of N seeds): the rack, the breaker (unless
    ``options["breaker"]`` names it: 0, 1 or an array [N]) and the shot
    noise of each table come from its own stream.

    **Info**: the shot record (``legal``, ``foul``: the foul's code,
    ``rules.records.FOUL_NAMES``, 0 none, where the one-player tasks'
    ``foul`` is a bool; ``turn_over``,
    ``game_over``, ``winner``, ``end``, ``push_out``, ``passed``,
    ``shooter``, ``respotted``, ``option``: 10-ball, the shot pocketed a
    ball illegally), ``pocketed``, ``first_contact``, ``called_pocket``,
    ``called_ball`` (10-ball; -1 none, 0 a safety), ``placement`` (where the cue ball was played from)
    and ``placement_moved`` (a ball-in-hand spot was illegal and moved),
    ``action_clipped``, ``n_events``, ``sim_time``, ``shot``; the next
    shooter's constraints as ``ball_in_hand``, ``targets``,
    ``push_out_allowed``, ``may_pass``, ``call_needed``, ``to_move``.
    """ + OBSERVATION_DOC

    metadata = {"render_modes": ["rgb_array"], "render_fps": 4, "autoreset_mode": AutoresetMode.NEXT_STEP}

    def __init__(self, num_envs: int = 1, game: str = DEFAULT_GAME, config=None, **overrides: Any):
        super().__init__(num_envs, game, config, overrides)

    def reset(self, *, seed=None, options: dict | None = None):
        seed_vector_env(self, self.core.streams, seed)
        idx, breaker = self._reset_rows(options)
        self.core.reset_tables(idx, breaker)
        self._autoreset_envs[idx] = False
        return self.core.observe(), self._constraint_info()

    def step(self, actions):
        if not self._seeded:
            raise RuntimeError("call reset() before step()")
        N = self.num_envs
        a = self.core.validate_actions(actions, N)
        done_prev = self._autoreset_envs
        act = np.nonzero(~done_prev)[0]
        reward = np.zeros(N)
        terminated = np.zeros(N, dtype=bool)
        truncated = np.zeros(N, dtype=bool)
        info: dict[str, Any] = {}
        if len(act):
            out = self.core.step(a[act], act)
            if len(act) == N:
                reward, terminated, truncated, info = out["reward"], out["terminated"], out["truncated"], out["info"]
            else:
                reward[act], terminated[act], truncated[act] = out["reward"], out["terminated"], out["truncated"]
                for k, v in out["info"].items():
                    full = np.zeros((N,) + np.shape(v)[1:], dtype=np.asarray(v).dtype)
                    if k in ("winner", "first_contact", "called_pocket", "called_ball"):
                        full[:] = -1
                    full[act] = v
                    info[k] = full
        rst = np.nonzero(done_prev)[0]
        if len(rst):
            self.core.reset_tables(rst)
        info["reset"] = done_prev.copy()
        shooter = info.get("shooter", np.zeros(N, dtype=np.int64))
        rewards = np.zeros((N, 2))
        rewards[np.arange(N), shooter] = reward
        rewards[np.arange(N), 1 - shooter] = -reward
        info["rewards"] = rewards
        info.update(self._constraint_info())
        self._autoreset_envs = terminated | truncated
        return self.core.observe(), reward, terminated, truncated, info


def game_vector(num_envs: int = 1, game: str = DEFAULT_GAME, opponent=None, **kwargs):
    """The vector entry point of a game id: the agent against ``opponent``
    (``versus.GameVersusVectorEnv``, the batched ``GameEnv``) when one is
    named, else self-play (``GameVectorEnv``)."""
    if opponent is not None:
        from .versus import GameVersusVectorEnv
        return GameVersusVectorEnv(num_envs, game=game, opponent=opponent, **kwargs)
    mode = kwargs.pop("autoreset_mode", AutoresetMode.NEXT_STEP)
    if mode not in ("next_step", AutoresetMode.NEXT_STEP):
        raise ValueError(f"self-play ({game}) autoresets in next_step mode only, got autoreset_mode={mode!r}; "
                         "name an opponent= for the agent-against-opponent env")
    return GameVectorEnv(num_envs, game=game, **kwargs)


_FUNCTIONS: dict = {}  # game -> (its spec, its vector entry point)


def vector_entry(name: str):
    """The vector entry point of a registered game, ``<name>_vector(num_envs, **kwargs)`` (``game_vector`` for
    it), made from its registry entry on first use."""
    spec = get_game(name)
    made = _FUNCTIONS.get(name)
    if made is None or made[0] is not spec:
        def vector(num_envs: int = 1, **kwargs):
            return game_vector(num_envs, spec.name, **kwargs)

        vector.__name__ = vector.__qualname__ = f"{spec.name}_vector"
        vector.__module__ = __name__
        vector.__doc__ = (f"The vector entry point of {spec.title}: self-play, or the agent against ``opponent=`` "
                          "(``game_vector``).")
        made = _FUNCTIONS[name] = (spec, vector)
    return made[1]


def __getattr__(attr: str):
    """``nine_ball_vector``, ``snooker_vector``, ...: a registered game's vector entry point (``vector_entry``)."""
    for name in GAMES:
        if attr == f"{name}_vector":
            return vector_entry(name)
    raise AttributeError(f"module {__name__!r} has no attribute {attr!r}")
