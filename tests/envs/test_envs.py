"""Gymnasium environments: registration, env checker, vector/single
equivalence, autoreset, configuration, action handling, random rollouts."""
import dataclasses
import math
import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env
from gymnasium.vector import AutoresetMode

import billiards_env  # noqa: F401  (registers the tasks)
from billiards_env.envs import (ENV_IDS, BilliardsVectorEnv, NineBallEnv, PotOneEnv, RunOutVectorEnv,
                                TaskConfig, register_envs)
from billiards_env.envs.config import CONFIG_DIR, NoiseConfig
from billiards_env.physics import Models
from billiards_env.physics.strike import draw_to_speed, speed_to_draw

IDS = list(ENV_IDS)


def make_vec(env_id, n, **kw):
    return gym.make_vec(env_id, num_envs=n, vectorization_mode="vector_entry_point", **kw)


def test_registered_with_both_entry_points():
    register_envs()  # idempotent
    for env_id in IDS:
        spec = gym.spec(env_id)
        assert spec.entry_point.startswith("billiards_env.envs.billiards:")
        assert spec.vector_entry_point.startswith("billiards_env.envs.billiards:")
        v = make_vec(env_id, 2)
        assert isinstance(v.unwrapped, BilliardsVectorEnv)
        assert v.metadata["autoreset_mode"] is AutoresetMode.NEXT_STEP
        v.close()


@pytest.mark.parametrize("env_id", IDS)
def test_check_env(env_id):
    env = gym.make(env_id).unwrapped
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env)
    # the only acceptable warning: render_mode="human" on a machine without display
    msgs = [str(w.message) for w in caught if "needs a display" not in str(w.message)]
    assert msgs == []


def _rollout_singles(env_id, seed, n, actions, **kw):
    envs = [gym.make(env_id, **kw).unwrapped for _ in range(n)]
    obs = [e.reset(seed=seed + k)[0] for k, e in enumerate(envs)]
    done = [False] * n
    out = [np.stack(obs)]
    rewards, terms, dones = [], [], []
    for act in actions:
        o, r, te, tr = [], [], [], []
        for k, e in enumerate(envs):
            if done[k]:  # NEXT_STEP autoreset: this step only resets
                o.append(e.reset()[0]); r.append(0.0); te.append(False); tr.append(False)
                done[k] = False
                continue
            ob, rw, t1, t2, _ = e.step(act[k])
            o.append(ob); r.append(rw); te.append(t1); tr.append(t2)
            done[k] = t1 or t2
        out.append(np.stack(o)); rewards.append(r); dones.append((te, tr))
    return out, np.array(rewards), dones


@pytest.mark.parametrize("env_id", IDS)
def test_vector_matches_single_envs(env_id):
    n, steps, seed = 3, 8, 11
    rng = np.random.default_rng(0)
    # aim near the target so episodes last more than one shot; noise exercises the RNG path
    actions = np.clip(rng.normal(0, [0.03, 0.5, 0.3, 0.3], size=(steps, n, 4)), -1, 1).astype(np.float32)
    singles, rew, dones = _rollout_singles(env_id, seed, n, actions, noise="tournament")
    v = make_vec(env_id, n, noise="tournament")
    obs, _ = v.reset(seed=seed)
    np.testing.assert_array_equal(obs, singles[0])
    for t in range(steps):
        obs, r, te, tr, info = v.step(actions[t])
        np.testing.assert_array_equal(obs, singles[t + 1])
        np.testing.assert_array_equal(r, rew[t])
        np.testing.assert_array_equal(te, dones[t][0])
        np.testing.assert_array_equal(tr, dones[t][1])


def test_autoreset_next_step():
    v = make_vec("Billiards-PotOne-v1", 4).unwrapped
    v.reset(seed=3)
    _, _, te, tr, info = v.step(np.zeros((4, 4), np.float32))
    assert np.all(te | tr)  # PotOne: one shot per episode
    assert not info["reset"].any()
    obs, r, te2, tr2, info = v.step(np.ones((4, 4), np.float32))
    assert info["reset"].all() and np.all(r == 0) and not te2.any() and not tr2.any()
    assert np.all(info["n_events"] == 0)  # the action was ignored, nothing was simulated
    assert np.all(obs[:, [2, 5]] == 1.0)  # fresh table: both balls present
    assert np.all(np.abs(v.state.vel).max() == 0)
    _, _, te3, _, info = v.step(np.zeros((4, 4), np.float32))
    assert te3.all() and not info["reset"].any() and np.all(info["n_events"] > 0)


def test_reset_seeding_reproducible_and_tables_differ():
    v = make_vec("Billiards-RunOut-v1", 4).unwrapped
    a, _ = v.reset(seed=5)
    b, _ = v.reset(seed=5)
    np.testing.assert_array_equal(a, b)
    assert len({tuple(row) for row in a}) == 4  # each table seeded differently
    e = gym.make("Billiards-RunOut-v1").unwrapped
    np.testing.assert_array_equal(e.reset(seed=7)[0], a[2])


def test_observation_layout():
    env = gym.make("Billiards-RunOut-v1", n_balls=3).unwrapped
    obs, _ = env.reset(seed=1)
    B = 4
    assert obs.shape == (4 * B + 1,) and obs.dtype == np.float32
    s = env.state
    per = obs[:3 * B].reshape(B, 3)
    np.testing.assert_allclose(per[:, 0], s.pos[0, :, 0] / env.table.width, rtol=1e-6)
    np.testing.assert_allclose(per[:, 1], s.pos[0, :, 1] / env.table.length, rtol=1e-6)
    assert np.all(per[:, 2] == 1)
    np.testing.assert_array_equal(obs[3 * B:4 * B], [0, 1, 0, 0])
    assert obs[4 * B] == 0
    # pocket ball 1: its slot is zeroed, target moves to ball 2, order unchanged
    pk = s.pocket.copy(); pk[0, 1] = 0
    from billiards_env.physics import BallState
    obs2 = env.set_state(BallState(s.pos.copy(), s.vel.copy(), s.omega.copy(), pk))
    assert np.all(obs2[3:6] == 0) and np.array_equal(obs2[6:9], obs[6:9])
    np.testing.assert_array_equal(obs2[3 * B:4 * B], [0, 0, 1, 0])
    assert env.legal_target() == 2


def test_nine_ball_break_reset():
    env = NineBallEnv()
    obs, info = env.reset(seed=4)
    s = env.state
    assert s.n_balls == 10 and s.pocket[0, 0] == -1 and s.pocket[0, 9] == -1
    assert np.all(s.vel == 0) and np.all(s.omega == 0)
    # the break moved the rack
    assert np.linalg.norm(s.pos[0, 1] - [env.table.width / 2, 0.75 * env.table.length]) > 1e-3
    assert info["legal_target"] == env.legal_target() >= 1
    obs2, _ = NineBallEnv().reset(seed=4)
    np.testing.assert_array_equal(obs, obs2)
    assert NineBallEnv.__doc__.count("Rules") == 1


def _yaml(task):
    import yaml
    return yaml.safe_load((CONFIG_DIR / f"{task}.yaml").read_text())


BUILTIN_DEFAULTS = {task: _yaml(task) for task in ("pot_one", "run_out", "nine_ball")}  # the YAML files


def test_config_yaml_and_overrides(tmp_path):
    for task in ("pot_one", "run_out", "nine_ball"):
        cfg = TaskConfig.from_yaml(CONFIG_DIR / f"{task}.yaml")
        assert cfg == TaskConfig.from_dict(BUILTIN_DEFAULTS[task]) == TaskConfig.default(task)
        assert cfg.version == 2 and cfg.solver == "event"  # the equipment section's layout
        assert TaskConfig.from_dict(cfg.to_dict()) == cfg
        with pytest.raises(dataclasses.FrozenInstanceError):
            cfg.n_balls = 3
    with pytest.raises(ValueError, match="unknown key.*'bogus'"):
        TaskConfig.from_dict({**BUILTIN_DEFAULTS["run_out"], "bogus": 1})
    with pytest.raises(ValueError, match="unknown key.*'pocket_bonus'"):
        TaskConfig.from_dict(BUILTIN_DEFAULTS["run_out"], reward={"pocket_bonus": 2})
    with pytest.raises(ValueError, match="unknown effects"):
        TaskConfig.from_dict(BUILTIN_DEFAULTS["run_out"], effects={"magnus": True})
    with pytest.raises(ValueError, match="version 3 is not supported"):
        TaskConfig.from_dict(BUILTIN_DEFAULTS["run_out"], version=3)
    with pytest.raises(ValueError, match="dt"):
        TaskConfig.from_dict(BUILTIN_DEFAULTS["run_out"], solver="step")
    p = tmp_path / "bad.yaml"
    p.write_text("task: pot_one\nn_bals: 1\n")
    with pytest.raises(ValueError, match="bad.yaml.*n_bals"):
        TaskConfig.from_yaml(p)
    cfg = TaskConfig.default("run_out", n_balls=3, noise="tournament", reward={"pocket": 2.0},
                             effects={"spin": False})
    p = tmp_path / "ro.yaml"
    cfg.to_yaml(p)
    env = RunOutVectorEnv(num_envs=2, config=p)
    assert env.config == cfg and env.config.noise == NoiseConfig.preset("tournament")
    assert env.single_observation_space.shape == (17,) and not env.effects.spin
    with pytest.raises(ValueError, match="task"):
        PotOneEnv(config=p)


def test_models_config(tmp_path):
    """``models:`` reaches every simulation of the env and round-trips."""
    cfg = TaskConfig.default("pot_one", models={"cushion": "mathavan2010"})
    assert cfg.models == Models(cushion="mathavan2010") and TaskConfig.default("pot_one").models == Models()
    p = tmp_path / "m.yaml"
    cfg.to_yaml(p)
    assert TaskConfig.from_yaml(p) == cfg and TaskConfig.from_dict(cfg.to_dict()) == cfg
    action = np.array([0.0, 1.0, 0.0, 0.0], np.float32)  # full speed: many cushion impacts
    final = {}
    for name, env in (("han2005", PotOneEnv()), ("mathavan2010", PotOneEnv(config=p))):
        assert env.models.cushion == name
        env.reset(seed=3)
        assert np.all(np.isfinite(env.step(action)[0]))
        final[name] = env.state.pos
    assert not np.array_equal(final["han2005"], final["mathavan2010"])  # the cushion model was used
    with pytest.raises(ValueError, match="unknown cushion model 'nope'"):
        TaskConfig.default("pot_one", models={"cushion": "nope"})
    with pytest.raises(ValueError, match="unknown model interactions.*'bumper'"):
        PotOneEnv(models={"bumper": "han2005"})


def test_step_solver_runs():
    v = make_vec("Billiards-PotOne-v1", 2, solver="step", dt=1e-3)
    v.reset(seed=0)
    obs, r, te, tr, info = v.step(np.array([[0, -0.6, 0, 0]] * 2, np.float32))
    assert np.all(np.isfinite(obs)) and np.all(info["n_events"] > 0)


def test_bad_actions_raise_and_clip_is_reported():
    env = gym.make("Billiards-PotOne-v1").unwrapped
    env.reset(seed=0)
    with pytest.raises(ValueError, match="NaN or infinite"):
        env.step(np.array([0, np.nan, 0, 0], np.float32))
    with pytest.raises(ValueError, match="NaN or infinite"):
        env.step(np.array([0, np.inf, 0, 0]))
    with pytest.raises(ValueError, match=r"shape \(4,\)"):
        env.step(np.zeros(3))
    _, _, _, _, info = env.step(np.array([0.0, 3.0, 0.0, 0.0]))
    assert info["action_clipped"] is True
    with pytest.raises(RuntimeError, match="reset"):
        env.step(np.zeros(4))
    v = make_vec("Billiards-PotOne-v1", 3).unwrapped
    v.reset(seed=0)
    with pytest.raises(ValueError, match=r"shape \(3, 4\)"):
        v.step(np.zeros((2, 4)))
    bad = np.zeros((3, 4)); bad[1, 2] = np.nan
    with pytest.raises(ValueError, match="NaN"):
        v.step(bad)
    acts = np.zeros((3, 4)); acts[2, 0] = -1.5
    _, _, _, _, info = v.step(acts)
    np.testing.assert_array_equal(info["action_clipped"], [False, False, True])


@pytest.mark.parametrize("aim", ["relative", "absolute"])
def test_action_shot_round_trip(aim):
    v = make_vec("Billiards-RunOut-v1", 5, aim=aim).unwrapped
    v.reset(seed=2)
    p = v.params
    rng = np.random.default_rng(0)
    acts = rng.uniform(-1, 1, size=(5, 4)).astype(np.float32)
    acts[:, 2:] *= 0.7  # inside the offset disc, where the map is invertible
    shots = v.actions_to_shots(acts)
    phi, speed, a, b = shots
    draw = speed_to_draw(speed, p)
    assert np.all((speed >= draw_to_speed(v.config.min_draw, p)) & (speed <= p.max_speed))
    assert np.all((draw >= v.config.min_draw * (1 - 1e-15)) & (draw <= p.max_draw * (1 + 1e-15)))
    assert np.all(np.hypot(a, b) <= p.miscue_limit)
    np.testing.assert_allclose(v.shots_to_actions(shots), acts, atol=1e-6)
    if aim == "relative":  # a0 = 0 aims at the legal target's centre
        phi0 = v.actions_to_shots(np.zeros((5, 4))).phi
        s, t = v.state, v.legal_target()
        d = s.pos[np.arange(5), t] - s.pos[:, 0]
        np.testing.assert_allclose(phi0, np.arctan2(d[:, 1], d[:, 0]), atol=1e-12)
    # offsets outside the disc are scaled radially onto it
    _, _, a, b = v.actions_to_shots(np.tile([0, 0, 1, 1], (5, 1)))
    np.testing.assert_allclose(np.hypot(a, b), p.miscue_limit, rtol=1e-8)
    np.testing.assert_allclose(a, b)


@pytest.mark.parametrize("env_id", IDS)
def test_random_policy_1000_vector_steps(env_id):
    v = make_vec(env_id, 8)
    obs, _ = v.reset(seed=123)
    v.action_space.seed(123)
    episodes = 0
    for _ in range(1000):
        obs, r, te, tr, info = v.step(v.action_space.sample())
        assert np.all(np.isfinite(obs)) and np.all(np.isfinite(r))
        assert v.observation_space.contains(obs)
        for val in info["reward_terms"].values():
            assert np.all(np.isfinite(val))
        episodes += int(np.sum(te | tr))
    assert episodes > 100
    v.close()


# ------------------------------------------------ autoreset modes and masks --
@pytest.mark.parametrize("mode", ["same_step", "disabled"])
def test_autoreset_modes_other_than_next_step(mode):
    import gymnasium as gym
    from gymnasium.vector import AutoresetMode
    env = gym.make_vec("Billiards-PotOne-v1", num_envs=4, vectorization_mode="vector_entry_point",
                       autoreset_mode=mode)
    assert env.metadata["autoreset_mode"] == {"same_step": AutoresetMode.SAME_STEP,
                                              "disabled": AutoresetMode.DISABLED}[mode]
    obs0, _ = env.reset(seed=3)
    act = np.zeros((4, 4), dtype=np.float32)
    obs, rew, term, trunc, info = env.step(act)
    assert term.all()  # PotOne: one shot per episode
    if mode == "same_step":
        assert info["_final_obs"].all()
        assert not np.array_equal(info["final_obs"], obs)  # new episodes already started
        obs2, *_ = env.step(act)  # no step is spent on resets
        assert obs2.shape == obs.shape
    else:
        with pytest.raises(RuntimeError, match="reset_mask"):
            env.step(act)
        mask = np.array([True, False, True, False])
        obs3, _ = env.reset(options={"reset_mask": mask})
        assert np.array_equal(obs3[~mask], obs[~mask])
        assert not np.array_equal(obs3[mask], obs[mask])
        with pytest.raises(RuntimeError):
            env.step(act)  # tables 1 and 3 are still finished


def test_same_step_matches_next_step_episodes():
    """The two autoreset modes give the same episodes, only arranged in time differently."""
    import gymnasium as gym
    envs = {m: gym.make_vec("Billiards-PotOne-v1", num_envs=3, vectorization_mode="vector_entry_point",
                            autoreset_mode=m) for m in ("next_step", "same_step")}
    for e in envs.values():
        e.reset(seed=11)
    act = np.random.default_rng(0).uniform(-1, 1, (3, 4)).astype(np.float32)
    _, r_same, *_ = envs["same_step"].step(act)
    _, r_next, *_ = envs["next_step"].step(act)
    np.testing.assert_array_equal(r_same, r_next)
    _, r2_same, *_ = envs["same_step"].step(act)
    envs["next_step"].step(act)  # the autoreset step
    _, r2_next, *_ = envs["next_step"].step(act)
    np.testing.assert_array_equal(r2_same, r2_next)


# ------------------------------------- per-table streams, placement, break --
def test_table_streams_independent_of_batching_and_seeded():
    from billiards_env.envs.streams import TableStreams
    seeds = [3, 4, 5, 6, 7, 8]
    s, t = TableStreams(6), TableStreams(6)
    s.seed(np.arange(6), seeds)
    t.seed(np.arange(6), seeds)
    u, z = s.uniform(np.arange(6), 5), s.normal(np.arange(6), 3)
    # the same draws whichever tables draw together, and in whatever order
    np.testing.assert_array_equal(t.uniform([2], 5)[0], u[2])
    np.testing.assert_array_equal(t.uniform([5, 0, 1, 3, 4], 5), u[[5, 0, 1, 3, 4]])
    np.testing.assert_array_equal(t.normal([4, 2], 3), z[[4, 2]])
    np.testing.assert_array_equal(t.normal([0, 1, 3, 5], 3), z[[0, 1, 3, 5]])
    t.seed([2], [5])  # reseeding restarts the stream
    np.testing.assert_array_equal(t.uniform([2], 5)[0], u[2])
    assert len({tuple(r) for r in u}) == 6  # different seeds, different draws
    t.seed([0, 1], [2**64 + 3, 3])  # seeds are taken modulo 2**64
    np.testing.assert_array_equal(t.uniform([0, 1], 5), u[[0, 0]])


def test_table_streams_statistics():
    from billiards_env.envs.streams import TableStreams
    s = TableStreams(5)
    s.seed(np.arange(5), np.arange(5))
    u = s.uniform(np.arange(5), 20_000)
    n = u.size
    assert u.min() >= 0.0 and u.max() < 1.0
    assert abs(u.mean() - 0.5) < 5 * math.sqrt(1 / 12 / n)
    assert abs(u.var() - 1 / 12) < 5 * math.sqrt((1 / 80 - 1 / 144) / n)
    assert abs(np.corrcoef(u[0], u[1])[0, 1]) < 5 / math.sqrt(u.shape[1])  # consecutive seeds: unrelated
    z = s.normal(np.arange(5), 20_001)  # odd count: the last pair's second normal is dropped
    assert abs(z.mean()) < 5 / math.sqrt(z.size)
    assert abs(z.std() - 1.0) < 5 / math.sqrt(2 * z.size)
    assert abs(np.mean(z ** 4) - 3.0) < 5 * math.sqrt(96 / z.size)  # Gaussian kurtosis


def test_random_placement_is_legal():
    from billiards_env.envs.core import BilliardsCore
    cfg = TaskConfig.default("run_out", n_balls=9)
    core = BilliardsCore(cfg, 300)
    core.streams.seed(np.arange(300), np.arange(300))
    pos = core.place(np.arange(300))
    R, m, t = core.params.R, cfg.margin, core.table
    assert pos.shape == (300, 10, 2)
    assert np.all(pos >= R + m) and np.all(pos[..., 0] <= t.width - R - m) and np.all(pos[..., 1] <= t.length - R - m)
    pk = t.pockets
    d2 = ((pos[:, :, None, :] - pk[None, None, :, :2]) ** 2).sum(-1)
    assert np.all(d2 > pk[:, 2] ** 2)
    d = np.linalg.norm(pos[:, :, None] - pos[:, None], axis=-1) + np.eye(10) * 1e9
    assert d.min() >= 2 * R + m
    assert t.contains(pos.reshape(-1, 2), R, 0.0).all()
    with pytest.raises(ValueError, match="could not place 10 balls without overlap"):
        core.place(np.arange(3), max_tries=9)


def test_free_spot_search_order():
    from billiards_env.physics.state import free_spot
    env = NineBallEnv()
    t, R = env.table, env.params.R
    foot = (t.width / 2, 0.75 * t.length)
    pos = np.array([[foot[0], foot[1]], [0.3, 0.3]])
    on = np.array([False, True])
    args = (t.width, t.length, R, t.pockets)
    assert free_spot(pos, on, *foot, 0.0, 1.0, *args) == (foot[0], foot[1], True)
    on[0] = True  # the spot is taken: one step along the search direction
    x, y, found = free_spot(pos, on, *foot, 0.0, 1.0, *args)
    assert found and x == foot[0] and y == pytest.approx(foot[1] + 2 * R + 1e-3)
    x, y, found = free_spot(pos, on, *foot, 0.0, -1.0, *args)
    assert found and y == pytest.approx(foot[1] - 2 * R - 1e-3)


def test_nine_ball_breaks_leave_cue_and_nine_on_a_legal_table(monkeypatch):
    import billiards_env.envs.tasks.nine_ball as nine_mod
    calls = []
    spot = nine_mod.free_spot
    monkeypatch.setattr(nine_mod, "free_spot", lambda *a: calls.append(1) or spot(*a))
    v = make_vec("Billiards-NineBall-v1", 128).unwrapped
    R, t = v.params.R, v.table
    for seed in (0, 1000):
        v.reset(seed=seed)
        s = v.state
        assert np.all(s.pocket[:, [0, 9]] == -1)
        on = s.pocket < 0
        assert t.contains(s.pos[on], R, 1e-9).all()
        d = np.linalg.norm(s.pos[:, :, None] - s.pos[:, None], axis=-1)
        both = on[:, :, None] & on[:, None, :] & ~np.eye(10, dtype=bool)
        assert d[both].min() >= 2 * R - 1e-9
    assert calls  # some breaks pocketed the 9 or the cue ball and were respotted
