"""Billiards-NineBall-v1: simplified single-player 9-ball after a seeded break."""
from __future__ import annotations

import numpy as np

from ...bots.geometry.breaks import break_shots
from ...physics import BallState, strike_velocity
from ...physics.state import free_spot
from ...rules.racks import nine_ball_rack
from .base import Judgement, ShotOutcome, Task


class NineBall(Task):
    """Billiards-NineBall-v1: simplified single-player 9-ball.

    Rules:

    1. Each episode starts from a seeded 9-ball rack (1 on the foot spot, 9 in
       the centre, others shuffled) broken from the head-spot area at
       ~``break_speed`` (8 m/s) with small seeded variation of position, aim,
       speed and tip offset. A cue ball pocketed on the break is respotted on
       the head spot (or the nearest free spot behind it); a 9 pocketed on
       the break is respotted on the foot spot (or the nearest free spot).
    2. The legal target is the lowest-numbered ball on the table; the cue
       ball must hit it first.
    3. A wrong first contact (another ball, or none) is a foul; a pocketed
       cue ball is a scratch. Either ends the episode (terminated).
    4. Balls pocketed on a legal shot stay down (+``pocket`` each); pocketing
       the 9 on a legal shot (directly or by combination) wins: success,
       episode terminated. A 9 pocketed on a foul or scratch ends the episode
       without success.
    5. A legal shot that pockets nothing is a miss: the player shoots again
       from where the balls lie (no turn passes). The episode is truncated
       after ``max_shots`` shots (default 20).
"""

    name = "nine_ball"
    env_id = "Billiards-NineBall-v1"
    class_prefix = "NineBall"

    def validate(self, cfg) -> None:
        if cfg.n_balls != 9:
            raise ValueError("nine_ball uses exactly nine object balls (n_balls: 9)")

    def reset(self, core, idx) -> BallState:
        """Seeded 9-ball rack and break: cue ball near the head spot, struck at
        ~break_speed towards the 1-ball with small random variation; a 9 or
        cue ball pocketed on the break is respotted (foot / head spot)."""
        t, p = core.table, core.params
        u = core.streams.uniform(idx, 12)  # 7 rack shuffle, 2 cue position, speed, 2 offsets
        z = core.streams.normal(idx, 1)[:, 0]  # aim
        pos = nine_ball_rack(t, p.R, u[:, :7])
        pos[:, 0], phi, speed, a, b = break_shots(t, pos[:, 1], core.cfg.break_speed, u[:, 7:], z)
        res = core.simulate(strike_velocity(BallState.from_positions(pos), phi, speed, a, b, p))
        out = core.at_rest(res.state)
        foot, head = (t.width / 2, 0.75 * t.length), (t.width / 2, 0.25 * t.length)
        for e in np.nonzero((out.pocket[:, 9] >= 0) | (out.pocket[:, 0] >= 0))[0]:
            for ball, spot, dy in ((9, foot, 1.0), (0, head, -1.0)):
                if out.pocket[e, ball] >= 0:  # respot the 9 (foot spot) or the cue ball (head spot)
                    x, y, found = free_spot(out.pos[e], out.pocket[e] < 0, spot[0], spot[1], 0.0, dy,
                                            t.width, t.length, p.R, core.pockets)
                    if not found:
                        raise RuntimeError("no free spot on the table to respot a ball")
                    out.pos[e, ball] = (x, y)
                    out.pocket[e, ball] = -1
        return out

    def judge(self, shot: ShotOutcome) -> Judgement:
        foul = ~shot.contact
        nine = shot.pocketed[:, 9]
        scratch = shot.scratch
        return Judgement(foul=foul, success=~foul & ~scratch & nine, terminated=scratch | foul | nine)
