"""Expert Iteration's games: the expert (the search over a round's network's proposals, or over the hand prior in
round 0) plays itself, and every decision but the breaks is kept with the search's allocation as its target.

A round's games are ``MatchJob``s played by ``agents.evaluation.distributed.play_jobs``, in this process or on Ray
(one task per chunk of racks; the same games either way, since the chunks are fixed by the job). The entrants are
spec strings that travel to the workers: ``exit:<run>:<snapshot>:<budget>``, made by ``entrant`` (``snapshot`` a
stem under ``<run>/snapshots``, or ``-`` for the hand prior; ``budget`` a key of the config: ``expert0``,
``expert`` or ``play``). ``chunk_records`` (``play_jobs``' ``extra``) turns the two players' traces into one
record per decision, labelled by whether its shooter won the game (1, 0; 1/2 for a game cut at the shot cap), and
``write_shard`` stores a job's records as ``<run>/data/round_<r>/job_<j>.npz`` (written whole or not at all).

A record (``FIELDS``): the table's inputs ``g`` [G], every slot's inputs ``x`` [S, F] (float16), the legal
(slot, turn) pairs ``mask`` [S, T], the candidates (``cand_joint``, their target ``cand_y`` and noisy samples
``cand_count``, flat, decision d's at ``cand_ptr[d]:cand_ptr[d + 1]``), the rest's target ``y_rest``, the played
proposal ``chosen``, the search's value ``value``, the game's result ``z`` for the shooter and the game ``game``.
"""
from __future__ import annotations

import dataclasses
import functools
import os
from pathlib import Path

import numpy as np

from billiards_env.bots.learned import proposal_net as PN
from billiards_env.bots.learned.proposal_bot import ProposalPlayer

from ..evaluation.distributed import MatchJob, play_jobs
from .config import MAX_JOBS, ExItConfig

PREFIX = "exit:"
HAND = "-"                  # the snapshot field of the hand prior's expert
FIELDS = ("g", "x", "mask", "cand_ptr", "cand_joint", "cand_y", "cand_count", "y_rest", "chosen", "value", "z",
          "game")


def spec(run, snapshot: str | None, budget: str) -> str:
    return f"{PREFIX}{Path(run)}:{snapshot or HAND}:{budget}"


def entrant(spec_: str, seed: int, config: dict):
    """A bot by spec: ``exit:...`` (module docstring) as a recording ``ProposalPlayer``, else
    ``billiards_env.bots.make_bot``'s (an evaluation's opponent)."""
    if not spec_.startswith(PREFIX):
        from billiards_env.bots import make_bot
        return make_bot(spec_, seed=seed)
    run, snap, budget = spec_[len(PREFIX):].rsplit(":", 2)
    cfg = ExItConfig.from_dict(config)
    nets = {cfg.game: (None, {}) if snap == HAND else PN.load(Path(run) / "snapshots" / snap)}
    bot = ProposalPlayer(spec_, seed=seed, nets=nets, budget=getattr(cfg, budget),
                         searched_break=cfg.searched_break, record=budget != "play")
    return bot


def chunk_records(job, bots, result) -> dict | None:
    """``play_jobs``' ``extra``: the records (module docstring) both players of a chunk kept."""
    parts = []
    for bot in bots:
        for t in getattr(bot, "trace", None) or []:
            parts.append(_records(t, result.winner))
    if not parts:
        return None
    out = {}
    for k in FIELDS:
        if k == "cand_ptr":
            sizes = np.concatenate([np.diff(p[k]) for p in parts])
            out[k] = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
        else:
            out[k] = np.concatenate([p[k] for p in parts])
    return out


def _records(t: dict, winner: np.ndarray) -> dict:
    m = len(t["tables"])
    w = winner[t["tables"]]
    z = np.where(w < 0, 0.5, (w == t["movers"]).astype(np.float64))
    ptr = np.concatenate([[0], np.cumsum(np.bincount(t["li"], minlength=m))])
    return dict(g=t["g"].astype(np.float32), x=t["x"].astype(np.float16), mask=t["mask"], cand_ptr=ptr,
                cand_joint=t["joint"].astype(np.int32), cand_y=t["y"].astype(np.float32),
                cand_count=t["count"].astype(np.int32), y_rest=t["y_rest"].astype(np.float32),
                chosen=t["chosen"].astype(np.int32), value=t["value"].astype(np.float32), z=z.astype(np.float32),
                game=np.asarray(t["tables"], np.int64))


def shard_path(run, r: int, j: int) -> Path:
    return Path(run) / "data" / f"round_{r:03d}" / f"job_{j:03d}.npz"


def write_shard(path: Path, records: dict) -> None:
    """``records`` as ``path``, written to a temporary file first and renamed (a shard is whole or absent)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.stem + ".tmp.npz")
    np.savez_compressed(tmp, **records)
    os.replace(tmp, path)


def round_jobs(run, cfg: ExItConfig, r: int, snapshot: str | None) -> list:
    """Round ``r``'s self-play jobs: the expert of ``snapshot`` (None: the hand prior) against itself."""
    s = spec(run, snapshot, "expert" if snapshot else "expert0")
    return [MatchJob(s, s, cfg.game, cfg.racks, cfg.seed_base + r * MAX_JOBS + j, cfg.noise, cfg.max_shots,
                     cfg.chunk_racks) for j in range(cfg.jobs)]


def play_round(run, cfg: ExItConfig, r: int, snapshot: str | None, address=None, log=print,
               workers: int | None = None) -> list:
    """Play round ``r``'s jobs whose shards are missing (``jobs_per_call`` at a time), writing each job's shard;
    returns every job's shard path."""
    jobs = round_jobs(run, cfg, r, snapshot)
    factory = functools.partial(entrant, config=cfg.to_dict())
    todo = [j for j in range(len(jobs)) if not shard_path(run, r, j).exists()]
    if len(todo) < len(jobs):
        log(f"  round {r}: {len(jobs) - len(todo)} of {len(jobs)} jobs' shards already written")
    for lo in range(0, len(todo), cfg.jobs_per_call):
        part = todo[lo:lo + cfg.jobs_per_call]
        got: dict = {}
        games = play_jobs([jobs[j] for j in part], address, bot_factory=factory, extra=chunk_records, num_cpus=workers,
                          on_extra=lambda chunk, value: got.setdefault(chunk[0], []).append((chunk[1], value)))
        for i, j in enumerate(part):
            chunks = [v for _, v in sorted(got.get(i, []), key=lambda t: t[0]) if v is not None]
            rec = merge(chunks, jobs[j], i)
            write_shard(shard_path(run, r, j), rec)
            won = np.mean([games[(i, k, s)].winner == s for k in range(jobs[j].racks) for s in (0, 1)])
            log(f"  round {r} job {j} (seed {jobs[j].seed}): {len(rec['z'])} decisions, "
                f"{2 * jobs[j].racks} games (the breaking side won {won:.2f})")
    return [shard_path(run, r, j) for j in range(len(jobs))]


def merge(chunks: list, job: MatchJob, i: int) -> dict:
    """One job's records from its chunks' (in chunk order), game ids made unique within the round."""
    if not chunks:
        raise RuntimeError(f"job {i} ({job.seed}) recorded no decisions")
    out = {}
    for k in FIELDS:
        if k == "cand_ptr":
            off = np.cumsum([0] + [c["cand_ptr"][-1] for c in chunks[:-1]])
            out[k] = np.concatenate([chunks[0][k][:1]] + [c[k][1:] + o for c, o in zip(chunks, off)])
        elif k == "game":   # a chunk's table -> a game id unique in the run: (job seed, chunk, table)
            out[k] = np.concatenate([(job.seed * (job.racks + 1) + q) * 2 * (job.racks + 1) + c[k]
                                     for q, c in enumerate(chunks)])
        else:
            out[k] = np.concatenate([c[k] for c in chunks])
    return out


@dataclasses.dataclass
class Data:
    """Records of several shards in memory (``FIELDS``), the candidates flat with ``cand_row`` [M] (their
    decision)."""

    arrays: dict

    @property
    def n(self) -> int:
        return len(self.arrays["z"])

    @classmethod
    def load(cls, paths, max_samples: int | None = None) -> "Data":
        parts = []
        for p in paths:
            with np.load(p, allow_pickle=False) as z:
                parts.append({k: z[k] for k in FIELDS})
        out = {}
        for k in FIELDS:
            if k == "cand_ptr":
                sizes = np.concatenate([np.diff(p[k]) for p in parts])
                out[k] = np.concatenate([[0], np.cumsum(sizes)])
            else:
                out[k] = np.concatenate([p[k] for p in parts])
        data = cls(out)
        if max_samples is not None and data.n > max_samples:
            data = data.take(np.arange(data.n - max_samples, data.n))
        return data

    def take(self, idx) -> "Data":
        """The records ``idx`` (in that order), candidates carried along."""
        a = self.arrays
        idx = np.asarray(idx, np.int64)
        lo, hi = a["cand_ptr"][idx], a["cand_ptr"][idx + 1]
        cand = np.concatenate([np.arange(s, e) for s, e in zip(lo, hi)]) if len(idx) else np.zeros(0, np.int64)
        out = {k: a[k][idx] for k in FIELDS if not k.startswith("cand_")}
        out.update({k: a[k][cand] for k in ("cand_joint", "cand_y", "cand_count")})
        out["cand_ptr"] = np.concatenate([[0], np.cumsum(hi - lo)])
        return Data(out)

    @property
    def cand_row(self) -> np.ndarray:
        p = self.arrays["cand_ptr"]
        return np.repeat(np.arange(len(p) - 1), np.diff(p))
