"""Shared fixtures of the bot tests."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

# A process in which importing torch or stable-baselines3 fails: it plays each (game, bot) pairing against
# ghost twice from the same seed and prints the winners and shot counts of both runs as JSON.
WITHOUT_TORCH = r'''
import sys, importlib.abc
class Block(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in ("torch", "stable_baselines3"):
            raise ImportError(f"blocked: {name}")
sys.meta_path.insert(0, Block())
import json
from billiards_env.studies.matches import play_pairing
out = {}
for game, name in %r:
    runs = [play_pairing(name, "ghost", game, n_racks=%d, seed=11, noise="tournament", max_shots=%d)
            for _ in range(2)]
    out[game] = [[r.winner.tolist(), r.shots.tolist()] for r in runs]
assert "torch" not in sys.modules and "stable_baselines3" not in sys.modules
print(json.dumps(out))
'''


@pytest.fixture
def played_twice_without_torch():
    """``(pairs, n_racks, max_shots) -> {game: [run 1, run 2]}``, each run [winners, shots], played in a
    fresh process that cannot import torch or stable-baselines3 (``WITHOUT_TORCH``)."""
    def play(pairs, n_racks: int, max_shots: int) -> dict:
        code = WITHOUT_TORCH % (list(pairs), n_racks, max_shots)
        res = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=600,
                             env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"})
        assert res.returncode == 0, res.stderr[-2000:]
        return json.loads(res.stdout.strip().splitlines()[-1])
    return play
