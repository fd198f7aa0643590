"""``random``: uniformly random shots, a floor for every other bot."""
from __future__ import annotations

import numpy as np

from ..physics.strike import Shots, draw_to_speed
from ..contract.plan import ShotPlan

N_POCKETS = 6


class RandomBot:
    """Per table: an aim uniform over the circle, a cue draw uniform over the
    env's range (``view.min_draw`` .. ``params.max_draw``), tip offsets
    uniform over the miscue disc, with ball in hand a spot uniform over the
    table (``legal_placement`` makes it legal), a push-out or pass declared
    half the time where allowed and a random called pocket."""

    name = "random"

    def __init__(self, seed: int | None = 0):
        self.rng = np.random.default_rng(seed)

    def act(self, view) -> ShotPlan:
        n, p, t, rng = view.n, view.params, view.table, self.rng
        phi = rng.uniform(-np.pi, np.pi, n)
        speed = draw_to_speed(rng.uniform(view.min_draw, p.max_draw, n), p)
        r = p.miscue_limit * 0.999 * np.sqrt(rng.random(n))
        th = rng.uniform(0.0, 2.0 * np.pi, n)
        xy = np.column_stack([rng.uniform(p.R, t.width - p.R, n), rng.uniform(p.R, t.length - p.R, n)])
        declare = rng.random(n) < 0.5
        pocket = rng.integers(0, N_POCKETS, n)
        placement = np.full((n, 2), np.nan)
        h = np.nonzero(view.in_hand)[0]
        if len(h):
            placement[h], _ = view.legal_placement(xy[h], h)
        return ShotPlan.of(Shots(phi, np.minimum(speed, p.max_speed), r * np.cos(th), r * np.sin(th)),
                           placement, declare, pocket)
