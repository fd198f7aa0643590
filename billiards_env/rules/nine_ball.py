"""9-ball (World Pool-Billiard Association rules; simplifications in docs/rules.md).

Balls 1-9; the lowest-numbered ball on the table is the only legal first
contact. The break (cue ball in hand behind the head string) must hit the 1
first and pocket a ball or drive at least four object balls to a rail. A
shot pocketing a ball legally keeps the shooter at the table; the 9
pocketed on a legal shot wins, the break included; a 9 pocketed on a foul
or a push-out is respotted. The shot right after a legal break (no foul on
it: WPA 2.4) may be declared a push-out (no contact or rail needed); the
opponent then shoots or passes the shot back. Every foul gives the opponent ball in hand anywhere; a
player's third consecutive foul loses the game.

Option (``NineBallRules(spot_break_nine=True)``, ``GameConfig(break_nine=
"spotted")``, the rule of some professional events): a 9 pocketed on the
break is respotted and does not win; it counts as a ball pocketed, so a
legal break that pockets it keeps the breaker at the table.

Balls off the table (``ShotInput.off_table``; docs/rules.md, "Balls off the
table"): driving any ball off the table, the cue ball included, is a foul
(``FOUL_OFF_TABLE``, WPA General Rules, standard fouls; ball in hand anywhere
for the opponent, as after every foul). WPA 9-ball's spotting rule (2.6):
the 9 pocketed on a foul or a push-out, or driven off the table, is spotted;
no other object ball is ever spotted, so a jumped 1-8 stays off the table.
The cue ball off the table comes back in hand.
"""
from __future__ import annotations

import numpy as np

from .common import RotationShot, Rules, lowest_on_table, next_state
from .records import (END_NINE, END_NONE, END_THREE_FOULS, IN_HAND_ANYWHERE, IN_HAND_NONE, PHASE_AFTER_BREAK,
                      PHASE_BREAK, PHASE_PUSHED, Constraints, GameState, ShotInput, ShotRecord)

NINE = 9


class NineBallRules(Rules):
    name = "nine_ball"
    n_balls = 9
    game_ball = NINE  # a rotation game on fewer balls sets its own

    def __init__(self, spot_break_nine: bool = False):
        self.spot_break_nine = bool(spot_break_nine)

    def judge(self, game: GameState, shot: ShotInput) -> tuple[ShotRecord, GameState]:
        self.check(game, shot)
        r = RotationShot.of(game, shot)
        f, legal, pushed, played, three = r.facts, r.legal, r.pushed, r.played, r.three
        nine = f.pocketed[:, self.game_ball] & played
        nine_off = f.off_table[:, self.game_ball] & played  # a foul, so never a win: spotted (WPA 9-ball 2.6)
        win = legal & nine & ~pushed & ~(r.is_break & self.spot_break_nine)
        over = win | three
        winner = np.where(win, game.shooter, np.where(three, 1 - game.shooter, -1))
        end = np.where(win, END_NINE, np.where(three, END_THREE_FOULS, END_NONE))
        keeps = played & legal & ~pushed & f.object_pocketed
        respot = np.zeros_like(f.pocketed)
        respot[:, self.game_ball] = (nine | nine_off) & ~over
        rec = ShotRecord(legal=legal, foul=r.foul, turn_over=~keeps & ~over, game_over=over, winner=winner, end=end,
                         push_out=pushed, passed=r.passed, respot=respot, shooter=game.shooter.copy())
        g = next_state(game, rec, r.foul, played)
        g.phase = r.next_phase()
        g.ball_in_hand = np.where(r.foul > 0, IN_HAND_ANYWHERE, IN_HAND_NONE).astype(np.int64)
        return rec, g

    def constraints(self, game: GameState, pocket: np.ndarray) -> Constraints:
        E, B = np.shape(pocket)
        targets = np.zeros((E, B), dtype=bool)
        low = lowest_on_table(pocket)
        has = low > 0
        targets[np.nonzero(has)[0], low[has]] = True
        targets[game.over] = False
        live = ~game.over
        return Constraints(shooter=game.shooter.copy(), ball_in_hand=np.where(live, game.ball_in_hand, IN_HAND_NONE),
                           targets=targets, push_out_allowed=live & (game.phase == PHASE_AFTER_BREAK),
                           may_pass=live & (game.phase == PHASE_PUSHED), call_needed=np.zeros(E, dtype=bool),
                           is_break=live & (game.phase == PHASE_BREAK), over=game.over.copy())
