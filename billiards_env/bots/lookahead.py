"""``lookahead``: a search baseline that plays position.

For every table (all tables at once, in batched ``physics.simulate`` calls):

1. **Candidates.** ``k`` first shots from ``SearchPolicy.candidates`` (the
   ghost-ball shot of every pocket, then jittered aims, speeds from 0.6 to
   2.2 times the ghost-ball speed, side and height spin), simulated once
   without noise and ``n_noise`` times with sampled execution noise
   (``noise``, default the ``tournament`` preset).
2. **Rules.** Each outcome is judged by the env's own task (``Task.judge``):
   a win scores 1, a shot that ends the episode otherwise scores 0, a shot
   that pockets a ball and keeps the table scores the value of its leave, a
   legal shot that pockets nothing (the free miss of single-player 9-ball)
   ``miss_weight`` times that value.
3. **Leave.** For the ``m`` candidates that are most often successful under
   noise, the leave is where the balls stop after the noise-free shot; its
   value is the success probability of the best next shot, estimated from
   ``n_noise_next`` noisy samples of each next candidate (the ghost-ball
   shot of every pocket at ``next_speeds`` times the ghost-ball speed).
4. **Choice.** Score = (success rate of the shot under noise) x (value of
   its leave); candidates that fail without noise score 0. The best is
   played; without any success the easiest pocket's ghost-ball shot is.

Noise is always sampled, whatever the env's own noise, because a leave
whose next shot works only when struck perfectly is a bad leave.
The cost per decision is ``k (1 + n_noise) + m P len(next_speeds)
n_noise_next`` simulated shots per table (P pockets).
"""
from __future__ import annotations


import numpy as np

from ..physics import BallState
from ..physics.noise import NoiseConfig
from ..physics.strike import Shots
from . import geometry as G
from .one_player import SearchPolicy
from ..contract.plan import ShotPlan
from ..contract.preview import rest_state

# a score this small still beats "no candidate works"; it orders the fallbacks
# by the search's closeness to the ghost-ball shot
_FALLBACK_WEIGHT = 1e-3
# the value of a pot that leaves no next shot, relative to a leave that
# always gives one: small, so any leave with a shot wins, but above a failure
_LEAVELESS = 0.01


class LookaheadPolicy:
    """Pots that leave a next shot (see the module docstring)."""

    name = "lookahead"

    def __init__(self, k: int = 48, m: int = 6, n_noise: int = 6, n_noise_next: int = 6,
                 next_speeds: tuple = (1.0, 1.5), noise="tournament", miss_weight: float = 0.5,
                 seed: int = 0, chunk: int = 65536):
        self.search = SearchPolicy(k=k, seed=seed, chunk=chunk)
        self.k, self.m, self.n_noise, self.n_noise_next = int(k), int(m), int(n_noise), int(n_noise_next)
        self.next_speeds = tuple(float(s) for s in next_speeds)
        self.noise = NoiseConfig.from_any(noise)
        self.miss_weight = float(miss_weight)
        self.rng = np.random.default_rng(seed)
        self.sims = 0   # shots simulated so far (cost accounting)

    # -- simulation and rules -------------------------------------------------
    def play(self, view, start: BallState, shots, noise=None):
        """Preview one shot on each table of ``start`` (at rest; ``noise``: a
        ``NoiseConfig`` drawn from this bot's generator, or None); returns the
        end states (at rest) and the value class of each outcome: +1 win,
        0 keeps the table with a ball pocketed, -1 a legal miss that keeps the
        table, -2 the episode ends without a win."""
        n = start.n_envs
        pv = view.preview(ShotPlan.of(Shots.of_arrays(*shots)), noise=noise, rng=self.rng, start=start)
        self.sims += n
        j, shot = pv.judged, pv.outcome
        cls = np.where(j.success, 1, np.where(j.terminated, -2, np.where(shot.n_pocketed > 0, 0, -1)))
        end = BallState(pv.pos, np.zeros_like(start.vel), np.zeros_like(start.omega), pv.pocket)
        return end, cls

    def _noisy_success(self, view, start: BallState, shots, n_samples: int) -> np.ndarray:
        """Fraction of ``n_samples`` noisy executions of each shot that win or
        keep the table with a ball pocketed (all tables x samples in one call)."""
        if n_samples == 0:
            return np.ones(start.n_envs)
        n = start.n_envs
        rep = np.tile(np.arange(n), n_samples)
        phi, speed, a, b = shots
        _, cls = self.play(view, start.take(rep), (phi[rep], speed[rep], a[rep], b[rep]), self.noise)
        return (cls >= 0).reshape(n_samples, n).mean(axis=0)

    # -- leave ---------------------------------------------------------------
    def leave_value(self, view, state: BallState) -> np.ndarray:
        """Success probability of the best next shot from each table of
        ``state`` (balls at rest), under sampled noise; 0 with no target."""
        env = view
        n = state.n_envs
        target = view.rules.legal_target(state.pos, state.pocket)
        has = target > 0
        tgt = np.where(has, target, 1)
        sh = G.ghost_shots(state.pos, state.pocket < 0, tgt, env.table, env.params, 0.0)
        P = sh["phi"].shape[1]
        v0 = G.required_speed(sh["d_cg"], sh["d_op"], sh["cut"], env.params, b=0.0, margin=1.0)
        S = len(self.next_speeds)
        phi = np.repeat(sh["phi"][:, None], S, axis=1).reshape(n, -1)          # [n, S*P]
        speed = (np.asarray(self.next_speeds)[None, :, None] * v0[:, None]).reshape(n, -1)
        speed = np.clip(speed, 0.05, env.params.max_speed)
        valid = np.repeat(sh["valid"][:, None], S, axis=1).reshape(n, -1)
        C = S * P
        rep = np.repeat(np.arange(n), C)
        zeros = np.zeros(n * C)
        p = self._noisy_success(view, state.take(rep), (phi.ravel(), speed.ravel(), zeros, zeros), self.n_noise_next)
        p = np.where(valid.ravel(), p, 0.0).reshape(n, C)
        return np.where(has, p.max(axis=1), 0.0)

    # -- decision ------------------------------------------------------------
    def shots(self, view, state: BallState, target: np.ndarray) -> Shots:
        E = state.n_envs
        start = BallState(state.pos.copy(), np.zeros_like(state.vel), np.zeros_like(state.omega),
                          state.pocket.copy())
        phi, speed, a, b, closeness = self.search.candidates(view, start, np.where(target > 0, target, 1))
        K = phi.shape[1]
        rep = np.repeat(np.arange(E), K)
        big = start.take(rep)
        cands = (phi.ravel(), speed.ravel(), a.ravel(), b.ravel())
        end, cls = self.play(view, big, cands)
        cls = cls.reshape(E, K)
        p_noisy = self._noisy_success(view, big, cands, self.n_noise).reshape(E, K)
        works = cls > -2
        pre = np.where(works, p_noisy + (cls == 1), -1.0) - _FALLBACK_WEIGHT * closeness
        # leaves of the m most promising candidates that keep the table
        m = min(self.m, K)
        top = np.argsort(-pre, axis=1)[:, :m]                                   # [E, m]
        top_cls = np.take_along_axis(cls, top, axis=1)
        need = (top_cls == 0) | (top_cls == -1)
        value = np.where(top_cls == 1, 1.0, 0.0)
        if need.any():
            e_idx, j_idx = np.nonzero(need)
            flat = e_idx * K + top[e_idx, j_idx]
            v = self.leave_value(view, end.take(flat))
            value[e_idx, j_idx] = np.where(top_cls[e_idx, j_idx] == -1, self.miss_weight * v, v)
        p_top = np.take_along_axis(p_noisy, top, axis=1)
        # a pot with no leave still beats a shot that fails (value + _LEAVELESS)
        score = np.where(np.take_along_axis(works, top, axis=1), p_top * (value + _LEAVELESS), -1.0)
        score = score - _FALLBACK_WEIGHT * 1e-3 * np.take_along_axis(closeness, top, axis=1)
        best = top[np.arange(E), np.argmax(score, axis=1)]
        ar = np.arange(E)
        self.last_scores = score
        return Shots(phi[ar, best], speed[ar, best], a[ar, best], b[ar, best])

    def act(self, view) -> ShotPlan:
        return ShotPlan.of(self.shots(view, rest_state(view), np.asarray(view.target, dtype=np.int64)))
