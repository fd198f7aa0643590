"""The lookahead's searched break: candidate strikes along the head
string, judged under noise on the first breaking racks and kept once per
game and table."""
from __future__ import annotations

import numpy as np

from ...contract.plan import ShotPlan
from ...physics.strike import Shots

BREAK_BEHIND = 0.02                # m: a searched break's cue ball this far behind the head string
BREAK_X = 0.35                     # m: and within this of the table's long axis
BREAK_OFF = 0.6                    # the aim at the front ball's centre, offset across by up to this (units of R)
BREAK_SPEEDS = (6.0, 9.0)          # m/s: range of the searched breaks' speeds
BREAK_HEIGHTS = (-0.5, 0.2)        # range of their tip heights (units of R): draw to follow
BREAK_REFINE = 6                   # the best searched breaks re-judged with BREAK_REFINE_X times the samples
BREAK_REFINE_X = 4


class Breaks:
    """The searched break of ``GameLookahead`` (a mixin: it reads the bot's ``budget``, ``rng`` and
    ``break_strikes`` and values breaks with its ``values``)."""

    def break_plan(self, view, rows, strikes) -> ShotPlan:
        """Breaks on view rows ``rows`` [m] from ``strikes`` [m, 4]: (the cue ball's offset across the table's
        long axis (m), the aim's offset across the front ball (units of R), speed, tip height); the cue ball
        ``BREAK_BEHIND`` behind the head string (made legal), aimed at the rack's front ball (the object ball
        nearest to it)."""
        W, R_ = view.table.width, view.params.R
        want = np.column_stack([W / 2 + strikes[:, 0], np.full(len(rows), view.marks.head_string - BREAK_BEHIND)])
        cue, _ = view.legal_placement(want, rows)
        pos, on = view.pos[rows], view.on_table[rows]
        d = pos[:, 1:] - cue[:, None]
        dist = np.where(on[:, 1:], np.linalg.norm(d, axis=-1), np.inf)
        front = np.argmin(dist, axis=1)
        u = d[np.arange(len(rows)), front] / dist[np.arange(len(rows)), front][:, None]
        aim = pos[np.arange(len(rows)), front + 1] + (strikes[:, 1] * R_)[:, None] * np.column_stack([-u[:, 1], u[:, 0]])
        phi = np.arctan2(aim[:, 1] - cue[:, 1], aim[:, 0] - cue[:, 0])
        return ShotPlan.of(Shots(phi, np.minimum(strikes[:, 2], view.params.max_speed), 0.0, strikes[:, 3]),
                           placement=cue)

    def searched_break(self, view, rows) -> np.ndarray:
        """The break strike [4] (``break_plan``) this bot plays in ``view.game`` on ``view.table``, searched on
        the first call and kept (the racks differ only by their gaps and the balls' order): ``break_search``
        candidates (the first one ``ghost``'s nominal break), each previewed ``break_samples`` times under noise
        on each of up to ``break_racks`` of the breaking rows ``rows`` and valued as any shot (``values``: the
        9 on the break wins; keeping the table is worth the leave; a foul gives the opponent ball in hand); the
        ``BREAK_REFINE`` best judged again with ``BREAK_REFINE_X`` times the samples; the best mean is kept."""
        key = (view.game, id(view.table), id(view.params))
        hit = self.break_strikes.get(key)
        if hit is not None and hit[0] is view.table and hit[1] is view.params:
            return hit[2]
        C, racks = self.budget.break_search, rows[:self.budget.break_racks]
        rng = np.random.default_rng(self.rng.integers(2 ** 63))
        cand = np.column_stack([rng.uniform(-BREAK_X, BREAK_X, C), rng.uniform(-BREAK_OFF, BREAK_OFF, C),
                                rng.uniform(*BREAK_SPEEDS, C), rng.uniform(*BREAK_HEIGHTS, C)])
        cand[0] = (0.0, 0.0, 8.0, -0.025)  # ghost's nominal break (bots.ghost.BREAK_SPEED, its mean tip height)

        def judge(idx, samples):
            rep = np.repeat(idx, len(racks) * samples)
            r = np.tile(np.repeat(racks, samples), len(idx))
            pv = view.preview(self.break_plan(view, r, cand[rep]), r, noise=self.noise(view), rng=rng)
            self.sims += len(r)
            return self.values(view, pv).reshape(len(idx), -1).mean(axis=1)

        S = self.budget.break_samples
        v = judge(np.arange(C), S)
        top = np.argsort(-v, kind="stable")[:BREAK_REFINE]
        v2 = (v[top] + BREAK_REFINE_X * judge(top, BREAK_REFINE_X * S)) / (1 + BREAK_REFINE_X)
        best = cand[top[np.argmax(v2)]].copy()
        self.break_strikes[key] = (view.table, view.params, best)
        self.last_break_search = dict(candidates=cand, value=v, refined=top, refined_value=v2)
        return best
