"""The impact-parameter aim (``aim: impact``, envs/impact.py) and the
target-frame observation (``observation: target_frame``, envs/target_frame.py)
on constructed layouts."""
import math

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import billiards_env  # noqa: F401  (registers the tasks)
from billiards_env.envs import TaskConfig

# Departure angles: without friction between the balls the object ball
# leaves along the line of centres at contact; the event solver resolves the
# contact to ~1e-8 rad here, so 1e-6 rad still catches any error in the map.
DEPARTURE_TOL = 1e-6
# Observations are float32: layouts equal up to rounding give entries equal to ~1e-7.
OBS_TOL = 1e-6


def _shoot(env, cue, target, action):
    """Shoot a two-ball layout; the object ball's direction of travel (rad)."""
    env.set_state(np.array([cue, target]))
    _, _, _, _, info = env.step(np.asarray(action, dtype=np.float32))
    assert info["first_contact"] == 1
    d = env.state.pos[0, 1] - np.asarray(target)
    assert np.hypot(*d) > 1e-3  # it moved
    return math.atan2(d[1], d[0])


@pytest.mark.parametrize("line", [0.3, 2.0, -2.8])  # direction of cue -> target (rad)
def test_impact_aim_sets_the_object_ball_departure_angle(line):
    """a0 = 0 is a full hit: the object ball moves along cue -> target. For
    any a0 it leaves at asin(a0) counter-clockwise from the cue ball's path,
    which turns asin(2R a0 / d) clockwise from cue -> target."""
    env = gym.make("Billiards-PotOne-v1", aim="impact", table="pocketless",
                   effects=dict(ball_friction=False)).unwrapped
    env.reset(seed=0)
    R, dist = env.params.R, 0.3
    cue = np.array([env.table.width / 2, env.table.length / 2])
    target = cue + dist * np.array([math.cos(line), math.sin(line)])
    for a0 in (0.0, 0.5, -0.8, 0.95):
        dep = _shoot(env, cue, target, [a0, -1.0, 0.0, 0.0])
        expected = line + math.asin(a0) - math.asin(2 * R * a0 / dist)
        assert abs((dep - expected + math.pi) % (2 * math.pi) - math.pi) < DEPARTURE_TOL, a0


def test_impact_aim_misses_beyond_the_thinnest_touch():
    """|a0| = 1 grazes the object ball; the relative aim a little further
    out misses it (a foul), so the impact aim's range is every hitting aim."""
    env = gym.make("Billiards-PotOne-v1", aim="impact", table="pocketless").unwrapped
    env.reset(seed=0)
    cue = np.array([0.6, 1.0])
    env.set_state(np.array([cue, cue + [0.0, 0.4]]))
    phi = env.actions_to_shots(np.array([1.0, 0, 0, 0])).phi[0]
    assert math.isclose(phi, math.pi / 2 - math.asin(2 * env.params.R / 0.4), rel_tol=1e-12)
    _, _, _, _, info = env.step(np.array([0.999, -0.5, 0, 0], dtype=np.float32))
    assert info["first_contact"] == 1


@pytest.mark.parametrize("speed_scale", ["linear", "log"])
@pytest.mark.parametrize("env_id", ["Billiards-PotOne-v1", "Billiards-RunOut-v1", "Billiards-NineBall-v1"])
def test_impact_shot_round_trip(env_id, speed_scale):
    v = gym.make_vec(env_id, num_envs=6, vectorization_mode="vector_entry_point", aim="impact",
                     speed_scale=speed_scale).unwrapped
    v.reset(seed=4)
    acts = np.random.default_rng(1).uniform(-1, 1, size=(6, 4))
    acts[:, 2:] *= 0.7
    np.testing.assert_allclose(v.shots_to_actions(v.actions_to_shots(acts)), acts, atol=1e-9)


def test_log_speed_scale_spans_the_draw_geometrically():
    """a1 = -1, 0, 1 give min_draw, the geometric mean and max_draw; equal
    steps of a1 are equal speed ratios."""
    from billiards_env.physics.strike import draw_to_speed
    v = gym.make_vec("Billiards-PotOne-v1", num_envs=5, vectorization_mode="vector_entry_point",
                     speed_scale="log").unwrapped
    v.reset(seed=0)
    lo, hi, p = v.config.min_draw, v.params.max_draw, v.params
    acts = np.zeros((5, 4))
    acts[:, 1] = [-1.0, -0.5, 0.0, 0.5, 1.0]
    speed = v.actions_to_shots(acts).speed
    np.testing.assert_allclose(speed[[0, 2, 4]], draw_to_speed(np.array([lo, math.sqrt(lo * hi), hi]), p),
                               rtol=1e-12)
    np.testing.assert_allclose(speed[1:] / speed[:-1], (hi / lo) ** 0.25, rtol=1e-12)


def test_impact_aim_keeps_the_ghost_ball_shot():
    """The ghost-ball baseline's shot maps to an impact action and back to the same aim."""
    from billiards_env.bots.geometry import ghost_ball_shot
    v = gym.make_vec("Billiards-PotOne-v1", num_envs=50, vectorization_mode="vector_entry_point",
                     aim="impact").unwrapped
    v.reset(seed=7)
    s = v.state
    ghost = ghost_ball_shot(s.pos, s.on_table, np.ones(50, dtype=np.int64), v.table, v.params)
    back = v.actions_to_shots(v.shots_to_actions(ghost)).phi
    np.testing.assert_allclose((back - ghost.phi + np.pi) % (2 * np.pi) - np.pi, 0.0, atol=1e-9)


def _layouts(env, n):
    """n random layouts [n, B, 2] of the env's task (from its own placement)."""
    v = gym.make_vec(env.spec.id, num_envs=n, vectorization_mode="vector_entry_point").unwrapped
    v.reset(seed=11)
    return v.state.pos.copy()


@pytest.mark.parametrize("env_id", ["Billiards-PotOne-v1", "Billiards-RunOut-v1"])
def test_target_frame_observation_is_invariant_under_the_table_symmetries(env_id):
    """Rotating a layout by 180 degrees about the table's centre leaves the
    observation unchanged; mirroring it negates every y and uy entry."""
    env = gym.make(env_id, observation="target_frame").unwrapped
    env.reset(seed=0)
    W, L = env.table.width, env.table.length
    B, P = env.state.n_balls, len(env.table.pockets)
    y_cols = [2 + 3 * i for i in range(B)] + [2 + 4 * B + 5 * k + j for k in range(P) for j in (1, 4)]
    for pos in _layouts(env, 5):
        obs = env.set_state(pos)
        rot = env.set_state(np.stack([W - pos[:, 0], L - pos[:, 1]], axis=1))
        np.testing.assert_allclose(rot, obs, atol=OBS_TOL)
        for mirrored in (np.stack([W - pos[:, 0], pos[:, 1]], axis=1), np.stack([pos[:, 0], L - pos[:, 1]], axis=1)):
            mir = env.set_state(mirrored)
            flip = obs.copy()
            flip[y_cols] *= -1
            np.testing.assert_allclose(mir, flip, atol=OBS_TOL)
        # and it moves with the layout: the cue ball lies at (-d, 0), the target at the origin
        d = np.hypot(*(pos[1] - pos[0])) / math.hypot(W, L)
        np.testing.assert_allclose(obs[[0, 1, 2, 4, 5]], [d, -d, 0.0, 0.0, 0.0], atol=OBS_TOL)


def test_target_frame_pockets_are_ordered_straightest_first():
    env = gym.make("Billiards-PotOne-v1", observation="target_frame").unwrapped
    env.reset(seed=0)
    W, L = env.table.width, env.table.length
    # target halfway between the centre and the far corner pocket, the cue ball straight behind it
    centres = env.table.pockets[:, :2]
    corner = centres[np.argmax(centres @ np.array([1.0, 1.0]))]
    target = np.array([W / 2, L / 2]) + 0.5 * (corner - [W / 2, L / 2])
    cue = target - 0.3 * (corner - target) / np.hypot(*(corner - target))
    obs = env.set_state(np.array([cue, target]))
    first = obs[2 + 4 * 2: 2 + 4 * 2 + 5]
    np.testing.assert_allclose(first[:2], [1.0, 0.0], atol=1e-6)
    np.testing.assert_allclose(first[2], np.hypot(*(corner - target)) / math.hypot(W, L), atol=1e-6)
    # the corner pocket's axis points back into the table, at 45 degrees to the cushions
    axis = np.array([-1.0, -1.0]) / math.sqrt(2.0)
    u = (corner - cue) / np.hypot(*(corner - cue))
    np.testing.assert_allclose(first[3:], [u @ axis, u[0] * axis[1] - u[1] * axis[0]], atol=1e-6)


def test_target_frame_lists_pockets_the_ball_cannot_enter_last():
    """A side pocket dead ahead but approached about 60 degrees off its axis (more
    than SIDE_ACCEPT_DEG) comes after every pocket the target can enter;
    each group is ordered straightest first."""
    from billiards_env.contract.pockets import pocket_accept_cos, pocket_axes
    from billiards_env.envs.target_frame import SORT_LAST

    env = gym.make("Billiards-PotOne-v1", observation="target_frame").unwrapped
    env.reset(seed=0)
    W, L = env.table.width, env.table.length
    centres = env.table.pockets[:, :2]
    side = centres[np.argmin(np.hypot(centres[:, 0], centres[:, 1] - L / 2))]  # the left side pocket
    target = side + [0.15 - side[0], -0.3]
    cue = target - 0.3 * (side - target) / np.hypot(*(side - target))
    obs = env.set_state(np.array([cue, target]))
    slots = obs[2 + 4 * 2:].reshape(-1, 5)
    ahead = np.flatnonzero(np.all(np.abs(slots[:, :2] - [1.0, 0.0]) < 1e-6, axis=1))
    assert ahead.size == 1 and ahead[0] > 0
    # the order the docstring states, computed in table coordinates
    rel = centres - target
    u = rel / np.linalg.norm(rel, axis=1)[:, None]
    enters = -np.sum(u * pocket_axes(env.table.pockets, W, L), axis=1) >= pocket_accept_cos(env.table.pockets, L)
    assert not enters[np.argmin(np.linalg.norm(centres - side, axis=1))]
    line = (target - cue) / np.hypot(*(target - cue))
    ang = np.abs(np.arctan2(u[:, 1] * line[0] - u[:, 0] * line[1], u @ line))
    key = ang + np.where(enters, 0.0, SORT_LAST)
    np.testing.assert_allclose(np.abs(np.arctan2(slots[:, 1], slots[:, 0])), np.sort(key) % SORT_LAST, atol=1e-6)


@pytest.mark.parametrize("kw", [dict(aim="impact"), dict(observation="target_frame"),
                                dict(aim="impact", observation="target_frame")])
@pytest.mark.parametrize("env_id", ["Billiards-PotOne-v1", "Billiards-NineBall-v1"])
def test_check_env_with_the_new_options(env_id, kw):
    env = gym.make(env_id, **kw).unwrapped
    check_env(env, skip_render_check=True)
    v = gym.make_vec(env_id, num_envs=8, vectorization_mode="vector_entry_point", **kw)
    obs, _ = v.reset(seed=3)
    v.action_space.seed(3)
    for _ in range(20):
        obs, *_ = v.step(v.action_space.sample())
        assert v.observation_space.contains(obs)


def test_bad_option_values_name_the_choices():
    with pytest.raises(ValueError, match="aim must be one of .*impact"):
        TaskConfig.default("pot_one", aim="fullness")
    with pytest.raises(ValueError, match="observation must be one of .*target_frame"):
        TaskConfig.default("pot_one", observation="cue_frame")
    with pytest.raises(ValueError, match="speed_scale must be one of .*log"):
        TaskConfig.default("pot_one", speed_scale="exp")
    with pytest.raises(ValueError, match="observation must be one of"):
        gym.make("Billiards-PotOne-v1", observation=3)
