"""Rule pieces shared by the games: the facts of a shot every ruling reads,
and the ruleset interface.

A ball off the table (``ShotInput.off_table``: ``BallState.pocket`` >=
``physics.constants.OFF_TABLE``, a ball that left the table over a cushion,
on the rail top or the floor) is never pocketed; ``Facts`` reads it apart
(``off_table``, ``cue_off``, ``object_off``) and ``foul_code`` rules it a
foul, ``FOUL_OFF_TABLE``: WPA General Rules, standard fouls "Cue Ball
Scratch or off the Table" (the cue ball driven off the table is a foul) and
"Ball Driven off the Table" (an object ball driven off the table is a foul;
whether it is spotted is each game's rule). Each game says what goes back
on the table (its module docstring; docs/rules.md, "Balls off the table")."""
from __future__ import annotations

import dataclasses

import numpy as np

from .records import (FOUL_BAD_BREAK, FOUL_NO_CONTACT, FOUL_NO_RAIL, FOUL_NONE, FOUL_OFF_TABLE, FOUL_SCRATCH,
                      FOUL_WRONG_BALL, PHASE_AFTER_BREAK, PHASE_BREAK, PHASE_OPTION, PHASE_PLAY, PHASE_PUSHED,
                      Constraints, GameState, ShotInput, ShotRecord)
from .respot import respot

BREAK_RAIL_BALLS = 4  # a legal break pockets a ball or drives at least this many object balls to a rail
THREE_FOULS = 3       # a player's third consecutive foul loses the game (9-ball, 10-ball)


@dataclasses.dataclass(frozen=True, eq=False)
class Facts:
    """What every ruling needs from a ``ShotInput`` [E]: ``pocketed`` [E, B]
    (in a pocket), ``scratch`` (the cue ball in a pocket), ``object_pocketed``
    (any object ball), ``rail`` (some ball, the cue ball included, touched a
    rail after the first contact), ``break_rails`` (object balls that touched
    a rail), ``first``; and the balls driven off the table, never pocketed:
    ``off_table`` [E, B], ``cue_off`` (the cue ball) and ``object_off``
    (any object ball)."""

    pocketed: np.ndarray
    scratch: np.ndarray
    object_pocketed: np.ndarray
    rail: np.ndarray
    break_rails: np.ndarray
    first: np.ndarray
    off_table: np.ndarray
    cue_off: np.ndarray
    object_off: np.ndarray

    @classmethod
    def of(cls, shot: ShotInput) -> "Facts":
        pk, off = shot.pocketed, shot.off_table
        return cls(pocketed=pk, scratch=pk[:, 0].copy(), object_pocketed=pk[:, 1:].any(axis=1),
                   rail=(np.asarray(shot.rails) > 0).any(axis=1),
                   break_rails=(np.asarray(shot.object_rails)[:, 1:] > 0).sum(axis=1),
                   first=np.asarray(shot.first_contact, dtype=np.int64),
                   off_table=off, cue_off=off[:, 0].copy(), object_off=off[:, 1:].any(axis=1))

    @property
    def any_off(self) -> np.ndarray:
        """[E] some ball, the cue ball included, left the table."""
        return self.cue_off | self.object_off

    @property
    def cue_lost(self) -> np.ndarray:
        """[E] the cue ball is no longer on the table: pocketed (a scratch) or off the table."""
        return self.scratch | self.cue_off


def in_phases(phase: np.ndarray, phases) -> np.ndarray:
    """[E] bool: ``phase`` is one of ``phases`` (a few constants; ``np.isin`` costs more than the comparisons)."""
    out = phase == phases[0]
    for p in phases[1:]:
        out |= phase == p
    return out


def lowest_on_table(pocket: np.ndarray) -> np.ndarray:
    """The lowest-numbered object ball on each table (-1 none)."""
    on = np.asarray(pocket)[:, 1:] < 0
    return np.where(on.any(axis=1), np.argmax(on, axis=1) + 1, -1).astype(np.int64)


def foul_code(f: Facts, first_ok: np.ndarray, is_break: np.ndarray, exempt: np.ndarray) -> np.ndarray:
    """The foul of each shot (FOUL_*), the most serious first: scratch, a
    ball off the table, no contact, wrong ball first, illegal break, no rail
    after contact. ``first_ok``: the first contact was a legal target;
    ``exempt``: shots free of the contact and rail requirements (a 9-ball
    push-out; a ball off the table is a foul on it too: WPA 9-ball 2.4
    suspends only the wrong-ball and no-rail fouls)."""
    code = np.full(len(f.first), FOUL_NONE, dtype=np.int64)
    no_rail = ~is_break & ~exempt & ~f.object_pocketed & ~f.rail
    bad_break = is_break & ~f.object_pocketed & (f.break_rails < BREAK_RAIL_BALLS)
    code[no_rail] = FOUL_NO_RAIL
    code[bad_break] = FOUL_BAD_BREAK
    code[~exempt & (f.first >= 1) & ~first_ok] = FOUL_WRONG_BALL
    code[~exempt & (f.first < 1)] = FOUL_NO_CONTACT
    code[f.any_off] = FOUL_OFF_TABLE
    code[f.scratch] = FOUL_SCRATCH
    return code


@dataclasses.dataclass(frozen=True, eq=False)
class RotationShot:
    """What 9-ball and 10-ball judge alike on one shot per table [E]: the
    ``facts``, ``is_break``, ``passed`` (the shot was handed back where the
    phase allows it: ``pass_phases``), ``played`` (not passed), ``pushed``
    (a push-out declared on the shot after the break), the ``foul`` (the
    lowest-numbered ball is the only legal first contact; a push-out is
    free of the contact and rail rules), ``legal`` and ``three`` (the
    shooter's third consecutive foul)."""

    facts: Facts
    is_break: np.ndarray
    passed: np.ndarray
    played: np.ndarray
    pushed: np.ndarray
    foul: np.ndarray
    legal: np.ndarray
    three: np.ndarray

    @classmethod
    def of(cls, game: GameState, shot: ShotInput, pass_phases=(PHASE_PUSHED,)) -> "RotationShot":
        f = Facts.of(shot)
        is_break = game.phase == PHASE_BREAK
        passed = np.asarray(shot.passed, dtype=bool) & in_phases(game.phase, pass_phases)
        played = ~passed
        pushed = np.asarray(shot.push_out, dtype=bool) & (game.phase == PHASE_AFTER_BREAK) & played
        lowest = lowest_on_table(shot.pocket_before)
        foul = np.where(played, foul_code(f, f.first == lowest, is_break, pushed), FOUL_NONE)
        three = (foul > 0) & (game.fouls[np.arange(game.n), game.shooter] + 1 >= THREE_FOULS)
        return cls(f, is_break, passed, played, pushed, foul, foul == FOUL_NONE, three)

    def next_phase(self, option: np.ndarray | None = None) -> np.ndarray:
        """The phase after the shot: the shot after the break only after a
        legal break (WPA 9-ball 2.4: a push-out only "if no foul is
        committed on the break shot"), pushed after a legal push-out, the
        incoming player's option where ``option`` [E] (10-ball), else open play."""
        phase = np.where(self.pushed & self.legal, PHASE_PUSHED, PHASE_PLAY)
        if option is not None:
            phase = np.where(option, PHASE_OPTION, phase)
        return np.where(self.is_break, np.where(self.legal, PHASE_AFTER_BREAK, PHASE_PLAY), phase).astype(np.int64)


class Rules:
    """A game's rules: ``n_balls`` object balls, ``judge`` (state and shot ->
    record and the next state, pure) and ``constraints`` (state and pockets
    -> what the next shooter may do)."""

    name: str = ""
    n_balls: int = 0
    calls_ball: bool = False  # the shooter calls a ball as well as a pocket (``ShotInput.called_ball``; 10-ball)
    game_ball: int = 0  # the ball whose legal pot wins the game (9-ball's 9, 8-ball's 8, 10-ball's 10; 0: none)
    groups: bool = False  # the players take groups (8-ball's solids and stripes: ``GameState.group``)
    game_ball_loses: bool = False  # the game ball pocketed early or on a foul loses the game (8-ball), not respotted
    # The equipment and what the game reads beyond the pool games (three-cushion sets them): the table
    # (``Table.style``: "pool" is ``Table.pool``), the physics preset the config's "standard" stands for
    # (None: "standard" itself), the cue-ball contacts kept in order (``SimOptions.contacts``; 0 none),
    # whether each player has their own cue ball (the envs keep the shooter's in slot 0), and the
    # observation entries the game adds (``observe_extra``).
    table_style: str = "pool"
    physics: str | None = None
    contacts: int = 0
    own_cue_balls: bool = False
    extra_obs: int = 0
    foul_points: bool = False  # a foul scores points for the opponent (``ShotRecord.penalty``; snooker)
    to_points: bool = False   # won on points (``GameState.score``: snooker, three-cushion), not by a last ball
    reads_position: bool = False  # ``constraints`` and ``judge`` read where the balls lie (free ball, touching ball)
    # a declaration may have the balls replaced (a6 in (0, 0.5]): snooker after a foul and a miss, three-cushion with
    # the cue ball touching a ball
    replaces: bool = False
    env_doc: str = ""  # what the game's envs add to the shared env docstring (its observation entries, its info)

    def new_game(self, breaker) -> GameState:
        """Fresh games before the opening shot (``GameState.new``)."""
        return GameState.new(breaker)

    def observe_extra(self, game: GameState) -> np.ndarray:
        """The game's own observation entries [E, extra_obs] in [0, 1] (none by default)."""
        return np.zeros((game.n, 0), dtype=np.float32)

    def judge(self, game: GameState, shot: ShotInput) -> tuple[ShotRecord, GameState]:
        raise NotImplementedError

    def constraints(self, game: GameState, pocket: np.ndarray) -> Constraints:
        raise NotImplementedError

    def respot(self, pos: np.ndarray, pocket: np.ndarray, balls: np.ndarray, table, R: float,
               pockets: np.ndarray) -> None:
        """Put the balls a ruling marks (``ShotRecord.respot`` [n, B]) back on the table, in place on ``pos``
        [n, B, 2] and ``pocket`` [n, B] (``contract.turn.play_turn`` calls it after every ruling): on the foot
        spot or the nearest free point behind it (``respot.respot``). Snooker spots its colours
        (``snooker.respot_colours``), three-cushion puts its balls on its own spots (``respot.carom_spots``)."""
        respot(pos, pocket, balls, table, R, pockets)

    def check(self, game: GameState, shot: ShotInput) -> None:
        """Shapes agree and no finished game is shot (ValueError otherwise)."""
        B = self.n_balls + 1
        if np.shape(shot.pocket_before) != (game.n, B):
            raise ValueError(f"{self.name}: shot must cover {game.n} tables of {B} balls, "
                             f"got pockets of shape {np.shape(shot.pocket_before)}")
        if np.any(game.over):
            raise ValueError(f"{self.name}: tables {np.nonzero(game.over)[0].tolist()} have finished their games")
        if np.any(np.asarray(shot.pocket_before)[:, 0] >= 0):
            raise ValueError(f"{self.name}: the cue ball must be on the table before a shot (place it first)")


def next_state(game: GameState, rec: ShotRecord, foul: np.ndarray, played: np.ndarray) -> GameState:
    """The state after ``rec`` common to both games: the shooter (switched
    on ``turn_over``), consecutive fouls (counted for the shooter on a foul,
    cleared on a legal shot; untouched when no shot was played), the shot
    count, over and winner. Phase, ball in hand and groups are the game's."""
    g = game.copy()
    ar = np.arange(g.n)
    s = game.shooter
    f = g.fouls[ar, s]
    g.fouls[ar, s] = np.where(played, np.where(foul > 0, f + 1, 0), f)
    g.shots += played
    g.shooter = np.where(rec.turn_over, 1 - s, s)
    g.over = rec.game_over.copy()
    g.winner = rec.winner.copy()
    return g
