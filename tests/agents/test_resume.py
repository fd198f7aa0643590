"""Resuming a killed training run from its newest checkpoint (agents.sb3.checkpoints)."""
import json
import pickle
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from agents.sb3.checkpoints import latest_checkpoint, load_checkpoint
from agents.config import load_config, load_run_config
from agents.sb3.training import build_env, train

ROOT = Path(__file__).resolve().parents[2]
N_ENVS, N_STEPS, TOTAL, EVERY = 64, 16, 16384, 2048   # rollouts of 1,024 steps
OVERRIDES = [f"n_envs={N_ENVS}", f"ppo.n_steps={N_STEPS}", "ppo.batch_size=256", "ppo.n_epochs=1",
             "policy.net_arch=[16]", f"train.total_timesteps={TOTAL}", f"train.checkpoint_every={EVERY}",
             "train.eval_episodes=0", "train.progress_bar=false", "train.tensorboard=false"]
KILL_WAIT_S = 120.0   # the first checkpoint comes after two rollouts plus start-up and compilation


def _script(*args):
    return [sys.executable, str(ROOT / "scripts" / "train.py"), *args]


@pytest.mark.slow  # several training runs in subprocesses: about a minute
def test_killed_run_resumes_to_the_same_step_count(tmp_path):
    sets = [a for o in OVERRIDES for a in ("--set", o)]
    proc = subprocess.Popen(_script("--name", "run", "--runs-dir", str(tmp_path), *sets),
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    run = tmp_path / "run"
    t0 = time.monotonic()
    while latest_checkpoint(run) is None:
        assert proc.poll() is None, f"the run ended before its first checkpoint: {proc.stderr.read()[-2000:]}"
        assert time.monotonic() - t0 < KILL_WAIT_S, "no checkpoint written"
        time.sleep(0.02)
    proc.kill()
    proc.wait()
    assert proc.returncode != 0, "the run finished before it could be killed"
    assert not (run / "train_summary.json").exists()
    ck = latest_checkpoint(run)
    with np.load(ck.normalizer_path) as z:
        saved_count, saved_mean = float(z["obs_count"]), z["obs_mean"].copy()

    # the checkpoint's statistics come back into a fresh env
    cfg = load_run_config(run)
    env, vecnorm = build_env(cfg, cfg.train.seed)
    model = load_checkpoint(ck, cfg.algo, env, vecnorm)
    assert model.num_timesteps == ck.steps and ck.steps % (N_ENVS * N_STEPS) == 0
    assert vecnorm.obs_rms.count == saved_count and np.array_equal(vecnorm.obs_rms.mean, saved_mean)
    # a checkpoint loaded for evaluation normalises like the restored VecNormalize
    from agents.sb3.policy import SB3Policy
    pol = SB3Policy.load(ck.model_path)
    obs = np.random.default_rng(0).random((5, vecnorm.obs_rms.mean.shape[0])).astype(np.float32)
    vecnorm.training = False
    assert np.allclose(pol.vecnormalize.normalize_obs(obs), vecnorm.normalize_obs(obs))
    env.close()

    out = subprocess.run(_script("--resume", str(run)), capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-3000:]
    summary = json.loads((run / "train_summary.json").read_text())
    resumed = summary["resumed"]
    assert resumed["from_step"] == ck.steps and resumed["steps_redone"] >= 0
    assert "steps redone" in out.stdout

    uninterrupted = train(load_config(None, overrides=OVERRIDES), tmp_path / "straight", "pytest")
    assert summary["timesteps"] == uninterrupted["timesteps"] >= TOTAL
    # the resumed statistics continued from the checkpoint's: the count grew
    # by the steps after it plus the one reset observation of every table
    with open(run / "vecnormalize.pkl", "rb") as f:
        final = pickle.load(f)
    assert final.obs_rms.count == pytest.approx(saved_count + (summary["timesteps"] - ck.steps) + N_ENVS)
    # the log keeps the rows up to the checkpoint and then continues
    steps = [int(line.split(",")[0]) for line in (run / "progress.csv").read_text().splitlines()[1:]]
    assert steps == sorted(steps) and steps[-1] == summary["timesteps"]


def test_resume_without_checkpoint_is_an_error(tmp_path):
    cfg = load_config(None, overrides=OVERRIDES)
    with pytest.raises(FileNotFoundError, match="no complete checkpoint"):
        train(cfg, tmp_path, resume=True)
