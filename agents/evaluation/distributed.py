"""Match jobs played in this process or on a Ray cluster, with the same per-game results.

A ``MatchJob`` is one pairing: entrants ``a`` and ``b`` by name (what
``scripts/match.py`` takes: the built-in bots, ``ladder-<k>``,
``module:factory`` bots, paths of saved models), the game and its options,
racks 0 .. ``racks`` - 1 (each played twice, each side breaking once), the
seed, the noise and the shot cap, and ``chunk_racks``: how many consecutive
racks are played together on one ``GameCore`` (``None``: all of them).
``play_jobs(jobs, address)`` splits every job into its chunks, plays each
with ``studies.matches.play_racks`` (the match harness: ``play_pairing`` on
chosen racks) and returns one ``GameResult`` per (job, rack, side), side 0
with ``a`` breaking, side 1 with ``b`` breaking; ``pairing_results`` turns
them back into the harness's ``PairingResult``s and ``tournament`` is
``studies.matches.tournament`` through ``play_jobs``.

Why the results do not depend on where they ran: rack k's table is drawn
from the job's seed and k alone, but the bots decide for a chunk's tables
together and draw their random numbers for all of them, so a game's result
depends on the chunk it was played in. The chunks are fixed by the job
(``chunks``), not by the cluster or its size, so the local path and the Ray
path play the same chunks and give the same results. With
``chunk_racks=None`` a job is ``play_pairing``'s single batch: the results
equal the harness's before this module existed.

``address``: ``None`` plays every chunk here, in order. Otherwise each chunk
is a one-CPU Ray task (``agents.rllib.evaluation.ray_map``) on the cluster
``agents.rllib.backend.start_ray`` joins: ``"local"`` starts a Ray instance on
this machine, ``"auto"`` or ``HOST:PORT`` joins a running one. A chunk whose
worker dies (a killed process, a lost node) is played again from its start;
only complete chunk results are kept and each key is filled once, so every
game is counted exactly once. Errors a chunk raises itself (a bad bot) are
raised, not retried. The workers import ``agents`` and ``module:factory`` bots
from the project root and the current directory (added to their
``PYTHONPATH``); a saved model's path must exist on every node.
"""
from __future__ import annotations

import dataclasses
import itertools
import os
from pathlib import Path

import numpy as np

RETRIES = 3  # plays of a chunk after its first whose worker died, before giving up (Ray's own default for tasks)


@dataclasses.dataclass(frozen=True)
class MatchJob:
    """One pairing to play (module docstring). ``config``: further game
    options (``GameConfig``: ``rack``, ``break_nine``, ``rule_options`` ...)."""

    a: str
    b: str
    game: str = "nine_ball"
    racks: int = 100
    seed: int = 0
    noise: str = "tournament"
    max_shots: int = 200
    chunk_racks: int | None = None
    config: dict = dataclasses.field(default_factory=dict)

    def __post_init__(self):
        for key in ("racks", "seed", "max_shots"):
            v = getattr(self, key)
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)):
                raise TypeError(f"MatchJob.{key} must be an integer, got {v!r}")
        if self.racks < 1:
            raise ValueError(f"MatchJob.racks must be at least 1, got {self.racks}")
        c = self.chunk_racks
        if c is not None and (isinstance(c, bool) or not isinstance(c, (int, np.integer)) or c < 1):
            raise ValueError(f"MatchJob.chunk_racks must be None (all racks at once) or a positive integer, got {c!r}")
        for side in (self.a, self.b):
            if not isinstance(side, str):
                raise TypeError(f"a MatchJob's entrants are names (they travel to other machines), got {side!r}")


@dataclasses.dataclass(frozen=True)
class GameResult:
    """One game: ``winner`` 0 (a), 1 (b) or -1 (a draw, cut at the shot cap),
    its shots, each side's points and innings begun (games to a score), and
    its ``Replay`` when it was recorded (not compared)."""

    winner: int
    shots: int
    score: tuple = (0, 0)
    innings: tuple = (0, 0)
    replay: object = dataclasses.field(default=None, compare=False, repr=False)


def chunks(job: MatchJob) -> list[tuple[int, int]]:
    """The job's chunks: ranges [start, stop) of consecutive racks."""
    size = job.chunk_racks or job.racks
    return [(s, min(s + size, job.racks)) for s in range(0, job.racks, size)]


def play_chunk(job: MatchJob, start: int, stop: int, save_replays: int = 0, bot_factory=None, extra=None):
    """Racks [start, stop) of ``job``, both sides: ``{(rack, side): GameResult}``.
    ``save_replays``: the job's first that many games (rack 0 with a
    breaking, rack 0 with b breaking, rack 1, ...) carry their replay.
    ``extra(job, bots, result)``: called with the chunk's two bots and its
    ``PairingResult`` (tables: racks start .. stop - 1 with a breaking, then
    with b breaking); with it, returns (games, what it returned)."""
    from billiards_env.studies.matches import play_racks

    if bot_factory is None:
        from .entrants import bot_factory as base
    else:
        base = bot_factory
    bots = []

    def factory(spec, seed):
        bots.append(base(spec, seed))
        return bots[-1]

    m = stop - start
    save = int(np.clip(save_replays - 2 * start, 0, 2 * m))
    r = play_racks(job.a, job.b, job.game, np.arange(start, stop), job.seed, job.noise, job.max_shots, factory,
                   save, **job.config)
    # play_racks records, in order, rack start with each side breaking, then rack start + 1, ...
    replays = {(start + i // 2, i % 2): rep for i, rep in enumerate(r.replays)}
    out = {}
    for t in range(2 * m):
        key = (start + t % m, t // m)
        out[key] = GameResult(int(r.winner[t]), int(r.shots[t]), tuple(int(x) for x in r.score[t]),
                              tuple(int(x) for x in r.innings[t]), replays.get(key))
    return out if extra is None else (out, extra(job, bots, r))


def _worker_paths() -> None:
    """The project root (``agents``) and the current directory (``module:factory``
    bots) at the front of ``PYTHONPATH``, which ``start_ray`` gives the workers."""
    paths = [str(Path(__file__).resolve().parents[2]), os.getcwd()]
    old = [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]
    os.environ["PYTHONPATH"] = os.pathsep.join(dict.fromkeys(paths + old))


def play_jobs(jobs, address: str | None = None, **opts) -> dict:
    """Every game of ``jobs`` (``MatchJob``s): ``{(job index, rack, side): GameResult}``
    (module docstring), the same for the same jobs wherever they ran.

    ``address``: ``None`` (here), ``"local"`` (a Ray instance on this machine),
    ``"auto"`` or ``HOST:PORT`` (a running cluster). Options: ``num_cpus``
    (of a local Ray instance; default all cores), ``retries`` (plays again of
    a chunk whose worker died; default ``RETRIES``), ``save_replays`` (per
    job, as ``play_chunk``), ``bot_factory`` (``spec, seed -> bot``; default
    ``entrants.bot_factory``), ``progress(done, total)`` after each chunk,
    ``on_retry(chunk, error)`` when a chunk is played again (``chunk``: (job
    index, start, stop)). ``extra(job, bots, result)`` runs after each chunk
    where the chunk ran (``play_chunk``; for example the league's samples of
    the tables its bots saw) and ``on_extra(chunk, value)`` gets what it
    returned, here, once per chunk (from the chunk's complete run), in chunk
    order. Functions sent to Ray must pickle (module-level functions,
    closures over picklable values)."""
    unknown = set(opts) - {"num_cpus", "retries", "save_replays", "bot_factory", "progress", "on_retry", "extra",
                           "on_extra"}
    if unknown:
        raise TypeError(f"play_jobs: unknown options {sorted(unknown)}")
    jobs = list(jobs)
    for j, job in enumerate(jobs):
        if not isinstance(job, MatchJob):
            raise TypeError(f"jobs[{j}] is a {type(job).__name__}, not a MatchJob")
    _check_entrants(jobs, opts.get("bot_factory"))
    plan = [(j, s, e) for j, job in enumerate(jobs) for s, e in chunks(job)]
    extra, on_extra = opts.get("extra"), opts.get("on_extra")
    if (extra is None) != (on_extra is None):
        raise TypeError("play_jobs: extra and on_extra go together")
    args = [(jobs[j], s, e, opts.get("save_replays", 0), opts.get("bot_factory"), extra) for j, s, e in plan]
    progress = opts.get("progress")
    if address is None:
        parts = []
        for n, a in enumerate(args, 1):
            parts.append(play_chunk(*a))
            if progress is not None:
                progress(n, len(args))
    else:
        from ..rllib.backend import start_ray
        from ..rllib.evaluation import ray_map

        _worker_paths()
        start_ray(None if address == "local" else address, num_cpus=opts.get("num_cpus"))
        on_retry = opts.get("on_retry")
        parts = ray_map(play_chunk, args, retries=opts.get("retries", RETRIES), on_done=progress,
                        on_retry=None if on_retry is None else (lambda i, exc: on_retry(plan[i], exc)))
    games = {}
    for chunk, part in zip(plan, parts):
        j = chunk[0]
        if extra is not None:
            part, value = part
            on_extra(chunk, value)
        for (rack, side), g in part.items():
            if (j, rack, side) in games:
                raise RuntimeError(f"game (job {j}, rack {rack}, side {side}) came back twice")
            games[(j, rack, side)] = g
    return games


def _check_entrants(jobs: list, factory) -> None:
    """Every job's game options and entrants, here, before any game is played."""
    from billiards_env.envs.games import GameConfig

    if factory is None:
        from .entrants import bot_factory as factory
    for job in jobs:
        GameConfig(game=job.game, noise=job.noise, max_shots=job.max_shots, **job.config)
    for spec, seed in dict.fromkeys((s, job.seed) for job in jobs for s in (job.a, job.b)):
        factory(spec, seed)


def pairing_results(jobs, games: dict) -> list:
    """One ``studies.matches.PairingResult`` per job from ``play_jobs``'s games,
    in the harness's table order (racks with a breaking, then with b breaking)."""
    from billiards_env.studies.matches import PairingResult

    out = []
    for j, job in enumerate(jobs):
        order = [games[(j, rack, side)] for side in (0, 1) for rack in range(job.racks)]
        out.append(PairingResult(
            job.a, job.b, job.game, job.noise, np.array([g.winner for g in order]),
            np.repeat([True, False], job.racks), np.array([g.shots for g in order]),
            [g.replay for rack in range(job.racks) for side in (0, 1)
             if (g := games[(j, rack, side)]).replay is not None],
            np.array([g.score for g in order]), np.array([g.innings for g in order])))
    return out


def tournament(names: list, game: str, n_racks: int, seed: int, noise: str, address: str | None = None,
               chunk_racks: int | None = None, max_shots: int = 200, config: dict | None = None,
               **opts) -> tuple[list, list]:
    """``studies.matches.tournament`` through ``play_jobs``: every pairing of
    ``names`` as a job; (pairing results, Bradley-Terry ratings)."""
    from billiards_env.studies.matches import ratings

    jobs = [MatchJob(a, b, game, n_racks, seed, noise, max_shots, chunk_racks, dict(config or {}))
            for a, b in itertools.combinations(names, 2)]
    results = pairing_results(jobs, play_jobs(jobs, address, **opts))
    return results, ratings(names, results, seed=seed)
