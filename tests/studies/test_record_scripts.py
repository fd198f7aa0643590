"""The fingerprint scripts run (quick sizes) and a recording compares equal to itself: scripts/record_rollouts.py (the
one-player tasks) and scripts/record_games.py (every game id, self-play and a bot opponent)."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("script,extra", [("record_rollouts.py", []), ("record_games.py", ["--quick"])])
def test_record_then_compare(tmp_path, script, extra):
    out = tmp_path / "rec.npz"
    run = lambda *a: subprocess.run([sys.executable, str(ROOT / "scripts" / script), *a],  # noqa: E731
                                    capture_output=True, text=True, timeout=600)
    r = run("record", str(out), "--steps", "2", "--tables", "2", *extra)
    assert r.returncode == 0, r.stderr[-2000:]
    r = run("compare", str(out), str(out))
    assert r.returncode == 0 and "0 differences" in r.stdout, r.stdout + r.stderr
