"""The airborne option of the envs (``effects={"airborne": True}``, issue 46): one more action component, the
cue's elevation; balls that fly, and balls driven off the table ruled by each game, end to end through
``gym.make`` on constructed positions; Gymnasium's checker on the option's envs; the default ids untouched
(their spaces here, their behaviour in tests/envs/test_fingerprints.py)."""
import math

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import billiards_env  # noqa: F401  (registers the ids)
from billiards_env.contract import ShotPlan
from billiards_env.contract.codec import MAX_ACTION_ELEVATION
from billiards_env.envs.registration import ENV_IDS, GAME_IDS
from billiards_env.physics import constants as C
from billiards_env.physics.strike import Shots
from billiards_env.rules import records as R
from billiards_env.testing.positions import game_table, set_table

AIR = {"airborne": True}
GAME_ACTION = {"Billiards-TenBall-v1": 9, "Billiards-Snooker-v2": 9}  # the planar sizes (a8: a called ball; 8 elsewhere)


@pytest.mark.parametrize("env_id", sorted(ENV_IDS) + sorted(GAME_IDS))
def test_the_option_adds_the_elevation_and_passes_the_checker(env_id):
    """Off (the default) the action space is the planar one; on, one component more, and Gymnasium's
    checker passes (its random actions elevate the cue: jumps, balls off the table)."""
    planar = gym.make(env_id)
    d = 4 if env_id in ENV_IDS else GAME_ACTION.get(env_id, 8)
    assert planar.action_space.shape == (d,)
    env = gym.make(env_id, effects=AIR)
    assert env.action_space.shape == (d + 1,)
    assert env.observation_space == planar.observation_space
    check_env(env.unwrapped, skip_render_check=True)
    env.reset(seed=0)
    _, _, _, _, info = env.step(env.action_space.sample())
    assert info["off_table"].dtype == bool and info["off_table"].ndim == 1
    planar.reset(seed=0)
    assert "off_table" not in planar.step(planar.action_space.sample())[4]


def _game(env_id, balls, **kw):
    env = gym.make(env_id, effects=AIR, **kw)
    env.reset(seed=0)
    core = env.unwrapped.core
    set_table(core, balls)
    return env, core


def _jump(core, phi, speed, theta_deg):
    """The action of one shot with the cue elevated ``theta_deg``, through the codec (``ShotPlan.theta``)."""
    plan = ShotPlan.of(Shots(np.array([phi]), np.array([speed]), 0.0, 0.0, np.radians([theta_deg])))
    return core.actions_of(plan, [0])[0].astype(np.float32)


def test_nine_ball_cue_ball_jumped_off_is_a_foul_with_ball_in_hand():
    """9-ball: the cue ball jumped over the foot rail lands on the floor: FOUL_OFF_TABLE (WPA); the same
    shot level stays on the table (a foul of another kind: no contact)."""
    balls = {0: (0.635, 2.2), 1: (0.3, 0.5), 9: (1.0, 0.5)}
    env, core = _game("Billiards-NineBall2P-v1", balls, opponent="random")
    _, _, _, _, info = env.step(_jump(core, math.pi / 2, 6.0, 45.0))
    assert info["off_table"].tolist() == [True] + [False] * 9
    assert info["foul"] == R.FOUL_OFF_TABLE and info["turn_over"] and not info["pocketed"][0]
    env, core = _game("Billiards-NineBall2P-v1", balls, opponent="random")
    _, _, _, _, level = env.step(_jump(core, math.pi / 2, 6.0, 0.0))
    assert not level["off_table"].any() and level["foul"] == R.FOUL_NO_CONTACT


def test_nine_ball_object_ball_knocked_off_by_a_jumped_cue_ball_is_a_foul():
    """9-ball: the cue ball jumped (53 deg, 5.1 m/s) comes down on the 1, 5.5 cm from the foot cushion; the 1
    is driven into the slate, jumps over the cushion and lands on the rail top (its code OFF_RAIL): a foul
    (WPA), the 1 not spotted, the cue ball left on the table."""
    env = gym.make("Billiards-NineBall2P-v1", effects=AIR, opponent="random")
    env.reset(seed=0)
    core = env.unwrapped.core
    y = core.table.length - core.params.R - 0.055
    set_table(core, {0: (0.635, y - 0.9), 1: (0.635, y), 9: (1.0, 0.5)})
    _, _, _, _, info = env.step(_jump(core, math.pi / 2, 5.1, 53.0))
    assert info["off_table"].tolist() == [False, True] + [False] * 8
    assert info["foul"] == R.FOUL_OFF_TABLE and info["turn_over"]


def test_nine_ball_the_next_shooter_places_the_cue_ball_that_left():
    """After the cue ball left the table (its pocket code OFF_FLOOR), the opponent has ball in hand anywhere
    and plays it from where they place it."""
    core = game_table("nine_ball", {0: (0.635, 2.2), 1: (0.3, 0.5), 9: (1.0, 0.5)}, effects=AIR)
    out = core.step(_jump(core, math.pi / 2, 6.0, 45.0)[None].astype(np.float64), [0])
    assert out["record"].foul[0] == R.FOUL_OFF_TABLE and core.state.pocket[0, 0] == C.OFF_FLOOR
    c = core.constraints()
    assert c.ball_in_hand[0] == R.IN_HAND_ANYWHERE and c.shooter[0] == 1
    plan = ShotPlan.of(Shots(np.array([0.0]), np.array([1.0]), 0.0, 0.0), placement=np.array([[0.635, 1.0]]))
    core.step(core.actions_of(plan, [0], core.view([0]).codec), [0])
    assert core.state.pocket[0, 0] == -1


def test_snooker_cue_ball_forced_off_is_a_foul_of_four():
    """Snooker: the cue ball jumped over the top cushion: a foul (WPBSA: at least 4 points to the opponent)."""
    env = gym.make("Billiards-Snooker-v2", effects=AIR)
    env.reset(seed=0)
    core = env.unwrapped.core
    W, L = core.table.width, core.table.length
    set_table(core, {0: (W / 2, L - 0.34), 1: (0.3, 1.5), 21: (0.9, 1.245)})
    _, _, _, _, info = env.step(_jump(core, math.pi / 2, 6.0, 45.0))
    assert info["off_table"][0] and not info["off_table"][1:].any()
    assert info["foul"] == R.FOUL_OFF_TABLE and info["penalty"] >= 4


def test_three_cushion_ball_jumped_off_is_a_foul_and_respotted():
    """Three-cushion: the shooter's ball jumped off the table: a foul (no point, inning over), the ball back
    on a spot (UMB Art. 28)."""
    env = gym.make("Billiards-ThreeCushion-v3", effects=AIR)
    env.reset(seed=0)
    core = env.unwrapped.core
    W, L = core.table.width, core.table.length
    set_table(core, {0: (W / 2, L - 0.34), 1: (0.3, 0.6), 2: (W - 0.3, 0.6)})
    _, _, _, _, info = env.step(_jump(core, math.pi / 2, 6.0, 45.0))
    assert info["off_table"][0] and info["foul"] == R.FOUL_OFF_TABLE and info["points"] == 0
    assert (core.state.pocket[0] == -1).all()  # every ball on the table again: the jumped one on a spot


def test_a_jump_shot_clears_a_blocker_in_a_one_player_task():
    """RunOut with two object balls: the 2 lies between the cue ball and the 1. Level, the cue ball hits the 2
    first; elevated 50 degrees at 3 m/s it jumps the 2, hits the 1 first and pockets it, and stays on the
    table; the episode goes on."""
    ang = math.radians(60)
    d = np.array([math.cos(ang), math.sin(ang)])
    cue = np.array([0.5, 1.3])
    pos = np.array([cue, cue + 0.8 * d, cue + 0.2 * d])
    out = {}
    for theta in (0.0, 50.0):
        env = gym.make("Billiards-RunOut-v1", effects=AIR, n_balls=2)
        env.reset(seed=0)
        env.unwrapped.set_state(pos)
        shots = Shots(np.array([ang]), np.array([3.0]), 0.0, 0.0, np.radians([theta]))
        a = env.unwrapped.actions_of(ShotPlan.of(shots))[0]
        assert a[4] == pytest.approx(2 * math.radians(theta) / MAX_ACTION_ELEVATION - 1, abs=1e-6)
        out[theta] = env.step(a)
    assert out[0.0][4]["first_contact"] == 2
    _, reward, terminated, _, info = out[50.0]
    assert info["first_contact"] == 1 and info["pocketed"].tolist() == [False, True, False]
    assert not info["off_table"].any() and not terminated and info["reward_terms"]["contact"] > 0


def test_match_script_plays_with_balls_flying(tmp_path):
    """``scripts/match.py --airborne`` (docs/games.md, champion's escapes): the games are played with the effect on
    (recorded in the match's JSON), champion against itself without the escapes (the ablation's entrant)."""
    import importlib.util
    import json
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    spec = importlib.util.spec_from_file_location("match_script", root / "scripts" / "match.py")
    match = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(match)
    assert match.main(["--quick", "--airborne", "--policies", "champion",
                       "billiards_env.bots.planner.ablations:no_escapes", "--out", str(tmp_path)]) == 0
    doc = json.loads((tmp_path / "nine_ball_tournament.json").read_text())
    assert doc["effects"] == {"airborne": True} and sum(p["games"] for p in doc["pairings"]) == 4


def test_escapes_worth_script_quick(tmp_path):
    """``scripts/escapes_worth.py --quick`` (docs/games.md): champion against itself without the escapes, balls
    flying; the JSON counts each side's decisions and elevated strokes (none without the escapes)."""
    import importlib.util
    import json
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    spec = importlib.util.spec_from_file_location("escapes_worth", root / "scripts" / "escapes_worth.py")
    script = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(script)
    assert script.main(["--quick", "--out", str(tmp_path / "w.json")]) == 0
    doc = json.loads((tmp_path / "w.json").read_text())
    assert doc["summary"]["games"] == 4 and doc["elevated"]["champion-no-escapes"] == 0
    assert doc["decisions"]["champion"] > 0
