"""The one-player tasks' baseline bots (``random``, ``ghost``, ``search<K>``).

A one-player bot acts like a game bot, on a read-only ``TaskView``
(``contract.view``: float64 positions, the legal target, the equipment, the
noise and the task's rules) and returns a ``ShotPlan`` (only its shots
matter here) or the env's actions [n, 4]. The env turns a plan into its
actions with its own inverse mapping (``actions_of``), so a bot works with
every aim mode. ``BotPolicy`` gives a bot the ``act(obs) -> actions``
interface the evaluation harness, the training's baselines and the SB3 and
RLlib adapters call: it asks the env for its view first.

- ``RandomPolicy``: uniform actions.
- ``GhostBallPolicy``: ghost-ball aim at the easiest pocket (``bots.geometry``)
  and a speed from the distances.
- ``SearchPolicy``: K candidate shots per table (ghost-ball aims for every
  pocket, jittered, at various speeds and spins) played on K copies of
  each table through the bots' preview path (``preview.play_shots``, one
  batched simulator call per chunk); plays the best. An upper reference (it uses the simulator as a perfect model).
"""
from __future__ import annotations

import dataclasses
import math
from typing import Protocol

import numpy as np

from ..contract.unwrap import env_chain
from ..physics import BallState
from ..physics.strike import Shots, draw_to_speed
from . import geometry as G
from ..contract.plan import ShotPlan
from ..contract.preview import play_shots, rest_state


class Policy(Protocol):
    name: str

    def act(self, obs: np.ndarray) -> np.ndarray: ...


def task_env(env):
    """The native one-player vector env (or core) under wrappers: the first
    env of ``contract.unwrap.env_chain(env)`` that has ``view()`` and ``actions_of()``."""
    for e in env_chain(env):
        if hasattr(e, "view") and hasattr(e, "actions_of"):
            return e
    raise TypeError("a bot needs a billiards env that hands views (view() and actions_of())")


class BotPolicy:
    """A bot behind ``act(obs) -> actions``: each call asks the native env
    (``task_env(env)``) for its ``view()``, lets the bot act on it and maps
    the plan with the env's ``actions_of``."""

    def __init__(self, bot, env):
        self.bot, self.env = bot, task_env(env)
        self.name = bot.name

    def act(self, obs=None) -> np.ndarray:
        return self.env.actions_of(self.bot.act(self.env.view()))


class RandomPolicy:
    name = "random"

    def __init__(self, seed: int | None = 0, action_dim: int = 4):
        self.rng = np.random.default_rng(seed)
        self.action_dim = action_dim

    def act(self, view) -> np.ndarray:
        """Uniform actions [n, action_dim] (``view``: a view, or observations [n, ...])."""
        n = view.n if hasattr(view, "n") else view.shape[0]
        return self.rng.uniform(-1.0, 1.0, size=(n, self.action_dim)).astype(np.float32)


class GhostBallPolicy:
    """Aim the cue ball at the ghost ball of the easiest pocket.

    Pocket choice: smallest ``cut + dist_weight * (d_cg + d_op)`` among
    pockets whose paths are not blocked by another ball and which the object
    ball approaches at most 60 deg (corner) / 50 deg (side) off the pocket's
    axis. Speed: ``geometry.required_speed`` (rolling resistance mu_r, cut
    transfer cos(theta)(1 + e_b)/2, slide losses) times ``margin``; a centre
    ball hit (stun) so that on straight shots the cue ball stops.
    """

    name = "ghost"

    def __init__(self, b: float = 0.0, margin: float = 1.0, dist_weight: float = 0.5, inset: float = 0.0):
        self.b, self.margin, self.dist_weight, self.inset = b, margin, dist_weight, inset

    def act(self, view) -> ShotPlan:
        return ShotPlan.of(G.ghost_ball_shot(view.pos, view.on_table, view.target, view.table, view.params, b=self.b,
                                             margin=self.margin, dist_weight=self.dist_weight, inset=self.inset))


def candidate_success(view, start: BallState, shots: Shots, target: np.ndarray) -> np.ndarray:
    """Success of each candidate shot (one per table of ``start``), played
    through the bots' one strike-and-simulate path (``preview.play_shots``,
    no noise): first contact with its ``target`` ball, that ball pocketed,
    the cue ball not."""
    res = play_shots(view, start, shots)
    before = start.pocket >= 0
    after = res.state.pocket >= 0
    newly = after & ~before
    legal_first = res.first_contact == target
    cue_safe = ~after[:, 0]
    potted_target = newly[np.arange(len(target)), target]
    return legal_first & cue_safe & potted_target


class SearchPolicy:
    """Try ``k`` candidate shots per table in the batched simulator; play the best.

    Candidates (per table): the ghost-ball shot of every pocket at the
    nominal speed, then random perturbations of them: aim jitter
    N(0, ``aim_jitter_deg``), speed x log-uniform [0.6, 2.2], side a and
    height b uniform in a disc of radius 0.35 R. Score: success (first
    contact with the legal ball, an object ball pocketed, cue ball not
    pocketed) + a small bonus for shots close to the nominal ghost-ball shot
    (they are more robust to execution noise).
    """

    name = "search"

    def __init__(self, k: int = 256, seed: int = 0, aim_jitter_deg: float = 1.5, chunk: int = 65536,
                 map_chunks=None):
        self.k = int(k)
        self.rng = np.random.default_rng(seed)
        self.aim_jitter = math.radians(aim_jitter_deg)
        self.chunk = chunk
        # map_chunks(fn, list of argument tuples) -> list of results, in order;
        # the default runs them here, agents.rllib.evaluation on Ray workers
        self.map_chunks = map_chunks or (lambda fn, args: [fn(*a) for a in args])
        self.name = f"search{self.k}"

    def candidates(self, view, state: BallState, target: np.ndarray):
        """K candidates per table of ``state`` (the view gives the table,
        physics and the env's slowest shot, ``min_draw``): arrays [E, K] of
        aim, speed, side, height and closeness to the nominal shot."""
        table, params = view.table, view.params
        E, K = state.n_envs, self.k
        sh = G.ghost_shots(state.pos, state.on_table, target, table, params, 0.0)
        P = sh["phi"].shape[1]
        # pockets ranked by the ghost-ball cost; candidates favour the easy ones
        cost = np.where(sh["valid"], G.pot_cost(sh, 0.5), np.inf)
        order = np.argsort(cost, axis=1)                       # [E, P]
        n_valid = np.maximum(np.isfinite(cost).sum(axis=1), 1)
        # pocket rank for each candidate: first P candidates cover every pocket
        # once (nominal shot), the rest sample ranks with weights 1/(rank+1)
        ranks = np.empty((E, K), dtype=np.int64)
        ranks[:, :min(P, K)] = np.arange(min(P, K))[None]
        if K > P:
            w = 1.0 / (np.arange(P) + 1.0)
            u = self.rng.random((E, K - P))
            # restrict to the valid pockets of each table
            wv = np.where(np.arange(P)[None] < n_valid[:, None], w[None], 0.0)
            cdf = np.cumsum(wv, axis=1) / wv.sum(axis=1, keepdims=True)
            ranks[:, P:] = (u[..., None] > cdf[:, None, :]).sum(axis=2)
        ranks = np.minimum(ranks, P - 1)
        pk = np.take_along_axis(order, ranks, axis=1)          # [E, K]
        take = lambda a: np.take_along_axis(a, pk, axis=1)     # noqa: E731
        phi0, cut, d_cg, d_op = take(sh["phi"]), take(sh["cut"]), take(sh["d_cg"]), take(sh["d_op"])
        v0 = G.required_speed(d_cg, d_op, cut, params, b=0.0, margin=1.0)
        nominal = np.zeros((E, K), dtype=bool)
        nominal[:, :min(P, K)] = True
        dphi = np.where(nominal, 0.0, self.rng.normal(0.0, self.aim_jitter, (E, K)))
        smul = np.where(nominal, 1.0, np.exp(self.rng.uniform(math.log(0.6), math.log(2.2), (E, K))))
        r = 0.35 * np.sqrt(self.rng.random((E, K)))
        th = self.rng.uniform(0, 2 * math.pi, (E, K))
        a = np.where(nominal, 0.0, r * np.cos(th))
        b = np.where(nominal, 0.0, r * np.sin(th))
        speed = np.clip(v0 * smul, 0.05, params.max_speed)
        # keep speeds the env can express (its draw range)
        lo = view.min_draw
        speed = np.maximum(speed, draw_to_speed(lo, params))
        closeness = np.abs(dphi) / self.aim_jitter + np.abs(np.log(smul)) + (a ** 2 + b ** 2)
        return phi0 + dphi, speed, a, b, closeness

    def evaluate(self, view, state: BallState, target: np.ndarray, shots) -> np.ndarray:
        """Success [E, K] of each candidate (``shots``: aims, speeds, sides,
        heights [E, K]) on K copies of each table, in chunks of ``chunk``
        candidates (each one ``candidate_success`` call; ``map_chunks`` may
        run them elsewhere, so the chunks carry the view without its
        observation callback)."""
        E, K = shots[0].shape
        rep = np.repeat(np.arange(E), K)
        big = state.take(rep)
        flat = [np.ravel(v) for v in shots]
        lean = dataclasses.replace(view, _observe=None)
        args = []
        for s0 in range(0, E * K, self.chunk):
            sl = slice(s0, min(E * K, s0 + self.chunk))
            sub = BallState(big.pos[sl], big.vel[sl], big.omega[sl], big.pocket[sl])
            args.append((lean, sub, Shots(*(v[sl] for v in flat)), target[rep[sl]]))
        return np.concatenate(self.map_chunks(candidate_success, args)).reshape(E, K)

    def shots(self, view, state: BallState, target: np.ndarray):
        phi, speed, a, b, closeness = self.candidates(view, state, target)
        ok = self.evaluate(view, state, target, (phi, speed, a, b))
        score = ok.astype(np.float64) * 10.0 - 0.01 * closeness
        best = np.argmax(score, axis=1)
        ar = np.arange(state.n_envs)
        self.last_found = ok.any(axis=1)
        return Shots(phi[ar, best], speed[ar, best], a[ar, best], b[ar, best])

    def act(self, view) -> ShotPlan:
        return ShotPlan.of(self.shots(view, rest_state(view), np.asarray(view.target, dtype=np.int64)))
