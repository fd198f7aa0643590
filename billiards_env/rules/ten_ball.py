"""10-ball (World Pool-Billiard Association rules, the Ten Ball section;
simplifications in docs/rules.md).

Balls 1-10, racked in a triangle with the 1 on the foot spot and the 10 in
the centre; the lowest-numbered ball on the table is the only legal first
contact. The break (cue ball in hand behind the head string) must hit the 1
first and pocket a ball or drive at least four object balls to a rail; a
10 pocketed on the break is spotted, and a legal break that pockets a ball
keeps the breaker at the table. Every other shot is a called shot: the
shooter names a ball and a pocket (or calls a safety). The shooter stays at
the table only when the called ball drops in the called pocket on a legal
shot; pocketing the 10 that way wins. A ball pocketed otherwise without a
foul (not the called ball, the called ball in another pocket, or anything
on a called safety) is pocketed illegally: it stays down (the 10 is
spotted), the turn passes and the incoming player chooses to shoot or to
hand the shot back. The shot right after a legal break may be a push-out,
as in 9-ball. Every foul gives the opponent ball in hand anywhere (a 10
pocketed on a foul is spotted); a player's third consecutive foul loses.

Balls off the table (``ShotInput.off_table``; docs/rules.md, "Balls off the
table"): driving any ball off the table, the cue ball included, is a foul
(``FOUL_OFF_TABLE``, WPA General Rules, standard fouls; ball in hand anywhere).
WPA 10-ball's spotting rule: only the 10 is ever spotted (pocketed on a foul,
on a push-out or illegally, or driven off the table); any other ball driven
off the table stays off. The cue ball off the table comes back in hand.
"""
from __future__ import annotations

import numpy as np

from .common import RotationShot, Rules, in_phases, next_state
from .nine_ball import NineBallRules
from .records import (CALL_SAFETY, END_NONE, END_TEN, END_THREE_FOULS, IN_HAND_ANYWHERE, IN_HAND_NONE, PHASE_BREAK,
                      PHASE_OPTION, PHASE_PUSHED, Constraints, GameState, ShotInput, ShotRecord)

TEN = 10
PASS_PHASES = (PHASE_PUSHED, PHASE_OPTION)  # the shot may be handed back after a push-out or an illegal pot


class TenBallRules(Rules):
    name = "ten_ball"
    n_balls = 10
    game_ball = TEN
    calls_ball = True

    def judge(self, game: GameState, shot: ShotInput) -> tuple[ShotRecord, GameState]:
        self.check(game, shot)
        r = RotationShot.of(game, shot, PASS_PHASES)
        f, legal, played, three = r.facts, r.legal, r.played, r.three
        E, s = game.n, game.shooter
        ar = np.arange(E)
        called_shot = played & ~r.is_break & ~r.pushed              # the shots that need a call
        ball = np.asarray(shot.called_ball, dtype=np.int64)
        pocket = np.asarray(shot.called_pocket, dtype=np.int64)
        b = np.clip(ball, 0, self.n_balls)
        made = (called_shot & (ball > CALL_SAFETY) & f.pocketed[ar, b]
                & (np.asarray(shot.pocket_after)[ar, b] == pocket))  # the called ball in the called pocket
        win = legal & made & (ball == TEN)
        over = win | three
        winner = np.where(win, s, np.where(three, 1 - s, -1))
        end = np.where(win, END_TEN, np.where(three, END_THREE_FOULS, END_NONE))
        keeps = legal & ~over & np.where(r.is_break, f.object_pocketed, made)
        option = legal & called_shot & f.object_pocketed & ~made     # pocketed illegally, no foul
        respot = np.zeros_like(f.pocketed)
        respot[:, TEN] = (f.pocketed[:, TEN] | f.off_table[:, TEN]) & played & ~win  # the 10 off: a foul, spotted
        rec = ShotRecord(legal=legal, foul=r.foul, turn_over=~keeps & ~over, game_over=over, winner=winner, end=end,
                         push_out=r.pushed, passed=r.passed, respot=respot, shooter=s.copy(), option=option)
        g = next_state(game, rec, r.foul, played)
        g.phase = r.next_phase(option)
        g.ball_in_hand = np.where(r.foul > 0, IN_HAND_ANYWHERE, IN_HAND_NONE).astype(np.int64)
        return rec, g

    def constraints(self, game: GameState, pocket: np.ndarray) -> Constraints:
        c = NineBallRules.constraints(self, game, pocket)  # the lowest ball; push-out after a legal break
        live = ~game.over
        return Constraints(shooter=c.shooter, ball_in_hand=c.ball_in_hand, targets=c.targets,
                           push_out_allowed=c.push_out_allowed, may_pass=live & in_phases(game.phase, PASS_PHASES),
                           call_needed=live & (game.phase != PHASE_BREAK), is_break=c.is_break, over=c.over)
