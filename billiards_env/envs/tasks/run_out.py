"""Billiards-RunOut-v1: pot every object ball, one after another."""
from __future__ import annotations

from .base import Judgement, ShotOutcome, Task, random_tables


class RunOut(Task):
    """Billiards-RunOut-v1: ``n_balls`` object balls (default 5) at random
    positions. Any object ball may be hit first and pocketed; the legal
    *target* (for relative aim, contact reward and shaping) is the
    lowest-numbered ball on the table. The episode continues while every shot
    pockets at least one ball without foul or scratch. It terminates on a
    miss (nothing pocketed), a scratch (cue ball pocketed), a foul (the cue
    ball hits no object ball) or when the table is cleared (success); it is
    truncated after ``max_shots`` shots (default 10).
"""

    name = "run_out"
    env_id = "Billiards-RunOut-v1"
    class_prefix = "RunOut"

    def reset(self, core, idx):
        return random_tables(core, idx)

    def judge(self, shot: ShotOutcome) -> Judgement:
        foul = shot.first_contact < 1
        scratch, cleared = shot.scratch, shot.cleared
        return Judgement(foul=foul, success=~foul & ~scratch & cleared,
                         terminated=scratch | foul | (shot.n_pocketed == 0) | cleared)
