"""scripts/benchmark.py runs end to end (small sizes) and writes its tables."""
import csv
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_benchmark_env_section_quick(tmp_path):
    out = subprocess.run([sys.executable, str(ROOT / "scripts" / "benchmark.py"), "--quick", "--only", "env", "--out", str(tmp_path)],
                         capture_output=True, text=True, timeout=900, cwd=ROOT)
    assert out.returncode == 0, out.stderr[-2000:]
    table = (tmp_path / "env.md").read_text()
    assert "PotOne" in table and "NineBall" in table and "env overhead" in table
    assert (tmp_path / "benchmark.csv").exists()


def test_benchmark_against_head_quick(tmp_path):
    """--against HEAD: a temporary worktree of HEAD, both trees timed in turn,
    a comparison table, both trees' rows appended with their revisions, and
    the worktree removed afterwards."""
    worktrees = subprocess.run(["git", "-C", str(ROOT), "worktree", "list"], capture_output=True, text=True).stdout
    out = subprocess.run([sys.executable, str(ROOT / "scripts" / "benchmark.py"), "--against", "HEAD", "--quick",
                          "--only", "solver", "--scene", "one ball", "--batch", "4", "--repeats", "1",
                          "--rounds", "1", "--out", str(tmp_path)],
                         capture_output=True, text=True, timeout=600, cwd=ROOT)
    assert out.returncode == 0, out.stderr[-2000:]
    head = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short=10", "HEAD"], capture_output=True,
                          text=True).stdout.strip()
    table = (tmp_path / "against.md").read_text()
    assert f"against HEAD ({head})" in table
    rows = [line for line in table.splitlines() if line.startswith("| one ball")]
    assert [r.split(" | ")[1] for r in rows] == ["event", "step dt=0.001", "step dt=0.0001"]
    for r in rows:
        cells = [c.strip() for c in r.strip("|").split("|")]
        assert float(cells[-1]) > 0 and float(cells[6]) > 0  # latency ratio, shots/s ratio
    recorded = list(csv.DictReader((tmp_path / "benchmark.csv").open()))
    assert len(recorded) == 6
    assert {r["tree"] for r in recorded} == {"new", "old"}
    assert {r["revision"] for r in recorded if r["tree"] == "old"} == {head}
    assert all(r["revision"].startswith(head) for r in recorded)
    assert subprocess.run(["git", "-C", str(ROOT), "worktree", "list"], capture_output=True,
                          text=True).stdout == worktrees
