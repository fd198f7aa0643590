"""The benchmark protocol: which tasks, against whom, trained how long, evaluated how.

A score on the suite is only comparable with another if both followed the same protocol, so everything that
decides a number is fixed here, in frozen dataclasses, under ``PROTOCOL.version``:

- the tasks (``Task``): the one-player tasks (score: the success rate) and the two-player games against a fixed
  opponent (score: the win rate; a game cut at the shot cap counts as lost), each at ``tournament`` noise, with
  the training budget in env steps an agent may use, the policy that scores 0 (``random``) and the named bot
  that scores 1 (``reference``);
- the evaluation: run k (k = 0..4: the k-th training seed of an agent, or a bot seeded k) plays ``episodes``
  held tables reset from ``EVAL_SEEDS[k]`` (far from any training seed; each run its own tables, so the
  spread over runs includes the tables' own), the first episode of each table
  (``agents.evaluation.harness.evaluate``'s convention);
- quick mode (``QUICK``): the same tasks at a few episodes and two runs, for a smoke test of the pipeline;
  its numbers mean nothing.

``Billiards-ThreeCushionPoint-v1`` is not in the suite: no one-player bot plays it (the pool bots aim at
pockets), so it has no reference to normalize by.
"""
from __future__ import annotations

import dataclasses


@dataclasses.dataclass(frozen=True)
class Task:
    """One task of the suite.

    ``env_id``: the Gymnasium id; ``kind``: ``"task"`` (one player; score = success rate) or ``"game"``
    (against ``opponent``; score = win rate); ``budget``: training env steps allowed; ``reference``: the bot
    whose score is normalized to 1 (``baseline``'s to 0); ``noise``: the env's noise preset at evaluation;
    ``episodes``: held tables per run; ``since``: the first protocol version whose evaluation of the task is
    this one (its id, opponent, noise, episodes and seeds): a bot's score from that version on still counts,
    and a trained agent's too when its budgets are this protocol's (``Protocol.budgets_since``)."""

    env_id: str
    kind: str
    budget: int
    reference: str
    episodes: int
    opponent: str | None = None
    noise: str = "tournament"
    baseline: str = "random"
    since: int = 1   # the protocol version since which the task's evaluation is unchanged (score.check_results)

    def __post_init__(self):
        if self.kind not in ("task", "game"):
            raise ValueError(f"{self.env_id}: kind must be 'task' or 'game', got {self.kind!r}")
        if (self.kind == "game") != (self.opponent is not None):
            raise ValueError(f"{self.env_id}: a game names its opponent, a one-player task none")

    @property
    def name(self) -> str:
        """The short name: ``PotOne`` for ``Billiards-PotOne-v1``."""
        return self.env_id.removeprefix("Billiards-").rsplit("-v", 1)[0]

    @property
    def metric(self) -> str:
        return "success rate" if self.kind == "task" else f"win rate against {self.opponent}"


@dataclasses.dataclass(frozen=True)
class Protocol:
    """The suite and its evaluation: ``tasks``, ``eval_seeds`` (one per run), ``batch_size`` (tables simulated
    together; results do not depend on it for the one-player tasks, and the protocol fixes it for the games,
    whose opponents' noise draws follow the batch)."""

    version: int
    tasks: tuple
    eval_seeds: tuple
    batch_size: int = 500
    budgets_since: int = 1  # the first protocol version with these training budgets: an agent trained under an
    #                         older one is trained again (score.check_results)

    @property
    def runs(self) -> int:
        return len(self.eval_seeds)

    def task(self, env_id: str) -> Task:
        for t in self.tasks:
            if env_id in (t.env_id, t.name):
                return t
        raise ValueError(f"{env_id!r} is not a task of the benchmark; tasks: {', '.join(t.env_id for t in self.tasks)}")

    def select(self, spec: str) -> tuple:
        """The tasks of ``spec``: ``all``, or comma-separated ids or short names."""
        if spec == "all":
            return self.tasks
        return tuple(self.task(s.strip()) for s in spec.split(",") if s.strip())

    def quick(self) -> "Protocol":
        """The quick mode: every task at ``QUICK_EPISODES`` (games ``QUICK_GAMES``), the first two runs."""
        tasks = tuple(dataclasses.replace(t, episodes=QUICK_GAMES if t.kind == "game" else QUICK_EPISODES)
                      for t in self.tasks)
        return dataclasses.replace(self, tasks=tasks, eval_seeds=self.eval_seeds[:2])


# Protocol 3 (from 2): Billiards-ThreeCushion-v3 and Billiards-Snooker-v2 (their observations say when the balls
# may be replaced and when the cue ball lies touching a ball; the carom and snooker bots, their opponents, use the
# replace choice); the other tasks, the budgets and the evaluation are protocol 2's.
# Protocol 2 (from 1): the budgets only, chosen so the reference agents' whole table (PPO and SAC, five seeds,
# every task: python -m agents.evaluation.reference --jobs 2) regenerates in under three hours on 2 cores
# (docs/benchmark.md, "Reference agents"); protocol 1's 0.5-10 M steps would have taken 3-16 hours per algorithm.
EPISODES = 500        # one-player tables per run: a success rate's 95% interval within +-0.044
GAMES = 200           # games per run against the opponent: +-0.07 per run, +-0.031 over the five runs
EVAL_SEEDS = (900_000, 910_000, 920_000, 930_000, 940_000)  # run k's tables: seeds EVAL_SEEDS[k] + i, i < 10,000
QUICK_EPISODES = 12
QUICK_GAMES = 4

PROTOCOL = Protocol(
    version=3,
    budgets_since=2,
    tasks=(
        # one player, success rate; 1 = lookahead (pots that leave a next shot), the strongest one-player bot
        Task("Billiards-PotOne-v1", "task", budget=300_000, reference="lookahead", episodes=EPISODES),
        Task("Billiards-RunOut-v1", "task", budget=400_000, reference="lookahead", episodes=EPISODES),
        Task("Billiards-NineBall-v1", "task", budget=400_000, reference="lookahead", episodes=EPISODES),
        # two players, win rate against a fixed opponent; 1 = the opponent's own win rate against itself (~0.5:
        # "as strong as the opponent"; search64 was measured too, and does not beat ghost in 8-ball: 0.494)
        Task("Billiards-NineBall2P-v1", "game", budget=500_000, reference="ghost", episodes=GAMES,
             opponent="ghost"),
        Task("Billiards-EightBall-v1", "game", budget=500_000, reference="ghost", episodes=GAMES,
             opponent="ghost"),
        Task("Billiards-TenBall-v1", "game", budget=500_000, reference="ghost", episodes=GAMES,
             opponent="ghost"),
        # no pockets / its own rules: against the game's own bot
        Task("Billiards-ThreeCushion-v3", "game", budget=500_000, reference="carom", episodes=GAMES, since=3,
             opponent="carom"),
        Task("Billiards-Snooker-v2", "game", budget=500_000, reference="snooker", episodes=GAMES, since=3,
             opponent="snooker"),
    ),
    eval_seeds=EVAL_SEEDS,
)
QUICK = PROTOCOL.quick()
