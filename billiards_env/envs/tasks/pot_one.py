"""Billiards-PotOne-v1: pot one object ball in one shot."""
from __future__ import annotations

import numpy as np

from .base import Judgement, ShotOutcome, Task, random_tables


class PotOne(Task):
    """Billiards-PotOne-v1: the cue ball and one object ball at random
    positions; one shot per episode. Success (``info["success"]``): the object
    ball is pocketed and the cue ball is not. Every episode terminates after
    its shot. Foul: the cue ball misses the object ball.
"""

    name = "pot_one"
    env_id = "Billiards-PotOne-v1"
    class_prefix = "PotOne"

    def validate(self, cfg) -> None:
        if cfg.n_balls != 1:
            raise ValueError("pot_one uses exactly one object ball (n_balls: 1)")

    def reset(self, core, idx):
        return random_tables(core, idx)

    def judge(self, shot: ShotOutcome) -> Judgement:
        return Judgement(foul=shot.first_contact < 1, success=shot.pocketed[:, 1] & ~shot.scratch,
                         terminated=np.ones(len(shot.target), dtype=bool))
