"""Snooker (WPBSA Official Rules of the Games of Snooker and English
Billiards, Section 2 Definitions and Section 3 The Game; simplifications in
docs/rules.md).

Balls: 0 the cue ball, 1..15 the reds (1 point each), 16..21 the colours
yellow, green, brown, blue, pink, black (2..7 points). A player's turn
(a break) continues while each stroke scores. While reds remain, the ball
on is any red, and after each potted red a colour the striker nominates
(``ShotInput.called_ball``); a potted colour is respotted while reds remain
(and the colour taken after the last red). With no reds left the colours
are on in ascending value and stay down when potted. A foul (the cue ball
pocketed, no ball hit, a ball not on hit first, a ball not on pocketed)
gives the opponent its value: at least 4, or the value of the ball on, of
the ball hit first or of a ball pocketed, whichever is highest; colours
pocketed on a foul are respotted, reds stay down. After a foul the incoming
player may play, or put the offender back in (``ShotInput.passed``), or, when the referee called
a miss (``judge_miss``: a foul that failed to hit a ball on although a
full-ball contact lay open, with no player needing snookers), have the
balls replaced where they were and the offender play again
(``ShotInput.replaced``); a cue ball at rest touching a ball
(``touching``) must be played away from it: hitting it first is a push
stroke, and with a ball on touched, hitting nothing is no foul; if
the cue ball lies snookered on every ball on (``snookered``, decided from
the position), the incoming player may nominate a free ball
(``called_ball``): it counts as the ball on, must be the first ball hit,
and is respotted when potted. After an in-off the cue ball is in hand in
the D. With only the black left the first score or foul ends the frame; on
equal scores the black is spotted (potted or not) and played again with
the cue ball in hand.

Balls forced off the table (``ShotInput.off_table``; docs/rules.md, "Balls
off the table"): WPBSA Section 2 defines a ball forced off the table (it
comes to rest other than on the bed of the table or in a pocket); Section 3
makes it a foul (``FOUL_OFF_TABLE``) with the penalty of the ball on or the
ball concerned, at least 4 (the ball forced off counts as the ball
concerned, like a ball pocketed on a foul), and puts the balls back: a red
forced off stays off, a colour is spotted (as a colour pocketed on a foul),
and the cue ball forced off is in hand in the D (as after an in-off). With
only the black left, forcing it off is a foul and so ends the frame (or,
on equal scores, re-spots the black) as any other foul does.
"""
from __future__ import annotations

import numpy as np
import numba

from ..physics.state import SPOT_CLEAR, SPOT_EDGE, spot_free
from .common import Rules, next_state
from .placement import d_of, legal_spots
from .records import (END_LAST_BLACK, END_NONE, FOUL_NO_CONTACT, FOUL_NONE, FOUL_OFF_TABLE, FOUL_PUSH, FOUL_SCRATCH,
                      FOUL_WRONG_BALL, FOUL_WRONG_POT, IN_HAND_D, IN_HAND_NONE, PHASE_BREAK, PHASE_COLOUR, PHASE_OPTION,
                      PHASE_PLAY, Constraints, GameState, ShotInput, ShotRecord)

N_REDS = 15
REDS = slice(1, 1 + N_REDS)
FIRST_COLOUR = 1 + N_REDS          # the yellow; the colours are FIRST_COLOUR .. BLACK in ascending value
BLACK = FIRST_COLOUR + 5
N_BALLS = BLACK                    # object balls
VALUE = np.array([0] + [1] * N_REDS + [2, 3, 4, 5, 6, 7], dtype=np.int64)  # points of each ball
MIN_FOUL = 4                       # the least penalty of a foul (WPBSA Section 3, rule 12)
SCORE_SCALE = 147.0                # observed scores and points left are divided by the maximum break
SNOOKER_R = 0.02625                # m, the ball radius of PhysicsParams.snooker() (the default for ``snookered``)
# The cue ball touches a ball whose centre lies within 2R plus this (m): above the solver's rounding of a
# resting contact, below SPOT_CLEAR (1e-6 m), so a placed or respotted ball never counts as touching.
TOUCH_TOL = 5e-7
# A grazing path is obstructed if a ball not on comes nearer to it than 2R less this (m): balls touching the
# path at exactly 2R (a frozen neighbour) do not obstruct, as the rules' "wholly or partially obstructed" reads.
OBSTRUCT_TOL = 1e-9


def colour_on_table(before: np.ndarray) -> np.ndarray:
    """The lowest-valued colour on each table [E] (-1 none); ``before`` [E, B] balls on the table."""
    on = before[:, FIRST_COLOUR:]
    return np.where(on.any(axis=1), FIRST_COLOUR + np.argmax(on, axis=1), -1).astype(np.int64)


def balls_on(phase: np.ndarray, before: np.ndarray, nominated: np.ndarray | None = None) -> np.ndarray:
    """[E, B] the balls on: the reds while reds remain, a colour after a red
    (the ``nominated`` one [E], -1: any colour), the lowest colour when no
    reds remain."""
    E, B = before.shape
    on = np.zeros((E, B), dtype=bool)
    reds_left = before[:, REDS].any(axis=1)
    colour = phase == PHASE_COLOUR
    red = reds_left & ~colour
    on[:, REDS] = before[:, REDS] & red[:, None]
    nom = np.full(E, -1, dtype=np.int64) if nominated is None else nominated
    any_colour = colour & (nom < 0)
    on[:, FIRST_COLOUR:] |= before[:, FIRST_COLOUR:] & any_colour[:, None]
    ar = np.arange(E)
    one = colour & (nom >= 0)
    on[ar[one], nom[one]] = True
    low = colour_on_table(before)
    clear = ~reds_left & ~colour & (low >= 0)
    on[ar[clear], low[clear]] = True
    return on


def snookered(pos: np.ndarray, before: np.ndarray, on: np.ndarray, R: float = SNOOKER_R) -> np.ndarray:
    """[E] whether the cue ball (ball 0 at ``pos [E, B, 2]``) is snookered
    (WPBSA Section 2: a straight stroke to every ball on is wholly or partly
    obstructed by balls not on): for every ball on, at least one of the two
    straight paths that graze its extreme edges passes within 2R of a ball
    not on before the cue ball reaches it. ``before`` [E, B] balls on the
    table, ``on`` [E, B] the balls on. Cushions never obstruct here."""
    return on.any(axis=1) & ~open_on(pos, before, on, R).any(axis=1)


def open_on(pos: np.ndarray, before: np.ndarray, on: np.ndarray, R: float = SNOOKER_R) -> np.ndarray:
    """[E, B] the balls on (``on``) that the cue ball (ball 0 at ``pos``) can
    strike at both extreme edges in a straight line, no ball not on within
    2R of either grazing path (so every contact between them, the full-ball
    one included, is open too): ``snookered``'s test per ball, and the miss
    rule's "clear path to a full-ball contact" (``judge_miss``)."""
    E, B = before.shape
    c = pos[:, 0]                                             # [E, 2]
    d = pos - c[:, None]                                      # [E, B, 2]
    L = np.hypot(d[..., 0], d[..., 1])
    L = np.where(L > 0, L, 1.0)
    base = np.arctan2(d[..., 1], d[..., 0])
    half = np.arcsin(np.clip(2 * R / L, 0.0, 1.0))            # grazing paths at base +- half
    reach = L * np.cos(half)                                  # cue-centre travel to the grazing contact
    blockers = before & ~on
    blockers[:, 0] = False
    clear = np.ones((E, B), dtype=bool)
    for sgn in (1.0, -1.0):
        a = base + sgn * half
        u = np.stack([np.cos(a), np.sin(a)], axis=-1)          # [E, T, 2]
        # every ball q against every path to target t: projection and distance
        rel = pos[:, None, :, :] - c[:, None, None, :]        # [E, 1, Q, 2]
        s = np.einsum("etk,eqk->etq", u, rel[:, 0])           # [E, T, Q] along the path
        perp = np.abs(u[..., 0][..., None] * rel[..., 1] - u[..., 1][..., None] * rel[..., 0])  # [E, T, Q]
        sc = np.clip(s, 0.0, reach[..., None])
        dist = np.sqrt(np.maximum(perp ** 2 + (s - sc) ** 2, 0.0))
        hit = blockers[:, None, :] & (dist < 2 * R - OBSTRUCT_TOL)
        hit &= ~np.eye(B, dtype=bool)[None]                   # a ball never obstructs its own path
        clear &= ~hit.any(axis=2)
    return clear & on


def touching(pos: np.ndarray, before: np.ndarray, R: float = SNOOKER_R) -> np.ndarray:
    """[E, B] the object balls on the table (``before``) that the cue ball
    (ball 0 at ``pos`` [E, B, 2], on the table) touches: centres within
    2R + ``TOUCH_TOL`` (WPBSA Section 3, Rule 15, the touching ball)."""
    d = np.linalg.norm(pos - pos[:, :1], axis=2)
    out = before & (d < 2 * R + TOUCH_TOL) & before[:, :1]
    out[:, 0] = False
    return out


def points_left(before: np.ndarray, phase: np.ndarray) -> np.ndarray:
    """[E] the most points the balls on the table can still score: 8 per red
    (the red and the black after it), the colours' face values, and 7 more
    when a colour is on after a potted red (``before`` [E, B] on the table)."""
    reds = before[:, REDS].sum(axis=1)
    colours = (before[:, FIRST_COLOUR:] * VALUE[None, FIRST_COLOUR:]).sum(axis=1)
    return reds * (VALUE[1] + VALUE[BLACK]) + colours + VALUE[BLACK] * (phase == PHASE_COLOUR)


def needs_snookers(score: np.ndarray, left: np.ndarray) -> np.ndarray:
    """[E] either player trails by more than the points ``left`` (``score`` [E, 2]): they need snookers."""
    return np.abs(score[:, 0] - score[:, 1]) > left


def judge_miss(failed: np.ndarray, open_path: np.ndarray, needs: np.ndarray) -> np.ndarray:
    """[E] the referee calls a miss (WPBSA Section 3, Rule 14), as this
    rules layer judges it: the striker failed to hit a ball on first
    (``failed``: no contact, or another ball first), the cue ball had a clear
    straight line to a full-ball contact on some ball on (``open_path``, both
    edges unobstructed; the Rule's case where a miss is called whatever the
    striker's effort), and neither player needed snookers before or after
    the stroke (``needs``: the Rule's exception; the referee's judgement of
    intent and of a thin but open edge is not modelled)."""
    return failed & open_path & ~needs


# The last resort of the colour respot search: steps of R / 4 past a pocket's capture circle on the line.
LINE_STEP = 0.25
LINE_EPS = 1e-9                    # m: a point on the line is taken this far past the edge of a ball it would touch


@numba.njit(cache=True, nogil=True)
def _line_spot(pos, on, x, y, sgn, width, length, R, pockets):
    """The nearest free point to (x, y) on the line x = const going
    ``sgn`` (+1: towards the top cushion, -1: towards the bottom one),
    the point itself included: every ball on the table within 2R of the
    line shuts an interval of it, which the search steps past; a point in a
    pocket's capture circle is stepped past by R / 4. Free: ``spot_free``
    (edge R + SPOT_EDGE, min_dist 2R + SPOT_CLEAR). Returns (y, found)."""
    edge, md = R + SPOT_EDGE, 2 * R + SPOT_CLEAR
    for _ in range(1000):
        if y < edge or y > length - edge:
            return y, False
        moved = False
        for q in range(pos.shape[0]):
            if on[q]:
                dx = x - pos[q, 0]
                if abs(dx) < md:
                    h = np.sqrt(md * md - dx * dx)
                    if abs(y - pos[q, 1]) < h:
                        y = pos[q, 1] + sgn * (h + LINE_EPS)
                        moved = True
        if moved:
            continue
        if spot_free(x, y, pos, on, width, length, edge, pockets, md):
            return y, True
        y += sgn * LINE_STEP * R
    return y, False


@numba.njit(cache=True, nogil=True)
def _respot(pos, on, balls, spots, width, length, R, pockets):
    edge, md = R + SPOT_EDGE, 2 * R + SPOT_CLEAR
    for e in range(pos.shape[0]):
        if balls[e, 0]:                                       # the cue ball is in hand: it takes no spot
            on[e, 0] = False
        for k in range(6):
            if balls[e, FIRST_COLOUR + k]:                    # a colour spotted from the table (the last black)
                on[e, FIRST_COLOUR + k] = False               # never blocks its own spot
        for k in range(5, -1, -1):                            # the highest value first
            b = FIRST_COLOUR + k
            if not balls[e, b]:
                continue
            x, y, found = spots[k, 0], spots[k, 1], False
            if spot_free(x, y, pos[e], on[e], width, length, edge, pockets, md):
                found = True
            else:                                             # the highest free spot
                for j in range(5, -1, -1):
                    if spot_free(spots[j, 0], spots[j, 1], pos[e], on[e], width, length, edge, pockets, md):
                        x, y, found = spots[j, 0], spots[j, 1], True
                        break
            if not found:                                     # every spot taken: as near its own spot as possible,
                y, found = _line_spot(pos[e], on[e], x, y, 1.0, width, length, R, pockets)  # towards the top
                if not found:                                 # cushion, else below it, in line
                    y, found = _line_spot(pos[e], on[e], x, spots[k, 1], -1.0, width, length, R, pockets)
            if not found:
                return False
            pos[e, b, 0], pos[e, b, 1] = x, y
            on[e, b] = True
    return True


def respot_colours(pos: np.ndarray, pocket: np.ndarray, balls: np.ndarray, table, R: float,
                   pockets: np.ndarray) -> None:
    """Spot the colours marked in ``balls`` [n, B] (WPBSA Section 3, the
    rule on spotting colours), in place, the highest value first: each on
    its own spot; if that is occupied, on the highest-valued free spot; if
    every spot is occupied, as near its own spot as possible on the straight
    line from it to the top cushion (parallel to the long axis), or, if that
    line has no room, as near as possible on the same line below the spot.
    A colour marked while still on the table (the black of the re-spotted
    black) is lifted first, so it never occupies its own spot. ``balls[:, 0]``
    (the re-spotted black): the cue ball is in hand, so it occupies no spot;
    if the spotted balls leave it touching one, it goes to the free point of
    the D nearest the D's centre (the next stroke places it anyway)."""
    if not balls.any():
        return
    on = pocket < 0
    ok = _respot(pos, on, np.ascontiguousarray(balls), np.ascontiguousarray(table.marks.spots, dtype=np.float64),
                 table.width, table.length, R, pockets)
    if not ok:
        raise RuntimeError("no free spot on the table to respot a colour")
    pocket[:, 1:][balls[:, 1:]] = -1
    hand = np.nonzero(balls[:, 0] & (pocket[:, 0] < 0))[0]
    if len(hand):
        d = np.linalg.norm(pos[hand, 1:] - pos[hand, :1], axis=2)
        clash = hand[(np.where(pocket[hand, 1:] < 0, d, np.inf) < 2 * R + SPOT_CLEAR).any(axis=1)]
        if len(clash):
            m = table.marks
            want = np.tile([m.d_centre[0], m.d_centre[1]], (len(clash), 1))
            pos[clash, 0], _ = legal_spots(want, pos[clash], pocket[clash], np.zeros(len(clash), dtype=bool),
                                           table.width, table.length, R, pockets, d_of(table))


class SnookerRules(Rules):
    name = "snooker"
    n_balls = N_BALLS
    calls_ball = True   # the nominated colour, or the free ball, in ``ShotInput.called_ball``
    foul_points = True  # a foul scores points for the opponent (``ShotRecord.penalty``)
    to_points = True
    reads_position = True
    table_style = "snooker"   # Table.snooker()
    physics = "snooker"       # PhysicsParams.snooker(): snooker balls
    extra_obs = 6             # observation: both scores, the points left, a free ball, replace, touching (``observe_extra``)

    def __init__(self, R: float = SNOOKER_R):
        self.R = R

    replaces = True           # after a foul and a miss the balls may be replaced (``ShotInput.replaced``)

    def new_game(self, breaker) -> GameState:
        g = GameState.new(breaker)
        g.ball_in_hand[:] = IN_HAND_D
        E, B = g.n, N_BALLS + 1
        g.miss_pos = np.zeros((E, B, 2))
        g.miss_pocket = np.full((E, B), -1, dtype=np.int64)
        g.miss_phase = np.full(E, -1, dtype=np.int64)
        g.miss_hand = np.full(E, IN_HAND_NONE, dtype=np.int64)
        return g

    def observe_extra(self, game: GameState, pocket=None, constraints=None) -> np.ndarray:
        """[E, 6] in [0, 1]: the shooter's score, the opponent's, the face value of the balls on the
        table (each / SCORE_SCALE, clipped), 1 where a free ball may be nominated, 1 where the balls may be
        replaced (after the opponent's foul and a miss) and 1 where the cue ball lies touching a ball."""
        E = game.n
        ar = np.arange(E)
        out = np.zeros((E, self.extra_obs), dtype=np.float32)
        out[:, 0] = np.minimum(game.score[ar, game.shooter] / SCORE_SCALE, 1.0)
        out[:, 1] = np.minimum(game.score[ar, 1 - game.shooter] / SCORE_SCALE, 1.0)
        if pocket is not None:
            out[:, 2] = np.minimum(((np.asarray(pocket) < 0) * VALUE[None, :]).sum(axis=1) / SCORE_SCALE, 1.0)
        if constraints is not None:
            out[:, 3] = constraints.call_needed & constraints.may_pass  # a nomination right after a foul
            out[:, 4] = constraints.may_replace
            out[:, 5] = constraints.touching.any(axis=1)
        return out

    def free_ball(self, game: GameState, pos: np.ndarray | None, before: np.ndarray) -> np.ndarray:
        """[E] a free ball is awarded: after a foul, the cue ball on the table (not in hand) and snookered."""
        E = game.n
        if pos is None:
            return np.zeros(E, dtype=bool)
        after_foul = (game.phase == PHASE_OPTION) & (game.ball_in_hand == IN_HAND_NONE) & ~game.over
        out = np.zeros(E, dtype=bool)
        if after_foul.any():
            r = np.nonzero(after_foul)[0]
            out[r] = snookered(pos[r], before[r], balls_on(game.phase[r], before[r]), self.R)
        return out

    def check(self, game: GameState, shot: ShotInput) -> None:
        """``Rules.check``, except that a pass (the offender put back in) or the balls replaced after a miss
        need no cue ball on the table (no stroke is played)."""
        passed = (np.asarray(shot.passed, dtype=bool) | np.asarray(shot.replaced, dtype=bool)) & (game.phase == PHASE_OPTION)
        if passed.any():
            pb = np.array(shot.pocket_before, copy=True)
            pb[passed, 0] = -1
            shot = ShotInput(pb, shot.pocket_after, shot.first_contact, shot.rails)
        super().check(game, shot)

    def judge(self, game: GameState, shot: ShotInput) -> tuple[ShotRecord, GameState]:
        self.check(game, shot)
        E, s = game.n, game.shooter
        ar = np.arange(E)
        before = np.asarray(shot.pocket_before) < 0
        pk = shot.pocketed
        off = shot.off_table                    # forced off the table: a foul; reds stay off, colours are spotted
        phase = game.phase
        replaced = np.asarray(shot.replaced, dtype=bool) & self.may_replace(game)  # the balls back, the offender on
        passed = np.asarray(shot.passed, dtype=bool) & (phase == PHASE_OPTION) & ~replaced  # the offender back in
        played = ~passed & ~replaced
        first = np.asarray(shot.first_contact, dtype=np.int64)
        nom = np.asarray(shot.called_ball, dtype=np.int64)
        nom_ok = (nom >= 1) & (nom <= N_BALLS)
        nom_on = nom_ok & before[ar, np.clip(nom, 0, N_BALLS)]
        colour = phase == PHASE_COLOUR
        # the nominated colour; none declared: the colour hit first (an "obvious" nomination)
        nominated = np.where(colour, np.where(nom_on & (nom >= FIRST_COLOUR), nom,
                                              np.where(first >= FIRST_COLOUR, first, -1)), -1)
        on = balls_on(phase, before, nominated)
        reds_left = before[:, REDS].any(axis=1)
        low = colour_on_table(before)
        on_value = np.where(colour, VALUE[np.maximum(nominated, 0)] * (nominated >= 0),
                            np.where(reds_left, 1, VALUE[np.maximum(low, 0)]))
        free_ok = self.free_ball(game, shot.pos_before, before) & played
        free = np.where(free_ok & nom_on & ~on[ar, np.clip(nom, 0, N_BALLS)], nom, -1)   # the nominated free ball
        is_free = np.zeros_like(on)
        is_free[ar[free >= 0], free[free >= 0]] = True
        value = np.where(is_free, on_value[:, None], VALUE[None, :])                  # a free ball is worth the ball on
        # the ball hit first must be a ball on; with a free ball nominated, the free ball itself (WPBSA Section 3,
        # snookered after a foul: the cue ball must hit the nominated ball first, or it and a ball on at once;
        # the simulator reports one first ball, so an exactly simultaneous hit counts as the one it reports)
        first_ok = (first >= 1) & np.where(free >= 0, first == free, on[ar, np.clip(first, 0, N_BALLS)])
        bad_pot = (pk[:, 1:] & ~(on | is_free)[:, 1:]).any(axis=1)
        # the touching ball (WPBSA Section 3, Rule 15): playing away from a touching ball on hits no ball and
        # is no foul; moving the touching ball is a push stroke, read here as the cue ball's first contact
        touch = self.touching_balls(shot, before)
        touch_on = (touch & (on | is_free)).any(axis=1)
        push = (first >= 1) & touch[ar, np.clip(first, 0, N_BALLS)]
        foul = np.full(E, FOUL_NONE, dtype=np.int64)
        foul[bad_pot] = FOUL_WRONG_POT
        foul[(first >= 1) & ~first_ok] = FOUL_WRONG_BALL
        foul[(first < 1) & ~touch_on] = FOUL_NO_CONTACT
        foul[push] = FOUL_PUSH
        foul[off.any(axis=1)] = FOUL_OFF_TABLE
        foul[pk[:, 0]] = FOUL_SCRATCH
        foul[~played] = FOUL_NONE
        fouled = foul > 0
        involved = np.where(first >= 1, value[ar, np.clip(first, 0, N_BALLS)], 0)
        potted_value = np.where(pk | off, value, 0).max(axis=1)  # a ball pocketed or forced off: "the ball concerned"
        penalty = np.where(fouled, np.maximum.reduce([np.full(E, MIN_FOUL), on_value, involved, potted_value]), 0)
        # the points of a legal stroke: every red (and a free ball taken as a red) potted; otherwise the ball on,
        # or the free ball when the ball on stayed up (WPBSA Section 3, rule 12 (c)-(e))
        red_turn = reds_left & ~colour
        reds_potted = pk[:, REDS].sum(axis=1) + (pk & is_free).any(axis=1)
        ball_on_potted = (pk & on).any(axis=1)
        colour_points = np.where(ball_on_potted, on_value, np.where((pk & is_free).any(axis=1), on_value, 0))
        points = np.where(played & ~fouled, np.where(red_turn, reds_potted, colour_points), 0).astype(np.int64)
        g = game.copy()
        g.score[ar, s] += points
        g.score[ar, 1 - s] += penalty
        # colours back on the table: any colour pocketed on a foul, the colour taken after a red, a free ball
        respot = np.zeros_like(pk)
        col = (pk | off)[:, FIRST_COLOUR:]    # a colour forced off is always a foul's: spotted
        keep_down = played & ~fouled & ~colour & ~red_turn                      # the clearance: the colour on stays down
        respot[:, FIRST_COLOUR:] = col & ~(keep_down[:, None] & on[:, FIRST_COLOUR:])
        # the frame: with only the black left, the first score or foul ends it. On equal scores the black is
        # spotted, potted or not (a foul that ties leaves it where it stopped: it goes back to its spot), and the
        # cue ball is in hand (``respot[:, 0]``: it occupies no spot; ``respot_colours``)
        last_black = before[:, 1:].sum(axis=1) == 1
        last_black &= before[:, BLACK] & played & (fouled | (points > 0))
        tie = last_black & (g.score[:, 0] == g.score[:, 1])
        over = last_black & ~tie
        winner = np.where(over, np.argmax(g.score, axis=1), -1)
        respot[tie, BLACK] = True
        respot[tie, 0] = True
        turn_over = (fouled | (points == 0) | passed | replaced) & ~over
        miss = self._miss(game, shot, fouled & ~over & played & ~first_ok & ~push, on | is_free, g.score)
        rec = ShotRecord(legal=played & ~fouled, foul=foul, turn_over=turn_over, game_over=over, winner=winner,
                         end=np.where(over, END_LAST_BLACK, END_NONE), push_out=np.zeros(E, dtype=bool),
                         passed=passed, respot=respot, shooter=s.copy(), option=fouled & ~over,
                         points=points, penalty=penalty, miss=miss, replaced=replaced)
        g2 = next_state(g, rec, foul, played)
        g2.score = g.score
        # the re-spotted black: the cue ball in hand in the D; the player who did not break off plays first
        g2.shooter = np.where(tie, 1 - game.breaker, g2.shooter)
        pot_red = played & ~fouled & red_turn & (points > 0)
        g2.phase = np.where(fouled, PHASE_OPTION, np.where(pot_red, PHASE_COLOUR, PHASE_PLAY)).astype(np.int64)
        g2.phase = np.where(tie, PHASE_PLAY, g2.phase)
        cue_lost = pk[:, 0] | off[:, 0]         # an in-off, or the cue ball forced off the table: in hand in the D
        hand = np.where(passed, game.ball_in_hand, np.where(played & cue_lost, IN_HAND_D, IN_HAND_NONE))
        g2.ball_in_hand = np.where(tie, IN_HAND_D, hand).astype(np.int64)
        self._keep_miss(g2, game, shot, miss, replaced)
        return rec, g2

    def respot(self, pos, pocket, balls, table, R, pockets) -> None:
        """The colours a ruling marks back on their spots (``respot_colours``; ``balls[:, 0]``: the re-spotted
        black's cue ball in hand)."""
        respot_colours(pos, pocket, balls, table, R, pockets)

    def touching_balls(self, shot: ShotInput, before: np.ndarray) -> np.ndarray:
        """[E, B] the balls the cue ball touched where the stroke was played from (none without positions)."""
        if shot.pos_before is None:
            return np.zeros_like(before)
        return touching(np.asarray(shot.pos_before), before, self.R)

    def may_replace(self, game: GameState) -> np.ndarray:
        """[E] the incoming player may have the balls replaced: a miss was called on the last stroke."""
        if game.miss_phase is None:
            return np.zeros(game.n, dtype=bool)
        return ~game.over & (game.phase == PHASE_OPTION) & (game.miss_phase >= 0)

    def _miss(self, game: GameState, shot: ShotInput, failed: np.ndarray, on: np.ndarray,
              score_after: np.ndarray) -> np.ndarray:
        """[E] ``judge_miss`` on this stroke: ``failed`` [E] fouls that hit no ball on first, ``on`` [E, B] the
        balls on (a free ball included); snookers needed on the scores before the stroke with the balls before
        it, or on the scores after it with the reds left after it (colours are respotted on a foul)."""
        if shot.pos_before is None or not failed.any():
            return np.zeros(game.n, dtype=bool)
        before = np.asarray(shot.pocket_before) < 0
        any_on = balls_on(game.phase, before) | on      # "a ball that is or could be on": any colour after a red
        r = np.nonzero(failed)[0]
        open_path = np.zeros(game.n, dtype=bool)
        open_path[r] = open_on(np.asarray(shot.pos_before)[r], before[r], any_on[r], self.R).any(axis=1)
        left_after = before.copy()
        left_after[:, REDS] &= np.asarray(shot.pocket_after)[:, REDS] < 0
        needs = (needs_snookers(game.score, points_left(before, game.phase))
                 | needs_snookers(score_after, points_left(left_after, np.full(game.n, PHASE_OPTION))))
        return judge_miss(failed, open_path, needs)

    @staticmethod
    def _keep_miss(g2: GameState, game: GameState, shot: ShotInput, miss: np.ndarray, replaced: np.ndarray) -> None:
        """In place on ``g2``: where a miss was called, the balls as struck and the phase the offender played in
        (a free-ball stroke's option phase becomes open play: the replayed stroke has no free ball) and the
        offender's ball in hand; where the balls were replaced, the offender plays again from there in that
        phase, with the cue ball in hand in the D again if the miss was played from it (``play_turn`` puts the
        balls back); elsewhere no miss is pending."""
        if game.miss_phase is None:
            return
        g2.phase = np.where(replaced, game.miss_phase, g2.phase).astype(np.int64)
        g2.ball_in_hand = np.where(replaced, game.miss_hand, g2.ball_in_hand).astype(np.int64)
        g2.miss_hand = np.where(miss, game.ball_in_hand, IN_HAND_NONE).astype(np.int64)
        g2.miss_phase = np.where(miss, np.where(game.phase == PHASE_OPTION, PHASE_PLAY, game.phase), -1)
        g2.miss_phase = g2.miss_phase.astype(np.int64)
        if miss.any():
            g2.miss_pos[miss] = np.asarray(shot.pos_before)[miss]
            g2.miss_pocket[miss] = np.asarray(shot.pocket_before)[miss]

    def constraints(self, game: GameState, pocket: np.ndarray, pos: np.ndarray | None = None) -> Constraints:
        before = np.asarray(pocket) < 0
        live = ~game.over
        free = self.free_ball(game, pos, before)
        targets = balls_on(game.phase, before)
        targets[free, 1:] = before[free, 1:]          # a free ball: any ball may be hit first
        targets &= live[:, None]
        E = game.n
        return Constraints(shooter=game.shooter.copy(), ball_in_hand=np.where(live, game.ball_in_hand, IN_HAND_NONE),
                           targets=targets, push_out_allowed=np.zeros(E, dtype=bool),
                           may_pass=live & (game.phase == PHASE_OPTION),
                           call_needed=live & ((game.phase == PHASE_COLOUR) | free),
                           is_break=live & (game.phase == PHASE_BREAK), over=game.over.copy(),
                           may_replace=self.may_replace(game),
                           touching=(np.zeros_like(before) if pos is None else touching(pos, before, self.R))
                           & live[:, None] & (game.ball_in_hand == IN_HAND_NONE)[:, None])
