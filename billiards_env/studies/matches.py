"""Seeded matches between game policies, and ratings.

``play_pairing`` plays ``n_racks`` racks twice between two policies, once
with each breaking, on one ``GameCore`` of 2 * n_racks tables: table k and
table n_racks + k share their seed, so both sides meet the same racks (and,
with ``variable`` noise, the same noise factor). Each step shoots every live
table once with one simulator call; each bot acts only on the tables where
its player is to move (``envs.games.play``). ``play_racks`` plays chosen
racks of a pairing (its chunks, ``agents.evaluation.distributed``).

``tournament`` plays every pairing of the entrants and fits a
Bradley-Terry model (ratings on the Elo scale, 95% intervals by bootstrap
over games); a win rate's 95% interval is Wilson's
(``stats.wilson_interval``). A draw (a game cut at the shot cap) counts half
a win.

Entrants are bots (``bots.make_bot``: names, ``module:factory`` strings or
bot objects) or, through ``bot_factory(spec, seed) -> bot``, anything
else (``scripts/match.py`` passes one that also loads trained models).
"""
from __future__ import annotations

import dataclasses
import itertools
import math

import numpy as np

from ..bots import make_bot
from ..envs.games import GameConfig, GameCore
from ..envs.games.play import play_out
from ..rendering.game_replay import GameRecorder
from ..rules import DEFAULT_GAME
from .stats import wilson_interval

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
    replays: list = dataclasses.field(default_factory=list)  # whole games as Replays (``save_replays``)
    score: np.ndarray | None = None    # [2n, 2] points of a and b (games to a score: three-cushion)
    innings: np.ndarray | None = None  # [2n, 2] innings a and b began

    @property
    def score_a(self) -> float:
        """a's points: wins plus half the draws."""
        return float((self.winner == 0).sum() + 0.5 * (self.winner < 0).sum())

    @property
    def n(self) -> int:
        return len(self.winner)

    def summary(self) -> dict:
        lo, hi = wilson_interval(self.score_a, self.n)
        return dict(a=self.a, b=self.b, game=self.game, noise=self.noise, games=self.n,
                    a_wins=int((self.winner == 0).sum()), b_wins=int((self.winner == 1).sum()),
                    draws=int((self.winner < 0).sum()), a_win_rate=self.score_a / self.n, ci95=[lo, hi],
                    a_win_rate_breaking=float((self.winner[self.a_broke] == 0).mean()),
                    a_win_rate_not_breaking=float((self.winner[~self.a_broke] == 0).mean()),
                    mean_shots=float(self.shots.mean()), **self._per_inning())

    def _per_inning(self) -> dict:
        """Games to a score: each side's points per inning (all its points over all its innings)."""
        if self.score is None or not self.innings.any():
            return {}
        return dict(a_points_per_inning=float(self.score[:, 0].sum() / max(1, self.innings[:, 0].sum())),
                    b_points_per_inning=float(self.score[:, 1].sum() / max(1, self.innings[:, 1].sum())))


def play_pairing(a, b, game: str = DEFAULT_GAME, n_racks: int = 100, seed: int = 0,
                 noise: str = "tournament", max_shots: int = 200, bot_factory=make_bot, save_replays: int = 0,
                 **config) -> PairingResult:
    """``n_racks`` racks, each played twice (a breaks, then b breaks) between
    bots ``a`` and ``b`` (specs for ``bot_factory(spec, seed)``).
    ``save_replays``: record this many whole games (rack 1 with a breaking,
    rack 1 with b breaking, rack 2, ...) as ``Replay``s in ``replays``."""
    return play_racks(a, b, game, np.arange(n_racks), seed, noise, max_shots, bot_factory, save_replays, **config)


def play_racks(a, b, game: str = DEFAULT_GAME, racks=(0,), seed: int = 0, noise: str = "tournament",
               max_shots: int = 200, bot_factory=make_bot, save_replays: int = 0, **config) -> PairingResult:
    """``play_pairing`` on the racks numbered ``racks`` (rack k is drawn from
    ``seed * 1_000_003 + k``, whichever other racks are played with it):
    table i plays ``racks[i]`` with a breaking, table len(racks) + i with b
    breaking. The bots are made afresh (seeded with ``seed`` and ``seed + 1``)
    and decide for all these tables at once, so a game's result depends on
    the set of racks played together (``agents.evaluation.distributed``
    fixes that set per chunk)."""
    cfg = GameConfig(game=game, noise=noise, max_shots=max_shots, **config)
    racks = np.asarray(racks, dtype=np.int64)
    n_racks = len(racks)
    E = 2 * n_racks
    core = GameCore(cfg, E, record=save_replays > 0)
    seeds = np.tile(seed * 1_000_003 + racks, 2)
    core.streams.seed(np.arange(E), seeds)
    breaker = np.repeat([0, 1], n_racks)  # player 0 is a
    core.reset_tables(np.arange(E), breaker)
    bots = [bot_factory(a, seed), bot_factory(b, seed + 1)]
    names = (_name(a, bots[0]), _name(b, bots[1]))
    tables = np.stack([np.arange(n_racks), n_racks + np.arange(n_racks)], axis=1).ravel()[:max(save_replays, 0)]
    recorder = GameRecorder(core, tables, players=names, meta={"noise": noise}) if len(tables) else None
    play_out(core, bots, np.arange(E))
    replays = []
    for k in tables:
        rep = recorder.games(int(k))[0]
        rep.data["meta"].update(rack=int(racks[k % n_racks]), seed=int(seeds[k]), breaker=names[int(breaker[k])])
        replays.append(rep)
    return PairingResult(*names, game, noise, core.game.winner.copy(), breaker == 0, core.game.shots.copy(), replays,
                         core.game.score.copy(), core.game.innings.copy())


def _name(spec, bot) -> str:
    return spec if isinstance(spec, str) else getattr(bot, "name", type(bot).__name__)


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
            res.append(dataclasses.replace(r, winner=r.winner[pick], a_broke=r.a_broke[pick], shots=r.shots[pick],
                                           score=None if r.score is None else r.score[pick],
                                           innings=None if r.innings is None else r.innings[pick]))
        boot[t] = bradley_terry(names, res) * ELO
    lo, hi = np.percentile(boot, [2.5, 97.5], axis=0)
    order = np.argsort(-est)
    return [dict(name=names[i], elo=float(est[i]), ci95=[float(lo[i]), float(hi[i])]) for i in order]


def tournament(names: list, game: str, n_racks: int, seed: int, noise: str, **kw) -> tuple[list, list]:
    """Every pairing of ``names``: (pairing results, ratings)."""
    results = [play_pairing(a, b, game, n_racks, seed, noise, **kw) for a, b in itertools.combinations(names, 2)]
    return results, ratings(names, results, seed=seed)
