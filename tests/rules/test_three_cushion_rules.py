"""Three-cushion rules (rules.three_cushion, UMB), one test per rule: constructed positions and shots played
through the simulator (the point reads the order of the cue ball's contacts)."""
import math

import numpy as np
import pytest

from billiards_env.physics import constants as C
from billiards_env.physics.params import PhysicsParams
from billiards_env.physics.simulate import SimOptions, simulate
from billiards_env.physics.state import BallState
from billiards_env.physics.strike import strike_velocity
from billiards_env.physics.table import Table
from billiards_env.rules import ShotInput, get_rules
from billiards_env.rules import records as R
from billiards_env.rules.snooker import TOUCH_TOL
from billiards_env.rules.three_cushion import CONTACTS_KEPT, ThreeCushionRules, point_made

T, P = Table.carom(), PhysicsParams.carom()
# the shooter's cue ball, the opponent's ball, the red (the rules' frame)
POS = np.array([[0.35, 0.45], [0.95, 1.25], [0.45, 2.25]])
N = 3072


@pytest.fixture(scope="module")
def shots():
    """N seeded shots from POS through the simulator: (struck state, result)."""
    rng = np.random.default_rng(11)
    s = BallState.from_positions(np.repeat(POS[None], N, axis=0))
    s = strike_velocity(s, rng.uniform(0, 2 * np.pi, N), rng.uniform(1.5, 7.0, N), rng.uniform(-0.4, 0.4, N),
                        rng.uniform(-0.3, 0.3, N), params=P)
    return s, simulate(s, T, P, options=SimOptions(contacts=CONTACTS_KEPT))


def _word(res, e):
    """The cue ball's contacts of shot e as a word: 'C' a cushion, '1' / '2' a ball."""
    n = min(int(res.n_contacts[e]), CONTACTS_KEPT)
    return "".join("C" if k == C.EV_CUSHION else str(b) for k, b in res.contacts[e, :n])


def _find(res, ok):
    for e in range(N):
        if ok(_word(res, e), e):
            return e
    raise AssertionError("no shot of the seeded set has this contact pattern")


def _judge(res, rows, phase=R.PHASE_PLAY, rules=None, game=None):
    rules = rules or ThreeCushionRules()
    rows = np.atleast_1d(rows)
    if game is None:
        game = rules.new_game(np.zeros(len(rows), dtype=np.int64))
        game.phase[:] = phase
    pk = np.full((len(rows), 3), -1)
    shot = ShotInput(pk, pk.copy(), res.first_contact[rows], res.cushion_hits_after_contact[rows],
                     res.cushion_hits[rows], contacts=res.contacts[rows], n_contacts=res.n_contacts[rows])
    return rules.judge(game, shot)


def _strip(word):
    """The word up to the first contact with the second object ball."""
    seen = set()
    for k, ch in enumerate(word):
        if ch in "12":
            seen.add(ch)
            if len(seen) == 2:
                return word[:k + 1]
    return word


def test_point_ball_first_then_three_cushions_then_the_second_ball(shots):
    _, res = shots
    e = _find(res, lambda w, e: _strip(w) in ("1CCC2", "2CCC1"))
    rec, g = _judge(res, e)
    assert rec.points[0] == 1 and g.score[0, 0] == 1
    assert not rec.turn_over[0] and g.shooter[0] == 0  # the inning continues after a point
    assert g.innings[0, 0] == 1 and g.innings[0, 1] == 0


def test_point_cushions_first_bank_shot(shots):
    _, res = shots
    e = _find(res, lambda w, e: _strip(w).startswith("CCC") and _strip(w).count("C") >= 3 and _strip(w)[-1] in "12"
              and len(set(_strip(w)) & {"1", "2"}) == 2)
    rec, _ = _judge(res, e)
    assert rec.points[0] == 1


def test_near_miss_two_cushions_before_the_second_ball(shots):
    _, res = shots
    e = _find(res, lambda w, e: _strip(w) in ("1CC2", "2CC1", "C1C2", "C2C1", "CC12", "CC21"))
    rec, g = _judge(res, e)
    assert rec.points[0] == 0 and rec.turn_over[0] and rec.legal[0]  # a miss, not a foul
    assert g.shooter[0] == 1 and g.innings[0, 1] == 1  # the opponent begins an inning


def test_near_miss_third_cushion_after_the_second_ball(shots):
    _, res = shots
    e = _find(res, lambda w, e: _strip(w).count("C") == 2 and len(set(_strip(w)) & {"1", "2"}) == 2
              and w[len(_strip(w)):].count("C") >= 1)
    assert _word(res, e).count("C") >= 3  # three cushions in all: the third came after the second ball
    rec, _ = _judge(res, e)
    assert rec.points[0] == 0 and rec.turn_over[0]


def test_near_miss_cushions_struck_by_an_object_ball_do_not_count(shots):
    _, res = shots
    # both balls reached, fewer than three cue-ball cushions before the second, but the object balls
    # struck three or more cushions (they would make it a point if they counted)
    e = _find(res, lambda w, e: len(set(_strip(w)) & {"1", "2"}) == 2 and _strip(w).count("C") < 3
              and res.cushion_hits[e, 1:].sum() >= 3 and res.cushion_hits[e, 0] + res.cushion_hits[e, 1:].sum() >= 3)
    rec, _ = _judge(res, e)
    assert rec.points[0] == 0


def test_one_object_ball_only_is_no_point(shots):
    _, res = shots
    e = _find(res, lambda w, e: w.count("C") >= 3 and ("1" in w) != ("2" in w))
    assert _judge(res, e)[0].points[0] == 0


def test_opening_shot_must_strike_the_red_first(shots):
    _, res = shots
    wrong = _find(res, lambda w, e: res.first_contact[e] == 1)
    red = _find(res, lambda w, e: res.first_contact[e] == 2 and not point_made(res.contacts[e:e + 1],
                                                                              res.n_contacts[e:e + 1])[0][0])
    rec, g = _judge(res, [wrong, red], phase=R.PHASE_BREAK)
    assert rec.foul.tolist() == [R.FOUL_WRONG_BALL, R.FOUL_NONE]
    assert rec.turn_over.tolist() == [True, True] and (g.phase == R.PHASE_PLAY).all()
    # a point made with the opponent's ball first on the opening shot is a foul and scores nothing
    pt_wrong = [e for e in range(N) if res.first_contact[e] == 1
                and point_made(res.contacts[e:e + 1], res.n_contacts[e:e + 1])[0][0]]
    if pt_wrong:
        rec, g = _judge(res, pt_wrong[:1], phase=R.PHASE_BREAK)
        assert rec.points[0] == 0 and rec.foul[0] == R.FOUL_WRONG_BALL and g.score[0].sum() == 0
    cons = ThreeCushionRules().constraints(ThreeCushionRules().new_game([0]), np.full((1, 3), -1))
    assert cons.targets[0].tolist() == [False, False, True] and cons.is_break[0]


def _scripted(rules, points, breaker=0):
    """Play shots that make a point (True) or miss (False) in turn; the state after each."""
    # a point off the red first (a point on any shot: the equal-innings last inning's first shot must strike it first)
    good = ShotInput(np.full((1, 3), -1), np.full((1, 3), -1), np.array([2]), np.zeros((1, 3), int),
                     contacts=np.array([[[C.EV_BALL_BALL, 2]] + [[C.EV_CUSHION, k] for k in (0, 1, 2)]
                                        + [[C.EV_BALL_BALL, 1]]]), n_contacts=np.array([5]))
    miss = ShotInput(np.full((1, 3), -1), np.full((1, 3), -1), np.array([2]), np.zeros((1, 3), int),
                     contacts=np.array([[[C.EV_BALL_BALL, 2], [C.EV_CUSHION, 0], [C.EV_BALL_BALL, 1]] + [[-1, -1]] * 2]),
                     n_contacts=np.array([3]))
    g = rules.new_game([breaker])
    g.phase[:] = R.PHASE_PLAY
    out = []
    for p in points:
        rec, g = rules.judge(g, good if p else miss)
        out.append((rec, g))
        if g.over[0]:
            break
    return out


def test_game_to_the_target_score():
    out = _scripted(ThreeCushionRules(target=3), [True, True, True])
    rec, g = out[-1]
    assert rec.game_over[0] and rec.winner[0] == 0 and rec.end[0] == R.END_TARGET and g.score[0].tolist() == [3, 0]


def test_innings_limit_and_the_higher_score_wins():
    # starter misses, opponent scores once then misses: after 2 innings each the opponent leads 1-0
    out = _scripted(ThreeCushionRules(target=5, max_innings=2), [False, True, False, False, False])
    rec, g = out[-1]
    assert rec.game_over[0] and rec.end[0] == R.END_INNINGS and rec.winner[0] == 1
    assert g.innings[0].tolist() == [2, 2] and g.score[0].tolist() == [0, 1]
    # equal scores at the limit: a draw
    rec, g = _scripted(ThreeCushionRules(target=5, max_innings=1), [False, False])[-1]
    assert rec.game_over[0] and rec.winner[0] == -1


def test_equal_innings_gives_the_opponent_a_last_inning():
    rules = ThreeCushionRules(target=2, equal_innings=True)
    # the starter runs 2 points: the opponent gets a last inning and runs 2 as well: a draw
    out = _scripted(rules, [True, True, True, True])
    assert not out[1][0].game_over[0] and out[1][1].phase[0] == R.PHASE_FINAL_OPENING and out[1][1].shooter[0] == 1
    assert out[2][1].phase[0] == R.PHASE_FINAL  # after the last inning's first shot
    rec, g = out[-1]
    assert rec.game_over[0] and rec.winner[0] == -1 and g.score[0].tolist() == [2, 2]
    # the opponent misses in the last inning: the starter wins
    rec, g = _scripted(rules, [True, True, True, False])[-1]
    assert rec.game_over[0] and rec.winner[0] == 0 and g.score[0].tolist() == [2, 1]
    # the opponent (not the starter) reaching the target wins at once: the innings are already equal
    rec, g = _scripted(rules, [False, True, True])[-1]
    assert rec.game_over[0] and rec.winner[0] == 1
    # without the option the starter wins at once
    assert _scripted(ThreeCushionRules(target=2), [True, True])[-1][0].winner[0] == 0


def test_settings_and_missing_contacts_are_refused():
    with pytest.raises(ValueError, match="target"):
        ThreeCushionRules(target=0)
    with pytest.raises(TypeError, match="equal_innings"):
        get_rules("three_cushion", equal_innings="yes")
    rules = ThreeCushionRules()
    pk = np.full((1, 3), -1)
    with pytest.raises(ValueError, match="contacts"):
        rules.judge(rules.new_game([0]), ShotInput(pk, pk, np.array([1]), np.zeros((1, 3), int)))


def test_the_equal_innings_last_inning_starts_from_the_starting_position():
    rules = ThreeCushionRules(target=2, equal_innings=True)
    out = _scripted(rules, [True, True])
    rec, g = out[-1]
    # the starter reached the target: the balls go back to the starting position for the opponent's last inning
    assert rec.restart[0] and rec.turn_over[0] and not rec.game_over[0] and g.phase[0] == R.PHASE_FINAL_OPENING
    assert not out[0][0].restart[0]                        # an ordinary point: the balls stay where they lie
    c = rules.constraints(g, np.full((1, 3), -1))
    assert c.is_break[0] and c.targets[0].tolist() == [False, False, True]  # the red first, as on the opening
    assert rules.observe_extra(g)[0, 3] == 1.0             # the last inning is flagged from its first shot
    # that first shot strikes the opponent's ball first: a foul, the last inning ends, the starter wins
    wrong = ShotInput(np.full((1, 3), -1), np.full((1, 3), -1), np.array([1]), np.zeros((1, 3), int),
                      contacts=np.array([[[C.EV_BALL_BALL, 1]] + [[C.EV_CUSHION, k] for k in (0, 1, 2)]
                                         + [[C.EV_BALL_BALL, 2]]]), n_contacts=np.array([5]))
    rec2, g2 = rules.judge(g, wrong)
    assert rec2.foul[0] == R.FOUL_WRONG_BALL and rec2.points[0] == 0 and rec2.game_over[0] and rec2.winner[0] == 0
    assert not rec2.restart[0] and g2.score[0].tolist() == [2, 0]
    # without equal innings, and in the other games, nothing is re-placed
    assert not _scripted(ThreeCushionRules(target=2), [True, True])[-1][0].restart[0]


# --- balls in contact (UMB Art. 27) and the wrong cue ball (UMB Art. 41) -------------------------------------------
R_ = P.R
# the shooter's ball frozen to the red along +x (centres exactly 2R apart, as the simulator leaves touching balls),
# the opponent's ball up the table on the side away from the red
FROZEN = np.array([[0.6, 0.8], [0.3, 2.0], [0.6 + 2 * R_, 0.8]])


def _play(pos, phi, speed=2.0, rows_struck=None, replaced=None, phase=R.PHASE_PLAY, rules=None):
    """Shots [k] (aim ``phi``) from the position ``pos`` [3, 2] through the simulator, judged with the positions
    they were played from: (record, state after, simulator result)."""
    rules = rules or ThreeCushionRules()
    phi = np.atleast_1d(np.asarray(phi, dtype=float))
    k = len(phi)
    s = BallState.from_positions(np.repeat(pos[None], k, axis=0))
    s = strike_velocity(s, phi, np.full(k, speed), np.zeros(k), np.zeros(k), params=P)
    res = simulate(s, T, P, options=SimOptions(contacts=CONTACTS_KEPT))
    game = rules.new_game(np.zeros(k, dtype=np.int64))
    game.phase[:] = phase
    pk = np.full((k, 3), -1)
    shot = ShotInput(pk, pk.copy(), res.first_contact, res.cushion_hits_after_contact, res.cushion_hits,
                     contacts=res.contacts, n_contacts=res.n_contacts, pos_before=np.repeat(pos[None], k, axis=0),
                     replaced=replaced, struck=rows_struck)
    rec, g = rules.judge(game, shot)
    return rec, g, res


def test_balls_in_contact_are_named_and_may_be_replaced():
    """A cue ball within 2R + TOUCH_TOL of a ball touches it (snooker's test, one for both games): the
    constraints name the ball and allow the replace declaration; 1.5 TOUCH_TOL apart nothing is touching."""
    rules = ThreeCushionRules()
    g, pk = rules.new_game([0]), np.full((1, 3), -1)
    g.phase[:] = R.PHASE_PLAY
    c = rules.constraints(g, pk, pos=FROZEN[None])
    assert c.touching[0].tolist() == [False, False, True] and c.may_replace[0]
    near = FROZEN.copy()
    near[2, 0] += 0.5 * TOUCH_TOL
    assert rules.constraints(g, pk, pos=near[None]).touching[0, 2]
    far = FROZEN.copy()
    far[2, 0] += 1.5 * TOUCH_TOL
    c = rules.constraints(g, pk, pos=far[None])
    assert not c.touching[0].any() and not c.may_replace[0]
    assert not rules.constraints(g, pk).may_replace[0]  # without positions nothing is known to touch
    g.over[:] = True
    assert not rules.constraints(g, pk, pos=FROZEN[None]).may_replace[0]  # a finished game: no declaration


def test_balls_in_contact_played_straight_into_the_touching_ball_is_a_foul():
    """Through the simulator from the frozen position: straight into the red (the cue ball's first contact
    is the red) is a foul that ends the inning; away from it, to the opponent's ball first or to a cushion
    first, is fair; the same shot into the red from 1 mm away is no foul (nothing was touching)."""
    into, to_ball, to_cushion = 0.0, math.atan2(FROZEN[1, 1] - 0.8, FROZEN[1, 0] - 0.6), math.pi
    rec, g, res = _play(FROZEN, [into, to_ball, to_cushion])
    assert res.contacts[0, 0].tolist() == [C.EV_BALL_BALL, 2] and res.first_contact[1] == 1
    assert res.contacts[2, 0, 0] == C.EV_CUSHION
    assert rec.foul.tolist() == [R.FOUL_PUSH, R.FOUL_NONE, R.FOUL_NONE]
    assert rec.turn_over[0] and rec.points[0] == 0 and g.shooter[0] == 1 and not rec.legal[0]
    gap = FROZEN.copy()
    gap[2, 0] += 1e-3
    rec, _, res = _play(gap, [into])
    assert res.first_contact[0] == 2 and rec.foul[0] == R.FOUL_NONE


def test_balls_in_contact_replaced_on_the_starting_position():
    """The replace declaration with the cue ball touching a ball: no shot, no inning change, the balls to the
    starting position (``restart``) and the same shooter's next shot an opening shot (the red first; in the
    equal-innings last inning its opening phase). Declared with nothing touching, it is ignored."""
    rules = ThreeCushionRules()
    pk, pos = np.full((2, 3), -1), np.stack([FROZEN, FROZEN + [0.0, 0.5]])
    pos[1, 2, 0] += 1e-3                                   # table 1: nothing touching
    g = rules.new_game(np.zeros(2, dtype=np.int64))
    g.phase[:] = R.PHASE_PLAY
    none = np.full((2, CONTACTS_KEPT, 2), -1)
    shot = ShotInput(pk, pk.copy(), np.full(2, -1), np.zeros((2, 3), int), contacts=none,
                     n_contacts=np.zeros(2, dtype=np.int64), pos_before=pos, replaced=np.array([True, True]))
    rec, g2 = rules.judge(g, shot)
    assert rec.replaced.tolist() == [True, False] and rec.restart.tolist() == [True, False]
    assert not rec.turn_over[0] and g2.shooter[0] == 0 and g2.innings[0].tolist() == [1, 0]
    assert g2.shots[0] == 0 and g2.phase[0] == R.PHASE_BREAK and rec.points[0] == 0 and rec.foul[0] == 0
    assert g2.shots[1] == 1 and rec.turn_over[1]           # table 1 played its (empty) shot: a miss
    c = rules.constraints(g2.take([0]), pk[:1])
    assert c.is_break[0] and c.targets[0].tolist() == [False, False, True]
    fin = rules.new_game([0])
    fin.phase[:] = R.PHASE_FINAL
    rec, g3 = rules.judge(fin, ShotInput(pk[:1], pk[:1], np.array([-1]), np.zeros((1, 3), int),
                                         contacts=none[:1], n_contacts=np.zeros(1, dtype=np.int64),
                                         pos_before=pos[:1], replaced=np.array([True])))
    assert rec.replaced[0] and g3.phase[0] == R.PHASE_FINAL_OPENING


def test_the_wrong_cue_ball_is_a_foul_and_scores_nothing(shots):
    """The cue striking the opponent's ball or the red (``ShotInput.struck``) is a foul that ends the inning,
    even where the contacts read as a point; the shooter's own ball (0) is the default."""
    _, res = shots
    e = _find(res, lambda w, e: bool(point_made(res.contacts[e:e + 1], res.n_contacts[e:e + 1])[0][0]))
    rows = np.array([e, e, e])
    rules = ThreeCushionRules()
    game = rules.new_game(np.zeros(3, dtype=np.int64))
    game.phase[:] = R.PHASE_PLAY
    pk = np.full((3, 3), -1)
    shot = ShotInput(pk, pk.copy(), res.first_contact[rows], res.cushion_hits_after_contact[rows],
                     res.cushion_hits[rows], contacts=res.contacts[rows], n_contacts=res.n_contacts[rows],
                     struck=np.array([0, 1, 2]))
    rec, g = rules.judge(game, shot)
    assert rec.points.tolist() == [1, 0, 0] and g.score[:, 0].tolist() == [1, 0, 0]
    assert rec.foul.tolist() == [R.FOUL_NONE, R.FOUL_WRONG_CUE_BALL, R.FOUL_WRONG_CUE_BALL]
    assert rec.turn_over.tolist() == [False, True, True] and g.shooter.tolist() == [0, 1, 1]
    assert R.FOUL_NAMES[R.FOUL_WRONG_CUE_BALL] == "the wrong cue ball struck"
