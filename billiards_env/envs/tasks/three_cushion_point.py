"""Billiards-ThreeCushionPoint-v1: make a three-cushion point in one shot."""
from __future__ import annotations

import numpy as np

from ...rules.three_cushion import CONTACTS_KEPT, POINT_CUSHIONS, point_made
from .base import Judgement, ShotOutcome, Task, random_tables


def _reached(shot: ShotOutcome) -> np.ndarray:
    """[n, 2] whether the cue ball touched object ball 1, ball 2."""
    from ...physics import constants as C
    c, n = shot.contacts, shot.n_contacts
    K = c.shape[1]
    valid = np.arange(K)[None, :] < np.minimum(n, K)[:, None]
    ball = valid & (c[..., 0] == C.EV_BALL_BALL)
    return np.stack([(ball & (c[..., 1] == b)).any(axis=1) for b in (1, 2)], axis=1)


class ThreeCushionPoint(Task):
    """Billiards-ThreeCushionPoint-v1: three balls at random positions on the
    carom match table with carom equipment (``Table.carom()``,
    ``PhysicsParams.carom()``): ball 0 the cue ball, 1 and 2 the object balls
    (the opponent's ball and the red); one shot per episode, and every
    episode terminates after it.

    **Success** (``info["success"]``): a three-cushion point, as the UMB rule
    (rules.md, Three-cushion): the cue ball contacts both object balls and
    touches cushions at least three times before its first contact with the
    second (read from the order of the cue ball's contacts, which the
    simulator keeps for this task). **Foul**: the cue ball touches no ball.

    **Observation**: the one-player table layout (``observation: table``):
    per ball x / width, y / length and on-table, the legal target's one-hot
    (ball 1: the aim a0 is relative to it) and the shot count.

    **Reward** (weights in the config's ``reward``; defaults in brackets),
    shaped towards the point: ``success`` [1.0] for the point, ``contact``
    [0.2] when the cue ball reaches both object balls, ``shaping`` [0.3]
    times min(cushions before the second ball, 3) / 3 for a shot that reaches
    both, ``foul`` [-0.1] when it touches none; ``pocket`` and ``scratch``
    are 0 (no pockets). A point earns 1.5 in all; reaching both balls with two
    cushions first 0.4.
"""

    name = "three_cushion_point"
    env_id = "Billiards-ThreeCushionPoint-v1"
    class_prefix = "ThreeCushionPoint"
    contacts = CONTACTS_KEPT

    def validate(self, cfg) -> None:
        if cfg.n_balls != 2:
            raise ValueError("three_cushion_point uses exactly two object balls (n_balls: 2)")
        if cfg.table != "carom":
            raise ValueError("three_cushion_point is played on the carom table (table: carom)")

    def reset(self, core, idx):
        return random_tables(core, idx)

    def legal_target(self, pos, pocket):
        return np.ones(len(pocket), dtype=np.int64)  # either ball may come first; a0 aims relative to ball 1

    def judge(self, shot: ShotOutcome) -> Judgement:
        point, _ = point_made(shot.contacts, shot.n_contacts)
        return Judgement(foul=shot.first_contact < 1, success=point,
                         terminated=np.ones(len(shot.target), dtype=bool))

    def reward_terms(self, w, shot: ShotOutcome, judged: Judgement, potential_before, potential_after) -> dict:
        _, before = point_made(shot.contacts, shot.n_contacts)
        both = _reached(shot).all(axis=1)
        zero = np.zeros(len(shot.target))
        return {"pocket": zero, "scratch": zero.copy(), "foul": w.foul * judged.foul + 0.0,
                "contact": w.contact * both + 0.0, "success": w.success * judged.success + 0.0,
                "shaping": w.shaping * both * np.minimum(before, POINT_CUSHIONS) / POINT_CUSHIONS + 0.0}
