"""Reward terms on scripted shots, and seeded shot noise."""
import math

import gymnasium as gym
import numpy as np
import pytest

import billiards_env  # noqa: F401
from billiards_env.envs import PotOneEnv, PotOneVectorEnv
from billiards_env.physics import BallState, simulate, strike_velocity
from billiards_env.physics.strike import Shots, draw_to_speed

# cue ball, object ball and the corner pocket at (0, 0) on one line
STRAIGHT_IN = np.array([[0.6, 0.6], [0.3, 0.3]])
AIM = math.atan2(-0.3, -0.3)


def test_straight_in_shot_earns_pocket_reward():
    env = PotOneEnv(reward={"pocket": 1.0, "contact": 0.25, "success": 0.5, "shaping": 0.0})
    env.reset(seed=0)
    env.set_state(STRAIGHT_IN)
    act = env.shots_to_actions(Shots(AIM, draw_to_speed(0.05, env.params), 0.0, -0.3))[0]  # draw back: the cue ball stays up
    _, r, term, trunc, info = env.step(act)
    assert info["pocketed"].tolist() == [False, True] and info["success"] and not info["scratch"]
    assert info["first_contact"] == 1 and not info["foul"] and term and not trunc
    t = info["reward_terms"]
    assert t["pocket"] == 1.0 and t["contact"] == 0.25 and t["success"] == 0.5
    assert t["scratch"] == 0.0 and t["foul"] == 0.0
    assert r == pytest.approx(sum(t.values()), abs=1e-12) and r == pytest.approx(1.75)


def test_scratch_earns_penalty_and_shaping_is_potential_based():
    w = {"scratch": -2.0, "foul": -0.5, "shaping": 0.7, "gamma": 0.9}
    env = PotOneEnv(reward=w)
    env.reset(seed=0)
    obj = np.array([0.6, 1.5])
    env.set_state(np.array([[0.3, 0.3], obj]))
    act = env.shots_to_actions(Shots(math.atan2(-0.3, -0.3), draw_to_speed(0.05, env.params), 0.0, 0.0))[0]  # cue ball straight into the corner
    _, r, term, _, info = env.step(act)
    assert info["scratch"] and info["foul"] and info["first_contact"] == -1 and not info["success"]
    t = info["reward_terms"]
    assert t["scratch"] == -2.0 and t["foul"] == -0.5 and t["pocket"] == 0.0
    # terminal: Phi(s') = 0, so shaping = -w * Phi(s) = w * d(target, nearest pocket) / diagonal
    d = np.min(np.hypot(*(env.table.pockets[:, :2] - obj).T))
    assert t["shaping"] == pytest.approx(0.7 * d / math.hypot(env.table.width, env.table.length))
    assert r == pytest.approx(sum(t.values()), abs=1e-12)


@pytest.mark.parametrize("env_id", ["Billiards-RunOut-v1", "Billiards-NineBall-v1"])
def test_reward_terms_add_up_in_vector_env(env_id):
    v = gym.make_vec(env_id, num_envs=6, vectorization_mode="vector_entry_point")
    v.reset(seed=1)
    rng = np.random.default_rng(1)
    for _ in range(15):
        act = np.clip(rng.normal(0, [0.02, 0.5, 0.3, 0.3], size=(6, 4)), -1, 1)
        _, r, te, tr, info = v.step(act)
        total = sum(info["reward_terms"].values())
        np.testing.assert_allclose(r, total, atol=1e-12)
        assert set(info["reward_terms"]) == {"pocket", "scratch", "foul", "contact", "success", "shaping"}
        # non-terminal RunOut/NineBall shots keep the cue ball up and raise no foul
        assert not np.any((info["scratch"] | info["foul"]) & ~te)


def test_zero_noise_reproduces_the_noiseless_shot():
    env = PotOneEnv(noise={"aim_deg": 0.0, "speed": 0.0, "side_mm": 0.0, "height_mm": 0.0})
    env.reset(seed=3)
    start = env.state.copy()
    act = np.array([0.02, -0.2, 0.3, -0.4], np.float32)
    shots = env.actions_to_shots(act[None])
    obs, *_ = env.step(act)
    ref = simulate(strike_velocity(start, *shots, env.params), env.table, env.params)
    np.testing.assert_array_equal(env.state.pos, ref.state.pos)
    np.testing.assert_array_equal(env.state.pocket, ref.state.pocket)


def test_same_seed_same_noisy_shot_and_noise_changes_it():
    act = np.array([0.0, -0.3, 0.1, 0.1], np.float32)
    outs = []
    for noise in ("tournament", "tournament", "none"):
        env = PotOneEnv(noise=noise)
        env.reset(seed=9)
        outs.append(env.step(act)[0])
    np.testing.assert_array_equal(outs[0], outs[1])
    assert not np.array_equal(outs[0], outs[2])


def test_measured_noise_std_matches_config():
    n, rounds = 128, 3
    noise = {"aim_deg": 0.5, "speed": 0.075, "side_mm": 0.5, "height_mm": 0.5}
    v = PotOneVectorEnv(num_envs=n, noise=noise, render_mode="rgb_array")  # rgb_array records events
    v.reset(seed=0)
    p = v.params
    pos = np.tile(np.array([[0.6, 0.6], [0.6, 1.6]]), (n, 1, 1))
    samples = []
    for _ in range(rounds):
        v.set_state(pos)
        acts = np.tile([0.0, -0.4, 0.2, -0.2], (n, 1))
        phi0, speed0, a0, b0 = v.actions_to_shots(acts)
        v.step(acts)
        # struck cue-ball state: the 'start' event of ball 0
        st = np.stack([log.states[0, 0] for log in v.last_events])
        vx, vy, wx, wy, wz = st[:, 2], st[:, 3], st[:, 4], st[:, 5], st[:, 6]
        speed = np.hypot(vx, vy)
        dx, dy = vx / speed, vy / speed
        k = 2.5 * speed / p.R
        a, b = wz / k, (wy * dx - wx * dy) / k
        dphi = np.angle(np.exp(1j * (np.arctan2(vy, vx) - phi0)))
        samples.append(np.stack([dphi, speed - speed0, a - a0, b - b0], 1))
    s = np.concatenate(samples)
    want = np.array([math.radians(0.5), 0.075, 0.5e-3 / p.R, 0.5e-3 / p.R])
    np.testing.assert_allclose(s.std(axis=0), want, rtol=0.15)
    assert np.all(np.abs(s.mean(axis=0)) < 4 * want / math.sqrt(len(s))), s.mean(axis=0)


def test_noise_respects_limits():
    v = PotOneVectorEnv(num_envs=200, noise={"aim_deg": 1.0, "speed": 5.0, "side_mm": 50.0, "height_mm": 50.0})
    v.reset(seed=0)
    core, p = v._core, v.params
    phi, speed, a, b = core.apply_noise(Shots(np.zeros(200), np.full(200, p.max_speed), np.full(200, 0.49),
                                              np.zeros(200)), np.arange(200))
    assert np.all((speed >= 0) & (speed <= p.max_speed)) and np.any(speed < p.max_speed)
    assert np.all(np.hypot(a, b) <= p.miscue_limit)
