"""The task registry (a toy task registered from this module works with
gymnasium.make, make_vec in both modes and check_env) and the shot space
(actions_to_shots / shots_to_actions are inverse; one cached shot context)."""
from __future__ import annotations

import math
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env
from hypothesis import given, settings
from hypothesis import strategies as st

import billiards_env  # noqa: F401  (registers the built-in tasks)
from billiards_env.envs import (TASKS, BilliardsEnv, BilliardsVectorEnv, Shots, Task, TaskConfig, env_classes,
                                get_task, register_task)
from billiards_env.physics.noise import OFFSET_SAFETY
from billiards_env.envs.tasks import Judgement, ShotOutcome
from billiards_env.physics.strike import draw_to_speed, speed_to_draw


# ------------------------------------------------------------- the toy task --
class ToyPotAny(Task):
    """Billiards-ToyPotAny-v1: the cue ball and two object balls at random
    positions; one shot per episode. Success: any object ball pocketed, the
    cue ball not. Foul: the cue ball hits no ball.
"""

    name = "toy_pot_any"
    env_id = "Billiards-ToyPotAny-v1"
    class_prefix = "ToyPotAny"
    config_path = Path(__file__).parent / "tasks" / "toy_pot_any.yaml"

    def validate(self, cfg) -> None:
        if cfg.n_balls != 2:
            raise ValueError("toy_pot_any uses two object balls (n_balls: 2)")

    def reset(self, core, idx):
        from billiards_env.physics import BallState
        return BallState.from_positions(core.place(idx))

    def judge(self, shot: ShotOutcome) -> Judgement:
        return Judgement(foul=shot.first_contact < 1, success=(shot.n_pocketed > 0) & ~shot.scratch,
                         terminated=np.ones(len(shot.target), dtype=bool))


register_task(ToyPotAny())  # the one registry line
TOY = "Billiards-ToyPotAny-v1"


def test_toy_task_registered_with_both_entry_points():
    assert get_task("toy_pot_any") is TASKS["toy_pot_any"]
    spec = gym.spec(TOY)
    assert spec.entry_point == "billiards_env.envs.billiards:ToyPotAnyEnv"
    assert spec.vector_entry_point == "billiards_env.envs.billiards:ToyPotAnyVectorEnv"
    single, vector = env_classes("toy_pot_any")
    assert issubclass(single, BilliardsEnv) and issubclass(vector, BilliardsVectorEnv)
    assert single.__doc__.startswith("Billiards-ToyPotAny-v1") and "Observation" in single.__doc__
    from billiards_env.envs.billiards import ToyPotAnyEnv  # generated on demand
    assert ToyPotAnyEnv is single
    assert register_task(ToyPotAny()) is TASKS["toy_pot_any"]  # registering again: no-op


def test_toy_task_make_and_check_env():
    env = gym.make(TOY)
    assert env.unwrapped.config == TaskConfig.default("toy_pot_any")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env.unwrapped)
    assert [str(w.message) for w in caught if "needs a display" not in str(w.message)] == []
    obs, info = env.reset(seed=0)
    assert obs.shape == (13,) and info["legal_target"] == 1
    obs, r, te, tr, info = env.step(env.action_space.sample())
    assert te and not tr and set(info["reward_terms"]) == {"pocket", "scratch", "foul", "contact", "success",
                                                           "shaping"}
    env.close()


@pytest.mark.parametrize("mode", ["vector_entry_point", "sync"])
def test_toy_task_make_vec(mode):
    v = gym.make_vec(TOY, num_envs=3, vectorization_mode=mode)
    obs, _ = v.reset(seed=5)
    assert obs.shape == (3, 13)
    for _ in range(4):
        obs, r, te, tr, info = v.step(v.action_space.sample())
        assert np.all(np.isfinite(obs)) and np.all(np.isfinite(r))
    v.close()


def test_vector_entry_point_matches_sync_on_the_toy_task():
    acts = np.random.default_rng(1).uniform(-1, 1, (5, 3, 4)).astype(np.float32)
    out = {}
    for mode in ("vector_entry_point", "sync"):
        v = gym.make_vec(TOY, num_envs=3, vectorization_mode=mode)
        obs = [v.reset(seed=7)[0]]
        for a in acts:
            obs.append(v.step(a)[0])
        out[mode] = np.stack(obs)
        v.close()
    np.testing.assert_array_equal(out["vector_entry_point"], out["sync"])


def test_task_validation_and_unknown_names():
    with pytest.raises(ValueError, match="two object balls"):
        TaskConfig.default("toy_pot_any", n_balls=3)
    with pytest.raises(ValueError, match="exactly one object ball"):
        TaskConfig.default("pot_one", n_balls=2)
    with pytest.raises(ValueError, match="exactly nine"):
        TaskConfig.default("nine_ball", n_balls=5)
    with pytest.raises(ValueError, match="unknown task 'snooker'.*registered tasks"):
        TaskConfig.default("snooker")


def test_missing_yaml_is_a_clear_error(tmp_path):
    class NoFile(ToyPotAny):
        name = "toy_no_file"
        env_id = "Billiards-ToyNoFile-v1"
        class_prefix = "ToyNoFile"
        config_path = tmp_path / "absent.yaml"

    register_task(NoFile())
    with pytest.raises(FileNotFoundError, match="toy_no_file.*absent.yaml.*config_path"):
        gym.make("Billiards-ToyNoFile-v1")


def test_registry_refuses_clashes():
    class Clash(ToyPotAny):
        name = "pot_one"
    with pytest.raises(ValueError, match="taken"):
        register_task(Clash())
    with pytest.raises(TypeError):
        register_task("pot_one")


# -------------------------------------------------------------- shot space --
@pytest.fixture(scope="module", params=["relative", "absolute"])
def vec(request):
    v = gym.make_vec("Billiards-RunOut-v1", num_envs=4, vectorization_mode="vector_entry_point",
                     aim=request.param).unwrapped
    v.reset(seed=3)
    return v


unit = st.floats(-1.0, 1.0, allow_nan=False)


@settings(max_examples=200, deadline=None)
@given(a0=unit, a1=unit, r=st.floats(0.0, OFFSET_SAFETY * (1 - 1e-12)), th=st.floats(0.0, 2 * math.pi))
def test_actions_to_shots_then_back_is_identity(vec, a0, a1, r, th):
    acts = np.tile([a0, a1, r * math.cos(th), r * math.sin(th)], (4, 1))
    back = vec.shots_to_actions(vec.actions_to_shots(acts))
    # a0 is an angle / pi: a0 = 1 and a0 = -1 aim the same way, so compare it modulo 2
    da0 = (back[:, 0] - acts[:, 0] + 1.0) % 2.0 - 1.0
    np.testing.assert_allclose(da0, 0.0, rtol=0, atol=1e-12)
    np.testing.assert_allclose(back[:, 1:], acts[:, 1:], rtol=0, atol=1e-12)


@settings(max_examples=200, deadline=None)
@given(phi=st.floats(-math.pi, math.pi * (1 - 1e-12)), u=st.floats(0.0, 1.0),
       r=st.floats(0.0, OFFSET_SAFETY * (1 - 1e-12)), th=st.floats(0.0, 2 * math.pi))
def test_shots_to_actions_then_back_is_identity(vec, phi, u, r, th):
    p = vec.params
    lo, hi = draw_to_speed(vec.config.min_draw, p), p.max_speed
    lim = p.miscue_limit
    shots = Shots(phi + vec.aim_origin() * 0.0, lo + u * (hi - lo), r * lim * math.cos(th), r * lim * math.sin(th))
    back = vec.actions_to_shots(vec.shots_to_actions(shots))
    dphi = np.angle(np.exp(1j * (back.phi - shots.phi)))
    np.testing.assert_allclose(dphi, 0.0, atol=1e-12)
    np.testing.assert_allclose(back.speed, shots.speed, rtol=1e-12)
    np.testing.assert_allclose(back.a, shots.a, atol=1e-12)
    np.testing.assert_allclose(back.b, shots.b, atol=1e-12)


def test_draw_speed_functions_are_inverse_and_match_max_speed():
    p = TaskConfig.default("pot_one").params()
    d = np.linspace(0.0, p.max_draw, 101)
    np.testing.assert_allclose(speed_to_draw(draw_to_speed(d, p), p), d, rtol=1e-15, atol=1e-18)
    assert draw_to_speed(p.max_draw, p) == p.max_speed


def test_shot_context_is_computed_once_per_state_change(monkeypatch):
    v = gym.make_vec("Billiards-RunOut-v1", num_envs=4, vectorization_mode="vector_entry_point").unwrapped
    task = v._core.task
    calls = []
    inner = type(task).legal_target
    monkeypatch.setattr(type(task), "legal_target", lambda self, pos, pocket: calls.append(1) or inner(self, pos, pocket))
    v.reset(seed=0)
    assert len(calls) == 1  # the observation and the reset info share it
    ctx = v.shot_context()
    np.testing.assert_array_equal(v.legal_target(), ctx.target)
    s = v.state
    d = s.pos[np.arange(4), ctx.target] - s.pos[:, 0]
    np.testing.assert_allclose(v.aim_origin(), np.arctan2(d[:, 1], d[:, 0]), atol=1e-15)
    v.actions_to_shots(np.zeros((4, 4)))
    v.shots_to_actions(Shots(0.0, 1.0, 0.0, 0.0))
    assert len(calls) == 1
    _, _, _, _, info = v.step(np.zeros((4, 4), np.float32))  # shot, reward, observation: one more
    assert len(calls) == 2
    np.testing.assert_array_equal(info["legal_target"], ctx.target)
