"""One test per rule: a constructed position (which balls are on the table,
the game's phase, groups, fouls) and a constructed shot (first contact,
pockets, rails) judged by the rules layer."""
import numpy as np
import pytest

from billiards_env.rules import EightBallRules, GameState, NineBallRules, ShotInput
from billiards_env.rules import records as R

NINE, EIGHT = NineBallRules(), EightBallRules()


def position(rules, off=(), phase=R.PHASE_PLAY, shooter=0, fouls=(0, 0), groups=(0, 0), in_hand=R.IN_HAND_NONE):
    """One table: balls ``off`` already pocketed; a game state in ``phase``."""
    B = rules.n_balls + 1
    pocket = np.full((1, B), -1, dtype=np.int64)
    pocket[0, list(off)] = 0
    g = GameState.new([shooter])
    g.phase[:] = phase
    g.fouls[0] = fouls
    g.group[0] = groups
    g.ball_in_hand[:] = in_hand
    return g, pocket


def shot(pocket, first, potted=(), pocket_id=None, rails=(), object_rails=None, push_out=False, called=-1,
         passed=False):
    """A shot from ``pocket``: the cue ball hits ``first`` first, balls
    ``potted`` drop (into ``pocket_id`` for the 8 if given, else pocket 0),
    balls ``rails`` touch a rail after the contact."""
    after = pocket.copy()
    for b in potted:
        after[0, b] = 0
    if pocket_id is not None:
        after[0, 8] = pocket_id
    r = np.zeros(pocket.shape, dtype=np.int64)
    r[0, list(rails)] = 1
    orails = None
    if object_rails is not None:
        orails = np.zeros(pocket.shape, dtype=np.int64)
        orails[0, list(object_rails)] = 1
    return ShotInput(pocket, after, np.array([first]), r, orails, np.array([push_out]), np.array([called]),
                     np.array([passed]))


def judge(rules, g, s):
    rec, g2 = rules.judge(g, s)
    return rec, g2, rules.constraints(g2, s.pocket_after)


# ------------------------------------------------------------------ 9-ball --
def test_nine_legal_pot_keeps_the_table():
    g, p = position(NINE)
    rec, g2, c = judge(NINE, g, shot(p, 1, potted=[1]))
    assert rec.legal[0] and not rec.turn_over[0] and not rec.game_over[0]
    assert g2.shooter[0] == 0 and c.ball_in_hand[0] == R.IN_HAND_NONE and c.targets[0].tolist().index(True) == 2


def test_nine_legal_miss_passes_the_turn():
    g, p = position(NINE)
    rec, g2, c = judge(NINE, g, shot(p, 1, rails=[1]))
    assert rec.legal[0] and rec.turn_over[0] and g2.shooter[0] == 1 and c.ball_in_hand[0] == R.IN_HAND_NONE


@pytest.mark.parametrize("first,potted,rails,foul", [
    (3, [], [3], R.FOUL_WRONG_BALL),   # the 1 is the lowest ball: hitting the 3 first is a foul
    (-1, [], [], R.FOUL_NO_CONTACT),   # the cue ball touched nothing
    (1, [], [], R.FOUL_NO_RAIL),       # contact, but nothing pocketed and no ball to a rail
    (1, [0], [1], R.FOUL_SCRATCH),     # cue ball pocketed
    (1, [0, 1], [1], R.FOUL_SCRATCH),  # a ball pocketed with a scratch does not make the shot legal
])
def test_nine_fouls_give_ball_in_hand_anywhere(first, potted, rails, foul):
    g, p = position(NINE)
    rec, g2, c = judge(NINE, g, shot(p, first, potted=potted, rails=rails))
    assert rec.foul[0] == foul and not rec.legal[0] and rec.turn_over[0]
    assert g2.shooter[0] == 1 and c.ball_in_hand[0] == R.IN_HAND_ANYWHERE and g2.fouls[0].tolist() == [1, 0]


def test_nine_rail_by_cue_ball_counts():
    g, p = position(NINE)
    rec, _, _ = judge(NINE, g, shot(p, 1, rails=[0]))
    assert rec.legal[0]


def test_nine_on_a_legal_combination_wins():
    g, p = position(NINE, off=[1, 2, 3])
    rec, g2, c = judge(NINE, g, shot(p, 4, potted=[9]))
    assert rec.legal[0] and rec.game_over[0] and rec.winner[0] == 0 and rec.end[0] == R.END_NINE
    assert c.over[0] and not c.targets.any()


def test_nine_on_the_break_wins():
    g, p = position(NINE, phase=R.PHASE_BREAK, in_hand=R.IN_HAND_KITCHEN)
    rec, _, _ = judge(NINE, g, shot(p, 1, potted=[9]))
    assert rec.game_over[0] and rec.winner[0] == 0


def test_nine_on_the_break_spotted_option():
    """``spot_break_nine``: the 9 on a legal break is respotted, no win, and
    it counts as a ball pocketed (the breaker shoots on); later shots win."""
    spot = NineBallRules(spot_break_nine=True)
    g, p = position(spot, phase=R.PHASE_BREAK, in_hand=R.IN_HAND_KITCHEN)
    rec, g2, c = judge(spot, g, shot(p, 1, potted=[9]))
    assert rec.legal[0] and not rec.game_over[0] and rec.respot[0].tolist() == [False] * 9 + [True]
    assert not rec.turn_over[0] and g2.shooter[0] == 0 and c.push_out_allowed[0]
    g, p = position(spot, off=[1, 2])
    rec, _, _ = judge(spot, g, shot(p, 3, potted=[9]))
    assert rec.game_over[0] and rec.winner[0] == 0


def test_nine_on_a_foul_is_respotted():
    g, p = position(NINE, off=[1, 2])
    rec, g2, c = judge(NINE, g, shot(p, 5, potted=[9], rails=[5]))  # wrong ball first
    assert rec.foul[0] == R.FOUL_WRONG_BALL and not rec.game_over[0] and rec.respot[0, 9]
    assert rec.respot[0].sum() == 1 and c.ball_in_hand[0] == R.IN_HAND_ANYWHERE


def test_nine_break_must_hit_the_one_first():
    g, p = position(NINE, phase=R.PHASE_BREAK, in_hand=R.IN_HAND_KITCHEN)
    rec, _, _ = judge(NINE, g, shot(p, 2, potted=[5]))
    assert rec.foul[0] == R.FOUL_WRONG_BALL


def test_nine_break_four_balls_to_a_rail():
    g, p = position(NINE, phase=R.PHASE_BREAK, in_hand=R.IN_HAND_KITCHEN)
    rec, g2, c = judge(NINE, g, shot(p, 1, object_rails=[2, 3, 4]))
    assert rec.foul[0] == R.FOUL_BAD_BREAK and c.ball_in_hand[0] == R.IN_HAND_ANYWHERE and g2.shooter[0] == 1
    rec, g2, c = judge(NINE, g, shot(p, 1, object_rails=[2, 3, 4, 5]))
    assert rec.legal[0] and rec.turn_over[0] and c.push_out_allowed[0] and c.ball_in_hand[0] == R.IN_HAND_NONE


@pytest.mark.parametrize("first,potted,object_rails", [
    (1, [], [2, 3, 4]),    # an illegal break
    (1, [0, 5], [2]),      # a scratch on the break
    (3, [5], [3]),         # the 1 not hit first
])
def test_nine_no_push_out_after_a_foul_on_the_break(first, potted, object_rails):
    """WPA 2.4: a push-out only "if no foul is committed on the break shot";
    the incoming player has ball in hand and plays an ordinary shot."""
    g, p = position(NINE, phase=R.PHASE_BREAK, in_hand=R.IN_HAND_KITCHEN)
    rec, g2, c = judge(NINE, g, shot(p, first, potted=potted, object_rails=object_rails))
    assert not rec.legal[0] and g2.shooter[0] == 1 and c.ball_in_hand[0] == R.IN_HAND_ANYWHERE
    assert not c.push_out_allowed[0] and g2.phase[0] == R.PHASE_PLAY
    # a push-out declared anyway is judged as an ordinary shot: touching nothing is a foul
    rec2, _, _ = judge(NINE, g2, shot(p, -1, push_out=True))
    assert not rec2.push_out[0] and rec2.foul[0] == R.FOUL_NO_CONTACT


def test_nine_push_out_then_pass_back():
    g, p = position(NINE, phase=R.PHASE_AFTER_BREAK, shooter=1)
    # a push-out touching nothing and no rail is legal; a ball it pockets stays down
    rec, g2, c = judge(NINE, g, shot(p, -1, push_out=True))
    assert rec.legal[0] and rec.push_out[0] and rec.turn_over[0] and g2.shooter[0] == 0
    assert c.may_pass[0] and not c.push_out_allowed[0] and c.ball_in_hand[0] == R.IN_HAND_NONE
    rec2, g3, c3 = judge(NINE, g2, shot(p, -1, passed=True))  # player 0 hands the shot back
    assert rec2.passed[0] and rec2.legal[0] and g3.shooter[0] == 1 and not c3.may_pass[0]
    assert g3.shots[0] == g2.shots[0]  # no shot was played
    # a pass is only possible right after a push-out: elsewhere it is ignored (the shot is judged)
    rec4, _, _ = judge(NINE, g3, shot(p, 1, rails=[1], passed=True))
    assert not rec4.passed[0]


def test_nine_push_out_with_a_scratch_is_a_foul_and_nine_respotted():
    g, p = position(NINE, phase=R.PHASE_AFTER_BREAK)
    rec, g2, c = judge(NINE, g, shot(p, -1, potted=[0]))
    assert rec.foul[0] == R.FOUL_SCRATCH
    rec, g2, c = judge(NINE, g, shot(p, 3, potted=[0, 9], push_out=True))
    assert rec.foul[0] == R.FOUL_SCRATCH and c.ball_in_hand[0] == R.IN_HAND_ANYWHERE and not c.may_pass[0]
    rec, g2, c = judge(NINE, g, shot(p, 3, potted=[9], push_out=True))
    assert rec.legal[0] and rec.respot[0, 9] and not rec.game_over[0]  # a 9 pushed in is respotted


def test_nine_push_out_only_right_after_the_break():
    g, p = position(NINE, phase=R.PHASE_PLAY)
    rec, _, c = judge(NINE, g, shot(p, 3, rails=[3], push_out=True))
    assert not rec.push_out[0] and rec.foul[0] == R.FOUL_WRONG_BALL


def test_nine_three_consecutive_fouls_lose():
    g, p = position(NINE, fouls=(2, 0))
    rec, g2, _ = judge(NINE, g, shot(p, -1))
    assert rec.game_over[0] and rec.winner[0] == 1 and rec.end[0] == R.END_THREE_FOULS
    g, p = position(NINE, fouls=(1, 2))  # the opponent's fouls do not count against the shooter
    rec, g2, _ = judge(NINE, g, shot(p, -1))
    assert not rec.game_over[0] and g2.fouls[0].tolist() == [2, 2]


def test_nine_legal_shot_clears_the_foul_count():
    g, p = position(NINE, fouls=(2, 0))
    _, g2, _ = judge(NINE, g, shot(p, 1, rails=[1]))
    assert g2.fouls[0].tolist() == [0, 0]


def test_nine_finished_game_cannot_be_shot():
    g, p = position(NINE)
    g.over[:] = True
    with pytest.raises(ValueError, match="finished"):
        NINE.judge(g, shot(p, 1, rails=[1]))


# ------------------------------------------------------------------ 8-ball --
def test_eight_break_table_open_and_breaker_continues():
    g, p = position(EIGHT, phase=R.PHASE_BREAK, in_hand=R.IN_HAND_KITCHEN)
    rec, g2, c = judge(EIGHT, g, shot(p, 5, potted=[3]))
    assert rec.legal[0] and not rec.turn_over[0] and g2.group[0].tolist() == [0, 0]
    assert c.targets[0, 1:].sum() == 13 and not c.targets[0, 8]  # open: anything but the 8


def test_eight_break_scratch_ball_in_hand_behind_head_string():
    g, p = position(EIGHT, phase=R.PHASE_BREAK, in_hand=R.IN_HAND_KITCHEN)
    rec, g2, c = judge(EIGHT, g, shot(p, 1, potted=[0, 4]))
    assert rec.foul[0] == R.FOUL_SCRATCH and g2.shooter[0] == 1 and c.ball_in_hand[0] == R.IN_HAND_KITCHEN
    assert g2.group[0].tolist() == [0, 0]  # balls pocketed on the break assign no group


def test_eight_illegal_break_ball_in_hand_anywhere():
    g, p = position(EIGHT, phase=R.PHASE_BREAK, in_hand=R.IN_HAND_KITCHEN)
    rec, _, c = judge(EIGHT, g, shot(p, 1, object_rails=[1, 2, 3]))
    assert rec.foul[0] == R.FOUL_BAD_BREAK and c.ball_in_hand[0] == R.IN_HAND_ANYWHERE


def test_eight_on_the_break_is_respotted():
    g, p = position(EIGHT, phase=R.PHASE_BREAK, in_hand=R.IN_HAND_KITCHEN)
    rec, g2, _ = judge(EIGHT, g, shot(p, 1, potted=[8]))
    assert not rec.game_over[0] and rec.respot[0, 8] and not rec.turn_over[0]


@pytest.mark.parametrize("first,potted,group", [
    (2, [2], R.GROUP_SOLIDS), (12, [12], R.GROUP_STRIPES),
    (2, [12], R.GROUP_STRIPES),         # a solid hit first to pocket a stripe: stripes
    (11, [3, 10], R.GROUP_STRIPES),     # both groups: the group of the ball hit first
])
def test_eight_groups_by_first_legal_pot_after_the_break(first, potted, group):
    g, p = position(EIGHT, shooter=1)
    rec, g2, c = judge(EIGHT, g, shot(p, first, potted=potted))
    other = R.GROUP_SOLIDS + R.GROUP_STRIPES - group
    assert rec.legal[0] and not rec.turn_over[0] and g2.group[0].tolist() == [other, group]
    assert c.targets[0].sum() == 7 - sum(1 for b in potted if (b < 8) == (group == R.GROUP_SOLIDS))


def test_eight_no_group_on_a_foul():
    g, p = position(EIGHT)
    rec, g2, _ = judge(EIGHT, g, shot(p, 8, potted=[3]))  # the 8 first on an open table
    assert rec.foul[0] == R.FOUL_WRONG_BALL and g2.group[0].tolist() == [0, 0]


def test_eight_wrong_group_first_is_a_foul():
    g, p = position(EIGHT, groups=(R.GROUP_SOLIDS, R.GROUP_STRIPES))
    rec, g2, c = judge(EIGHT, g, shot(p, 10, potted=[10, 2]))
    assert rec.foul[0] == R.FOUL_WRONG_BALL and c.ball_in_hand[0] == R.IN_HAND_ANYWHERE and g2.shooter[0] == 1


def test_eight_only_opponent_balls_pocketed_passes_the_turn():
    g, p = position(EIGHT, groups=(R.GROUP_SOLIDS, R.GROUP_STRIPES))
    rec, g2, _ = judge(EIGHT, g, shot(p, 2, potted=[11]))
    assert rec.legal[0] and rec.turn_over[0]


def test_eight_early_eight_loses():
    g, p = position(EIGHT, groups=(R.GROUP_SOLIDS, R.GROUP_STRIPES), off=[1, 2, 3, 4, 5, 6])
    rec, _, _ = judge(EIGHT, g, shot(p, 7, potted=[7, 8]))  # the last solid and the 8 on one shot
    assert rec.game_over[0] and rec.winner[0] == 1 and rec.end[0] == R.END_EIGHT_EARLY


def test_eight_call_win_and_wrong_pocket():
    off = [1, 2, 3, 4, 5, 6, 7]
    g, p = position(EIGHT, groups=(R.GROUP_SOLIDS, R.GROUP_STRIPES), off=off)
    c = EIGHT.constraints(g, p)
    assert c.call_needed[0] and c.targets[0].tolist().count(True) == 1 and c.targets[0, 8]
    rec, _, _ = judge(EIGHT, g, shot(p, 8, potted=[8], pocket_id=4, called=4))
    assert rec.game_over[0] and rec.winner[0] == 0 and rec.end[0] == R.END_EIGHT
    rec, _, _ = judge(EIGHT, g, shot(p, 8, potted=[8], pocket_id=4, called=2))
    assert rec.game_over[0] and rec.winner[0] == 1 and rec.end[0] == R.END_EIGHT_POCKET


def test_eight_scratch_on_the_eight_loses():
    off = [9, 10, 11, 12, 13, 14, 15]
    g, p = position(EIGHT, groups=(R.GROUP_SOLIDS, R.GROUP_STRIPES), off=off, shooter=1)
    rec, _, _ = judge(EIGHT, g, shot(p, 8, potted=[0, 8], pocket_id=3, called=3))
    assert rec.foul[0] == R.FOUL_SCRATCH and rec.game_over[0] and rec.winner[0] == 0
    assert rec.end[0] == R.END_EIGHT_FOUL


def test_eight_foul_without_the_eight_does_not_lose():
    g, p = position(EIGHT, groups=(R.GROUP_SOLIDS, R.GROUP_STRIPES), off=[1, 2, 3, 4, 5, 6, 7])
    rec, _, c = judge(EIGHT, g, shot(p, 8, potted=[0]))
    assert rec.foul[0] == R.FOUL_SCRATCH and not rec.game_over[0] and c.ball_in_hand[0] == R.IN_HAND_ANYWHERE
    assert not c.call_needed[0]  # the opponent is on stripes


def test_batched_tables_are_independent():
    """Two tables judged in one call give the rulings of each judged alone."""
    g0, p = position(NINE)
    s_a, s_b = shot(p, 1, potted=[1]), shot(p, 4, rails=[4])
    g = GameState.new([0, 1])
    both = ShotInput(np.concatenate([s_a.pocket_before, s_b.pocket_before]),
                     np.concatenate([s_a.pocket_after, s_b.pocket_after]), np.array([1, 4]),
                     np.concatenate([s_a.rails, s_b.rails]))
    g.phase[:] = R.PHASE_PLAY
    rec, _ = NINE.judge(g, both)
    assert rec.legal.tolist() == [True, False] and rec.turn_over.tolist() == [False, True]
    assert rec.shooter.tolist() == [0, 1]
