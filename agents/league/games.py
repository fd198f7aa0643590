"""The league's games: its entrants, the recording of every decision, and jobs played through
``agents.evaluation.distributed.play_jobs`` (here, or on Ray with ``address``: the same results).

An entrant is a spec string (specs travel to Ray workers): a bot name for ``agents.evaluation.entrants``'s
``bot_factory``, or ``value@<stem>``, a league snapshot: ``value-lookahead`` with the value network
``<stem>.npz`` / ``.json``. Every bot the league plays with records the tables it is asked to shoot on (all but
breaks): the table seen by its shooter (``bots.learned.value.value_features``, and the balls' own eases,
``ball_eases``, which a league fits to or not), and, for a searching bot
(``lookahead``, ``value-lookahead``), the value its search gave the shot it chose (``last_value``; NaN for
the others). After each chunk of racks, ``chunk_samples`` (``play_jobs``' ``extra``, run where the chunk ran)
labels them with whether that shooter won the game (1, 0; a game cut at the shot cap counts 1/2).
"""
from __future__ import annotations

import dataclasses

import numpy as np

from billiards_env.bots.game_lookahead import GameLookahead
from billiards_env.bots.learned.value import ball_eases, value_features

from ..evaluation.distributed import MatchJob, play_jobs
from ..evaluation.entrants import bot_factory

SNAPSHOT = "value@"  # entrant prefix of a league snapshot (``agents.evaluation.entrants.SNAPSHOTS``)


class Recorder:
    """A bot that records the tables it is asked to shoot on (all but breaks) and passes them to ``bot``."""

    def __init__(self, bot):
        self.bot, self.name = bot, getattr(bot, "name", type(bot).__name__)
        self.geo = bot if isinstance(bot, GameLookahead) else GameLookahead()  # the pot model, for the ease
        self.rows, self.movers, self.x, self.balls, self.search = [], [], [], [], []

    def act(self, view):
        keep = np.nonzero(~view.is_break)[0]
        if len(keep):
            v = view.take(keep)
            ease = self.geo.leave_ease(v, v.pos, v.on_table, v.targets, v.in_hand)
            self.x.append(value_features(v.game, v.table.width, v.table.length, v.pos, v.on_table, v.targets,
                                         v.ball_in_hand, ease))
            self.balls.append(ball_eases(self.geo, v, v.pos, v.on_table, v.ball_in_hand))
            self.rows.append(np.asarray(v.rows))
            self.movers.append(np.asarray(v.to_move))
        plan = self.bot.act(view)
        if len(keep):
            sv = getattr(self.bot, "last_value", None)
            self.search.append(np.full(len(keep), np.nan) if sv is None else np.asarray(sv, np.float64)[keep])
        return plan


def recording_entrant(spec: str, seed: int) -> Recorder:
    """``bot_factory``'s entrant wrapped in a ``Recorder`` (the league's ``bot_factory``)."""
    return Recorder(bot_factory(spec, seed))


@dataclasses.dataclass
class Samples:
    """Recorded decisions: tables [S, D], their shooter's result [S], the table of the job's chunk each comes
    from [S] (a game id within the chunk), the shooter's search value [S] (NaN: it does not search) and the
    tables' balls' eases [S, 2B]."""
    x: np.ndarray
    y: np.ndarray
    table: np.ndarray
    search: np.ndarray
    balls: np.ndarray


def chunk_samples(job, bots, result) -> Samples | None:
    """``play_jobs``' ``extra``: the samples both bots of a chunk recorded, labelled by its games' winners."""
    parts = []
    for rec in bots:
        if not isinstance(rec, Recorder) or not rec.x:
            continue
        rows, movers = np.concatenate(rec.rows), np.concatenate(rec.movers)
        w = result.winner[rows]
        parts.append(Samples(np.concatenate(rec.x), np.where(w < 0, 0.5, (w == movers).astype(np.float64)), rows,
                             np.concatenate(rec.search), np.concatenate(rec.balls)))
    if not parts:
        return None
    return Samples(*(np.concatenate([getattr(p, f.name) for p in parts]) for f in dataclasses.fields(Samples)))


@dataclasses.dataclass
class JobResult:
    """One job's games (``winner`` [2 racks]: 0 a won, 1 b won, -1 cut; a breaking on the first half) and its
    samples."""
    job: MatchJob
    winner: np.ndarray
    samples: Samples | None

    @property
    def score_a(self) -> float:
        return float((self.winner == 0).sum() + 0.5 * (self.winner < 0).sum())


def play_league_jobs(jobs: list, address=None, progress=None, chunk_progress=None) -> list[JobResult]:
    """Play ``jobs`` (``MatchJob``s) through ``play_jobs`` with recording bots; one ``JobResult`` per job, in
    order. ``chunk_progress(done, total)`` as chunks end; ``progress(i, result)`` per job once all are done
    (chunks may end in any order on Ray)."""
    samples: dict = {}
    games = play_jobs(jobs, address, bot_factory=recording_entrant, extra=chunk_samples, progress=chunk_progress,
                      on_extra=lambda chunk, value: samples.setdefault(chunk[0], []).append((chunk[1], value)))
    out = []
    for j, job in enumerate(jobs):
        winner = np.array([games[(j, rack, side)].winner for side in (0, 1) for rack in range(job.racks)])
        parts = [(s, v) for s, v in sorted(samples.get(j, []), key=lambda t: t[0]) if v is not None]
        if parts:
            # a sample's table within its chunk -> its game within the job (rack, side)
            tables = []
            for start, v in parts:
                m = min(job.chunk_racks or job.racks, job.racks - start)
                tables.append((v.table // m) * job.racks + start + v.table % m)
            s = Samples(*(np.concatenate([getattr(v, f.name) for _, v in parts]) for f in dataclasses.fields(Samples)))
            s.table = np.concatenate(tables)
        else:
            s = None
        out.append(JobResult(job, winner, s))
        if progress is not None:
            progress(j, out[-1])
    return out
