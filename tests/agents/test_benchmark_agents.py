"""scripts/benchmark_agents.py --quick: every configured task x algorithm, tiny runs."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.slow  # several training runs in subprocesses: about a minute
def test_quick_benchmark_writes_table_curves_and_json(tmp_path):
    cmd = [sys.executable, str(ROOT / "scripts" / "benchmark_agents.py"), "--quick", "--out", str(tmp_path),
           "--task", "Billiards-PotOne-v1", "--task", "Billiards-RunOut-v1"]
    out = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-3000:]
    rows = json.loads((tmp_path / "benchmark.json").read_text())
    # both tasks have PPO and SAC blocks in configs/ppo.yaml and configs/sac.yaml
    assert [(r["env_id"], r["algo"]) for r in rows] == [
        ("Billiards-PotOne-v1", "ppo"), ("Billiards-PotOne-v1", "sac"), ("Billiards-RunOut-v1", "ppo"),
        ("Billiards-RunOut-v1", "sac")]
    for r in rows:
        for nz in ("none", "tournament"):
            e = r["eval"][nz]
            assert e["n_episodes"] == 20 and e["success_ci95"][0] <= e["success_rate"] <= e["success_ci95"][1]
        assert r["budget_steps"] >= 1024 and r["env_steps_per_s"] > 0
        curve = (tmp_path / r["curve"]).read_text().splitlines()
        assert curve[0].startswith("timesteps,train_s,success_rate") and len(curve) >= 3
    md = (tmp_path / "benchmark.md").read_text()
    assert md.count("| PotOne-v1 |") == 2 and "(short; config:" in md
    assert (tmp_path / "learning_curves.png").stat().st_size > 0

    # another config's row sits beside the default config's row of the same (task, algo)
    cmd = [sys.executable, str(ROOT / "scripts" / "benchmark_agents.py"), "--quick", "--out", str(tmp_path),
           "--task", "Billiards-PotOne-v1", "--algo", "ppo", "--config", str(ROOT / "configs" / "ppo_direct.yaml")]
    out = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-3000:]
    rows = json.loads((tmp_path / "benchmark.json").read_text())
    assert [(r["env_id"], r["algo"], r["config"]) for r in rows][:2] == [
        ("Billiards-PotOne-v1", "ppo", "configs/ppo.yaml"), ("Billiards-PotOne-v1", "ppo", "configs/ppo_direct.yaml")]
    assert len(rows) == 5
    assert (tmp_path / "runs" / "ppo_potone_ppo_direct" / "model.zip").exists()
    assert (tmp_path / "benchmark.md").read_text().count("| PotOne-v1 |") == 3

    # --from-run: the row of a run trained with scripts/train.py, labelled with the config it started from
    cfg = ROOT / "configs" / "ppo_nineball.yaml"
    train = [sys.executable, str(ROOT / "scripts" / "train.py"), "--config", str(cfg), "--name", "nine",
             "--runs-dir", str(tmp_path / "trained")]
    for kv in ("n_envs=16", "policy.net_arch=[16]", "ppo.n_steps=16", "ppo.batch_size=64", "ppo.n_epochs=1",
               "train.total_timesteps=512", "train.eval_every=256", "train.eval_every_episodes=20",
               "train.eval_episodes=0", "train.checkpoint_every=0", "train.tensorboard=false"):
        train += ["--set", kv]
    out = subprocess.run(train, capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-3000:]
    cmd = [sys.executable, str(ROOT / "scripts" / "benchmark_agents.py"), "--out", str(tmp_path), "--episodes", "20",
           "--doc", str(tmp_path / "benchmark.md"), "--from-run", str(tmp_path / "trained" / "nine"),
           "--config", str(cfg)]
    out = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-3000:]
    rows = json.loads((tmp_path / "benchmark.json").read_text())
    nine = [r for r in rows if r["env_id"] == "Billiards-NineBall-v1"]
    assert len(rows) == 6 and len(nine) == 1 and nine[0]["config"] == "configs/ppo_nineball.yaml"
    assert nine[0]["eval"]["none"]["n_episodes"] == 20 and (tmp_path / nine[0]["curve"]).exists()
    assert (tmp_path / "benchmark.md").read_text().count("| NineBall-v1 |") == 1
