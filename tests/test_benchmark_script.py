"""scripts/benchmark.py runs end to end (small sizes) and writes its tables."""
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
