"""Balls driven off the table (issue 46; docs/rules.md, "Balls off the table"), one test per ruling in
every game: constructed positions and shots whose ``pocket_after`` holds an off-table code
(``physics.constants.OFF_RAIL`` / ``OFF_FLOOR``, what the simulator's airborne effect leaves), judged by
the rules layer; no simulator is needed. Before these rulings every code >= 0 read as pocketed, so each
ball off the table below would have been a legal pot (the 9 off the table a win)."""
import numpy as np
import pytest

from billiards_env.physics import constants as C
from billiards_env.physics.params import PhysicsParams
from billiards_env.physics.table import Table
from billiards_env.rules import (EightBallRules, GameState, NineBallRules, ShotInput, SnookerRules, TenBallRules,
                                 ThreeCushionRules)
from billiards_env.rules import records as R
from billiards_env.rules.placement import CENTRE_SPOT, FOOT_SPOT, HEAD_STRING
from billiards_env.rules.respot import carom_spots
from billiards_env.rules.snooker import BLACK, FIRST_COLOUR

OFF = (C.OFF_RAIL, C.OFF_FLOOR)
PINK = FIRST_COLOUR + 4


def _shot(pocket, first, potted=(), off=(), code=C.OFF_FLOOR, rails=(), called=-1, ball=R.CALL_NONE, **kw):
    """A shot from ``pocket`` [1, B]: the cue ball hits ``first`` first, balls ``potted`` drop in pocket 2,
    balls ``off`` leave the table (``code``), balls ``rails`` touch a rail after the contact."""
    after = pocket.copy()
    after[0, list(potted)] = 2
    after[0, list(off)] = code
    r = np.zeros(pocket.shape, dtype=np.int64)
    r[0, list(rails)] = 1
    return ShotInput(pocket, after, np.array([first]), r, r.copy(), called_pocket=np.array([called]),
                     called_ball=np.array([ball]), **kw)


def _position(rules, down=(), phase=R.PHASE_PLAY, groups=(0, 0)):
    g = rules.new_game([0])
    g.phase[:] = phase
    g.ball_in_hand[:] = R.IN_HAND_NONE
    g.group[0] = groups
    pocket = np.full((1, rules.n_balls + 1), -1, dtype=np.int64)
    pocket[0, list(down)] = 0
    return g, pocket


def test_off_the_table_is_not_pocketed():
    p = np.full((1, 4), -1, dtype=np.int64)
    p[0, 3] = 1                                          # already down before the shot
    s = _shot(p, 1, potted=[1], off=[2])
    assert s.pocketed[0].tolist() == [False, True, False, False]
    assert s.off_table[0].tolist() == [False, False, True, False]
    assert R.FOUL_NAMES[R.FOUL_OFF_TABLE] == "a ball left the table"


# ------------------------------------------------------------------ 9-ball --
@pytest.mark.parametrize("code", OFF)
def test_nine_object_ball_off_is_a_foul_and_stays_off(code):
    """WPA: driving an object ball off the table is a foul; in 9-ball no ball but the 9 is spotted. The 3 off
    with the 1 potted legally would have kept the table before; now ball in hand, the 3 stays off."""
    rules = NineBallRules()
    g, p = _position(rules)
    rec, g2 = rules.judge(g, _shot(p, 1, potted=[1], off=[3], code=code, rails=[1]))
    assert rec.foul[0] == R.FOUL_OFF_TABLE and not rec.legal[0] and rec.turn_over[0]
    assert not rec.respot[0].any() and g2.ball_in_hand[0] == R.IN_HAND_ANYWHERE and g2.shooter[0] == 1
    c = rules.constraints(g2, np.where(rec.respot, -1, _shot(p, 1, potted=[1], off=[3]).pocket_after))
    assert np.flatnonzero(c.targets[0]).tolist() == [2]  # the 3 is gone: the 2 is the lowest ball


def test_nine_off_the_table_is_spotted_and_does_not_win():
    rules = NineBallRules()
    g, p = _position(rules)
    rec, g2 = rules.judge(g, _shot(p, 1, off=[9], rails=[1]))
    assert not rec.game_over[0] and rec.winner[0] == -1 and rec.foul[0] == R.FOUL_OFF_TABLE
    assert rec.respot[0].tolist() == [False] * 9 + [True] and g2.ball_in_hand[0] == R.IN_HAND_ANYWHERE


def test_nine_cue_ball_off_is_a_foul_with_ball_in_hand():
    rules = NineBallRules()
    g, p = _position(rules)
    rec, g2 = rules.judge(g, _shot(p, 1, potted=[2], off=[0], rails=[1]))
    assert rec.foul[0] == R.FOUL_OFF_TABLE and rec.turn_over[0] and not rec.respot[0].any()
    assert g2.shooter[0] == 1 and g2.ball_in_hand[0] == R.IN_HAND_ANYWHERE and g2.fouls[0].tolist() == [1, 0]


def test_nine_off_the_table_on_a_push_out_is_still_a_foul():
    rules = NineBallRules()
    g, p = _position(rules, phase=R.PHASE_AFTER_BREAK)
    rec, _ = rules.judge(g, _shot(p, -1, off=[5], push_out=np.array([True])))
    assert rec.push_out[0] and rec.foul[0] == R.FOUL_OFF_TABLE


# ----------------------------------------------------------------- 10-ball --
def test_ten_off_the_table_is_spotted_others_stay_off():
    rules = TenBallRules()
    g, p = _position(rules)
    rec, g2 = rules.judge(g, _shot(p, 1, potted=[1], off=[10, 4], rails=[1], called=2, ball=1))
    assert rec.foul[0] == R.FOUL_OFF_TABLE and not rec.game_over[0] and not rec.option[0]
    assert np.flatnonzero(rec.respot[0]).tolist() == [10] and g2.ball_in_hand[0] == R.IN_HAND_ANYWHERE


def test_ten_cue_ball_off_is_a_foul_with_ball_in_hand():
    rules = TenBallRules()
    g, p = _position(rules)
    rec, g2 = rules.judge(g, _shot(p, 1, potted=[1], off=[0], rails=[1], called=2, ball=1))
    assert rec.foul[0] == R.FOUL_OFF_TABLE and rec.turn_over[0] and g2.ball_in_hand[0] == R.IN_HAND_ANYWHERE


# ------------------------------------------------------------------ 8-ball --
def test_eight_off_the_table_loses_the_rack():
    rules = EightBallRules()
    g, p = _position(rules, down=range(1, 8), groups=(R.GROUP_SOLIDS, R.GROUP_STRIPES))  # on the 8
    rec, g2 = rules.judge(g, _shot(p, 8, off=[8], rails=[8], called=2))
    assert rec.game_over[0] and rec.end[0] == R.END_EIGHT_OFF and rec.winner[0] == 1 and not rec.respot[0].any()
    assert R.END_NAMES[R.END_EIGHT_OFF] == "8 driven off the table"


def test_eight_off_the_table_on_the_break_is_spotted_and_a_foul():
    rules = EightBallRules()
    g, p = _position(rules, phase=R.PHASE_BREAK)
    rec, g2 = rules.judge(g, _shot(p, 1, potted=[3], off=[8], rails=[1, 2, 4, 5]))
    assert not rec.game_over[0] and rec.foul[0] == R.FOUL_OFF_TABLE and rec.turn_over[0]
    assert np.flatnonzero(rec.respot[0]).tolist() == [8] and g2.ball_in_hand[0] == R.IN_HAND_ANYWHERE


def test_eight_group_ball_off_is_a_foul_and_stays_off():
    rules = EightBallRules()
    g, p = _position(rules, groups=(R.GROUP_SOLIDS, R.GROUP_STRIPES))
    rec, g2 = rules.judge(g, _shot(p, 1, potted=[1], off=[2], rails=[1]))
    assert rec.foul[0] == R.FOUL_OFF_TABLE and rec.turn_over[0] and not rec.respot[0].any()
    assert g2.ball_in_hand[0] == R.IN_HAND_ANYWHERE and not rec.game_over[0]


@pytest.mark.parametrize("phase,hand", [(R.PHASE_BREAK, R.IN_HAND_KITCHEN), (R.PHASE_PLAY, R.IN_HAND_ANYWHERE)])
def test_eight_cue_ball_off_is_ruled_as_a_scratch(phase, hand):
    rules = EightBallRules()
    g, p = _position(rules, phase=phase)
    rec, g2 = rules.judge(g, _shot(p, 1, potted=[3], off=[0], rails=[1, 2, 4, 5]))
    assert rec.foul[0] == R.FOUL_OFF_TABLE and rec.turn_over[0] and g2.ball_in_hand[0] == hand


# ----------------------------------------------------------------- snooker --
def test_snooker_colour_forced_off_is_a_foul_worth_it_and_spotted():
    rules = SnookerRules()
    g, p = _position(rules)                              # reds on: a red is on
    rec, g2 = rules.judge(g, _shot(p, 1, potted=[1], off=[PINK]))
    assert rec.foul[0] == R.FOUL_OFF_TABLE and rec.penalty[0] == 6 and rec.points[0] == 0
    assert g2.score[0].tolist() == [0, 6] and rec.turn_over[0] and rec.option[0]
    assert np.flatnonzero(rec.respot[0]).tolist() == [PINK]   # the pink spotted, the potted red stays down


def test_snooker_red_forced_off_stays_off_and_costs_at_least_four():
    rules = SnookerRules()
    g, p = _position(rules)
    rec, g2 = rules.judge(g, _shot(p, 1, off=[2]))
    assert rec.foul[0] == R.FOUL_OFF_TABLE and rec.penalty[0] == 4 and not rec.respot[0].any()


def test_snooker_cue_ball_forced_off_is_in_hand_in_the_d():
    rules = SnookerRules()
    g, p = _position(rules)
    rec, g2 = rules.judge(g, _shot(p, 1, off=[0]))
    assert rec.foul[0] == R.FOUL_OFF_TABLE and rec.penalty[0] == 4 and not rec.respot[0].any()
    assert g2.ball_in_hand[0] == R.IN_HAND_D and g2.shooter[0] == 1


def test_snooker_last_black_forced_off_ends_the_frame():
    rules = SnookerRules()
    g, p = _position(rules, down=range(1, BLACK))
    g.score[0] = (30, 40)
    rec, g2 = rules.judge(g, _shot(p, BLACK, off=[BLACK]))
    assert rec.foul[0] == R.FOUL_OFF_TABLE and rec.penalty[0] == 7 and rec.game_over[0]
    assert rec.winner[0] == 1 and g2.score[0].tolist() == [30, 47]


# ----------------------------------------------------------- three-cushion --
def _point_contacts():
    """A point: the opponent's ball, three cushions, the red."""
    k = [[C.EV_BALL_BALL, 1]] + [[C.EV_CUSHION, 0]] * 3 + [[C.EV_BALL_BALL, 2]]
    return np.array([k]), np.array([len(k)])


@pytest.mark.parametrize("jumped", [[0], [1], [2], [0, 2]])
def test_three_cushion_jumped_ball_is_a_foul_the_point_does_not_count(jumped):
    rules = ThreeCushionRules()
    g = rules.new_game([0])
    g.phase[:] = R.PHASE_PLAY
    p = np.full((1, 3), -1, dtype=np.int64)
    contacts, n = _point_contacts()
    rec, g2 = rules.judge(g, _shot(p, 1, off=jumped, contacts=contacts, n_contacts=n))
    assert rec.foul[0] == R.FOUL_OFF_TABLE and rec.points[0] == 0 and g2.score[0].tolist() == [0, 0]
    assert rec.turn_over[0] and g2.shooter[0] == 1 and np.flatnonzero(rec.respot[0]).tolist() == jumped


def test_three_cushion_jumped_balls_go_on_their_spots_or_the_occupier_s():
    T, R_ = Table.carom(), PhysicsParams.carom().R
    x, L = T.width / 2, T.length
    pos = np.array([[[0.3, 0.4], [1.0, 2.0], [0.5, 1.0]]] * 2)
    pocket = np.array([[-1, C.OFF_FLOOR, C.OFF_RAIL]] * 2)
    pos[1, 0] = (x, FOOT_SPOT * L)                       # table 1: the shooter's ball lies on the red's spot
    carom_spots(pos, pocket, pocket >= 0, T, R_)
    assert (pocket == -1).all()
    assert np.allclose(pos[0, 2], (x, FOOT_SPOT * L)) and np.allclose(pos[0, 1], (x, HEAD_STRING * L))
    # the red's spot taken by the shooter's ball: the red goes to that ball's spot (the centre spot)
    assert np.allclose(pos[1, 2], (x, CENTRE_SPOT * L)) and np.allclose(pos[1, 1], (x, HEAD_STRING * L))
    assert np.allclose(pos[1, 0], (x, FOOT_SPOT * L))


def test_pool_games_respot_on_the_foot_spot():
    """``Rules.respot`` (what ``contract.turn.play_turn`` applies): the 9 that left the table back on the foot
    spot, the pocket code cleared."""
    T, R_ = Table.pool(), PhysicsParams().R
    pos = np.zeros((1, 10, 2))
    pos[0, :, 0] = np.linspace(0.2, 1.0, 10)
    pos[0, :, 1] = 0.3
    pocket = np.full((1, 10), -1)
    pocket[0, 9] = C.OFF_FLOOR
    balls = pocket >= C.OFF_TABLE
    NineBallRules().respot(pos, pocket, balls, T, R_, np.asarray(T.geometry(True)[3], dtype=np.float64))
    assert pocket[0, 9] == -1 and np.allclose(pos[0, 9], (T.width / 2, FOOT_SPOT * T.length))


def test_the_ruling_words_name_the_balls_off_the_table():
    from billiards_env.rendering.game_words import foul_words, ruling_words
    shot = dict(shooter=0, before={"break": False}, after={"to_move": 1, "fouls": [1, 0], "ball_in_hand": "anywhere",
                                                           "shots": 3}, legal=False, turn_over=True, game_over=False,
                pocketed=[1], respotted=[9], off_table=[9], foul=foul_words(R.FOUL_OFF_TABLE), game_name="nine_ball")
    text = ruling_words(shot, ["Player 1", "Player 2"])
    assert "pots the 1, drives the 9 off the table: foul (a ball left the table)" in text and "respotted" in text
