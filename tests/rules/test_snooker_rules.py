"""Snooker, one test per rule: a constructed position and a constructed shot
(first contact, which balls fell, the nomination, the pass) judged by the
rules layer; the free ball's "snookered" is decided from constructed
positions. The rules through the simulator: tests/envs/test_snooker.py."""
import numpy as np
import pytest

from billiards_env.physics import PhysicsParams, Table
from billiards_env.rules import GameState, ShotInput, SnookerRules
from billiards_env.rules import records as R
from billiards_env.rules.snooker import (BLACK, FIRST_COLOUR, TOUCH_TOL, balls_on, needs_snookers, points_left,
                                         respot_colours, snookered)

SNK = SnookerRules()
YELLOW, GREEN, BROWN, BLUE, PINK = range(FIRST_COLOUR, FIRST_COLOUR + 5)
RED = 1
B = 22
TABLE = Table.snooker()
P = PhysicsParams.snooker()


def position(off=(), phase=R.PHASE_PLAY, shooter=0, score=(0, 0), in_hand=R.IN_HAND_NONE, pos=None):
    """One table: balls ``off`` already pocketed; a game state in ``phase``."""
    pocket = np.full((1, B), -1, dtype=np.int64)
    pocket[0, list(off)] = 0
    g = GameState.new([shooter])
    g.phase[:] = phase
    g.ball_in_hand[:] = in_hand
    g.score[0] = score
    return g, pocket


def shot(pocket, first, potted=(), nominate=R.CALL_NONE, passed=False, pos=None):
    after = pocket.copy()
    for b in potted:
        after[0, b] = 2
    z = np.zeros(pocket.shape, dtype=np.int64)
    return ShotInput(pocket, after, np.array([first]), z, z, None, None, np.array([passed]), np.array([nominate]),
                     pos_before=pos)


def reds_off(keep=()):
    return [b for b in range(1, 16) if b not in keep]


def judge(g, s):
    rec, g2 = SNK.judge(g, s)
    return rec, g2, SNK.constraints(g2, s.pocket_after)


def test_a_red_scores_one_and_a_colour_is_on_next():
    g, p = position()
    rec, g2, c = judge(g, shot(p, RED, potted=[RED, 2]))
    assert rec.legal[0] and rec.points[0] == 2 and g2.score[0].tolist() == [2, 0]
    assert not rec.turn_over[0] and g2.phase[0] == R.PHASE_COLOUR
    assert c.targets[0, FIRST_COLOUR:].all() and not c.targets[0, 1:16].any() and c.call_needed[0]


def test_the_nominated_colour_scores_and_is_respotted_while_reds_remain():
    g, p = position(off=[RED], phase=R.PHASE_COLOUR)
    rec, g2, c = judge(g, shot(p, BLUE, potted=[BLUE], nominate=BLUE))
    assert rec.legal[0] and rec.points[0] == 5 and rec.respot[0, BLUE] and not rec.turn_over[0]
    assert g2.phase[0] == R.PHASE_PLAY and c.targets[0, 2:16].all() and not c.targets[0, FIRST_COLOUR:].any()


def test_hitting_another_colour_than_the_nominated_one_is_a_foul_worth_the_higher():
    g, p = position(off=[RED], phase=R.PHASE_COLOUR)
    rec, g2, _ = judge(g, shot(p, BLACK, nominate=GREEN))
    assert rec.foul[0] == R.FOUL_WRONG_BALL and rec.penalty[0] == 7 and g2.score[0].tolist() == [0, 7]
    assert rec.turn_over[0]


def test_without_a_nomination_the_colour_hit_first_is_the_nominated_one():
    g, p = position(off=[RED], phase=R.PHASE_COLOUR)
    rec, _, _ = judge(g, shot(p, PINK, potted=[PINK]))
    assert rec.legal[0] and rec.points[0] == 6


def test_a_colour_potted_on_a_red_is_a_foul_and_respotted_reds_stay_down():
    g, p = position()
    rec, g2, c = judge(g, shot(p, RED, potted=[RED, PINK]))
    assert rec.foul[0] == R.FOUL_WRONG_POT and rec.penalty[0] == 6 and rec.points[0] == 0
    assert rec.respot[0, PINK] and not rec.respot[0, RED] and g2.score[0].tolist() == [0, 6]


@pytest.mark.parametrize("first, potted, value", [
    (-1, (), 4),                 # no ball hit: the least penalty, 4
    (RED, (0,), 4),              # an in-off off a red
    (BROWN, (), 4),              # a colour first when a red is on: its value, at least 4
    (BLUE, (), 5),
    (RED, (RED, BLACK), 7),      # a ball pocketed: its value
])
def test_foul_values(first, potted, value):
    g, p = position()
    rec, g2, _ = judge(g, shot(p, first, potted=potted))
    assert rec.foul[0] > 0 and rec.penalty[0] == value and g2.score[0, 1] == value and rec.points[0] == 0


def test_foul_value_is_the_ball_on_when_higher():
    g, p = position(off=reds_off() + [YELLOW, GREEN, BROWN, BLUE])  # pink and black left: the pink is on
    rec, _, _ = judge(g, shot(p, -1))
    assert rec.penalty[0] == 6


def test_clearance_in_order_colours_stay_down():
    g, p = position(off=reds_off())
    c = SNK.constraints(g, p)
    assert c.targets[0].tolist() == [i == YELLOW for i in range(B)]
    rec, g2, c2 = judge(g, shot(p, YELLOW, potted=[YELLOW]))
    assert rec.points[0] == 2 and not rec.respot[0].any() and c2.targets[0, GREEN] and c2.targets[0].sum() == 1
    rec, _, _ = judge(g, shot(p, GREEN, potted=[GREEN]))  # out of order: a foul, the green respotted
    assert rec.foul[0] == R.FOUL_WRONG_BALL and rec.penalty[0] == 4 and rec.respot[0, GREEN]


def test_the_colour_after_the_last_red_is_respotted_then_the_clearance_starts():
    g, p = position(off=reds_off() , phase=R.PHASE_COLOUR)
    rec, g2, c = judge(g, shot(p, BLACK, potted=[BLACK], nominate=BLACK))
    assert rec.points[0] == 7 and rec.respot[0, BLACK] and g2.phase[0] == R.PHASE_PLAY
    assert c.targets[0, YELLOW] and c.targets[0].sum() == 1


def test_the_incoming_player_may_put_the_offender_back_in():
    g, p = position()
    rec, g2, c = judge(g, shot(p, -1))  # player 0 misses everything
    assert rec.option[0] and g2.shooter[0] == 1 and g2.phase[0] == R.PHASE_OPTION and c.may_pass[0]
    rec2, g3, c3 = judge(g2, shot(p, -1, passed=True))
    assert rec2.passed[0] and g3.shooter[0] == 0 and g3.shots[0] == g2.shots[0] and not c3.may_pass[0]
    assert g3.score[0].tolist() == [0, 4]


def test_cue_ball_in_hand_in_the_d_after_an_in_off():
    g, p = position()
    rec, g2, c = judge(g, shot(p, RED, potted=[0]))
    assert rec.foul[0] == R.FOUL_SCRATCH and c.ball_in_hand[0] == R.IN_HAND_D
    g0 = SNK.new_game(np.array([0]))
    assert SNK.constraints(g0, p).ball_in_hand[0] == R.IN_HAND_D  # the break-off too


def test_the_frame_ends_on_the_last_black():
    g, p = position(off=[b for b in range(1, BLACK)], score=(40, 45))
    rec, g2, _ = judge(g, shot(p, BLACK, potted=[BLACK]))
    assert rec.game_over[0] and rec.winner[0] == 0 and g2.score[0].tolist() == [47, 45]
    assert rec.end[0] == R.END_LAST_BLACK
    rec, g2, _ = judge(g, shot(p, -1))  # a foul on the last black ends it too: 7 to the opponent
    assert rec.game_over[0] and rec.winner[0] == 1 and g2.score[0].tolist() == [40, 52]


def test_a_tie_respots_the_black_with_the_cue_ball_in_hand():
    g, p = position(off=[b for b in range(1, BLACK)], score=(40, 47))
    rec, g2 = SNK.judge(g, shot(p, BLACK, potted=[BLACK]))
    assert not rec.game_over[0] and rec.respot[0, BLACK] and g2.score[0].tolist() == [47, 47]
    c = SNK.constraints(g2, p)  # the black back on its spot
    assert c.ball_in_hand[0] == R.IN_HAND_D and c.targets[0, BLACK]
    assert g2.shooter[0] == 1 - g.breaker[0]


def _line(*xy):
    pos = np.zeros((1, B, 2))
    pos[0, :] = (0.1, 0.1)  # every ball not placed is pocketed below
    for b, (x, y) in xy:
        pos[0, b] = (x, y)
    return pos


def test_snookered_is_decided_from_the_position():
    R_ = P.R
    # the only red behind the black, the cue ball in line: snookered
    before = np.zeros((1, B), dtype=bool)
    before[0, [0, RED, BLACK]] = True
    pos = _line((0, (0.9, 1.0)), (RED, (0.9, 2.0)), (BLACK, (0.9, 1.5)))
    on = balls_on(np.array([R.PHASE_PLAY]), before)
    assert snookered(pos, before, on, R_)[0]
    # the black 3R to the side: the red's near edge is visible, but its far edge is not -> still snookered
    pos2 = _line((0, (0.9, 1.0)), (RED, (0.9, 2.0)), (BLACK, (0.9 + 1.2 * R_, 1.5)))
    assert snookered(pos2, before, on, R_)[0]
    # the black well clear of both grazing paths: not snookered
    pos3 = _line((0, (0.9, 1.0)), (RED, (0.9, 2.0)), (BLACK, (0.9 + 4 * R_, 1.5)))
    assert not snookered(pos3, before, on, R_)[0]
    # a ball on never snookers: a second red in the way is itself on
    before4 = before.copy(); before4[0, 2] = True; before4[0, BLACK] = False
    pos4 = _line((0, (0.9, 1.0)), (RED, (0.9, 2.0)), (2, (0.9, 1.5)))
    assert not snookered(pos4, before4, balls_on(np.array([R.PHASE_PLAY]), before4), R_)[0]


def test_free_ball_after_a_foul_that_leaves_a_snooker():
    pos = _line((0, (0.9, 1.0)), (RED, (0.9, 2.0)), (BLACK, (0.9, 1.5)))
    off = [b for b in range(2, BLACK)]
    g, p = position(off=off, phase=R.PHASE_OPTION)
    c = SNK.constraints(g, p, pos=pos)
    assert c.call_needed[0] and c.targets[0, BLACK] and c.targets[0, RED]   # any ball may be nominated
    # the black nominated as the free ball, potted: worth a red (1), respotted, then a colour is on
    rec, g2 = SNK.judge(g, shot(p, BLACK, potted=[BLACK], nominate=BLACK, pos=pos))
    assert rec.legal[0] and rec.points[0] == 1 and rec.respot[0, BLACK] and g2.phase[0] == R.PHASE_COLOUR
    # without nominating it, hitting the black first is a foul worth 7
    rec, _ = SNK.judge(g, shot(p, BLACK, pos=pos))
    assert rec.foul[0] == R.FOUL_WRONG_BALL and rec.penalty[0] == 7
    # not snookered: no free ball
    pos3 = _line((0, (0.9, 1.0)), (RED, (0.9, 2.0)), (BLACK, (0.5, 1.5)))
    assert not SNK.constraints(g, p, pos=pos3).call_needed[0]
    rec, _ = SNK.judge(g, shot(p, BLACK, potted=[BLACK], nominate=BLACK, pos=pos3))
    assert rec.foul[0] == R.FOUL_WRONG_BALL


def test_the_free_ball_call_is_void_when_the_offender_is_put_back_in():
    pos = _line((0, (0.9, 1.0)), (RED, (0.9, 2.0)), (BLACK, (0.9, 1.5)))
    g, p = position(off=[b for b in range(2, BLACK)], phase=R.PHASE_OPTION)
    _, g2 = SNK.judge(g, shot(p, -1, passed=True, pos=pos))
    assert g2.phase[0] == R.PHASE_PLAY and not SNK.constraints(g2, p, pos=pos).call_needed[0]


def test_points_left_and_snookers_needed():
    g, p = position()
    on = p < 0
    assert points_left(on, g.phase)[0] == 15 * 8 + 27
    assert points_left(on, np.array([R.PHASE_COLOUR]))[0] == 15 * 8 + 27 + 7  # a colour on after a red
    only = np.zeros((1, B), dtype=bool)
    only[0, [0, RED] + list(range(FIRST_COLOUR, BLACK + 1))] = True
    assert points_left(only, g.phase)[0] == 35
    assert needs_snookers(np.array([[0, 36]]), np.array([35]))[0]
    assert not needs_snookers(np.array([[36, 1]]), np.array([35]))[0]


def _miss_game(score=(0, 0), off=()):
    """Player 0 to play on a table of ``position``'s, with the miss bookkeeping of ``SnookerRules.new_game``."""
    _, p = position(off=off, score=score)
    g = SNK.new_game(np.array([0]))
    g.phase[:], g.ball_in_hand[:], g.score[0] = R.PHASE_PLAY, R.IN_HAND_NONE, score
    return g, p


def test_a_foul_with_an_open_full_ball_path_is_a_miss_and_the_balls_may_be_replaced():
    """No ball hit although the red lay open (both edges clear): a miss. The incoming player may put the
    offender back in or have the balls replaced: the offender plays again from where the miss was played,
    the penalty standing and no stroke counted; the red the foul sent down is back on the table."""
    pos = _line((0, (0.9, 1.0)), (RED, (0.9, 2.0)), (2, (0.5, 2.5)), (BLACK, (0.9, 3.2)))
    g, p = _miss_game(off=[b for b in range(3, BLACK)])
    after = p.copy()
    after[0, 2] = 1                                        # a red ball went down on the foul (no contact: impossible
    s = ShotInput(p, after, np.array([-1]), np.zeros_like(p), pos_before=pos)  # by the cue, but a record all the same)
    rec, g2 = SNK.judge(g, s)
    c = SNK.constraints(g2, after, pos=pos)
    assert rec.foul[0] == R.FOUL_NO_CONTACT and rec.miss[0] and rec.penalty[0] == 4
    assert c.may_pass[0] and c.may_replace[0] and g2.shooter[0] == 1
    assert (g2.miss_pos[0] == pos[0]).all() and (g2.miss_pocket[0] == p[0]).all()
    z = np.zeros_like(p)
    rep = ShotInput(after, after, np.array([-1]), z, pos_before=pos, replaced=np.array([True]))
    rec2, g3 = SNK.judge(g2, rep)
    c3 = SNK.constraints(g3, p, pos=pos)
    assert rec2.replaced[0] and not rec2.passed[0] and rec2.foul[0] == R.FOUL_NONE and rec2.turn_over[0]
    assert g3.shooter[0] == 0 and g3.phase[0] == R.PHASE_PLAY and g3.shots[0] == g2.shots[0]
    assert g3.score[0].tolist() == [0, 4] and not c3.may_replace[0] and not c3.may_pass[0]
    # the same foul, then a pass: no replace left on the table after it
    rec2, g3 = SNK.judge(g2, ShotInput(after, after, np.array([-1]), z, passed=np.array([True]), pos_before=pos))
    assert rec2.passed[0] and not SNK.constraints(g3, after, pos=pos).may_replace[0]


def test_a_miss_from_the_d_is_replaced_with_the_cue_ball_in_hand():
    pos = _line((0, (0.9, 0.7)), (RED, (0.9, 2.0)), (BLACK, (0.9, 3.2)))
    g, p = _miss_game(off=[b for b in range(2, BLACK)])
    g.ball_in_hand[:] = R.IN_HAND_D
    rec, g2 = SNK.judge(g, shot(p, -1, pos=pos))
    assert rec.miss[0] and g2.miss_hand[0] == R.IN_HAND_D and SNK.constraints(g2, p).ball_in_hand[0] == 0
    rec2, g3 = SNK.judge(g2, ShotInput(p, p, np.array([-1]), np.zeros_like(p), replaced=np.array([True])))
    assert rec2.replaced[0] and g3.shooter[0] == 0 and SNK.constraints(g3, p).ball_in_hand[0] == R.IN_HAND_D


def test_no_miss_when_snookered_or_when_snookers_are_needed_or_the_ball_on_was_hit():
    open_ = _line((0, (0.9, 1.0)), (RED, (0.9, 2.0)), (BLACK, (0.3, 3.2)))
    hidden = _line((0, (0.9, 1.0)), (RED, (0.9, 2.0)), (BLACK, (0.9 + 1.2 * P.R, 1.5)))  # one edge covered
    off = [b for b in range(2, BLACK)]
    cases = ((open_, (0, 0), -1, True), (hidden, (0, 0), -1, False),      # partly snookered: no miss
             (open_, (0, 16), -1, False),                                 # player 0 needs snookers before
             (open_, (0, 12), -1, False),                                 # ... or after the foul's 4
             (open_, (0, 11), -1, True),                                  # 0-15 after it: 15 left, no snookers
             (open_, (0, 0), BLACK, True),                                # a ball not on hit first: a miss
             (open_, (0, 0), RED, False))                                 # the red hit (no foul): nothing
    for pos, score, first, miss in cases:
        g, p = _miss_game(score, off)
        rec, g2 = SNK.judge(g, shot(p, first, pos=pos))
        assert rec.miss[0] == miss and SNK.constraints(g2, p, pos=pos).may_replace[0] == miss, (score, first)
    # points left: the red and the black, 8 + 7 = 15; snookers are needed when a player trails by more


def test_the_touching_ball():
    """Rule 15 from the position: the cue ball within 2R + TOUCH_TOL of a ball touches it. Touching a red
    (on), no contact is no foul; first contact on it, a push stroke; touching a colour (not on), no contact
    stays a foul, and so does a push on it (worth the colour)."""
    R_ = P.R
    pos = _line((0, (0.9, 1.0)), (RED, (0.9, 1.0 + 2 * R_ + 0.5 * TOUCH_TOL)), (BLUE, (0.5, 2.5)))
    g, p = position(off=[b for b in range(2, BLACK + 1) if b != BLUE])
    assert SNK.constraints(g, p, pos=pos).touching[0].tolist() == [b == RED for b in range(B)]
    rec, _ = SNK.judge(g, shot(p, -1, pos=pos))
    assert rec.legal[0] and rec.turn_over[0] and rec.penalty[0] == 0
    rec, _ = SNK.judge(g, shot(p, RED, pos=pos))
    assert rec.foul[0] == R.FOUL_PUSH and rec.penalty[0] == 4
    far = pos.copy()
    far[0, RED, 1] += 2 * TOUCH_TOL                    # a gap of 1.5 TOUCH_TOL: not touching
    assert not SNK.constraints(g, p, pos=far).touching[0].any()
    rec, _ = SNK.judge(g, shot(p, -1, pos=far))
    assert rec.foul[0] == R.FOUL_NO_CONTACT
    blue = _line((0, (0.9, 1.0)), (BLUE, (0.9, 1.0 + 2 * R_)), (RED, (0.5, 2.5)))
    rec, _ = SNK.judge(g, shot(p, -1, pos=blue))
    assert rec.foul[0] == R.FOUL_NO_CONTACT
    rec, _ = SNK.judge(g, shot(p, BLUE, pos=blue))
    assert rec.foul[0] == R.FOUL_PUSH and rec.penalty[0] == 5


def test_colours_respot_on_their_spot_or_the_highest_free_one():
    pos = np.zeros((1, B, 2))
    pocket = np.full((1, B), 0, dtype=np.int64)
    spots = TABLE.marks.spots
    pocket[0, 0] = -1
    pos[0, 0] = spots[5]                       # the cue ball on the black spot
    balls = np.zeros((1, B), dtype=bool)
    balls[0, [BLACK, PINK]] = True
    respot_colours(pos, pocket, balls, TABLE, P.R, TABLE.pockets)
    # the black first (the highest value): its own spot is taken, so the highest free spot, the pink's;
    # then the pink: its own spot is taken now, the highest free one is the blue's
    assert np.allclose(pos[0, BLACK], spots[4]) and np.allclose(pos[0, PINK], spots[3])
    assert (pocket[0, [BLACK, PINK]] == -1).all()
    balls[0, PINK] = False
    pocket[0, BLACK] = 0
    pos[0, 0] = (0.3, 0.3)
    respot_colours(pos, pocket, balls, TABLE, P.R, TABLE.pockets)
    assert np.allclose(pos[0, BLACK], spots[5])          # its own spot when free


def test_a_foul_that_ties_on_the_last_black_spots_the_black_where_it_lies():
    # an in-off after hitting the black: 7 to the opponent ties the frame at 47 all; the black was not potted
    g, p = position(off=[b for b in range(1, BLACK)], score=(47, 40))
    rec, g2, c = judge(g, shot(p, BLACK, potted=[0]))
    assert rec.foul[0] == R.FOUL_SCRATCH and rec.penalty[0] == 7 and g2.score[0].tolist() == [47, 47]
    assert not rec.game_over[0] and rec.respot[0, BLACK] and rec.respot[0, 0]  # the black spotted, cue ball in hand
    assert c.ball_in_hand[0] == R.IN_HAND_D and c.targets[0].tolist() == [i == BLACK for i in range(B)]
    assert g2.shooter[0] == 1 - g.breaker[0] and g2.phase[0] == R.PHASE_PLAY
    # a foul without contact that ties it, the cue ball left on the table: the same
    g, p = position(off=[b for b in range(1, BLACK)], score=(47, 40))
    rec, g2, c = judge(g, shot(p, -1))
    assert not rec.game_over[0] and rec.respot[0, BLACK] and rec.respot[0, 0] and c.ball_in_hand[0] == R.IN_HAND_D
    # the next score or foul ends the frame: a foul off the re-spotted black gives the frame to the other player
    rec, g3, _ = judge(g2, shot(p, -1))
    assert rec.game_over[0] and rec.winner[0] == 1 - g2.shooter[0] and rec.end[0] == R.END_LAST_BLACK
    # not equal: the frame ends and nothing is spotted
    g, p = position(off=[b for b in range(1, BLACK)], score=(47, 41))
    rec, _, _ = judge(g, shot(p, BLACK, potted=[0]))
    assert rec.game_over[0] and rec.winner[0] == 1 and not rec.respot[0].any()


def test_the_re_spotted_black_is_lifted_from_where_it_stopped_and_the_cue_ball_gives_way():
    spots = TABLE.marks.spots
    pos = np.zeros((1, B, 2))
    pocket = np.full((1, B), 0, dtype=np.int64)
    pocket[0, [0, BLACK]] = -1
    pos[0, BLACK] = spots[5] + (0.0, 0.5 * P.R)      # the black stopped half a radius from its spot
    pos[0, 0] = spots[5] - (0.0, 1.5 * P.R)           # the cue ball (in hand) stopped across the spot
    balls = np.zeros((1, B), dtype=bool)
    balls[0, [0, BLACK]] = True                       # what the ruling of a tie marks
    respot_colours(pos, pocket, balls, TABLE, P.R, TABLE.pockets)
    assert np.allclose(pos[0, BLACK], spots[5]) and pocket[0, BLACK] == -1   # on its own spot, not the pink's
    assert TABLE.marks.in_d(pos[0, 0, 0], pos[0, 0, 1]) and pocket[0, 0] == -1  # the cue ball moved into the D
    # a cue ball in hand clear of the spotted balls stays where it is
    pos[0, BLACK] = (0.3, 3.0)
    pos[0, 0] = (1.2, 2.0)
    respot_colours(pos, pocket, balls, TABLE, P.R, TABLE.pockets)
    assert np.allclose(pos[0, BLACK], spots[5]) and np.allclose(pos[0, 0], (1.2, 2.0))


def test_with_a_free_ball_nominated_the_red_hit_first_is_a_foul():
    pos = _line((0, (0.9, 1.0)), (RED, (0.9, 2.0)), (BLACK, (0.9, 1.5)))
    g, p = position(off=[b for b in range(2, BLACK)], phase=R.PHASE_OPTION)
    assert SNK.constraints(g, p, pos=pos).call_needed[0]  # snookered on the red: a free ball
    # the black nominated as the free ball, the red (the ball on) hit first and even potted: a foul worth 4
    rec, g2 = SNK.judge(g, shot(p, RED, potted=[RED], nominate=BLACK, pos=pos))
    assert rec.foul[0] == R.FOUL_WRONG_BALL and rec.penalty[0] == 4 and rec.points[0] == 0 and rec.turn_over[0]
    # the free ball hit first and the red potted off it: legal, the red scores (a colour on next)
    rec, g2 = SNK.judge(g, shot(p, BLACK, potted=[RED], nominate=BLACK, pos=pos))
    assert rec.legal[0] and rec.points[0] == 1 and g2.phase[0] == R.PHASE_COLOUR
    # the free ball not taken (the red nominated, or nothing): hitting the red first is an ordinary legal stroke
    for nom in (RED, R.CALL_NONE):
        rec, _ = SNK.judge(g, shot(p, RED, potted=[RED], nominate=nom, pos=pos))
        assert rec.legal[0] and rec.points[0] == 1
    # in the clearance (the yellow on), a free ball nominated and the yellow hit first: a foul too
    off = reds_off() + [GREEN, BROWN, BLUE]
    pos2 = _line((0, (0.9, 1.0)), (YELLOW, (0.9, 2.0)), (PINK, (0.9, 1.5)), (BLACK, (0.3, 3.0)))
    g, p = position(off=off, phase=R.PHASE_OPTION)
    assert SNK.constraints(g, p, pos=pos2).call_needed[0]
    rec, _ = SNK.judge(g, shot(p, YELLOW, nominate=PINK, pos=pos2))
    assert rec.foul[0] == R.FOUL_WRONG_BALL and rec.penalty[0] == 4  # the free ball is worth the ball on (2): 4


def _all_spots_taken(extra=()):
    """Every colour off, reds on all six spots (and at ``extra``), the cue ball far away."""
    spots = TABLE.marks.spots
    pos = np.zeros((1, B, 2))
    pocket = np.full((1, B), 0, dtype=np.int64)
    for k in range(6):
        pos[0, 1 + k] = spots[k]
        pocket[0, 1 + k] = -1
    for j, xy in enumerate(extra):
        pos[0, 7 + j] = xy
        pocket[0, 7 + j] = -1
    pos[0, 0], pocket[0, 0] = (0.3, 2.0), -1
    return pos, pocket


def _spot(pos, pocket, *colours):
    balls = np.zeros((1, B), dtype=bool)
    balls[0, list(colours)] = True
    respot_colours(pos, pocket, balls, TABLE, P.R, TABLE.pockets)
    return pos


def test_every_spot_taken_the_colour_goes_above_its_own_spot_in_line():
    spots, md = TABLE.marks.spots, 2 * P.R + 1e-6
    # the black: right above the red on its spot (towards the top cushion, nearer than any point below)
    pos = _spot(*_all_spots_taken(), BLACK)
    assert np.isclose(pos[0, BLACK, 0], spots[5, 0]) and np.isclose(pos[0, BLACK, 1], spots[5, 1] + md, atol=1e-8)
    # the yellow (a spot off the long axis): straight up from its own spot, not along the long axis; a red
    # just beside that line, 1.5 R off it, shuts more of it: the yellow goes past it, touching it
    side = (spots[0, 0] + 1.5 * P.R, spots[0, 1] + 3 * P.R)
    pos = _spot(*_all_spots_taken([side]), YELLOW)
    assert np.isclose(pos[0, YELLOW, 0], spots[0, 0])
    assert np.isclose(pos[0, YELLOW, 1], side[1] + np.sqrt(md ** 2 - (1.5 * P.R) ** 2), atol=1e-8)
    # two colours: the higher value first, each as near its own spot as it can
    pos = _spot(*_all_spots_taken(), PINK, BLACK)
    assert np.isclose(pos[0, BLACK, 1], spots[5, 1] + md, atol=1e-8)
    assert np.isclose(pos[0, PINK, 1], spots[4, 1] + md, atol=1e-8)


def test_every_spot_taken_and_no_room_above_the_black_goes_below_its_spot_in_line():
    spots, md = TABLE.marks.spots, 2 * P.R + 1e-6
    top = TABLE.length - P.R - 1e-4
    chain = [(spots[5, 0], spots[5, 1] + k * 2 * P.R) for k in range(1, 6)]   # frozen reds up to the cushion
    assert chain[-1][1] <= top < chain[-1][1] + md                             # no room above the last one
    pos = _spot(*_all_spots_taken(chain), BLACK)
    assert np.isclose(pos[0, BLACK, 0], spots[5, 0]) and np.isclose(pos[0, BLACK, 1], spots[5, 1] - md, atol=1e-8)
