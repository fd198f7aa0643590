"""The reference agents' command (agents/evaluation/reference.py): quick mode end to end, resumed unit by unit."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[2]


def _run(tmp_path, *extra):
    cmd = [sys.executable, "-m", "agents.evaluation.reference", "--quick", "--task", "PotOne", "--seed", "0",
           "--work", str(tmp_path / "work"), "--out", str(tmp_path / "out"), *extra]
    p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stdout[-2000:] + p.stderr[-3000:]
    return p.stdout


def test_quick_end_to_end_then_resumed(tmp_path):
    out = _run(tmp_path, "--algo", "ppo,sac")
    assert out.count(": training") == 2
    for algo in ("ppo", "sac"):
        doc = json.loads((tmp_path / "out" / algo / "PotOne" / "seed0.json").read_text())
        assert doc["quick"] and doc["algorithm"] == algo.upper() and doc["budget"] > 0
        runs = doc["tasks"]["Billiards-PotOne-v1"]["runs"]
        assert [r["run"] for r in runs] == [0] and 0.0 <= runs[0]["score"] <= 1.0
        curve = doc["training"]["curve"]
        assert curve[0][0] == 0 and curve[-1][0] == doc["training"]["timesteps"] and len(curve) >= 3
    table = (tmp_path / "out" / "table.md").read_text()
    assert "| `Billiards-PotOne-v1` | PPO |" in table and "| `Billiards-PotOne-v1` | SAC |" in table
    assert (tmp_path / "out" / "curves.png").stat().st_size > 10_000

    # done units are skipped
    assert ": training" not in _run(tmp_path, "--algo", "ppo,sac")
    # a unit whose scoring never ran is scored again without training; one stopped after a checkpoint resumes
    (tmp_path / "out" / "sac" / "PotOne" / "seed0.json").unlink()
    (tmp_path / "out" / "ppo" / "PotOne" / "seed0.json").unlink()
    (tmp_path / "work" / "ppo" / "PotOne" / "seed0" / "train_summary.json").unlink()
    out = _run(tmp_path, "--algo", "ppo,sac")
    assert out.count("resuming") == 1 and out.count(": training") == 2
    assert json.loads((tmp_path / "out" / "sac" / "PotOne" / "seed0.json").read_text())["training"]["curve"]


def test_every_task_has_a_block_within_its_budget():
    from agents.config import load_config
    from agents.evaluation.reference import ALGOS, budget_of, config_path
    from billiards_env.benchmark import PROTOCOL
    for algo in ALGOS:
        for task in PROTOCOL.tasks:
            assert 0 < budget_of(algo, task) <= task.budget
            assert load_config(config_path(algo), task.env_id).algo == algo


def test_a_block_over_the_budget_is_refused(tmp_path, monkeypatch):
    from agents.evaluation import reference
    from billiards_env.benchmark import PROTOCOL
    task = PROTOCOL.task("PotOne")
    doc = yaml.safe_load(reference.config_path("sac").read_text())
    doc[task.env_id]["train"] = dict(doc[task.env_id]["train"], total_timesteps=task.budget + 1)
    (tmp_path / "benchmark_sac.yaml").write_text(yaml.safe_dump(doc))
    monkeypatch.setattr(reference, "config_path", lambda algo: tmp_path / f"benchmark_{algo}.yaml")
    with pytest.raises(ValueError, match="exceeds the protocol's budget"):
        reference.budget_of("sac", task)
