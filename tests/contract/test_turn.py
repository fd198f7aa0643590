"""The preview is the env: ``GameView.preview`` and ``GameCore.step`` play a
turn through the one ``contract.turn.play_turn``, so the same plan under the
same noise draws gives the same record, balls, game state and next
constraints, bit for bit, in every game; and the three cases where the
preview once disagreed with the env (the 9 pocketed on a foul, a declared
push-out, a placement without ball in hand) each have their test."""
from __future__ import annotations

import copy
import dataclasses
import math

import numpy as np
import pytest

from billiards_env.contract import ShotPlan, common_draws
from billiards_env.envs.games import GAMES, GameConfig, GameCore
from billiards_env.physics.strike import Shots
from billiards_env.rules import records as R
from billiards_env.rules.placement import FOOT_SPOT
from billiards_env.testing.positions import game_table

N_TABLES = 24
TURNS = 6  # turns per game: the break, open play, ball in hand, push-outs and passes all come up at this seed


def _same(a, b, what):
    for f in dataclasses.fields(a):
        x, y = getattr(a, f.name), getattr(b, f.name)
        if isinstance(x, np.ndarray):
            assert np.array_equal(x, y), f"{what}.{f.name} differs: preview {x} env {y}"


def _actions(rng, core, n):
    a = rng.uniform(-1, 1, (n, core.action_dim))
    a[rng.random(n) < 0.3, 6] = 1.0  # declare often: push-outs and passes
    return a


def _previewed_step(core, view, plan, actions, idx):
    """Preview ``plan`` under the env's noise with the draws the step will make, step the env with ``actions``,
    and check that they agree on the record, the balls, the game state and the next constraints: (preview,
    step output)."""
    shoot = ~(view.may_pass & plan.declare)
    draws = np.zeros((len(idx), 4))
    draws[shoot] = copy.deepcopy(core.streams).normal(idx[shoot], 4)  # what the step will draw
    pv = view.preview(plan, noise="env", draws=draws)
    out = core.step(actions, idx)
    _same(pv.record, out["record"], "record")
    assert np.array_equal(pv.pos, core.state.pos) and np.array_equal(pv.pocket, core.state.pocket)
    _same(pv.state, core.game, "state")
    _same(pv.next, core.constraints(), "next")
    return pv, out


@pytest.mark.parametrize("game", GAMES)
def test_preview_is_the_env_bit_for_bit(game):
    """Random positions (the games played on by random turns) and random plans
    (the env's own decoding of random actions), under the env's noise with
    the env's own draws: the preview and the step agree on everything."""
    core = GameCore(GameConfig(game=game, noise="variable"), N_TABLES)
    idx = np.arange(N_TABLES)
    core.streams.seed(idx, 100 + idx)
    core.reset_tables(idx)
    rng = np.random.default_rng(1)
    for _ in range(TURNS):
        view = core.view(idx)
        actions = _actions(rng, core, N_TABLES)
        plan, moved = view.codec.decode(actions)
        pv, out = _previewed_step(core, view, plan, actions, idx)
        assert np.array_equal(pv.turn.placed, out["info"]["placement"])
        after = view.after(pv, idx, idx)  # the next shooter's view equals the env's own
        mine = core.view(idx)
        for f in ("pos", "pocket", "to_move", "ball_in_hand", "targets", "call_needed", "may_pass", "fouls"):
            assert np.array_equal(getattr(after, f), getattr(mine, f)), f
        done = np.nonzero(out["terminated"] | out["truncated"])[0]
        if len(done):
            core.reset_tables(done)


def test_the_nine_pocketed_on_a_foul_is_spotted_in_the_preview():
    """The cue ball hits the 9 first (the 1 is on) and the 9 drops: a foul, the
    9 back on the foot spot in the preview's balls and in ``view.after``."""
    core = game_table("nine_ball", {0: (0.32, 0.32), 9: (0.2, 0.2), 1: (0.9, 1.5)})
    view = core.view([0])
    pv = view.preview(ShotPlan.of(Shots(np.array([math.atan2(-1, -1)]), np.array([1.5]), 0.0, 0.0)))
    assert pv.record.foul[0] == R.FOUL_WRONG_BALL and not pv.record.game_over[0]
    t = core.table
    assert pv.pocket[0, 9] == -1
    assert np.allclose(pv.pos[0, 9], (t.width / 2, FOOT_SPOT * t.length), atol=4 * core.params.R)
    after = view.after(pv, [0], [0])
    assert after.on_table[0, 9] and after.in_hand[0]


def test_a_declared_push_out_is_previewed_as_a_push_out():
    """Right after the break the shooter may push out: a declared push-out
    that touches nothing is legal (the opponent may pass), where the same
    shot undeclared is a foul."""
    core = game_table("nine_ball", {0: (0.5, 0.5), 1: (0.9, 1.5), 9: (0.3, 2.0)}, phase=R.PHASE_AFTER_BREAK)
    view = core.view([0])
    assert view.push_out_allowed[0]
    shots = Shots(np.array([math.pi / 2, math.pi / 2]), np.array([0.3, 0.3]), 0.0, 0.0)
    pv = view.preview(ShotPlan.of(shots, declare=np.array([True, False])), rows=[0, 0])
    assert pv.record.push_out[0] and pv.record.foul[0] == R.FOUL_NONE and pv.next.may_pass[0]
    assert pv.record.foul[1] == R.FOUL_NO_CONTACT
    push = ShotPlan.of(Shots(np.array([math.pi / 2]), np.array([0.3]), 0.0, 0.0), declare=np.array([True]))
    out = core.step(core.actions_of(push, [0]), [0])
    assert out["record"].push_out[0] and out["record"].foul[0] == R.FOUL_NONE


def test_a_placement_without_ball_in_hand_is_ignored():
    """A plan's placement counts only with ball in hand: without it the cue
    ball is played from where it lies, as the env plays it."""
    core = game_table("nine_ball", {0: (0.5, 0.5), 1: (0.9, 1.5), 9: (0.3, 2.0)})
    view = core.view([0])
    assert not view.in_hand[0]
    plan = ShotPlan.of(Shots(np.array([1.0]), np.array([1.0]), 0.0, 0.0), placement=np.array([[0.6, 1.0]]))
    pv = view.preview(plan)
    assert np.array_equal(pv.turn.placed[0], view.pos[0, 0])
    out = core.step(core.actions_of(plan, [0]), [0])
    assert np.allclose(out["info"]["placement"][0], (0.5, 0.5))


def test_a_snooker_replace_after_a_miss_is_previewed_as_the_env():
    """After player 0's foul and a miss (no ball hit, the red open), player 1's replace declaration: the
    preview puts the balls back and hands the stroke back exactly as the env's step does, and its next view
    equals the env's; the same plan previewed as a pass differs (the balls stay where the miss left them)."""
    core = game_table("snooker", {0: (0.9, 1.0), 1: (0.9, 2.0), 21: (0.9, 3.245)})
    miss = ShotPlan.of(Shots(np.array([math.pi]), np.array([0.6]), 0.0, 0.0))
    core.step(core.actions_of(miss, [0]), [0])
    view = core.view([0])
    assert view.may_replace[0] and view.constraints.may_replace[0]
    shots = Shots(np.zeros(2), np.ones(2), 0.0, 0.0)
    plans = ShotPlan.of(shots, declare=np.array([False, True]), replace=np.array([True, False]))
    pv = view.preview(plans, rows=[0, 0])
    assert pv.record.replaced[0] and pv.record.passed[1] and not np.array_equal(pv.pos[0], pv.pos[1])
    plan = plans.take([0])
    out = core.step(core.actions_of(plan, [0], view.codec), [0])
    assert out["record"].replaced[0]
    one = view.preview(plan)
    _same(one.record, out["record"], "record")
    assert np.array_equal(one.pos, core.state.pos) and np.array_equal(one.pocket, core.state.pocket)
    _same(one.state, core.game, "state")
    _same(one.next, core.constraints(), "next")
    after, mine = view.after(one, [0], [0]), core.view([0])
    for f in ("pos", "pocket", "to_move", "ball_in_hand", "targets", "may_pass", "may_replace"):
        assert np.array_equal(getattr(after, f), getattr(mine, f)), f


def test_a_three_cushion_replace_is_previewed_as_the_env():
    """The shooter's ball frozen to the red: the replace declaration previewed puts the balls on the starting
    position with the same shooter to play, exactly as the env's step does (record, balls, state, next
    constraints, next view); the same aim without it plays the shot (here straight into the red: a foul)."""
    R_ = 0.03075
    core = game_table("three_cushion", {0: (0.6, 0.8), 1: (0.3, 2.0), 2: (0.6 + 2 * R_, 0.8)})
    view = core.view([0])
    assert view.may_replace[0] and view.constraints.may_replace[0] and view.touching[0, 2]
    plans = ShotPlan.of(Shots(np.zeros(2), np.full(2, 2.0), 0.0, 0.0), replace=np.array([True, False]))
    pv = view.preview(plans, rows=[0, 0])
    assert pv.record.replaced[0] and not pv.record.turn_over[0] and pv.next.is_break[0]
    assert pv.record.foul[1] == R.FOUL_PUSH and pv.record.turn_over[1]
    plan = plans.take([0])
    out = core.step(core.actions_of(plan, [0], view.codec), [0])
    assert out["record"].replaced[0]
    one = view.preview(plan)
    _same(one.record, out["record"], "record")
    assert np.array_equal(one.pos, core.state.pos) and np.array_equal(one.pocket, core.state.pocket)
    _same(one.state, core.game, "state")
    _same(one.next, core.constraints(), "next")
    after, mine = view.after(one, [0], [0]), core.view([0])
    for f in ("pos", "pocket", "to_move", "targets", "is_break", "may_replace", "touching"):
        assert np.array_equal(getattr(after, f), getattr(mine, f)), f


def test_the_wrong_cue_ball_is_played_and_ruled_but_never_encoded():
    """A plan naming the opponent's ball (``struck`` 1) or the red (2): the turn strikes that ball (the
    shooter's own ball stays where it lay) and the rules call a foul; such a plan has no env action, and a
    game without a cue ball per player refuses it."""
    core = game_table("three_cushion", {0: (0.4, 0.5), 1: (1.0, 0.5), 2: (0.7, 2.2)})
    view = core.view([0])
    up = Shots(np.full(3, math.pi / 2), np.full(3, 1.0), 0.0, 0.0)  # along +y: nothing in the way of any ball
    pv = view.preview(ShotPlan.of(up, struck=np.array([0, 1, 2])), rows=[0, 0, 0])
    assert pv.record.foul.tolist() == [R.FOUL_NONE, R.FOUL_WRONG_CUE_BALL, R.FOUL_WRONG_CUE_BALL]
    assert pv.record.turn_over.all() and (pv.record.points == 0).all()
    start = pv.turn.start.pos
    moved = np.linalg.norm(pv.turn.pos[:, [1, 0, 2]] - start, axis=2) > 1e-3  # after the hand-over, in the
    assert moved.tolist() == [[True, False, False], [False, True, False], [False, False, True]]  # old frame
    with pytest.raises(ValueError, match="struck"):
        core.actions_of(ShotPlan.of(up.take([1]), struck=np.array([1])), [0])
    pool = game_table("nine_ball", {0: (0.5, 0.5), 1: (0.9, 1.5), 9: (0.3, 2.0)})
    with pytest.raises(ValueError, match="struck"):
        pool.view([0]).preview(ShotPlan.of(Shots(np.array([1.0]), np.array([1.0]), 0.0, 0.0), struck=np.array([1])))


def test_common_draws_give_each_group_the_same_numbers():
    rng = np.random.default_rng(0)
    z = common_draws([0, 1, 0, 2, 1], rng)
    assert z.shape == (5, 4)
    assert np.array_equal(z[0], z[2]) and np.array_equal(z[1], z[4]) and not np.array_equal(z[0], z[1])


def test_preview_draws_are_checked():
    core = game_table("nine_ball", {0: (0.5, 0.5), 1: (0.9, 1.5), 9: (0.3, 2.0)})
    plan = ShotPlan.of(Shots(np.array([1.0]), np.array([1.0]), 0.0, 0.0))
    with pytest.raises(ValueError, match="draws must have shape"):
        core.view([0]).preview(plan, noise="tournament", draws=np.zeros((2, 4)))
    with pytest.raises(ValueError, match="needs rng"):
        core.view([0]).preview(plan, noise="tournament")


AIR = {"airborne": True}


@pytest.mark.parametrize("game", GAMES)
def test_elevated_preview_is_the_env_bit_for_bit(game):
    """The airborne option (``effects={"airborne": True}``): random actions, their last component the cue's
    elevation (0 to 60 degrees: jumps, balls off the table), decoded into plans with ``theta``; the preview and
    the step agree on everything, bit for bit, as on the planar tables."""
    n = 12
    core = GameCore(GameConfig(game=game, noise="variable", effects=AIR), n)
    assert core.action_dim == core.base_dim + 1
    idx = np.arange(n)
    core.streams.seed(idx, 200 + idx)
    core.reset_tables(idx)
    rng = np.random.default_rng(2)
    elevated = off = 0
    for _ in range(4):
        view = core.view(idx)
        actions = _actions(rng, core, n)
        plan, _ = view.codec.decode(actions)
        elevated += int((plan.theta > 0).sum())
        pv, out = _previewed_step(core, view, plan, actions, idx)
        assert np.array_equal(pv.off_table, out["info"]["off_table"])
        off += int(out["info"]["off_table"].sum())
        done = np.nonzero(out["terminated"] | out["truncated"])[0]
        if len(done):
            core.reset_tables(done)
    assert elevated > 0 and off > 0  # the option played elevated shots, and some balls left the table


def test_an_encoded_elevated_plan_is_played_as_previewed():
    """A bot's plan with the cue elevated (``ShotPlan.theta``) through the env's actions (``actions_of``: the
    codec's last component) plays as the preview of the decoded plan; the elevation round-trips through the
    codec to float32 precision."""
    core = game_table("nine_ball", {0: (0.635, 0.5), 1: (0.635, 0.75), 9: (0.3, 2.0)}, effects=AIR)
    view = core.view([0])
    plan = ShotPlan.of(Shots(np.array([math.pi / 2]), np.array([4.0]), 0.0, 0.0, np.radians([45.0])))
    actions = core.actions_of(plan, [0], view.codec)
    assert actions.shape == (1, 9) and actions[0, 8] == pytest.approx(0.5, abs=1e-6)
    played, _ = view.codec.decode(actions)
    assert played.theta[0] == pytest.approx(math.radians(45.0), rel=1e-6)
    pv = view.preview(played)
    out = core.step(actions, [0])
    _same(pv.record, out["record"], "record")
    assert np.array_equal(pv.pos, core.state.pos)


def test_an_elevated_plan_needs_the_airborne_option():
    """A plan that elevates the cue on planar equipment is refused, by the preview and by the codec, naming the
    switch; on the option's codec an elevation above its 60 degrees is refused too."""
    core = game_table("nine_ball", {0: (0.5, 0.5), 1: (0.9, 1.5), 9: (0.3, 2.0)})
    plan = ShotPlan.of(Shots(np.array([1.0]), np.array([1.0]), 0.0, 0.0, np.array([0.3])))
    with pytest.raises(ValueError, match="airborne"):
        core.view([0]).preview(plan)
    with pytest.raises(ValueError, match="airborne"):
        core.actions_of(plan, [0])
    air = game_table("nine_ball", {0: (0.5, 0.5), 1: (0.9, 1.5), 9: (0.3, 2.0)}, effects=AIR)
    steep = ShotPlan.of(Shots(np.array([1.0]), np.array([1.0]), 0.0, 0.0, np.array([1.2])))
    with pytest.raises(ValueError, match="elevation must lie in"):
        air.actions_of(steep, [0])
    with pytest.raises(ValueError, match="theta"):
        air.view([0]).preview(ShotPlan.of(Shots(np.array([1.0]), np.array([1.0]), 0.0, 0.0, np.array([-0.1]))))


def test_one_player_elevated_preview_is_the_env_bit_for_bit():
    """The one-player tasks with the option: the env's step of random 5-component actions and the view's
    preview of the shots they decode to (``actions_to_shots``, theta included) agree bit for bit."""
    import gymnasium as gym
    env = gym.make_vec("Billiards-RunOut-v1", num_envs=16, vectorization_mode="vector_entry_point", effects=AIR,
                       noise="tournament")
    env.reset(seed=3)
    assert env.single_action_space.shape == (5,)
    rng = np.random.default_rng(4)
    for _ in range(3):
        a = rng.uniform(-1, 1, (16, 5)).astype(np.float32)
        view = env.view()
        shots = env.actions_to_shots(a)
        assert (shots.theta > 0).all()
        draws = copy.deepcopy(env._core.streams).normal(np.arange(16), 4)
        pv = view.preview(ShotPlan.of(shots), noise="env", draws=draws)
        _, _, term, trunc, info = env.step(a)
        live = ~info["reset"]
        assert np.array_equal(pv.outcome.off_table[live], info["off_table"][live])
        assert np.array_equal(pv.judged.success[live], info["success"][live])
        keep = live & ~(term | trunc)
        assert np.array_equal(pv.pos[keep], env.state.pos[keep]) and np.array_equal(pv.pocket[keep],
                                                                                    env.state.pocket[keep])
