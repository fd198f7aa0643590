"""Snooker through the envs and the simulator: thousands of random frames
(ending within the cap, no ball lost or duplicated, scores equal to the
shot records), bot frames played to their end, rules that read contacts
played through the simulator on constructed positions, the bot, the match
script. PettingZoo's api_test, check_env and vector = singles for
Billiards-Snooker-v2: tests/envs/test_games.py."""
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from billiards_env.bots import make_bot
from billiards_env.contract import ShotPlan
from billiards_env.envs.games import GameConfig, GameCore
from billiards_env.physics.strike import Shots
from billiards_env.rules import records as R
from billiards_env.rules.snooker import BLACK, FIRST_COLOUR
from billiards_env.testing.positions import game_table

ROOT = Path(__file__).resolve().parents[2]
BLUE, PINK = FIRST_COLOUR + 3, FIRST_COLOUR + 4


def check_shot(core, idx, out, on_before, score_before, shooter_before):
    """One shot's invariants on tables ``idx``."""
    rec, info = out["record"], out["info"]
    on = core.state.pocket[idx] < 0
    reds_before, reds = on_before[:, 1:16], on[:, 1:16]
    shot = ~rec.replaced  # the balls replaced after a miss: reds may come back, as they stood before the foul
    assert not (reds & ~reds_before)[shot].any(), "a red came back"
    came_back = (on & ~on_before)[shot]
    assert not came_back[:, 1:][~rec.respot[shot][:, 1:]].any(), "a ball came back without a respot"
    assert (rec.penalty[rec.replaced] == 0).all() and (rec.foul[rec.replaced] == 0).all()
    assert (rec.turn_over[rec.replaced]).all() and not (rec.miss & ~(rec.foul > 0)).any()
    # colours are off the table only when every red is, and then only the lowest ones (the clearance)
    col_off = ~on[:, FIRST_COLOUR:]
    assert not (col_off.any(axis=1) & reds.any(axis=1)).any()
    assert (np.sort(col_off, axis=1)[:, ::-1] == col_off).all(), "a colour off out of order"
    pos = core.state.pos[idx]
    d = np.linalg.norm(pos[:, :, None] - pos[:, None], axis=-1)
    both = on[:, :, None] & on[:, None]
    d[:, np.arange(d.shape[1]), np.arange(d.shape[1])] = np.inf
    assert (d[both] >= 2 * core.params.R - 1e-9).all(), "two balls overlap (a duplicated ball)"
    ar = np.arange(len(idx))
    gain = np.zeros_like(score_before)
    gain[ar, shooter_before] += rec.points
    gain[ar, 1 - shooter_before] += rec.penalty
    assert (core.game.score[idx] == score_before + gain).all(), "scores differ from the shot records"
    assert (info["score"] == core.game.score[idx]).all()
    assert (rec.penalty[rec.foul > 0] >= 4).all() and (rec.penalty[rec.foul == 0] == 0).all()
    over = rec.game_over
    assert (core.game.winner[idx][over] == np.argmax(core.game.score[idx][over], axis=1)).all()


def test_random_frames_properties():
    """1,000 frames of random actions (ball in hand anywhere asked, the D given; random declarations)."""
    n, cap = 1000, 40
    core = GameCore(GameConfig(game="snooker", max_shots=cap, noise="tournament"), n)
    core.streams.seed(np.arange(n), np.arange(n) + 3)
    core.reset_tables(np.arange(n))
    rng = np.random.default_rng(2)
    live = np.ones(n, dtype=bool)
    steps = replaced = 0
    while live.any():
        idx = np.nonzero(live)[0]
        hand = core.constraints().ball_in_hand[idx] == R.IN_HAND_D
        on_before = core.state.pocket[idx] < 0
        score, shooter = core.game.score[idx].copy(), core.game.shooter[idx].copy()
        out = core.step(rng.uniform(-1.1, 1.1, (len(idx), core.action_dim)), idx)
        placed = out["info"]["placement"][hand & ~out["info"]["passed"]]  # a pass places nothing
        assert core.table.marks.in_d(placed[:, 0], placed[:, 1]).all(), "ball in hand outside the D"
        check_shot(core, idx, out, on_before, score, shooter)
        replaced += out["record"].replaced.sum()
        live[idx[out["terminated"] | out["truncated"]]] = False
        steps += 1
        assert steps <= 2 * cap + 1  # a pass (the offender put back in) is a step but no shot; one per foul at most
    assert (core.game.over | (core.game.shots >= cap)).all()
    assert core.game.score.sum() > 0
    assert replaced > 0  # random a6 in (0, 0.5] after a miss: the replace declaration came up


def test_bot_frames_end_on_the_last_black():
    """Frames between the snooker bots end by the rules (the last black), well inside the cap."""
    n = 6
    core = GameCore(GameConfig(game="snooker", max_shots=200, noise="tournament"), n)
    core.streams.seed(np.arange(n), np.arange(n) + 1)
    core.reset_tables(np.arange(n))
    bot = make_bot("snooker", seed=0)
    live = np.ones(n, dtype=bool)
    while live.any():
        idx = np.nonzero(live)[0]
        on_before = core.state.pocket[idx] < 0
        score, shooter = core.game.score[idx].copy(), core.game.shooter[idx].copy()
        view = core.view(idx)
        out = core.step(core.actions_of(bot.act(view), idx, view.codec), idx)
        check_shot(core, idx, out, on_before, score, shooter)
        live[idx[out["terminated"] | out["truncated"]]] = False
    g = core.game
    assert g.over.all() and (g.shots < 200).all()
    assert (core.state.pocket[:, 1:BLACK] >= 0).all()  # the frame ended with only the black left (or potted)


def shoot(core, phi, speed, ball=R.CALL_NONE, placement=None, declare=False, b=0.0):
    plan = ShotPlan.of(Shots(np.array([phi]), np.array([speed]), np.zeros(1), np.full(1, b)),
                       placement=None if placement is None else np.array([placement], dtype=np.float64),
                       declare=np.array([declare]), ball=np.array([ball]))
    return core.step(core.actions_of(plan, [0]), [0])


def aim(core, a, b):
    d = np.asarray(b, dtype=np.float64) - np.asarray(a, dtype=np.float64)
    return math.atan2(d[1], d[0])


def test_sim_red_then_nominated_colour_respotted():
    w = 1.778
    core = game_table("snooker", {0: (w - 0.4, 0.4), 1: (w - 0.2, 0.2), BLUE: (w - 0.2, 0.6), BLACK: (0.9, 3.245)})
    out = shoot(core, aim(core, (w - 0.4, 0.4), (w, 0.0)), 1.5)
    assert out["record"].legal[0] and out["info"]["points"][0] == 1 and core.game.phase[0] == R.PHASE_COLOUR
    assert core.constraints().call_needed[0]
    pk = core.pockets[np.argmin(np.linalg.norm(core.pockets[:, :2] - core.state.pos[0, BLUE], axis=1))]
    # the blue nominated and potted on a straight line from wherever the cue ball came to rest
    core.state.pos[0, 0] = core.state.pos[0, BLUE] + 0.3 * (core.state.pos[0, BLUE] - pk[:2]) / np.linalg.norm(
        core.state.pos[0, BLUE] - pk[:2])
    core._changed()
    out = shoot(core, aim(core, core.state.pos[0, 0], pk[:2]), 1.5, ball=BLUE)
    assert out["record"].legal[0] and out["info"]["points"][0] == 5 and core.game.score[0, 0] == 6
    assert out["record"].respot[0, BLUE] and np.allclose(core.state.pos[0, BLUE], core.table.marks.spots[3])


def test_sim_in_off_gives_ball_in_hand_in_the_d():
    core = game_table("snooker", {0: (0.3, 0.3), 1: (0.9, 2.0), BLACK: (0.9, 3.245)})
    out = shoot(core, aim(core, (0.3, 0.3), (0.0, 0.0)), 1.0)  # straight into the corner
    assert out["record"].foul[0] == R.FOUL_SCRATCH and out["info"]["penalty"][0] == 4
    c = core.constraints()
    assert c.ball_in_hand[0] == R.IN_HAND_D and c.shooter[0] == 1
    out = shoot(core, math.pi / 2, 1.0, placement=(0.2, 3.0))  # asks for a spot far from the D
    placed = out["info"]["placement"][0]
    assert out["info"]["placement_moved"][0] and core.table.marks.in_d(placed[0], placed[1])


def test_sim_free_ball_after_a_foul_that_snookers():
    """After player 0's foul the cue ball lies snookered on the last red (the pink in the way): player 1
    nominates the black as the free ball and pots it in the corner: one point, the black respotted,
    a colour on next."""
    cue, corner = np.array([0.889, 2.2]), np.array([1.778, 3.569])
    black = cue + 0.4 * (corner - cue) / np.linalg.norm(corner - cue)
    core = game_table("snooker", {0: tuple(cue), 1: (0.889, 3.0), PINK: (0.889, 2.6), BLACK: tuple(black)},
                      phase=R.PHASE_OPTION)
    core.game.shooter[0] = 1
    core._changed()
    c = core.constraints()
    assert c.call_needed[0] and c.may_pass[0] and c.targets[0, BLACK] and c.targets[0, PINK]
    out = shoot(core, aim(core, cue, black), 1.5, ball=BLACK, b=-0.4)
    rec = out["record"]
    assert rec.legal[0] and out["info"]["points"][0] == 1 and rec.respot[0, BLACK]
    assert np.allclose(core.state.pos[0, BLACK], core.table.marks.spots[5]) and core.game.phase[0] == R.PHASE_COLOUR
    # the same shot without nominating the black: hitting it first is a foul worth 7
    core2 = game_table("snooker", {0: tuple(cue), 1: (0.889, 3.0), PINK: (0.889, 2.6), BLACK: tuple(black)},
                       phase=R.PHASE_OPTION)
    out = shoot(core2, aim(core2, cue, black), 1.5, b=-0.4)
    assert out["record"].foul[0] == R.FOUL_WRONG_BALL and out["info"]["penalty"][0] == 7


def test_sim_a_foul_that_ties_on_the_last_black_spots_it():
    """Only the black left, player 0 leads 47-40 and goes in-off after a thin hit on the black (the black
    stays up): 7 to player 1 ties the frame, so the black goes back to its spot from where it stopped, the
    cue ball is in hand in the D for player 1, and the next foul ends the frame."""
    cue, corner = np.array([1.2, 3.0]), np.array([1.778, 3.569])
    d = (corner - cue) / np.linalg.norm(corner - cue)
    black = cue + 0.15 * d + 0.02 * np.array([-d[1], d[0]])
    core = game_table("snooker", {0: tuple(cue), BLACK: tuple(black)})
    core.game.score[0] = (47, 40)
    core._changed()
    out = shoot(core, math.atan2(d[1], d[0]) - 0.1425, 2.0, b=0.3)  # a thin cut with follow: into the corner
    rec, info = out["record"], out["info"]
    assert info["first_contact"][0] == BLACK and info["pocketed"][0, 0] and not info["pocketed"][0, BLACK]
    assert rec.foul[0] == R.FOUL_SCRATCH and info["penalty"][0] == 7 and core.game.score[0].tolist() == [47, 47]
    assert not rec.game_over[0] and core.state.pocket[0, BLACK] == -1
    assert np.allclose(core.state.pos[0, BLACK], core.table.marks.spots[5])  # spotted, not where it stopped
    c = core.constraints()
    assert c.ball_in_hand[0] == R.IN_HAND_D and c.shooter[0] == 1 and c.targets[0, BLACK] and c.targets[0].sum() == 1
    out = shoot(core, -math.pi / 2, 1.0, placement=(0.889, 0.6))  # from the D away from the black: no contact
    assert out["record"].foul[0] == R.FOUL_NO_CONTACT and out["record"].game_over[0]
    assert out["record"].winner[0] == 0 and core.game.score[0].tolist() == [54, 47]


def test_sim_a_free_ball_nominated_must_be_hit_first():
    """After player 0's foul the cue ball lies snookered on the only red (the pink covers one of its edges):
    player 1 nominates the pink as the free ball but hits the red first on its open edge: a foul (4). Without
    the free ball (the red nominated) the same stroke is legal."""
    R_ = 0.02625
    balls = {0: (0.889, 2.2), 1: (0.889, 3.0), PINK: (0.889 + 1.9 * R_, 2.6), BLACK: (0.889, 3.245)}
    phi = math.atan2(0.8, -0.03)   # the cue ball's centre 3 cm to the red's open side: a thick hit on the red
    for nominate, foul, penalty in ((PINK, R.FOUL_WRONG_BALL, 4), (1, R.FOUL_NONE, 0)):
        core = game_table("snooker", balls, phase=R.PHASE_OPTION)
        core.game.shooter[0] = 1
        core._changed()
        assert core.constraints().call_needed[0]  # snookered: a free ball may be nominated
        out = shoot(core, phi, 1.5, ball=nominate)
        assert out["info"]["first_contact"][0] == 1 and out["info"]["called_ball"][0] == nominate
        assert out["record"].foul[0] == foul and out["info"]["penalty"][0] == penalty


def test_sim_offender_put_back_in():
    core = game_table("snooker", {0: (0.9, 0.5), 1: (0.9, 2.0), BLACK: (0.9, 3.245)})
    out = shoot(core, math.pi, 0.5)  # away from the red: no ball hit
    assert out["record"].foul[0] == R.FOUL_NO_CONTACT and core.constraints().may_pass[0]
    pos = core.state.pos.copy()
    out = shoot(core, 0.0, 1.0, declare=True)  # player 1 puts player 0 back in
    assert out["record"].passed[0] and core.game.shooter[0] == 0 and (core.state.pos == pos).all()


def replace(core):
    """The incoming player has the balls replaced after a miss (the action's a6 = 0.25, the codec's encoding)."""
    plan = ShotPlan.of(Shots(np.zeros(1), np.ones(1), np.zeros(1), np.zeros(1)), replace=np.array([True]))
    actions = core.actions_of(plan, [0])
    assert actions[0, 6] == 0.25
    return core.step(actions, [0])


def test_sim_foul_and_a_miss_the_balls_replaced():
    """Player 0 plays away from an open red (a clear full-ball path) and hits nothing: a foul and a miss.
    Player 1 has the balls replaced: player 0 plays again from where the miss was played, 4 points down;
    missing again is another miss."""
    core = game_table("snooker", {0: (0.9, 1.0), 1: (0.9, 2.0), BLACK: (0.9, 3.245)})
    pos, pocket = core.state.pos.copy(), core.state.pocket.copy()
    out = shoot(core, math.pi, 0.6)  # to the side cushion and back along y = 1: the red untouched
    assert out["record"].foul[0] == R.FOUL_NO_CONTACT and out["record"].miss[0] and out["info"]["miss"][0]
    assert not np.array_equal(core.state.pos[0, 0], pos[0, 0])  # the cue ball moved
    c = core.constraints()
    assert c.shooter[0] == 1 and c.may_pass[0] and c.may_replace[0] and core.view([0]).may_replace[0]
    out = replace(core)
    rec = out["record"]
    assert rec.replaced[0] and out["info"]["replaced"][0] and out["info"]["passed"][0] and rec.foul[0] == 0
    assert np.array_equal(core.state.pos, pos) and np.array_equal(core.state.pocket, pocket)
    assert core.game.shooter[0] == 0 and core.game.score[0].tolist() == [0, 4] and core.game.shots[0] == 1
    c = core.constraints()
    assert not c.may_replace[0] and not c.may_pass[0] and c.targets[0, 1]
    out = shoot(core, math.pi, 0.6)
    assert out["record"].miss[0] and core.game.score[0].tolist() == [0, 8] and core.constraints().may_replace[0]


def test_the_observation_and_the_bot_after_a_miss():
    """After a foul and a miss the incoming player's observation says the balls may be replaced (obs
    4*B + 18); the ``snooker`` bot has them replaced where it has no pot (the only red frozen to the top
    cushion) and plays on where it has one (the red in the open)."""
    for red, replaces in (((0.889, 3.541), True), ((0.9, 2.0), False)):
        core = game_table("snooker", {0: (0.9, 1.0), 1: red, BLACK: (1.5, 2.5)})
        assert core.observe()[0, -2] == 0.0
        assert shoot(core, math.pi, 0.6)["record"].miss[0]  # away from the red: a foul and a miss
        obs = core.observe()[0]
        assert obs[4 * core.n_balls + 18] == 1.0 and obs[4 * core.n_balls + 19] == 0.0, obs[-6:]
        bot = make_bot("snooker")
        plan = bot.act(core.view([0]))
        assert plan.replace[0] == replaces and bot.last_mode[0] == ("replace" if replaces else "pot")
        out = core.step(core.actions_of(plan, [0]), [0])
        assert out["record"].replaced[0] == replaces and out["record"].shooter[0] == 1
        assert (out["info"]["n_events"][0] == 0) == replaces  # a replace plays no shot
        if replaces:
            assert core.game.shooter[0] == 0  # the offender plays again, from where the miss was played


def test_sim_no_miss_when_partly_snookered():
    """The same stroke with the black covering one edge of the red: a foul but no miss; a replace
    declaration is then ignored and player 1 plays the stroke (here one that hits the red)."""
    R_ = 0.02625
    core = game_table("snooker", {0: (0.9, 1.0), 1: (0.9, 2.0), BLACK: (0.9 + 1.2 * R_, 1.5)})
    out = shoot(core, math.pi, 0.6)
    assert out["record"].foul[0] == R.FOUL_NO_CONTACT and not out["record"].miss[0]
    assert core.constraints().may_pass[0] and not core.constraints().may_replace[0]
    out = replace(core)
    assert not out["record"].replaced[0] and not out["record"].passed[0] and out["record"].shooter[0] == 1


def test_sim_the_touching_ball():
    """The cue ball at rest touching a red (on): played straight away from it, the stroke hits nothing and
    is no foul (the turn passes, no points, no miss); played into it, the red's the first contact: a push
    stroke, 4 away. Touching the blue (not on) and played away from it without hitting a red: the usual
    no-contact foul (4; and a miss, the red being open on the other side)."""
    R_ = 0.02625
    red = np.array([0.9, 2.0])
    cue = red - np.array([0.0, 2 * R_])               # frozen to the red, below it
    core = game_table("snooker", {0: tuple(cue), 1: tuple(red), BLACK: (0.9, 3.245)})
    c = core.constraints()
    assert c.touching[0, 1] and c.touching[0].sum() == 1
    assert core.observe()[0, -1] == 1.0 and core.observe()[0, -2] == 0.0  # the observation says it touches
    out = shoot(core, -math.pi / 2, 0.5)               # straight away, towards the bottom cushion
    rec = out["record"]
    assert out["info"]["first_contact"][0] == -1 and rec.legal[0] and rec.foul[0] == R.FOUL_NONE
    assert rec.turn_over[0] and out["info"]["points"][0] == 0 and not rec.miss[0]
    assert np.array_equal(core.state.pos[0, 1], red)  # the red did not move
    core = game_table("snooker", {0: tuple(cue), 1: tuple(red), BLACK: (0.9, 3.245)})
    out = shoot(core, math.pi / 2, 0.5)                # into the red
    assert out["info"]["first_contact"][0] == 1 and out["record"].foul[0] == R.FOUL_PUSH
    assert out["info"]["penalty"][0] == 4 and not out["record"].miss[0]
    core = game_table("snooker", {0: tuple(cue), BLUE: tuple(red), 1: (0.3, 1.5), BLACK: (0.9, 3.245)})
    assert core.constraints().touching[0, BLUE]
    out = shoot(core, -math.pi / 2, 0.5)
    assert out["record"].foul[0] == R.FOUL_NO_CONTACT and out["info"]["penalty"][0] == 4 and out["record"].miss[0]


def test_bot_pots_the_ball_on_and_nominates_the_colour():
    w = 1.778
    core = game_table("snooker", {0: (w - 0.4, 0.4), 1: (w - 0.2, 0.2), BLUE: (0.9, 1.5), BLACK: (0.9, 3.245)})
    bot = make_bot("snooker")
    view = core.view([0])
    plan = bot.act(view)
    assert bot.last_mode[0] == "pot"
    out = core.step(core.actions_of(plan, [0], view.codec), [0])
    assert out["info"]["pocketed"][0, 1] and core.game.phase[0] == R.PHASE_COLOUR
    view = core.view([0])
    plan = bot.act(view)
    assert plan.ball[0] >= FIRST_COLOUR  # a colour nominated


def test_bot_plays_a_legal_safety_when_nothing_is_on():
    # the only red frozen to the top cushion, far away: no pot; a safety that hits it
    core = game_table("snooker", {0: (0.5, 0.5), 1: (1.3, 3.569 - 0.02625 - 1e-4), BLACK: (0.9, 3.245)})
    bot = make_bot("snooker")
    view = core.view([0])
    plan = bot.act(view)
    assert bot.last_mode[0] == "safety"
    out = core.step(core.actions_of(plan, [0], view.codec), [0])
    assert out["record"].legal[0]


def test_match_script_quick(tmp_path):
    r = subprocess.run([sys.executable, str(ROOT / "scripts" / "match.py"), "--game", "snooker", "--policies",
                        "random", "snooker", "--racks", "1", "--max-shots", "60", "--out", str(tmp_path)],
                       capture_output=True, text=True, cwd=ROOT, timeout=600)
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "snooker_tournament.json").exists()
