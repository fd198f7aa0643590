"""The agent against a fixed opponent on many tables at once: a
``gymnasium.vector.VectorEnv`` whose every table is ``GameEnv``'s game.

``opponent_turns`` and ``new_games`` are the loops both envs use: the
opponent shoots on every table where it is to move, all tables in one
batched call per round, until the agent is to move again or the game is
over; a new game the opponent ends first is replaced by the next rack.
"""
from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium.vector import AutoresetMode

from ..billiards import _autoreset_mode
from ..streams import seed_vector_env
from .batched import GameTables
from ...bots import BOT_NAMES, is_bot_name, make_bot
from ...rules import DEFAULT_GAME
from .core import GameCore
from .play import bot_actions
from .spaces import OBSERVATION_DOC

AGENT = 0  # the agent's player number on every table; the opponent is 1 - AGENT


def make_opponent(spec, seed: int):
    """The opponent bot of ``spec``: a bot name or ``module:factory``
    (``bots.make_bot``), or a bot (an object with ``act(view) -> ShotPlan``,
    docs/bots.md)."""
    return make_bot(spec, seed=seed)


def check_opponent(spec) -> None:
    """Raise a clear error now (at the env's construction) for an opponent that is no bot."""
    if not (hasattr(spec, "act") or is_bot_name(spec)):
        raise ValueError(f"opponent must be a bot name ({', '.join(BOT_NAMES)}) or an object with "
                         f"act(view) -> ShotPlan (docs/bots.md), got {spec!r}")


def opponent_turns(core: GameCore, opponent, idx) -> dict:
    """Let ``opponent`` shoot on tables ``idx`` until the agent is to move or
    the game ends; every round shoots all those tables in one call. Returns
    arrays [n]: ``reward`` (to the agent: +1 the opponent lost, -1 it won),
    ``terminated``, ``truncated`` and ``shots`` (the opponent's)."""
    idx = np.asarray(idx, dtype=np.int64)
    n = len(idx)
    reward, shots = np.zeros(n), np.zeros(n, dtype=np.int64)
    terminated, truncated = np.zeros(n, dtype=bool), np.zeros(n, dtype=bool)
    live = np.ones(n, dtype=bool)
    while True:
        rows = np.nonzero(live)[0]
        rows = rows[core.constraints().shooter[idx[rows]] != AGENT]
        if not len(rows):
            return dict(reward=reward, terminated=terminated, truncated=truncated, shots=shots)
        t = idx[rows]
        out = core.step(bot_actions(core, opponent, t), t)
        shots[rows] += 1
        terminated[rows], truncated[rows] = out["terminated"], out["truncated"]
        reward[rows] = 0.0 - out["reward"]  # (not -x: no -0.0 rewards)
        live[rows] = ~(out["terminated"] | out["truncated"])


def new_games(core: GameCore, opponent, idx, breaker=None) -> tuple[np.ndarray, np.ndarray]:
    """New games on tables ``idx`` (``breaker`` [n] or None: drawn), each
    played up to the agent's first shot; a game the opponent ends first is
    replaced by the next rack. Returns arrays [n]: the games skipped and the
    opponent's shots in the game that stands."""
    idx = np.asarray(idx, dtype=np.int64)
    skipped, shots = np.zeros(len(idx), dtype=np.int64), np.zeros(len(idx), dtype=np.int64)
    rows = np.arange(len(idx))
    while len(rows):
        core.reset_tables(idx[rows], None if breaker is None else np.asarray(breaker)[rows])
        out = opponent_turns(core, opponent, idx[rows])
        shots[rows] = out["shots"]
        ended = out["terminated"] | out["truncated"]
        skipped[rows[ended]] += 1
        rows = rows[ended]
    return skipped, shots


class GameVersusVectorEnv(GameTables):
    __doc__ = """``num_envs`` tables of ``game``, on each the agent is player 0
    and ``opponent`` (a bot: a name of ``bots.make_bot``,
    default ``"ghost"``, a ``module:factory`` or a bot object; docs/bots.md) player 1: the
    batched ``GameEnv`` (``gymnasium.make_vec(id, num_envs,
    vectorization_mode="vector_entry_point", opponent=...)``). A step plays
    the agent's shot on every table in one simulator call, then the
    opponent's shots (one call per round over the tables where it is to
    move) until the agent is to move again, so every observation is one the
    agent acts on. A game the opponent ends before the agent's first shot is
    replaced by the next rack (``info["skipped_games"]``).

    **Reward**: +1 when the agent wins, -1 when it loses, else 0 (a game
    cut at ``max_shots`` shots is a draw, truncated). **Seeding**:
    ``reset(seed=s)`` seeds table k like ``GameEnv`` seeded with ``s + k``
    (rack, breaker, shot noise) and reseeds the opponent with
    ``opponent_seed + s``; the opponents' own random choices (break
    variation, safeties) come from one generator over the batch.
    **Autoreset**: ``next_step`` (default) or ``same_step`` (the new game
    starts within the step; the final observation is in
    ``info["final_obs"]``), as the one-player vector envs.

    **Info** (per table): the agent's shot record (see ``GameVectorEnv``);
    ``success`` (the agent won the game that just ended), ``scratch`` (the
    agent's shot pocketed the cue ball), ``balls_pocketed`` (object balls
    its shot pocketed), ``opponent_shots`` (the opponent's shots since),
    ``winner``, ``final_score`` [N, 2] (the game's score, agent first, on
    the step it ended; zeros otherwise: ``score`` is the agent's own shot's,
    before the opponent replied), and the agent's next constraints (``to_move``, always 0,
    ``ball_in_hand``, ``targets``, ``push_out_allowed``, ``may_pass``,
    ``call_needed``).
    """ + OBSERVATION_DOC

    metadata = {"render_modes": ["rgb_array"], "render_fps": 4, "autoreset_mode": AutoresetMode.NEXT_STEP}

    def __init__(self, num_envs: int = 1, game: str = DEFAULT_GAME, opponent="ghost", opponent_seed: int = 0,
                 config=None, autoreset_mode: str | AutoresetMode = AutoresetMode.NEXT_STEP, **overrides: Any):
        mode = _autoreset_mode(autoreset_mode)
        if mode == AutoresetMode.DISABLED:
            raise ValueError("autoreset_mode must be 'next_step' or 'same_step' for a game against an opponent")
        self.metadata = {**type(self).metadata, "autoreset_mode": mode}
        super().__init__(num_envs, game, config, overrides)
        check_opponent(opponent)
        self._opponent_spec, self._opponent_seed = opponent, int(opponent_seed)
        self.opponent = None

    def reset(self, *, seed=None, options: dict | None = None):
        N = self.num_envs
        seed_vector_env(self, self.core.streams, seed)
        if self.opponent is None or seed is not None:  # a seeded reset reseeds the opponent too
            first = seed[0] if isinstance(seed, (list, tuple, np.ndarray)) else seed
            self.opponent = make_opponent(self._opponent_spec, self._opponent_seed + int(first or 0))
        idx, breaker = self._reset_rows(options)
        skipped = np.zeros(N, dtype=np.int64)
        skipped[idx] = new_games(self.core, self.opponent, idx, breaker)[0]
        self._autoreset_envs[idx] = False
        return self.core.observe(), self._constraint_info({"skipped_games": skipped})

    def step(self, actions):
        if not self._seeded:
            raise RuntimeError("call reset() before step()")
        N, B = self.num_envs, self.core.n_balls
        a = self.core.validate_actions(actions, N)
        mode = self.metadata["autoreset_mode"]
        done_prev = self._autoreset_envs
        act = np.nonzero(~done_prev)[0]
        reward = np.zeros(N)
        terminated, truncated = np.zeros(N, dtype=bool), np.zeros(N, dtype=bool)
        info: dict[str, Any] = {}
        opp_shots = np.zeros(N, dtype=np.int64)
        if len(act):
            out = self.core.step(a[act], act)
            for k, v in out["info"].items():
                v = np.asarray(v)
                full = np.full((N,) + v.shape[1:],
                               -1 if k in ("winner", "first_contact", "called_pocket", "called_ball") else 0,
                               dtype=v.dtype)
                full[act] = v
                info[k] = full
            reward[act], terminated[act], truncated[act] = out["reward"], out["terminated"], out["truncated"]
            go = act[~(out["terminated"] | out["truncated"])]
            if len(go):
                opp = opponent_turns(self.core, self.opponent, go)
                reward[go], terminated[go], truncated[go] = opp["reward"], opp["terminated"], opp["truncated"]
                opp_shots[go] = opp["shots"]
        else:
            info = {k: np.zeros(N, dtype=bool) for k in ("foul", "legal")}
            info["pocketed"] = np.zeros((N, B), dtype=bool)
        pk = info["pocketed"]
        info["scratch"] = pk[:, 0].copy()
        info["balls_pocketed"] = pk[:, 1:].sum(axis=1)
        info["opponent_shots"] = opp_shots
        info["winner"] = np.where(terminated, self.core.game.winner, -1)
        info["success"] = terminated & (self.core.game.winner == AGENT)
        done = terminated | truncated
        # the game's final score [agent, opponent] where it ended (``score`` is the agent's shot's, before the
        # opponent's replies): points in games to a score (zeros in the pool games, where ``winner`` is the result)
        info["final_score"] = np.where(done[:, None], self.core.game.score, 0)
        info["skipped_games"] = np.zeros(N, dtype=np.int64)
        if mode == AutoresetMode.NEXT_STEP:
            rst = np.nonzero(done_prev)[0]
            info["reset"] = done_prev.copy()
            if len(rst):
                info["skipped_games"][rst] = new_games(self.core, self.opponent, rst)[0]
            self._autoreset_envs = done
            obs = self.core.observe()
        else:
            obs = self.core.observe()
            if done.any():
                fin = np.nonzero(done)[0]
                info["final_obs"] = obs.copy()
                info["_final_obs"] = done.copy()
                info["skipped_games"][fin] = new_games(self.core, self.opponent, fin)[0]
                obs = self.core.observe()
            self._autoreset_envs = np.zeros(N, dtype=bool)
        return obs, reward, terminated, truncated, self._constraint_info(info)
