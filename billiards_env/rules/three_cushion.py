"""Three-cushion (UMB, "Rules of the Game of Three-Cushion" and the UMB
World Rules of Carom Billiard, 1989 edition, Art. 27 and Art. 41; the
simplifications are in docs/rules.md).

Three balls on a carom table without pockets: each player's own cue ball
(the starting player's white, the opponent's yellow) and the red. The
rules see every shot in the shooter's frame: ball 0 the shooter's cue ball,
ball 1 the opponent's, ball 2 the red (the envs keep the shooter's ball in
slot 0, ``Rules.own_cue_balls``).

- **A point** (a carom): the cue ball contacts both object balls, and
  touches cushions at least three times before its first contact with the
  second object ball (any cushions, the same one more than once; cushions
  struck by the object balls do not count). Read from the order of the cue
  ball's contacts (``ShotInput.contacts``, the simulator's
  ``SimOptions(contacts=K)``).
- **The inning** continues after each point; a shot without a point (or a
  foul) ends it and the opponent plays their ball from where it lies.
- **The opening shot**: the red on the foot spot, the opponent's ball on the
  head spot, the starting player's ball on the head string 18.2 cm beside
  it (``OPENING_OFFSET``); the cue ball must strike the red first: striking
  the opponent's ball first is a foul (``FOUL_WRONG_BALL``).
- **Balls in contact** (UMB Art. 27): a cue ball at rest touching a ball
  (centres within 2R + ``TOUCH_TOL``, snooker's touching-ball test,
  ``Constraints.touching``) may be played from where it lies, away from
  that ball: played straight into it (the cue ball's first contact of any
  kind is the touching ball) is a foul (``FOUL_PUSH``); a cushion first, or
  the other ball first, is fair. Or the shooter declares the balls replaced
  (``ShotInput.replaced``, allowed by ``Constraints.may_replace``): no shot
  is played, the balls go to the starting position (``ShotRecord.restart``;
  ``rules.respot.restart_position``) and the same shooter plays on, the
  first shot from there like the opening shot (the red first).
- **The wrong cue ball** (UMB Art. 41): the cue striking another ball than
  the shooter's own cue ball (``ShotInput.struck``: the opponent's ball or
  the red) is a foul (``FOUL_WRONG_CUE_BALL``).
- **A jumped ball** (``ShotInput.off_table``: a ball that left the table
  over a cushion, only with the simulator's airborne effect): a foul
  (``FOUL_OFF_TABLE``; UMB's rule on balls jumping off the table, World
  Rules of Carom Billiard Art. 28, "Balls bounding out of the billiard":
  the inning ends and the stroke scores nothing). The balls that left
  are put back on the spots (``ShotRecord.respot``, placed by
  ``rules.respot.carom_spots``): the red on the foot spot, the cue ball of
  the next stroke (the opponent's) on the head spot, the other on the
  centre spot, a ball whose spot is taken going to the spot of the ball
  that takes it.
- **A foul** scores nothing (not even a point made on that shot) and ends
  the inning. (A double hit, push shots through the cue ball and touching
  a ball by hand cannot happen here.)
- **The game** is to ``target`` points, or ends after ``max_innings``
  innings of each player with the higher score winning (equal: a draw).
  With ``equal_innings`` the opponent of the starting player gets a last
  inning when the starting player reaches the target (UMB's equal innings):
  reaching the target in it draws the game, else the starting player wins.
  That inning starts from the starting position, with the opponent's own
  ball beside the head spot (``ShotRecord.restart``; the envs re-place the
  balls: ``envs.games.setup.restart_position``), and its first shot, like
  the opening shot, must strike the red first (``PHASE_FINAL_OPENING``).
"""
from __future__ import annotations

import numpy as np

from ..physics import constants as PC
from ..physics.params import PhysicsParams
from .common import Rules, next_state
from .records import (END_INNINGS, END_NONE, END_TARGET, FOUL_NONE, FOUL_OFF_TABLE, FOUL_PUSH, FOUL_WRONG_BALL,
                      FOUL_WRONG_CUE_BALL, IN_HAND_NONE, PHASE_BREAK, PHASE_FINAL, PHASE_FINAL_OPENING, PHASE_PLAY,
                      Constraints, GameState, ShotInput, ShotRecord)
from .placement import OPENING_OFFSET  # noqa: F401  (the opening's offset beside the head spot, with the spots)
from .respot import carom_spots
from .snooker import touching  # the touching-ball test (centres within 2R + TOUCH_TOL): one for both games

CUE, OPPONENT_BALL, RED = 0, 1, 2  # slots in the shooter's frame
POINT_CUSHIONS = 3                 # cushions the cue ball needs before its contact with the second object ball
CONTACTS_KEPT = 64                 # the cue ball's contacts the simulator keeps: a point is decided within a few dozen
CAROM_R = PhysicsParams.carom().R  # m, the carom ball's radius: the default of the touching-ball test
TARGET = 15                        # default points to win (UMB matches: 40 or 50; shorter games train faster)
MAX_INNINGS = 50                   # default innings limit per player


def point_made(contacts: np.ndarray, n_contacts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per shot [E]: whether the cue ball made a point, and its cushion
    contacts before its first contact with the second object ball (all its
    cushions if it did not reach both). ``contacts`` [E, K, 2] in the
    shooter's frame (module docstring); ``n_contacts`` [E] (only the first K
    are read)."""
    contacts = np.asarray(contacts, dtype=np.int64)
    E, K = contacts.shape[:2]
    kind, other = contacts[..., 0], contacts[..., 1]
    valid = np.arange(K)[None, :] < np.minimum(np.asarray(n_contacts), K)[:, None]
    ball = valid & (kind == PC.EV_BALL_BALL)
    cushion = valid & ((kind == PC.EV_CUSHION) | (kind == PC.EV_JAW_TIP))
    firsts = []
    for b in (OPPONENT_BALL, RED):
        hit = ball & (other == b)
        firsts.append(np.where(hit.any(axis=1), np.argmax(hit, axis=1), K))
    second = np.maximum(*firsts)
    before = (cushion & (np.arange(K)[None, :] < second[:, None])).sum(axis=1)
    return (second < K) & (before >= POINT_CUSHIONS), before


class ThreeCushionRules(Rules):
    """UMB three-cushion to ``target`` points within ``max_innings`` innings
    each, with the equal-innings rule if ``equal_innings`` (module docstring)."""

    name = "three_cushion"
    n_balls = 2
    table_style = "carom"
    physics = "carom"
    contacts = CONTACTS_KEPT
    own_cue_balls = True
    extra_obs = 5
    to_points = True
    reads_position = True  # the balls in contact are read from where they lie (``touching``)
    replaces = True        # a frozen cue ball's balls may be replaced on the starting position (a6 in (0, 0.5])
    env_doc = """
    **Three-cushion** (UMB rules, docs/rules.md) on the carom match table
    with carom balls: B = 3 balls in the shooter's frame, ball 0 the cue
    ball of the player to move (the starting player plays white, the other
    yellow), ball 1 the opponent's cue ball, ball 2 the red. The action is
    the 8-component one above; a0 (aim, relative to ball 1; to the red
    on the opening shot), a1 (draw), a2 (side) and a3 (height) are used,
    and a6 where the cue ball lies touching a ball (``may_replace``):
    0 < a6 <= 0.5 has the balls replaced on the starting position (no shot;
    the same player then plays the opening shot from there), any other a6
    plays from where the ball lies, away from the touching ball (played
    straight into it is a foul).
    A point (the cue ball meets both object balls and >= 3 cushions before
    the second) keeps the player at the table; the game is to ``target``
    points (``rule_options``), ends after ``max_innings`` innings each, the
    equal-innings rule optional. The observation is the one above (B = 3)
    and five more entries:

    ==============  ===========================================================
    4*B + 14, 15    the shooter's score / target, the opponent's
    4*B + 16        the shooter's innings / max_innings
    4*B + 17        1 in the equal-innings last inning
    4*B + 18        1 where the cue ball lies touching a ball (the balls may
                    be replaced: ``may_replace``, a6 above)
    ==============  ===========================================================

    **Info** adds ``points`` (the shot's points), ``score`` [2] and
    ``replaced`` (the balls were replaced on the starting position: no shot).
"""

    def __init__(self, target: int = TARGET, max_innings: int = MAX_INNINGS, equal_innings: bool = False,
                 R: float = CAROM_R):
        for name, v in (("target", target), ("max_innings", max_innings)):
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 1:
                raise ValueError(f"three_cushion: {name} must be a positive integer, got {v!r}")
        if not isinstance(equal_innings, (bool, np.bool_)):
            raise TypeError(f"three_cushion: equal_innings must be True or False, got {equal_innings!r}")
        self.target, self.max_innings, self.equal_innings = int(target), int(max_innings), bool(equal_innings)
        self.R = float(R)

    def judge(self, game: GameState, shot: ShotInput) -> tuple[ShotRecord, GameState]:
        self.check(game, shot)
        if shot.contacts is None or shot.n_contacts is None:
            raise ValueError("three_cushion: the shot needs the cue ball's contacts in order (ShotInput.contacts "
                             "and n_contacts, from simulate(..., options=SimOptions(contacts=K)))")
        E = game.n
        ar, s = np.arange(E), game.shooter
        touch = self.touching_balls(shot)
        # balls in contact (UMB Art. 27): the shooter had them replaced on the starting position: no shot
        replaced = np.asarray(shot.replaced, dtype=bool) & touch.any(axis=1)
        played = ~replaced
        point, _ = point_made(shot.contacts, shot.n_contacts)
        # an opening shot: the game's first, or the first from the starting position (the equal-innings last
        # inning, balls in contact replaced): the red must be struck first
        is_break = (game.phase == PHASE_BREAK) | (game.phase == PHASE_FINAL_OPENING)
        first = np.asarray(shot.first_contact, dtype=np.int64)
        foul = np.where(is_break & (first == OPPONENT_BALL), FOUL_WRONG_BALL, FOUL_NONE).astype(np.int64)
        # played straight into the touching ball: the cue ball's first contact of any kind is that ball (a
        # cushion first, or the other ball first, plays away from it)
        kind, other = np.asarray(shot.contacts)[:, 0, 0], np.asarray(shot.contacts)[:, 0, 1]
        into = (np.asarray(shot.n_contacts) > 0) & (kind == PC.EV_BALL_BALL)
        into &= touch[ar, np.clip(other, 0, touch.shape[1] - 1)]
        foul[into] = FOUL_PUSH
        # a ball jumped off the table (UMB Art. 28): a foul; the balls that left go back on the spots (``respot``)
        off = shot.off_table & played[:, None]
        foul[off.any(axis=1)] = FOUL_OFF_TABLE
        # the wrong cue ball (UMB Art. 41): the cue struck the opponent's ball or the red
        foul[np.asarray(shot.struck) != CUE] = FOUL_WRONG_CUE_BALL
        foul[~played] = FOUL_NONE
        scored = point & played & (foul == FOUL_NONE)
        score = game.score.copy()
        score[ar, s] += scored
        reached = scored & (score[ar, s] >= self.target)
        starter = s == game.breaker
        final = (game.phase == PHASE_FINAL) | (game.phase == PHASE_FINAL_OPENING)
        missed = played & ~scored
        # the game ends: the target reached (with equal innings, the starter's opponent first plays a last
        # inning), that last inning ended, or each player's innings limit played out
        last_inning = final & (missed | reached)
        win_now = reached & ~final & ~(self.equal_innings & starter)
        limit = missed & ~starter & (game.innings[ar, s] >= self.max_innings) & ~final
        over = win_now | last_inning | limit
        by_score = np.where(score[:, 0] > score[:, 1], 0, np.where(score[:, 1] > score[:, 0], 1, -1))
        winner = np.where(win_now, s, np.where(last_inning, np.where(reached, -1, game.breaker),
                                                np.where(limit, by_score, -1)))
        end = np.where(win_now | last_inning, END_TARGET, np.where(limit, END_INNINGS, END_NONE))
        to_final = reached & starter & self.equal_innings & ~final
        turn_over = (missed | to_final) & ~over
        rec = ShotRecord(legal=played & (foul == FOUL_NONE), foul=foul, turn_over=turn_over, game_over=over,
                         winner=winner.astype(np.int64), end=end.astype(np.int64), push_out=np.zeros(E, dtype=bool),
                         passed=np.zeros(E, dtype=bool), respot=off,
                         shooter=s.copy(), points=scored.astype(np.int64), restart=to_final | replaced,
                         replaced=replaced)
        g = next_state(game, rec, foul, played)
        g.score = score
        g.innings[ar, 1 - s] += turn_over  # the incoming player begins an inning
        g.phase = np.where(to_final | (replaced & final), PHASE_FINAL_OPENING,
                           np.where(replaced, PHASE_BREAK, np.where(final, PHASE_FINAL, PHASE_PLAY))).astype(np.int64)
        g.ball_in_hand = np.full(E, IN_HAND_NONE, dtype=np.int64)
        return rec, g

    def respot(self, pos, pocket, balls, table, R, pockets) -> None:
        """The balls that jumped off the table back on the carom spots (``rules.respot.carom_spots``)."""
        carom_spots(pos, pocket, balls, table, R)

    def touching_balls(self, shot: ShotInput) -> np.ndarray:
        """[E, B] the balls the cue ball touched where the shot was played from (none without positions)."""
        on = np.asarray(shot.pocket_before) < 0
        if shot.pos_before is None:
            return np.zeros_like(on)
        return touching(np.asarray(shot.pos_before), on, self.R)

    def constraints(self, game: GameState, pocket: np.ndarray, pos: np.ndarray | None = None) -> Constraints:
        E, B = np.shape(pocket)
        live = ~game.over
        brk = live & ((game.phase == PHASE_BREAK) | (game.phase == PHASE_FINAL_OPENING))
        targets = np.zeros((E, B), dtype=bool)
        targets[:, RED] = live
        targets[:, OPPONENT_BALL] = live & ~brk  # the opening shot must strike the red first
        on = np.asarray(pocket) < 0
        touch = (np.zeros_like(on) if pos is None else touching(np.asarray(pos), on, self.R)) & live[:, None]
        no = np.zeros(E, dtype=bool)
        return Constraints(shooter=game.shooter.copy(), ball_in_hand=np.full(E, IN_HAND_NONE, dtype=np.int64),
                           targets=targets, push_out_allowed=no, may_pass=no.copy(), call_needed=no.copy(),
                           is_break=brk, over=game.over.copy(), may_replace=touch.any(axis=1), touching=touch)

    def observe_extra(self, game: GameState, pocket=None, constraints=None) -> np.ndarray:
        """The shooter's and the opponent's score / target, the shooter's
        innings / max_innings, 1 in the equal-innings last inning and 1 where
        the cue ball lies touching a ball (``constraints.may_replace``; 0
        without constraints; ``pocket`` is not needed)."""
        ar, s = np.arange(game.n), game.shooter
        x = np.zeros((game.n, self.extra_obs), dtype=np.float32)
        if constraints is not None:
            x[:, 4] = constraints.may_replace
        x[:, 0] = np.minimum(game.score[ar, s] / self.target, 1.0)
        x[:, 1] = np.minimum(game.score[ar, 1 - s] / self.target, 1.0)
        x[:, 2] = np.minimum(game.innings[ar, s] / self.max_innings, 1.0)
        x[:, 3] = (game.phase == PHASE_FINAL) | (game.phase == PHASE_FINAL_OPENING)
        return x

    def new_game(self, breaker) -> GameState:
        """A fresh game (``GameState.new``) with the starting player's first inning begun."""
        g = super().new_game(breaker)
        g.innings[np.arange(g.n), g.breaker] = 1
        g.ball_in_hand[:] = IN_HAND_NONE
        return g
