"""scripts/profile_training.py in quick mode: it trains a tiny PPO, splits
the profiled wall time and writes the table."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("stable_baselines3")
ROOT = Path(__file__).resolve().parents[2]


def test_profile_training_quick(tmp_path):
    out = tmp_path / "prof.md"
    res = subprocess.run([sys.executable, "scripts/profile_training.py", "--quick", "--out", str(out)], cwd=ROOT,
                         capture_output=True, text=True, timeout=900)
    assert res.returncode == 0, res.stderr[-2000:]
    text = out.read_text()
    rows = {line.split(" | ")[0].lstrip("| "): float(line.split(" | ")[1]) for line in text.splitlines()
            if line.startswith("| ") and not line.startswith("| part")}
    assert rows["updates (PPO train)"] > 0 and rows["simulator (physics.simulate)"] > 0
    assert rows["opponent decisions (bot act)"] > 0 and rows["agent features"] > 0
    assert rows["updates (PPO train)"] + rows["rollouts (collect_rollouts)"] <= rows["total"] * 1.01
    assert rows["simulator (physics.simulate)"] <= rows["env step (all of it)"] <= rows["rollouts (collect_rollouts)"]
    assert "per CPU-second of the process" in text.splitlines()[0]
