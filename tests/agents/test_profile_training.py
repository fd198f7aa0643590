"""scripts/profile_training.py in quick mode: it trains a tiny PPO, splits
the profiled wall time and writes the table."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("stable_baselines3")
ROOT = Path(__file__).resolve().parents[2]


def _profile(tmp_path, *args) -> tuple[str, dict]:
    out = tmp_path / "prof.md"
    res = subprocess.run([sys.executable, "scripts/profile_training.py", "--quick", "--out", str(out), *args],
                         cwd=ROOT, capture_output=True, text=True, timeout=900)
    assert res.returncode == 0, res.stderr[-2000:]
    text = out.read_text()
    rows = {line.split(" | ")[0].lstrip("| "): float(line.split(" | ")[1]) for line in text.splitlines()
            if line.startswith("| ") and not line.startswith("| part")}
    return text, rows


def test_profile_training_quick(tmp_path):
    """Against an opponent, every part of the split has time."""
    text, rows = _profile(tmp_path, "--set", "env_kwargs={opponent: ghost}")
    assert rows["updates (PPO train)"] > 0 and rows["simulator (physics.simulate)"] > 0
    assert rows["opponent decisions (bot act)"] > 0 and rows["agent features"] > 0
    assert rows["updates (PPO train)"] + rows["rollouts (collect_rollouts)"] <= rows["total"] * 1.01
    # the env step is this process's part (and the env workers', when the config has them)
    env_step = rows["env step (all of it in this process)"] + rows["env workers (all of their work)"]
    assert rows["simulator (physics.simulate)"] <= env_step
    assert rows["env step (all of it in this process)"] <= rows["rollouts (collect_rollouts)"]
    assert "per CPU-second of the process" in text.splitlines()[0]


def test_profile_training_quick_self_play(tmp_path):
    """The default game config (self-play): no opponent's time, the rest as before."""
    _, rows = _profile(tmp_path, "--set", "train.overlap_updates=false")
    assert rows["opponent decisions (bot act)"] == 0
    assert rows["updates (PPO train)"] > 0 and rows["simulator (physics.simulate)"] > 0 and rows["agent features"] > 0


def test_profile_training_compare_quick(tmp_path):
    """``--compare``: two configs' rates, interleaved, one row each with its tables x steps."""
    out = tmp_path / "rates.md"
    res = subprocess.run([sys.executable, "scripts/profile_training.py", "--quick", "--out", str(out),
                          "--compare", "new", "--compare", "old:ppo.n_steps=8,train.numba_threads=2"],
                         cwd=ROOT, capture_output=True, text=True, timeout=900)
    assert res.returncode == 0, res.stderr[-2000:]
    rows = [line.split(" | ") for line in out.read_text().splitlines() if line.startswith("| ") and "---" not in line]
    assert [r[0].lstrip("| ") for r in rows[1:]] == ["new", "old"]
    assert [r[1] for r in rows[1:]] == ["8 x 4", "8 x 8"]
    assert all(float(x.rstrip(" |").replace(",", "")) > 0 for r in rows[1:] for x in r[2:5])
