"""10-ball, one test per rule: a constructed position and a constructed shot
(first contact, which ball fell in which pocket, rails, the call) judged
by the rules layer. The rules that read contacts are also played through
the simulator in tests/envs/test_ten_ball.py."""
import numpy as np
import pytest

from billiards_env.rules import GameState, ShotInput, TenBallRules
from billiards_env.rules import records as R

TEN = TenBallRules()


def position(off=(), phase=R.PHASE_PLAY, shooter=0, fouls=(0, 0), in_hand=R.IN_HAND_NONE):
    """One table: balls ``off`` already pocketed; a game state in ``phase``."""
    pocket = np.full((1, 11), -1, dtype=np.int64)
    pocket[0, list(off)] = 0
    g = GameState.new([shooter])
    g.phase[:] = phase
    g.fouls[0] = fouls
    g.ball_in_hand[:] = in_hand
    return g, pocket


def shot(pocket, first, potted=None, rails=(), object_rails=None, ball=R.CALL_NONE, called=-1, push_out=False,
         passed=False):
    """A shot from ``pocket``: the cue ball hits ``first`` first, ``potted``
    maps each ball that drops to its pocket, balls ``rails`` touch a rail
    after the contact; the call is ``ball`` into pocket ``called``."""
    after = pocket.copy()
    for b, k in (potted or {}).items():
        after[0, b] = k
    r = np.zeros(pocket.shape, dtype=np.int64)
    r[0, list(rails)] = 1
    orails = None
    if object_rails is not None:
        orails = np.zeros(pocket.shape, dtype=np.int64)
        orails[0, list(object_rails)] = 1
    return ShotInput(pocket, after, np.array([first]), r, orails, np.array([push_out]), np.array([called]),
                     np.array([passed]), np.array([ball]))


def judge(g, s):
    rec, g2 = TEN.judge(g, s)
    return rec, g2, TEN.constraints(g2, s.pocket_after)


def test_called_ball_in_the_called_pocket_keeps_the_table():
    g, p = position()
    rec, g2, c = judge(g, shot(p, 1, potted={1: 3}, ball=1, called=3))
    assert rec.legal[0] and not rec.turn_over[0] and not rec.option[0] and g2.shooter[0] == 0
    assert c.call_needed[0] and c.targets[0].tolist().index(True) == 2 and not c.may_pass[0]


def test_a_combination_may_be_called():
    """Any ball may be called, the lowest is still hit first: the 1 into the 6, the 6 called."""
    g, p = position()
    rec, _, _ = judge(g, shot(p, 1, potted={6: 2}, ball=6, called=2))
    assert rec.legal[0] and not rec.turn_over[0]


@pytest.mark.parametrize("potted,ball,called", [
    ({1: 4}, 1, 3),          # the called ball in another pocket
    ({5: 3}, 1, 3),          # another ball pocketed, the called one missed
    ({1: 3}, R.CALL_SAFETY, -1),  # anything pocketed on a called safety
    ({10: 1}, 1, 3),         # the 10 pocketed without being called: spotted, and an illegal pot
])
def test_illegal_pot_gives_the_incoming_player_the_option(potted, ball, called):
    g, p = position()
    rec, g2, c = judge(g, shot(p, 1, potted=potted, rails=[1], ball=ball, called=called))
    assert rec.legal[0] and rec.turn_over[0] and rec.option[0] and not rec.game_over[0]
    assert g2.shooter[0] == 1 and g2.phase[0] == R.PHASE_OPTION
    assert c.may_pass[0] and c.ball_in_hand[0] == R.IN_HAND_NONE and not c.push_out_allowed[0]
    assert rec.respot[0, 10] == (10 in potted) and rec.respot[0].sum() == (10 in potted)


def test_option_pass_back_then_the_offender_must_shoot():
    g, p = position()
    rec, g2, c = judge(g, shot(p, 1, potted={5: 3}, rails=[1], ball=1, called=3))
    after = shot(p, 1, potted={5: 3}).pocket_after
    rec2, g3, c3 = judge(g2, shot(after, -1, passed=True))  # player 1 hands the table back
    assert rec2.passed[0] and rec2.legal[0] and g3.shooter[0] == 0 and g3.shots[0] == g2.shots[0]
    assert not c3.may_pass[0] and g3.phase[0] == R.PHASE_PLAY
    rec3, _, _ = judge(g3, shot(after, 1, rails=[1], ball=1, called=0, passed=True))  # no second pass
    assert not rec3.passed[0]
    # or the incoming player takes the shot: an ordinary called shot
    rec4, g4, _ = judge(g2, shot(after, 1, potted={1: 0}, ball=1, called=0))
    assert rec4.legal[0] and not rec4.turn_over[0] and g4.shooter[0] == 1


def test_a_miss_that_pockets_nothing_passes_the_turn_without_option():
    g, p = position()
    rec, g2, c = judge(g, shot(p, 1, rails=[1], ball=1, called=3))
    assert rec.legal[0] and rec.turn_over[0] and not rec.option[0] and not c.may_pass[0]


def test_a_legal_called_ten_wins():
    g, p = position(off=range(1, 10))
    rec, g2, c = judge(g, shot(p, 10, potted={10: 5}, ball=10, called=5))
    assert rec.game_over[0] and rec.winner[0] == 0 and rec.end[0] == R.END_TEN and not rec.respot[0].any()
    assert c.over[0]


def test_the_ten_called_on_a_combination_wins():
    g, p = position(off=range(1, 4))
    rec, _, _ = judge(g, shot(p, 4, potted={10: 2}, ball=10, called=2))
    assert rec.game_over[0] and rec.winner[0] == 0


def test_the_ten_in_another_pocket_is_spotted():
    g, p = position(off=range(1, 10))
    rec, g2, c = judge(g, shot(p, 10, potted={10: 4}, ball=10, called=5))
    assert not rec.game_over[0] and rec.respot[0, 10] and rec.option[0] and c.may_pass[0]


def test_the_ten_with_the_called_ball_is_spotted_and_the_shooter_continues():
    g, p = position()
    rec, _, _ = judge(g, shot(p, 1, potted={1: 0, 10: 2}, ball=1, called=0))
    assert rec.legal[0] and not rec.turn_over[0] and not rec.game_over[0] and rec.respot[0, 10]


def test_the_ten_on_a_foul_is_spotted_and_ball_in_hand():
    g, p = position(off=range(1, 10))
    rec, g2, c = judge(g, shot(p, 10, potted={0: 1, 10: 5}, ball=10, called=5))  # scratch
    assert rec.foul[0] == R.FOUL_SCRATCH and not rec.game_over[0] and rec.respot[0, 10]
    assert c.ball_in_hand[0] == R.IN_HAND_ANYWHERE and not c.may_pass[0] and g2.shooter[0] == 1


def test_the_ten_on_the_break_is_spotted_and_the_breaker_continues():
    g, p = position(phase=R.PHASE_BREAK, in_hand=R.IN_HAND_KITCHEN)
    rec, g2, c = judge(g, shot(p, 1, potted={10: 1}))
    assert rec.legal[0] and not rec.game_over[0] and rec.respot[0, 10] and not rec.turn_over[0]
    assert c.push_out_allowed[0] and g2.shooter[0] == 0


def test_the_break_needs_no_call_and_its_pots_keep_the_table():
    g, p = position(phase=R.PHASE_BREAK, in_hand=R.IN_HAND_KITCHEN)
    assert not TEN.constraints(g, p).call_needed[0]
    rec, _, c = judge(g, shot(p, 1, potted={4: 2, 7: 5}))
    assert rec.legal[0] and not rec.turn_over[0] and not rec.option[0] and c.call_needed[0]


@pytest.mark.parametrize("first,potted,object_rails,foul", [
    (2, {5: 1}, [2], R.FOUL_WRONG_BALL),     # the 1 not hit first
    (1, {}, [2, 3, 4], R.FOUL_BAD_BREAK),    # nothing pocketed, three balls to a rail
    (1, {0: 0, 3: 1}, [2], R.FOUL_SCRATCH),  # a scratch
])
def test_a_foul_on_the_break_gives_ball_in_hand_and_no_push_out(first, potted, object_rails, foul):
    g, p = position(phase=R.PHASE_BREAK, in_hand=R.IN_HAND_KITCHEN)
    rec, g2, c = judge(g, shot(p, first, potted=potted, object_rails=object_rails))
    assert rec.foul[0] == foul and g2.shooter[0] == 1 and c.ball_in_hand[0] == R.IN_HAND_ANYWHERE
    assert not c.push_out_allowed[0] and g2.fouls[0].tolist() == [1, 0]


def test_push_out_after_a_legal_break_then_pass_back():
    g, p = position(phase=R.PHASE_AFTER_BREAK, shooter=1)
    c0 = TEN.constraints(g, p)
    assert c0.push_out_allowed[0] and c0.call_needed[0]  # a call unless the shot is pushed
    rec, g2, c = judge(g, shot(p, -1, potted={4: 2, 10: 0}, push_out=True))  # no contact, balls drop: legal
    assert rec.legal[0] and rec.push_out[0] and rec.turn_over[0] and not rec.option[0] and rec.respot[0, 10]
    assert c.may_pass[0] and g2.phase[0] == R.PHASE_PUSHED and g2.shooter[0] == 0
    rec2, g3, _ = judge(g2, shot(p, -1, passed=True))
    assert rec2.passed[0] and g3.shooter[0] == 1


def test_push_out_only_on_the_shot_after_the_break():
    g, p = position(phase=R.PHASE_PLAY)
    rec, _, _ = judge(g, shot(p, 3, rails=[3], push_out=True, ball=3, called=0))
    assert not rec.push_out[0] and rec.foul[0] == R.FOUL_WRONG_BALL


@pytest.mark.parametrize("first,potted,rails,foul", [
    (3, {3: 0}, [3], R.FOUL_WRONG_BALL),
    (-1, {}, [], R.FOUL_NO_CONTACT),
    (1, {}, [], R.FOUL_NO_RAIL),
    (1, {0: 2, 1: 0}, [1], R.FOUL_SCRATCH),
])
def test_fouls_give_ball_in_hand_anywhere(first, potted, rails, foul):
    g, p = position()
    rec, g2, c = judge(g, shot(p, first, potted=potted, rails=rails, ball=first, called=0))
    assert rec.foul[0] == foul and rec.turn_over[0] and not rec.option[0]
    assert g2.shooter[0] == 1 and c.ball_in_hand[0] == R.IN_HAND_ANYWHERE and not c.may_pass[0]


def test_three_consecutive_fouls_lose_and_a_pass_does_not_clear_them():
    g, p = position(fouls=(2, 0))
    rec, _, _ = judge(g, shot(p, -1))
    assert rec.game_over[0] and rec.winner[0] == 1 and rec.end[0] == R.END_THREE_FOULS
    g, p = position(fouls=(2, 0), phase=R.PHASE_OPTION, shooter=0)
    rec, g2, _ = judge(g, shot(p, -1, passed=True))
    assert rec.passed[0] and g2.fouls[0].tolist() == [2, 0] and g2.shooter[0] == 1


def test_tables_are_judged_independently():
    g1, p = position()
    a, b = shot(p, 1, potted={1: 3}, ball=1, called=3), shot(p, 1, potted={1: 3}, rails=[1], ball=1, called=2)
    g = GameState.new([0, 0])
    g.phase[:] = R.PHASE_PLAY
    both = ShotInput(np.concatenate([a.pocket_before, b.pocket_before]), np.concatenate([a.pocket_after, b.pocket_after]),
                     np.array([1, 1]), np.concatenate([a.rails, b.rails]), called_pocket=np.array([3, 2]),
                     called_ball=np.array([1, 1]))
    rec, _ = TEN.judge(g, both)
    assert rec.turn_over.tolist() == [False, True] and rec.option.tolist() == [False, True]
