"""Seeded matches between game policies, and ratings.

``play_pairing`` plays ``n_racks`` racks twice between two policies, once
with each breaking, on one ``GameCore`` of 2 * n_racks tables: table k and
table n_racks + k share their seed, so both sides meet the same racks (and,
with ``variable`` noise, the same noise factor). Each step shoots every live
table once with one simulator call; each policy acts only on the tables
where its player is to move.

``tournament`` plays every pairing of the entrants and fits a
Bradley-Terry model (ratings on the Elo scale, 95% intervals by bootstrap
over games); ``wilson`` gives a win rate's 95% interval. A draw (a game cut
at the shot cap) counts half a win.
"""
from __future__ import annotations

import dataclasses
import itertools
import math

import numpy as np

from billiards_env.envs.games import GameConfig, GameCore

from .game_policies import make_game_policy

Z95 = 1.959963984540054   # two-sided 95% normal quantile
ELO = 400.0 / math.log(10.0)  # Elo points per unit of log-strength
BT_ITERATIONS = 500           # minorisation-maximisation steps of the Bradley-Terry fit (converged well before)
BT_PRIOR = 0.5                # virtual games won and lost by each entrant against a mean entrant (keeps
                              # ratings finite when an entrant wins or loses every game)


@dataclasses.dataclass
class PairingResult:
    a: str
    b: str
    game: str
    noise: str
    winner: np.ndarray    # [2n] 0: a won, 1: b won, -1: draw
    a_broke: np.ndarray   # [2n] bool
    shots: np.ndarray     # [2n] shots in the game

    @property
    def score_a(self) -> float:
        """a's points: wins plus half the draws."""
        return float((self.winner == 0).sum() + 0.5 * (self.winner < 0).sum())

    @property
    def n(self) -> int:
        return len(self.winner)

    def summary(self) -> dict:
        lo, hi = wilson(self.score_a, self.n)
        return dict(a=self.a, b=self.b, game=self.game, noise=self.noise, games=self.n,
                    a_wins=int((self.winner == 0).sum()), b_wins=int((self.winner == 1).sum()),
                    draws=int((self.winner < 0).sum()), a_win_rate=self.score_a / self.n, ci95=[lo, hi],
                    a_win_rate_breaking=float((self.winner[self.a_broke] == 0).mean()),
                    a_win_rate_not_breaking=float((self.winner[~self.a_broke] == 0).mean()),
                    mean_shots=float(self.shots.mean()))


def wilson(k: float, n: int) -> tuple[float, float]:
    """Wilson score 95% interval of a proportion k / n."""
    if n == 0:
        return 0.0, 1.0
    p = k / n
    d = 1 + Z95 ** 2 / n
    c = (p + Z95 ** 2 / (2 * n)) / d
    h = Z95 * math.sqrt(p * (1 - p) / n + Z95 ** 2 / (4 * n * n)) / d
    return max(0.0, c - h), min(1.0, c + h)


def play_pairing(a: str, b: str, game: str = "nine_ball", n_racks: int = 100, seed: int = 0,
                 noise: str = "tournament", max_shots: int = 200, policy_factory=make_game_policy,
                 **config) -> PairingResult:
    """``n_racks`` racks, each played twice (a breaks, then b breaks) between
    policies ``a`` and ``b`` (names for ``policy_factory(name, core, seed)``)."""
    cfg = GameConfig(game=game, noise=noise, max_shots=max_shots, **config)
    E = 2 * n_racks
    core = GameCore(cfg, E)
    seeds = np.tile(seed * 1_000_003 + np.arange(n_racks), 2)
    core.streams.seed(np.arange(E), seeds)
    breaker = np.repeat([0, 1], n_racks)  # player 0 is a
    core.reset_tables(np.arange(E), breaker)
    pol = [policy_factory(a, core, seed), policy_factory(b, core, seed + 1)]
    live = np.ones(E, dtype=bool)
    while live.any():
        idx = np.nonzero(live)[0]
        to_move = core.constraints().shooter[idx]
        actions = np.zeros((len(idx), 8))
        for p in (0, 1):
            m = to_move == p
            if m.any():
                actions[m] = pol[p].act(None, idx[m])
        out = core.step(actions, idx)
        live[idx[out["terminated"] | out["truncated"]]] = False
    return PairingResult(a, b, game, noise, core.game.winner.copy(), breaker == 0, core.game.shots.copy())


def bradley_terry(names: list, results: list) -> np.ndarray:
    """Log-strengths (mean 0) of ``names`` from pairing results, by
    minorisation-maximisation with ``BT_PRIOR`` virtual games per entrant."""
    k = len(names)
    pos = {n: i for i, n in enumerate(names)}
    wins = np.zeros((k, k))
    for r in results:
        i, j = pos[r.a], pos[r.b]
        wins[i, j] += r.score_a
        wins[j, i] += r.n - r.score_a
    games = wins + wins.T
    s = np.ones(k)
    for _ in range(BT_ITERATIONS):
        w = wins.sum(axis=1) + BT_PRIOR
        denom = (games / (s[:, None] + s[None, :])).sum(axis=1) + 2 * BT_PRIOR / (s + 1.0)
        s = w / denom
        s /= np.exp(np.log(s).mean())
    return np.log(s)


def ratings(names: list, results: list, n_boot: int = 200, seed: int = 0) -> list[dict]:
    """Bradley-Terry ratings on the Elo scale (mean 0) with 95% bootstrap
    intervals (games resampled within each pairing)."""
    rng = np.random.default_rng(seed)
    est = bradley_terry(names, results) * ELO
    boot = np.empty((n_boot, len(names)))
    for t in range(n_boot):
        res = []
        for r in results:
            pick = rng.integers(0, r.n, r.n)
            res.append(dataclasses.replace(r, winner=r.winner[pick], a_broke=r.a_broke[pick], shots=r.shots[pick]))
        boot[t] = bradley_terry(names, res) * ELO
    lo, hi = np.percentile(boot, [2.5, 97.5], axis=0)
    order = np.argsort(-est)
    return [dict(name=names[i], elo=float(est[i]), ci95=[float(lo[i]), float(hi[i])]) for i in order]


def tournament(names: list, game: str, n_racks: int, seed: int, noise: str, **kw) -> tuple[list, list]:
    """Every pairing of ``names``: (pairing results, ratings)."""
    results = [play_pairing(a, b, game, n_racks, seed, noise, **kw) for a, b in itertools.combinations(names, 2)]
    return results, ratings(names, results, seed=seed)
