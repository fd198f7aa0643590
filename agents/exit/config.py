"""Expert Iteration's settings (``configs/exit_<game>.yaml``), a frozen dataclass that round-trips through YAML."""
from __future__ import annotations

import dataclasses
from pathlib import Path

import yaml

from billiards_env.bots.learned.proposal_bot import games
from billiards_env.bots.planner.proposals import SearchBudget

MAX_JOBS = 1000           # jobs per round: job seeds are seed_base + round * MAX_JOBS + job
# the smoke run (``scripts/expert_iteration.py --quick``, the tests): two rounds of one job of one rack (two games)
# cut at 8 shots, small searches, two epochs per fit, a one-rack evaluation
QUICK = dict(rounds=2, jobs=1, racks=1, chunk_racks=None, jobs_per_call=1, max_shots=8, threads=1, eval_racks=1,
             expert0=dict(k=12, k_safe=4, first=4, first_safe=1, rounds=[2, 4]),
             expert=dict(k=8, k_safe=2, first=3, first_safe=1, rounds=[2, 4], explore=True, value_weight=0.3),
             play=dict(k=8, k_safe=2, first=3, first_safe=1, rounds=[2, 4], value_weight=0.3),
             net=dict(hidden_g=[16], hidden_s=[16], hidden_v=[8], epochs=2, batch=32),
             distill=dict(hidden_g=[16], hidden_s=[16], hidden_v=[8], epochs=2, batch=32))


@dataclasses.dataclass(frozen=True)
class NetConfig:
    """The network's hidden sizes (table, slot and value layers) and its fit."""

    hidden_g: tuple = (64,)
    hidden_s: tuple = (64, 64)
    hidden_v: tuple = (64,)
    epochs: int = 20
    batch: int = 128
    lr: float = 1e-3
    l2: float = 1e-5              # Adam's weight decay
    value_coef: float = 1.0       # the value loss's weight beside the policy loss
    val_frac: float = 0.1         # games held out to report the losses on
    max_samples: int = 120_000    # the newest decisions a fit keeps (memory: about 6-10 KB each)
    checkpoint_every: int = 1     # epochs between checkpoints of a fit (resume point)


@dataclasses.dataclass(frozen=True)
class ExItConfig:
    game: str = "nine_ball"
    rounds: int = 4               # rounds of self-play and fit; round 0's expert searches with the hand prior
    jobs: int = 8                 # self-play jobs per round
    racks: int = 16               # racks per job, each played twice (each side breaking once)
    chunk_racks: int | None = 8   # racks the bots play together (the chunk is the Ray task)
    jobs_per_call: int = 4        # jobs played per play_jobs call (a stopped run loses at most one call's games)
    noise: str = "tournament"
    max_shots: int = 120
    window: int = 2               # rounds of data each fit reads
    value_mix: float = 0.0        # the search value's weight in the value target (the rest: the game's result)
    seed: int = 0
    seed_base: int = 5000         # job rack seeds start here (matches at lower seeds meet racks training never saw)
    threads: int = 2              # torch's threads (fixed: a resumed fit must run as the first did)
    searched_break: bool = False  # self-play breaks: ghost's standard break (breaks are not learned from)
    expert0: SearchBudget = SearchBudget(k=64, k_safe=16, first=16, first_safe=4)
    expert: SearchBudget = SearchBudget(k=32, k_safe=8, first=10, first_safe=3, explore=True, value_weight=0.3)
    play: SearchBudget = SearchBudget(k=32, k_safe=8, first=10, first_safe=3, value_weight=0.3)
    net: NetConfig = NetConfig()
    distill: NetConfig = NetConfig(hidden_s=(128, 64), epochs=30)
    distill_hard: float = 0.5     # the student's target: this much the search's played shot, the rest its allocation
    distill_window: int = 2       # the newest rounds of data the student learns from
    eval_racks: int = 0           # after each fit: racks (x2) of the new network's search against eval_opponent
    eval_opponent: str = "champion"
    eval_seed: int = 7

    def __post_init__(self):
        if self.game not in games():
            raise ValueError(f"Expert Iteration trains {games()}, got game {self.game!r}")
        if self.rounds < 1 or self.racks < 1 or self.window < 1 or not 1 <= self.jobs <= MAX_JOBS:
            raise ValueError("rounds, racks and window must be at least 1, jobs in 1..MAX_JOBS")

    @classmethod
    def from_dict(cls, d: dict) -> "ExItConfig":
        d = dict(d or {})
        known = {f.name: f for f in dataclasses.fields(cls)}
        bad = sorted(set(d) - set(known))
        if bad:
            raise ValueError(f"unknown Expert Iteration config keys {bad}; known: {sorted(known)}")
        for key in ("expert0", "expert", "play"):
            if key in d:
                d[key] = _build(SearchBudget, d[key], key)
        for key in ("net", "distill"):
            if key in d:
                d[key] = _build(NetConfig, d[key], key)
        return cls(**d)

    @classmethod
    def load(cls, path, **overrides) -> "ExItConfig":
        d = yaml.safe_load(Path(path).read_text()) or {}
        d.update({k: v for k, v in overrides.items() if v is not None})
        return cls.from_dict(d)

    def to_dict(self) -> dict:
        return _plain(dataclasses.asdict(self))

    def replace(self, **changes) -> "ExItConfig":
        return ExItConfig.from_dict({**self.to_dict(), **changes})


def _build(cls, d, key):
    d = dict(d)
    names = {f.name for f in dataclasses.fields(cls)}
    if set(d) - names:
        raise ValueError(f"unknown {key} keys {sorted(set(d) - names)}; known: {sorted(names)}")
    return cls(**{k: tuple(v) if isinstance(v, list) else v for k, v in d.items()})


def _plain(o):
    if isinstance(o, dict):
        return {k: _plain(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [_plain(v) for v in o]
    return o
