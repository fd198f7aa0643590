"""What the rules read and return, as arrays batched over tables.

- ``GameState``: where each table's game stands (who shoots, the phase,
  ball in hand, consecutive fouls, 8-ball groups, over / winner).
- ``ShotInput``: one shot of each table as the simulator saw it (pockets
  before and after, first contact, rail contacts after it) plus the
  shooter's declarations (push-out, called pocket, called ball, passing the
  shot back).
- ``ShotRecord``: the ruling on that shot (legal or the foul and its
  reason, turn over, game over, winner, balls to respot).
- ``Constraints``: what the next shooter may and must do (ball in hand,
  legal targets, push-out, pass, call).

Codes are small ints so that records stay plain arrays; ``FOUL_NAMES`` and
``END_NAMES`` name them.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from ..physics.constants import OFF_TABLE

# --- foul reasons (ShotRecord.foul) ------------------------------------------
FOUL_NONE = 0
FOUL_NO_CONTACT = 1      # the cue ball touched no object ball
FOUL_WRONG_BALL = 2      # the first ball touched was not a legal target
FOUL_NO_RAIL = 3         # nothing pocketed and no ball touched a rail after the contact
FOUL_SCRATCH = 4         # the cue ball was pocketed
FOUL_BAD_BREAK = 5       # break: no ball pocketed and fewer than four object balls reached a rail
FOUL_WRONG_POT = 6       # snooker: a ball not on was pocketed
FOUL_PUSH = 7            # the cue ball played into the ball it lay touching (snooker's push stroke, three-cushion's
                         # ball in contact): its first contact, read from the simulator
FOUL_WRONG_CUE_BALL = 8  # three-cushion: the cue struck another ball than the shooter's own cue ball
FOUL_OFF_TABLE = 9       # a ball, the cue ball or an object ball, left the table (``ShotInput.off_table``)
FOUL_NAMES = {FOUL_NONE: "none", FOUL_NO_CONTACT: "no contact", FOUL_WRONG_BALL: "wrong ball first",
              FOUL_NO_RAIL: "no rail after contact", FOUL_SCRATCH: "scratch", FOUL_BAD_BREAK: "illegal break",
              FOUL_WRONG_POT: "a ball not on pocketed", FOUL_PUSH: "push stroke (the touching ball moved)",
              FOUL_WRONG_CUE_BALL: "the wrong cue ball struck", FOUL_OFF_TABLE: "a ball left the table"}

# --- how a game ended (ShotRecord.end) ----------------------------------------
END_NONE = 0
END_NINE = 1             # the 9 pocketed on a legal shot: the shooter wins
END_THREE_FOULS = 2      # third consecutive foul: the shooter loses
END_EIGHT = 3            # the 8 pocketed legally in the called pocket: the shooter wins
END_EIGHT_EARLY = 4      # the 8 pocketed before the shooter's group was cleared: the shooter loses
END_EIGHT_FOUL = 5       # the 8 pocketed on a foul: the shooter loses
END_EIGHT_POCKET = 6     # the 8 pocketed in another pocket than the one called: the shooter loses
END_TEN = 7              # 10-ball: the 10 called and pocketed in the called pocket on a legal shot: the shooter wins
END_TARGET = 8           # games to a score: a player reached the target score (winner -1: a draw, as equal innings allow)
END_INNINGS = 9          # games to a score: the innings limit was reached; the higher score wins (winner -1: a draw)
END_LAST_BLACK = 10      # snooker: the first score or foul with only the black left ended the frame on points
END_EIGHT_OFF = 11       # 8-ball: the 8 driven off the table (any shot but the break): the shooter loses
END_NAMES = {END_NONE: "none", END_NINE: "9 pocketed", END_THREE_FOULS: "three consecutive fouls",
             END_EIGHT: "8 pocketed", END_EIGHT_EARLY: "8 pocketed early", END_EIGHT_FOUL: "8 pocketed on a foul",
             END_EIGHT_POCKET: "8 in an uncalled pocket", END_TEN: "10 pocketed as called",
             END_TARGET: "target score reached", END_INNINGS: "innings limit reached",
             END_LAST_BLACK: "the last black decided the frame", END_EIGHT_OFF: "8 driven off the table"}

# --- called ball (ShotInput.called_ball, 10-ball) ----------------------------------
CALL_NONE = -1           # no ball called (the break, a push-out, a game without ball calls)
CALL_SAFETY = 0          # a called safety: no ball is called, every ball the shot pockets is pocketed illegally

# --- ball in hand (GameState.ball_in_hand, Constraints.ball_in_hand) ----------
IN_HAND_NONE = 0         # the cue ball is played from where it lies
IN_HAND_ANYWHERE = 1     # anywhere on the table
IN_HAND_KITCHEN = 2      # behind the head string (the break, and after a scratch on the 8-ball break)
IN_HAND_D = 3            # snooker: in the D (the break-off, and after an in-off)

# --- phases (GameState.phase) ---------------------------------------------------
PHASE_BREAK = 0          # the next shot is the opening break
PHASE_AFTER_BREAK = 1    # the first shot after the break (9-ball: push-out allowed)
PHASE_PUSHED = 2         # 9-ball, 10-ball: a push-out was played; the next player may pass the shot back
PHASE_PLAY = 3           # any other shot
PHASE_OPTION = 4         # 10-ball: the last shot pocketed a ball illegally (not the called ball in the called
                         # pocket) without a foul; the next player may shoot or pass the shot back.
                         # Snooker: the last shot was a foul; the incoming player may play or put the offender back in
PHASE_FINAL = 5          # games to a score with equal innings: the starting player reached the target; the
                         # opponent plays a last inning
PHASE_COLOUR = 6         # snooker: a red (or a free ball taken as a red) was potted; a nominated colour is on
PHASE_FINAL_OPENING = 7  # games to a score with equal innings (three-cushion): the opponent's last inning begins
                         # from the starting position; this first shot must strike the red first, as the opening

# --- 8-ball groups (GameState.group) ------------------------------------------------
GROUP_OPEN = 0
GROUP_SOLIDS = 1         # balls 1-7
GROUP_STRIPES = 2        # balls 9-15


@dataclasses.dataclass(eq=False)
class GameState:
    """Per table [E]: ``shooter`` (0 or 1), ``breaker`` (who broke),
    ``phase`` (PHASE_*), ``ball_in_hand`` (IN_HAND_*), ``fouls`` [E, 2]
    consecutive fouls per player, ``group`` [E, 2] each player's 8-ball
    group (GROUP_*), ``shots`` taken, ``over`` and ``winner`` (-1 none);
    games to a score (three-cushion, snooker) also keep ``score`` [E, 2] each
    player's points and ``innings`` [E, 2] the innings (turns at the table)
    each player has begun (zeros in the games won by a ball)."""

    shooter: np.ndarray
    breaker: np.ndarray
    phase: np.ndarray
    ball_in_hand: np.ndarray
    fouls: np.ndarray
    group: np.ndarray
    shots: np.ndarray
    over: np.ndarray
    winner: np.ndarray
    score: np.ndarray
    innings: np.ndarray
    # snooker's foul and a miss (WPBSA Section 3, Rule 14): the position the miss was played from, which the
    # incoming player may have replaced (``Constraints.may_replace``); None in the other games. ``miss_pos``
    # [E, B, 2] and ``miss_pocket`` [E, B] the balls as struck, ``miss_phase`` [E] the phase the offender
    # played in (-1: no miss called on the last stroke), ``miss_hand`` [E] their ball in hand (IN_HAND_*)
    miss_pos: np.ndarray | None = None
    miss_pocket: np.ndarray | None = None
    miss_phase: np.ndarray | None = None
    miss_hand: np.ndarray | None = None

    @classmethod
    def new(cls, breaker) -> "GameState":
        """Fresh games before the break; ``breaker`` [E] (0 or 1) breaks."""
        b = np.asarray(breaker, dtype=np.int64).copy()
        E = len(b)
        if np.any((b != 0) & (b != 1)):
            raise ValueError("breaker must be 0 or 1 for every table")
        return cls(shooter=b.copy(), breaker=b, phase=np.full(E, PHASE_BREAK, dtype=np.int64),
                   ball_in_hand=np.full(E, IN_HAND_KITCHEN, dtype=np.int64), fouls=np.zeros((E, 2), dtype=np.int64),
                   group=np.zeros((E, 2), dtype=np.int64), shots=np.zeros(E, dtype=np.int64),
                   over=np.zeros(E, dtype=bool), winner=np.full(E, -1, dtype=np.int64),
                   score=np.zeros((E, 2), dtype=np.int64), innings=np.zeros((E, 2), dtype=np.int64))

    @property
    def n(self) -> int:
        return len(self.shooter)

    def copy(self) -> "GameState":
        return GameState(*(_copy(getattr(self, k)) for k in _GAME_FIELDS))

    def take(self, idx) -> "GameState":
        return GameState(*(_take(getattr(self, k), idx) for k in _GAME_FIELDS))

    def put(self, idx, other: "GameState") -> None:
        """Write ``other`` (len(idx) tables) into tables ``idx`` (the optional fields only where both have them)."""
        for k in _GAME_FIELDS:
            v = getattr(self, k)
            if v is not None and getattr(other, k) is not None:
                v[idx] = getattr(other, k)


def _copy(v):
    return None if v is None else v.copy()


def _take(v, idx):
    return None if v is None else v[idx]


_GAME_FIELDS = tuple(f.name for f in dataclasses.fields(GameState))  # in order (copy, take and put run every shot)


@dataclasses.dataclass(frozen=True, eq=False)
class ShotInput:
    """One shot per table [E]: ``pocket_before`` / ``pocket_after`` [E, B]
    (``BallState.pocket``: -1 on the table, 0 .. K-1 in pocket k, and
    ``physics.constants.OFF_TABLE`` (100) or above off the table, over a
    cushion: ``pocketed`` and ``off_table`` tell the two apart; ball 0 the
    cue ball), ``first_contact`` (the
    first ball the cue ball touched, -1 none), ``rails`` [E, B] cushion hits
    of each ball after the cue ball's first contact (object balls rest until
    touched, so all of theirs count), ``object_rails`` [E, B] every ball's
    cushion hits during the shot (the break's four-ball count), and the
    declarations: ``push_out`` (bool), ``called_pocket`` (int, -1 none),
    ``replaced`` (no shot was played: in snooker, after a foul and a miss
    the incoming player had the balls replaced and the offender plays
    again; in three-cushion the shooter had the balls of a frozen cue ball
    put on the starting position),
    ``passed`` (bool: after a push-out, or in 10-ball after an illegally
    pocketed ball, the player handed the shot back and no shot was played)
    and ``called_ball`` (10-ball: the ball called, CALL_SAFETY for a called
    safety, CALL_NONE none; snooker: the nominated ball, a colour or a free
    ball); ``struck`` (the ball the cue struck: 0, the default, the
    shooter's own cue ball; three-cushion rules another ball a foul);
    ``pos_before`` (optional) the positions the shot was played from. From a ``physics.SimResult``: ``state.pocket``,
    ``first_contact``, ``cushion_hits_after_contact`` (``rails``) and
    ``cushion_hits`` (``object_rails``); games judged on the order of the
    cue ball's contacts (three-cushion) also take ``contacts`` [E, K, 2] and
    ``n_contacts`` [E] (``SimResult.contacts``, ``n_contacts``)."""

    pocket_before: np.ndarray
    pocket_after: np.ndarray
    first_contact: np.ndarray
    rails: np.ndarray
    object_rails: np.ndarray | None = None
    push_out: np.ndarray | None = None
    called_pocket: np.ndarray | None = None
    passed: np.ndarray | None = None
    called_ball: np.ndarray | None = None
    contacts: np.ndarray | None = None
    n_contacts: np.ndarray | None = None
    pos_before: np.ndarray | None = None  # [E, B, 2] the balls where the shot was played from (snooker's free ball)
    replaced: np.ndarray | None = None    # [E] the balls replaced on a declaration (no shot played; snooker, 3-cushion)
    struck: np.ndarray | None = None      # [E] the ball the cue struck (0: the shooter's own cue ball)

    def __post_init__(self):
        E, B = np.shape(self.pocket_before)
        for name in ("pocket_after", "rails"):
            if np.shape(getattr(self, name)) != (E, B):
                raise ValueError(f"ShotInput.{name} must have shape ({E}, {B}), got {np.shape(getattr(self, name))}")
        if np.shape(self.first_contact) != (E,):
            raise ValueError(f"ShotInput.first_contact must have shape ({E},), got {np.shape(self.first_contact)}")
        fill = dict(object_rails=np.asarray(self.rails), push_out=np.zeros(E, dtype=bool),
                    called_pocket=np.full(E, -1, dtype=np.int64), passed=np.zeros(E, dtype=bool),
                    called_ball=np.full(E, CALL_NONE, dtype=np.int64), replaced=np.zeros(E, dtype=bool),
                    struck=np.zeros(E, dtype=np.int64))
        for k, v in fill.items():
            if getattr(self, k) is None:
                object.__setattr__(self, k, v)

    @property
    def n(self) -> int:
        return len(self.first_contact)

    @property
    def pocketed(self) -> np.ndarray:
        """[E, B] balls this shot put in a pocket (a code 0 .. OFF_TABLE - 1; ``off_table`` are not pocketed)."""
        after = np.asarray(self.pocket_after)
        return (after >= 0) & (after < OFF_TABLE) & (np.asarray(self.pocket_before) < 0)

    @property
    def off_table(self) -> np.ndarray:
        """[E, B] balls this shot drove off the table over a cushion (a code >= OFF_TABLE: on the rail top or the
        floor; only the simulator's airborne effect produces them). Every game rules it a foul: ``rules.common``."""
        return (np.asarray(self.pocket_after) >= OFF_TABLE) & (np.asarray(self.pocket_before) < 0)


@dataclasses.dataclass(frozen=True, eq=False)
class ShotRecord:
    """The ruling on one shot per table [E]: ``legal`` (no foul), ``foul``
    (FOUL_*), ``turn_over`` (the other player shoots next), ``game_over``,
    ``winner`` (-1 none), ``end`` (END_*), ``push_out`` (this shot was a
    push-out), ``passed`` (no shot: the shot was handed back),
    ``respot`` [E, B] balls the table must put back on the foot spot
    (snooker: the colours to spot, a colour still on the table included, and
    ``respot[:, 0]`` the cue ball in hand, which takes no spot: the
    re-spotted black; ``rules.snooker.respot_colours``),
    ``shooter`` (who played it), ``option`` (10-ball: the shot pocketed a
    ball illegally without a foul, so the next player may shoot or pass the
    shot back; snooker: the shot was a foul, so the incoming player may put
    the offender back in; all False in the other games), ``miss`` (snooker:
    the foul was also a miss, WPBSA Section 3, Rule 14; ``rules.snooker.
    judge_miss``), ``replaced`` (no shot, the balls were put back: snooker,
    where the miss was played from; three-cushion, on the starting
    position, ``restart``), ``points`` (the
    points the shot scored for its shooter; games to a score, else zeros),
    ``penalty`` (what a foul gave the opponent; snooker, else zeros) and
    ``restart`` (the balls go back to the starting position before the next
    shot: three-cushion's equal-innings last inning and a frozen cue ball's
    balls replaced, ``rules.respot.restart_position``; all False elsewhere)."""

    legal: np.ndarray
    foul: np.ndarray
    turn_over: np.ndarray
    game_over: np.ndarray
    winner: np.ndarray
    end: np.ndarray
    push_out: np.ndarray
    passed: np.ndarray
    respot: np.ndarray
    shooter: np.ndarray
    option: np.ndarray | None = None
    points: np.ndarray | None = None
    penalty: np.ndarray | None = None
    restart: np.ndarray | None = None
    miss: np.ndarray | None = None
    replaced: np.ndarray | None = None

    def __post_init__(self):
        for name in ("option", "restart", "miss", "replaced"):
            if getattr(self, name) is None:
                object.__setattr__(self, name, np.zeros(len(self.legal), dtype=bool))
        for name in ("points", "penalty"):
            if getattr(self, name) is None:
                object.__setattr__(self, name, np.zeros(len(self.legal), dtype=np.int64))


@dataclasses.dataclass(frozen=True, eq=False)
class Constraints:
    """What the next shooter of each table [E] may and must do: ``shooter``,
    ``ball_in_hand`` (IN_HAND_*), ``targets`` [E, B] the balls the cue ball
    may legally touch first, ``push_out_allowed``, ``may_pass`` (after the
    opponent's push-out: hand the shot back instead of shooting),
    ``call_needed`` (8-ball: the shot is on the 8, a pocket must be called),
    ``is_break``, ``over`` (the game has ended: no shot), ``may_replace``
    (a declaration may have the balls replaced instead of a shot: snooker,
    after a foul and a miss, where they were before the foul, the offender
    to play again; three-cushion, a cue ball frozen to a ball, on the
    starting position, the shooter to play on; all False elsewhere)
    and ``touching`` [E, B] (snooker and three-cushion: the balls the cue
    ball lies touching, which the stroke must play away from; all False
    elsewhere)."""

    shooter: np.ndarray
    ball_in_hand: np.ndarray
    targets: np.ndarray
    push_out_allowed: np.ndarray
    may_pass: np.ndarray
    call_needed: np.ndarray
    is_break: np.ndarray
    over: np.ndarray
    may_replace: np.ndarray | None = None
    touching: np.ndarray | None = None

    def __post_init__(self):
        if self.may_replace is None:
            object.__setattr__(self, "may_replace", np.zeros(len(self.shooter), dtype=bool))
        if self.touching is None:
            object.__setattr__(self, "touching", np.zeros(np.shape(self.targets), dtype=bool))

    def nominal_target(self) -> np.ndarray:
        """The lowest-numbered legal target of each table (-1 none): what
        relative aim and the geometric policies aim at."""
        return nominal_target(self.targets)

    def take(self, idx) -> "Constraints":
        """The constraints of tables ``idx`` (copies)."""
        return Constraints(*(getattr(self, f.name)[idx] for f in dataclasses.fields(self)))


def nominal_target(targets: np.ndarray) -> np.ndarray:
    """The lowest-numbered legal target [n] of legal-target masks [n, B] (-1 none)."""
    return np.where(targets.any(axis=1), np.argmax(targets, axis=1), -1).astype(np.int64)
