"""scripts/cushion_curves.py in its quick mode, through a subprocess, and
the curves' limits."""
import csv
import pathlib
import subprocess
import sys

import pytest

from billiards_env.physics import PhysicsParams
from billiards_env.studies import cushion_curves

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_script_quick(tmp_path):
    out = tmp_path / "c.png"
    subprocess.run([sys.executable, str(ROOT / "scripts" / "cushion_curves.py"), "--quick", "--out", str(out)],
                   check=True, cwd=ROOT, capture_output=True, text=True)
    assert out.stat().st_size > 0
    rows = list(csv.DictReader(out.with_suffix(".csv").open()))
    assert len(rows) == 4 * 3 * 5  # models x balls x angles


def test_straight_in_stun_ball_comes_straight_back():
    """A stun ball straight in (0 degrees) leaves at 0 degrees for every
    model (no sideways impulse by symmetry), slower than it came."""
    rows = cushion_curves.curves([0.0], PhysicsParams.standard())
    for r in rows:
        if r["ball"] == "stun":
            assert r["angle_out"] == pytest.approx(0.0, abs=1e-9)
            assert 0.0 < r["speed_ratio"] < 1.0
