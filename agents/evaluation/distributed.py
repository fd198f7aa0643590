"""Games by the batch: ``play_jobs(jobs, address=None)`` plays a list of ``Job``s and returns one ``JobResult``
each, in order. The league (``agents.league``) plays every game through it.

A ``Job`` is a pairing's block of racks: entrants ``a`` and ``b`` (specs: a bot name for ``bots.make_bot``, a
saved model's path, or ``value@<stem>``, a league snapshot: ``value-lookahead`` with the value network
``<stem>.npz`` / ``.json``), the game, ``seed`` and ``n_racks`` (``studies.matches.play_pairing``: the racks
``seed * 1_000_003 + k``, each played twice, each side breaking once), the noise level, the shot cap and
whether to ``record`` the positions. Recorded, every decision but the breaks gives one sample: the table seen
by its shooter (``bots.learned.value.value_features``), whether that shooter went on to win the game (1,
0; a game cut at the shot cap counts 1/2) and, for a searching bot (``lookahead``, ``value-lookahead``), the
value its search gave the shot it chose (``last_value``: the mean over noisy previews of its leaves' values;
NaN for other bots).

Jobs are independent and seeded, so their results do not depend on where or in which order they run.
``address=None`` plays them here, one after the other.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from billiards_env.bots.game_lookahead import GameLookahead
from billiards_env.bots.learned.value import ValueLookahead, load_value, value_features
from billiards_env.studies.matches import play_pairing

from .entrants import bot_factory

SNAPSHOT = "value@"  # entrant prefix of a league snapshot


@dataclasses.dataclass(frozen=True)
class Job:
    a: str
    b: str
    game: str
    seed: int
    n_racks: int
    noise: str = "tournament"
    max_shots: int = 200
    record: bool = False


@dataclasses.dataclass
class JobResult:
    job: Job
    winner: np.ndarray    # [2 n_racks] 0: a won, 1: b won, -1: cut at the shot cap
    a_broke: np.ndarray   # [2 n_racks]
    shots: np.ndarray     # [2 n_racks]
    x: np.ndarray | None = None  # [S, D] recorded tables (``record``)
    y: np.ndarray | None = None  # [S] their shooter's result
    table: np.ndarray | None = None  # [S] the table (game) of the job each sample comes from
    search: np.ndarray | None = None  # [S] the shooter's search value of its shot (NaN: the bot does not search)

    @property
    def score_a(self) -> float:
        return float((self.winner == 0).sum() + 0.5 * (self.winner < 0).sum())


def entrant(spec: str, game: str, seed: int):
    """The bot of an entrant spec (module docstring)."""
    if isinstance(spec, str) and spec.startswith(SNAPSHOT):
        net, doc = load_value(spec[len(SNAPSHOT):])
        if doc.get("game") != game:
            raise ValueError(f"{spec}: a {doc.get('game')} value network cannot play {game}")
        bot = ValueLookahead(seed=seed, nets={game: net})
        bot.name = spec
        return bot
    return bot_factory(spec, seed)


class Recorder:
    """A bot that records the tables it is asked to shoot on (all but breaks) and passes them to ``bot``."""

    def __init__(self, bot):
        self.bot, self.name = bot, getattr(bot, "name", type(bot).__name__)
        self.geo = bot if isinstance(bot, GameLookahead) else GameLookahead()  # the pot model, for the ease
        self.rows, self.movers, self.x, self.search = [], [], [], []

    def act(self, view):
        keep = np.nonzero(~view.is_break)[0]
        if len(keep):
            v = view.take(keep)
            ease = self.geo.leave_ease(v, v.pos, v.on_table, v.targets, v.in_hand)
            self.x.append(value_features(v.game, v.table.width, v.table.length, v.pos, v.on_table, v.targets,
                                         v.ball_in_hand, ease))
            self.rows.append(np.asarray(v.rows))
            self.movers.append(np.asarray(v.to_move))
        plan = self.bot.act(view)
        if len(keep):
            sv = getattr(self.bot, "last_value", None)
            self.search.append(np.full(len(keep), np.nan) if sv is None else np.asarray(sv, np.float64)[keep])
        return plan

    def samples(self, winner: np.ndarray) -> tuple | None:
        """(tables [S, D], their shooter's result [S], the table of each [S], the search value [S]), or None if
        nothing was recorded."""
        if not self.x:
            return None
        rows, movers = np.concatenate(self.rows), np.concatenate(self.movers)
        w = winner[rows]
        y = np.where(w < 0, 0.5, (w == movers).astype(np.float64))
        return np.concatenate(self.x), y, rows, np.concatenate(self.search)


def play_job(job: Job) -> JobResult:
    """One job, here."""
    recorders = []

    def factory(spec, seed):
        bot = entrant(spec, job.game, seed)
        if job.record:
            bot = Recorder(bot)
            recorders.append(bot)
        return bot

    r = play_pairing(job.a, job.b, job.game, job.n_racks, job.seed, job.noise, max_shots=job.max_shots,
                     bot_factory=factory)
    out = JobResult(job, r.winner, r.a_broke, r.shots)
    if job.record:
        parts = [p for p in (rec.samples(r.winner) for rec in recorders) if p is not None]
        if parts:
            out.x, out.y, out.table, out.search = (np.concatenate([p[k] for p in parts]) for k in range(4))
    return out


def play_jobs(jobs, address=None, progress=None) -> list[JobResult]:
    """Play ``jobs`` (``Job``s) and return their results in order. ``address``: where to play them (None:
    here, one after the other); ``progress(i, result)`` is called as each job ends."""
    if address is not None:
        raise NotImplementedError("only local play (address=None) is available in this build")
    out = []
    for i, job in enumerate(jobs):
        out.append(play_job(job))
        if progress is not None:
            progress(i, out[-1])
    return out
