"""Agents: SB3 adapter, baselines, Wilson interval, training smoke tests, scripts."""
from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

pytest.importorskip("stable_baselines3")

from agents.sb3.policy import SB3Policy  # noqa: E402
from billiards_env.bots.one_player import BotPolicy, GhostBallPolicy, SearchPolicy  # noqa: E402
from agents.config import load_config  # noqa: E402
from agents.evaluation.harness import evaluate, parse_noise, wilson_interval  # noqa: E402
from agents.sb3.infos import VecInfos  # noqa: E402
from agents.sb3.vec_env import NativeVecEnv, make_sb3_vec_env  # noqa: E402
from billiards_env.physics import BallState  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
POT = "Billiards-PotOne-v1"


# ---------------------------------------------------------------- Wilson CI
def test_wilson_interval_matches_hand_computation():
    # 37 successes of 50, z = 1.96: p = 0.74, z^2/n = 0.076832,
    # centre = (0.74 + 0.038416) / 1.076832 = 0.722876,
    # half = 1.96 / 1.076832 * sqrt(0.74*0.26/50 + 3.8416/10000) = 1.820154 * 0.065055 = 0.118410
    lo, hi = wilson_interval(37, 50, z=1.96)
    assert lo == pytest.approx(0.722876 - 0.118410, abs=1e-5)
    assert hi == pytest.approx(0.722876 + 0.118410, abs=1e-5)
    # a known Bernoulli sample: 0/10 -> [0, z^2/(n+z^2)]
    lo, hi = wilson_interval(0, 10, z=1.96)
    assert lo == 0.0 and hi == pytest.approx(1.96 ** 2 / (10 + 1.96 ** 2), abs=1e-12)
    # symmetric around 1/2 for k = n/2, and within [0, 1]
    lo, hi = wilson_interval(500, 1000)
    assert lo + hi == pytest.approx(1.0) and 0.46 < lo < 0.5 < hi < 0.54


def test_wilson_interval_is_exact_at_the_ends_and_charts_them(tmp_path):
    """k = 0 and k = n give bounds of exactly 0 and 1 (the formula alone left
    2e-19, a negative error bar that stopped bar_chart)."""
    from agents.evaluation.harness import EvalResult, bar_chart
    assert wilson_interval(0, 1000)[0] == 0.0 and wilson_interval(1000, 1000)[1] == 1.0
    res = [EvalResult("none-ever", POT, "none", 1000, 11, 0.0, wilson_interval(0, 1000), 0.0, 0.0, 0.0, 0.0, 0.0,
                      1.0, 0.1)]
    bar_chart(res, tmp_path / "chart.png")
    assert (tmp_path / "chart.png").stat().st_size > 0


def test_wilson_interval_coverage_on_bernoulli_sample():
    rng = np.random.default_rng(0)
    p, n, hits = 0.9, 200, 0
    for _ in range(400):
        k = int((rng.random(n) < p).sum())
        lo, hi = wilson_interval(k, n)
        hits += lo <= p <= hi
    assert hits / 400 > 0.92  # nominal 95%


# ---------------------------------------------------------------- adapter
def test_vec_infos_masks_and_nesting():
    infos = {"a": np.array([1, 2, 3]), "_a": np.array([True, False, True]),
             "terms": {"x": np.array([0.5, 0.6, 0.7])}}
    out = VecInfos(infos, 3)
    assert out[0] == {"a": 1, "terms": {"x": 0.5}} and "a" not in out[1] and out[2]["a"] == 3


def test_adapter_shapes_terminal_obs_and_seeding():
    env = make_sb3_vec_env(POT, 16, seed=3)
    assert isinstance(env, NativeVecEnv) and env.num_envs == 16
    obs = env.reset()
    assert obs.shape == (16,) + env.observation_space.shape and obs.dtype == np.float32
    acts = np.zeros((16, 4), dtype=np.float32)
    obs2, rew, dones, infos = env.step(acts)
    assert obs2.shape == obs.shape and rew.shape == (16,) and dones.shape == (16,) and len(infos) == 16
    assert dones.all()  # PotOne: one shot per episode
    for i in range(16):
        assert infos[i]["terminal_observation"].shape == env.observation_space.shape
        assert infos[i]["TimeLimit.truncated"] is False
        assert "success" in infos[i] and "reward_terms" in infos[i]
    # the returned obs is the *reset* obs: a new table, different from the terminal one
    assert not np.allclose(obs2, np.stack([inf["terminal_observation"] for inf in infos]))
    # the native env has no pending autoreset left: the next step shoots every table
    _, _, _, infos3 = env.step(acts)
    assert not any(inf["reset"] for inf in infos3)
    # seeding via seed(): same seed -> same tables
    env.seed(7)
    a = env.reset()
    env.seed(7)
    b = env.reset()
    assert np.array_equal(a, b)
    assert env.get_attr("num_envs") == [16] * 16
    assert len(env.env_method("legal_target")) == 16
    env.close()


def test_adapter_partial_resets_on_multi_shot_task():
    env = make_sb3_vec_env("Billiards-RunOut-v1", 8, seed=0)
    obs = env.reset()
    rng = np.random.default_rng(0)
    for _ in range(5):
        obs, rew, dones, infos = env.step(rng.uniform(-1, 1, (8, 4)).astype(np.float32))
        assert np.all(np.isfinite(obs))
        for i in np.flatnonzero(dones):
            assert "terminal_observation" in infos[i]
            # reset obs: every ball back on the table, no shots taken
            assert obs[i, -1] == 0.0
    env.close()


def test_adapter_with_gymnasium_same_step_and_disabled_modes():
    from gymnasium.vector import AutoresetMode, SyncVectorEnv
    for mode in (AutoresetMode.SAME_STEP, AutoresetMode.DISABLED):
        venv = SyncVectorEnv([lambda: gym.make("CartPole-v1") for _ in range(4)], autoreset_mode=mode)
        env = NativeVecEnv(venv)
        env.seed(0)
        env.reset()
        n_done = 0
        for _ in range(200):
            obs, rew, dones, infos = env.step(np.zeros(4, dtype=np.int64))
            for i in np.flatnonzero(dones):
                n_done += 1
                assert infos[i]["terminal_observation"].shape == (4,)
                assert abs(obs[i]).max() <= 0.05  # the reset obs of CartPole
        assert n_done > 0
        env.close()


def test_sb3_env_checks_with_vec_check_nan():
    from stable_baselines3.common.vec_env import VecCheckNan
    env = VecCheckNan(make_sb3_vec_env(POT, 8, seed=0), raise_exception=True)
    env.reset()
    for _ in range(3):
        env.step(np.random.uniform(-1, 1, (8, 4)).astype(np.float32))
    env.close()


# ---------------------------------------------------------------- baselines
def test_ghost_ball_pots_a_straight_in_shot():
    env = make_sb3_vec_env(POT, 1, seed=0)
    env.reset()
    nat = env.unwrapped
    t = nat.table
    # cue ball, object ball and the bottom-left corner pocket on the diagonal
    d = np.array([1.0, 1.0]) / math.sqrt(2)
    obj = np.array([0.0, 0.0]) + 0.45 * d
    cue = obj + 0.5 * d
    st = nat.state
    st.pos[0] = np.stack([cue, obj])
    st.vel[:] = 0.0
    st.omega[:] = 0.0
    st.pocket[:] = -1
    pol = BotPolicy(GhostBallPolicy(), env)
    phi, speed, a, b = pol.bot.act(nat.view()).shots
    assert phi[0] == pytest.approx(math.atan2(-d[1], -d[0]), abs=1e-9)
    obs, rew, dones, infos = env.step(pol.act(env._obs))
    assert infos[0]["success"] and not infos[0]["scratch"]
    assert infos[0]["pocketed"][1]
    env.close()


def test_search_policy_finds_pots_and_beats_random():
    r = evaluate(lambda env: BotPolicy(SearchPolicy(k=32, seed=0), env), POT, 40, seed=5)
    g = evaluate(lambda env: BotPolicy(GhostBallPolicy(), env), POT, 40, seed=5)
    assert r.success_rate >= 0.8 and r.success_rate >= g.success_rate - 0.05
    assert isinstance(BallState, type)


def test_evaluation_same_tables_for_every_policy():
    a = evaluate(lambda env: BotPolicy(GhostBallPolicy(), env), POT, 30, seed=11)
    b = evaluate(lambda env: BotPolicy(GhostBallPolicy(), env), POT, 30, seed=11)
    assert a.per_episode == b.per_episode


def test_noise_spec_parsing_and_aim_noise_lowers_success():
    assert parse_noise("none") == "none" and parse_noise("tournament") == "tournament"
    assert parse_noise("preset=tournament,aim_deg=0.5") == {"preset": "tournament", "aim_deg": 0.5}
    for bad in ("aim_deg=x", "aim=1", "aim_deg=-1"):
        with pytest.raises(ValueError, match="aim"):
            parse_noise(bad)
    clean = evaluate(lambda env: BotPolicy(GhostBallPolicy(), env), POT, 60, seed=3)
    noisy = evaluate(lambda env: BotPolicy(GhostBallPolicy(), env), POT, 60, seed=3, noise="aim_deg=2")
    assert noisy.noise == "aim_deg=2" and noisy.success_rate < clean.success_rate - 0.2


# ---------------------------------------------------------------- config
def test_config_overrides_and_typos():
    cfg = load_config(None, overrides=["ppo.learning_rate=1e-4", "n_envs=32", "policy.net_arch=[64, 64]"])
    assert cfg.ppo["learning_rate"] == 1e-4 and cfg.n_envs == 32 and cfg.policy.net_arch == (64, 64)
    with pytest.raises(ValueError):
        load_config(None, overrides=["ppo.learnin_rate=1e-4"])
    with pytest.raises(ValueError):
        load_config(None, overrides=["polcy.net_arch=[1]"])
    sac = load_config(ROOT / "configs" / "sac.yaml")
    assert sac.algo == "sac" and sac.env_id == POT


# ---------------------------------------------------------------- training
@pytest.mark.parametrize("algo", ["ppo", "sac"])
def test_training_smoke_save_reload_evaluate(algo, tmp_path):
    from agents.sb3.training import train
    over = ["n_envs=16", "train.total_timesteps=2048", "train.progress_bar=false", "train.checkpoint_every=1024",
            "policy.net_arch=[32, 32]"]
    if algo == "ppo":
        over += ["ppo.n_steps=32", "ppo.batch_size=128", "ppo.n_epochs=2"]
    else:
        over += ["sac.learning_starts=256", "sac.gradient_steps=1", "sac.batch_size=64", "sac.buffer_size=4096"]
    cfg = load_config(ROOT / "configs" / f"{algo}.yaml", overrides=over)
    summary = train(cfg, tmp_path / algo, "pytest")
    assert summary["timesteps"] >= 2048
    for f in ("model.zip", "vecnormalize.pkl", "config.yaml", "command.txt", "progress.csv"):
        assert (tmp_path / algo / f).exists(), f
    assert list((tmp_path / algo / "checkpoints").glob("*.zip"))
    pol = SB3Policy.load(tmp_path / algo)
    res = evaluate(lambda env: pol.bind(env), POT, 20, seed=1)
    assert res.n_episodes == 20 and 0.0 <= res.success_rate <= 1.0


# ---------------------------------------------------------------- scripts
def test_train_and_evaluate_scripts(tmp_path):
    cmd = [sys.executable, str(ROOT / "scripts" / "train.py"), "--name", "smoke", "--runs-dir", str(tmp_path),
           "--set", "ppo.total_timesteps=512", "--set", "train.total_timesteps=512", "--set", "n_envs=16",
           "--set", "ppo.n_steps=32", "--set", "ppo.batch_size=128", "--set", "ppo.n_epochs=1",
           "--set", "train.eval_episodes=20", "--set", "train.search_k=8", "--set", "train.progress_bar=false",
           "--set", "train.eval_noise=[none]", "--set", "policy.net_arch=[32, 32]",
           # an env option that changes the observation's size: evaluate.py must play the run on its own options
           "--set", "env_kwargs.observation=target_frame"]
    out = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-3000:]
    run = tmp_path / "smoke"
    assert (run / "model.zip").exists() and (run / "eval.json").exists() and (run / "learning_curve.png").exists()
    assert "train.py" in (run / "command.txt").read_text()
    ev = json.loads((run / "eval.json").read_text())
    assert {r["policy"] for r in ev} == {"ppo", "random", "ghost", "search8"}

    cmd = [sys.executable, str(ROOT / "scripts" / "evaluate.py"), "--policy", "ghost", "--policy", str(run),
           "--episodes", "20", "--noise", "none", "--noise", "tournament", "--out", str(tmp_path / "ev")]
    out = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-3000:]
    assert "95% CI" in out.stdout
    res = json.loads((tmp_path / "ev.json").read_text())
    assert len(res) == 4 and all(0 <= r["success_ci95"][0] <= r["success_rate"] <= r["success_ci95"][1] for r in res)
    assert (tmp_path / "ev.png").exists()
