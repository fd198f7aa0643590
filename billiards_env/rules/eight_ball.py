"""8-ball (World Pool-Billiard Association rules with call shots of the 8
only; simplifications in docs/rules.md).

Balls 1-7 (solids), 8, 9-15 (stripes). The break (cue ball in hand behind
the head string) must pocket a ball or drive at least four object balls to
a rail; the table is open after it. On an open table any ball but the 8 may
be hit first; the first legal shot after the break that pockets balls of
one group gives the shooter that group (both groups: the group of the ball
hit first). Then the shooter must hit a ball of the group first, and the 8
once the group is cleared, calling its pocket. A shot pocketing a ball of
the shooter's group (any ball on an open table, or on the break) keeps the
shooter at the table. The 8 pocketed on the break is respotted; otherwise
pocketing it wins only when the group was cleared before the shot, on a
legal shot, in the called pocket, and loses in every other case. A scratch
on the break gives the opponent ball in hand behind the head string, any
other foul ball in hand anywhere.

Balls off the table (``ShotInput.off_table``; docs/rules.md, "Balls off the
table"): driving any ball off the table, the cue ball included, is a foul
(``FOUL_OFF_TABLE``, WPA General Rules, standard fouls). The 8 driven off the
table loses the rack (WPA 8-ball, loss of rack: "drives the eight ball off
the table"; ``END_EIGHT_OFF``), except on the break, where WPA 8-ball's
spotting rule spots an 8 pocketed or driven off the table (the break is
still a foul: ball in hand for the opponent). No other object ball is ever
spotted: a jumped solid or stripe stays off the table and counts as gone
from its group. The cue ball off the table is ruled as a scratch: ball in
hand anywhere, behind the head string when it happens on the break (WPA
groups "Cue Ball Scratch or off the Table" as one foul).
"""
from __future__ import annotations

import numpy as np

from .common import Facts, Rules, foul_code, next_state
from .records import (END_EIGHT, END_EIGHT_EARLY, END_EIGHT_FOUL, END_EIGHT_OFF, END_EIGHT_POCKET, END_NONE,
                      FOUL_OFF_TABLE, FOUL_SCRATCH, GROUP_OPEN, GROUP_SOLIDS, GROUP_STRIPES, IN_HAND_ANYWHERE,
                      IN_HAND_KITCHEN, IN_HAND_NONE, PHASE_BREAK, PHASE_PLAY, Constraints, GameState, ShotInput,
                      ShotRecord)

EIGHT = 8
SOLIDS = np.arange(1, 8)
STRIPES = np.arange(9, 16)


def group_masks(B: int = 16) -> np.ndarray:
    """[3, B] bool: the balls of GROUP_OPEN (every object ball but the 8),
    GROUP_SOLIDS and GROUP_STRIPES."""
    m = np.zeros((3, B), dtype=bool)
    m[GROUP_SOLIDS, SOLIDS] = True
    m[GROUP_STRIPES, STRIPES] = True
    m[GROUP_OPEN] = m[GROUP_SOLIDS] | m[GROUP_STRIPES]
    return m


def _group_of(ball: np.ndarray) -> np.ndarray:
    return np.where((ball >= 1) & (ball <= 7), GROUP_SOLIDS, np.where(ball >= 9, GROUP_STRIPES, GROUP_OPEN))


class EightBallRules(Rules):
    name = "eight_ball"
    n_balls = 15
    game_ball = EIGHT
    groups = True
    game_ball_loses = True

    def _on_eight(self, game: GameState, pocket: np.ndarray) -> np.ndarray:
        """The shooter's group is assigned and cleared: the shot is on the 8."""
        own = game.group[np.arange(game.n), game.shooter]
        left = ((np.asarray(pocket) < 0) & group_masks()[own]).sum(axis=1)
        return (own != GROUP_OPEN) & (left == 0)

    def targets(self, game: GameState, pocket: np.ndarray) -> np.ndarray:
        """[E, B] legal first contacts: any object ball on the break, any but
        the 8 on an open table, the shooter's group, or the 8."""
        on = np.asarray(pocket) < 0
        own = game.group[np.arange(game.n), game.shooter]
        t = on & group_masks()[own]
        eight = self._on_eight(game, pocket) | ~t.any(axis=1)
        t[:, EIGHT] = eight & on[:, EIGHT]
        brk = game.phase == PHASE_BREAK
        t[brk] = on[brk]
        t[:, 0] = False
        t[game.over] = False
        return t

    def judge(self, game: GameState, shot: ShotInput) -> tuple[ShotRecord, GameState]:
        self.check(game, shot)
        f = Facts.of(shot)
        E = game.n
        ar = np.arange(E)
        s = game.shooter
        is_break = game.phase == PHASE_BREAK
        tg = self.targets(game, shot.pocket_before)
        first_ok = tg[ar, np.clip(f.first, 0, None)] & (f.first >= 1)
        no = np.zeros(E, dtype=bool)
        foul = foul_code(f, first_ok, is_break, no)
        legal = foul == 0
        on_eight = self._on_eight(game, shot.pocket_before) & ~is_break
        eight = f.pocketed[:, EIGHT]
        called = np.asarray(shot.called_pocket, dtype=np.int64)
        pocket8 = np.asarray(shot.pocket_after)[:, EIGHT]
        end = np.full(E, END_NONE, dtype=np.int64)
        live8 = eight & ~is_break
        end[live8 & legal & on_eight & (pocket8 == called)] = END_EIGHT
        end[live8 & legal & on_eight & (pocket8 != called)] = END_EIGHT_POCKET
        end[live8 & legal & ~on_eight] = END_EIGHT_EARLY
        end[live8 & ~legal] = END_EIGHT_FOUL
        eight_off = f.off_table[:, EIGHT]
        end[eight_off & ~is_break] = END_EIGHT_OFF       # loss of rack; on the break it is spotted (below)
        over = end != END_NONE
        winner = np.where(end == END_EIGHT, s, np.where(over, 1 - s, -1))

        # groups: the first legal shot after the break that pockets balls of one group
        own = game.group[ar, s].copy()
        pk = f.pocketed
        sol, stp = pk[:, SOLIDS].any(axis=1), pk[:, STRIPES].any(axis=1)
        picked = np.where(sol & stp, _group_of(f.first), np.where(sol, GROUP_SOLIDS, GROUP_STRIPES))
        assign = (own == GROUP_OPEN) & ~is_break & legal & (sol | stp) & ~over
        own = np.where(assign, picked, own)
        own_pk = (pk & group_masks()[own]).any(axis=1)
        keeps = legal & ~over & np.where(is_break, f.object_pocketed, own_pk)

        respot = np.zeros_like(pk)
        respot[:, EIGHT] = (eight | eight_off) & is_break
        rec = ShotRecord(legal=legal, foul=foul, turn_over=~keeps & ~over, game_over=over, winner=winner, end=end,
                         push_out=no, passed=no.copy(), respot=respot, shooter=s.copy())
        g = next_state(game, rec, foul, ~no)
        g.group[ar[assign], s[assign]] = own[assign]
        g.group[ar[assign], 1 - s[assign]] = np.where(own[assign] == GROUP_SOLIDS, GROUP_STRIPES, GROUP_SOLIDS)
        g.phase = np.full(E, PHASE_PLAY, dtype=np.int64)
        # a scratch on the break, or the cue ball off the table on it (ruled as a scratch): behind the head string
        scratch_break = is_break & ((foul == FOUL_SCRATCH) | ((foul == FOUL_OFF_TABLE) & f.cue_off))
        g.ball_in_hand = np.where(scratch_break, IN_HAND_KITCHEN,
                                  np.where(foul > 0, IN_HAND_ANYWHERE, IN_HAND_NONE)).astype(np.int64)
        return rec, g

    def constraints(self, game: GameState, pocket: np.ndarray) -> Constraints:
        E = game.n
        live = ~game.over
        no = np.zeros(E, dtype=bool)
        return Constraints(shooter=game.shooter.copy(), ball_in_hand=np.where(live, game.ball_in_hand, IN_HAND_NONE),
                           targets=self.targets(game, pocket), push_out_allowed=no, may_pass=no.copy(),
                           call_needed=live & self._on_eight(game, pocket) & (game.phase != PHASE_BREAK),
                           is_break=live & (game.phase == PHASE_BREAK), over=game.over.copy())
