"""Policies for the two-player games (``billiards_env.envs.games``).

A game policy has ``act(obs, idx=None) -> actions [n, 8]`` for the tables
``idx`` (default: all) of the ``GameCore`` it is bound to (``core``), each
for that table's player to move. Geometric policies read the core's state
and constraints and turn ``Shots`` into actions with ``core.actions_for``.

- ``GameRandomPolicy``: uniform actions (placements and declarations
  included).
- ``GameGhostPolicy`` (``ghost``): the ghost-ball shot (``agents.geometry``,
  as kernels in ``agents.game_geometry``) on the easiest legal target and
  pocket; the seeded standard break; with ball in hand, the cue ball placed
  for a short straight-in shot on a legal target; after the opponent's
  push-out, it passes when it has no pot. When no pot is likely (every pot
  blocked or cut more than 70 deg) it hits the nearest legal target in
  sight full at 1.5 m/s (a legal contact that reaches a rail), or, with no
  legal target in sight, searches for a legal shot like a safety (8
  candidates); with
  ``safety=True`` (``ghost-safety``) it always plays a safety: ``safety_k``
  candidate soft shots at the legal targets simulated in one batched call,
  judged by the rules, keeping a legal one that leaves the opponent no
  straight line to any of their legal targets (else any legal one). On the
  8 it chooses the speed and draw of its pot in the simulator
  (``eight_ball_shot``); in 8-ball every other pot or full hit is first
  played in the simulator (no noise) and replaced by a searched legal shot
  if it would lose the game.
- ``GameSearchPolicy`` (``search<K>``): ``ghost-safety`` whose pots are
  chosen among K simulated candidates judged by the rules.
"""
from __future__ import annotations

import numpy as np

from billiards_env.physics.strike import Shots

from .game_ghost import GameGhostPolicy, native_game


class GameRandomPolicy:
    name = "random"

    def __init__(self, env, seed: int | None = 0):
        self.core = native_game(env)
        self.rng = np.random.default_rng(seed)

    def act(self, obs=None, idx=None) -> np.ndarray:
        n = self.core.n_envs if idx is None else len(idx)
        return self.rng.uniform(-1.0, 1.0, size=(n, 8)).astype(np.float32)


class GameSearchPolicy(GameGhostPolicy):
    """``GameGhostPolicy`` whose pots are searched: ``k`` candidate shots
    per table on the planned ball (``agents.baselines.SearchPolicy``'s
    candidates: every pocket's ghost-ball shot, then jittered aims, speeds
    and spins) simulated in one batched call and judged by the rules; it
    plays the best (a win, else a legal shot that keeps the table with the
    easiest next pot, else the ghost-ball plan), preferring candidates close
    to the nominal shots."""

    def __init__(self, env, seed: int = 0, k: int = 64):
        super().__init__(env, seed=seed, safety=True)
        from .baselines import SearchPolicy
        self.search = SearchPolicy(self.core, k=k, seed=seed)
        self.name = f"search{k}"

    def refine(self, idx, rows, pos, balls, phi, speed, a, b) -> None:
        if not len(rows):
            return
        core, K = self.core, self.search.k
        st = core.state.take(idx[rows])
        st.pos[:, 0], st.pocket[:, 0] = pos[rows, 0], -1
        cph, csp, ca, cb, close = self.search.candidates(st, balls)
        rep = np.repeat(rows, K)
        rec = self.judge(idx, pos, Shots(cph.ravel(), csp.ravel(), ca.ravel(), cb.ravel()), np.full(len(idx), -1), rep)
        win, loss = rec.winner == rec.shooter, rec.winner == 1 - rec.shooter
        res, nxt = self.last_judged
        keeps = rec.legal & ~rec.turn_over & ~rec.game_over
        follow = self.best_pots(res.state.pos, res.state.pocket < 0, nxt.targets)["cost"]  # the next pot's cost
        position = np.where(keeps & np.isfinite(follow), 2.0 - np.minimum(follow, 2.0), 0.0)
        score = (10.0 * win - 10.0 * loss + 3.0 * keeps + position).reshape(len(rows), K)
        score = score - 0.01 * close
        k = np.argmax(score, axis=1)
        ok = score[np.arange(len(rows)), k] > 1.0
        r, kk = rows[ok], k[ok]
        ar = np.nonzero(ok)[0]
        phi[r], speed[r], a[r], b[r] = cph[ar, kk], csp[ar, kk], ca[ar, kk], cb[ar, kk]


class GameModelPolicy:
    """A saved stable-baselines3 model (a run directory or a ``.zip``, with
    its normaliser statistics; ``SB3Policy.load``) trained on a game env,
    playing deterministically on the core's tables. A model trained against
    an opponent with the agent wrappers (``configs/ppo_games.yaml``) was
    always player 0 and chose its shots through ``game_view.GameView``: it
    plays through a view of this core and sees every table as player 0 saw
    it (the player-to-move entry set to 0; the group and foul entries are
    the shooter's already). A model of the env's own 8 action components
    plays on the raw observation."""

    def __init__(self, env, path, name: str | None = None):
        from .baselines import SB3Policy
        from .game_view import GameView
        self.core = native_game(env)
        self.inner = SB3Policy.load(path)
        self.viewed = self.inner.model.action_space.shape != (8,)
        if self.viewed:
            self.inner = self.inner.bind(GameView(self.core))
        self.name = name or f"model:{path}"

    def act(self, obs=None, idx=None) -> np.ndarray:
        o = self.core.observe()
        if self.viewed:
            o[:, 4 * self.core.n_balls + 1] = 0.0  # the player to move: the model always played as player 0
        a = np.asarray(self.inner.act(o), dtype=np.float32)
        if a.shape[1] != 8:
            raise ValueError(f"{self.name}: the model gives {a.shape[1]} action components, a game needs 8")
        return a if idx is None else a[np.asarray(idx)]


POLICIES = ("random", "ghost", "ghost-safety", "search<K>", "<path to a saved model>")


def make_game_policy(name: str, env, seed: int = 0):
    """A game policy by name: ``random``, ``ghost`` (rule-aware ghost-ball,
    geometry only), ``ghost-safety`` (the same with simulated safeties),
    ``search<K>`` (searched pots, K candidates, default 64, and safeties),
    or the path of a saved stable-baselines3 model (``GameModelPolicy``)."""
    if name == "random":
        return GameRandomPolicy(env, seed=seed)
    if name == "ghost":
        return GameGhostPolicy(env, seed=seed)
    if name == "ghost-safety":
        return GameGhostPolicy(env, seed=seed, safety=True)
    if name.startswith("search") and name[6:].isdigit() or name == "search":
        return GameSearchPolicy(env, seed=seed, k=int(name[6:]) if name[6:] else 64)
    from pathlib import Path
    if Path(name).exists():
        return GameModelPolicy(env, name)
    raise ValueError(f"unknown game policy {name!r}; choose one of {POLICIES}")
