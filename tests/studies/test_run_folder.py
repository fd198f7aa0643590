"""scripts/match.py and scripts/benchmark.py write into a new run folder,
runs/<script>/<timestamp>/, unless --out names another: never into the
committed results/ by default (studies/run_folder.py)."""
import subprocess
import sys
from pathlib import Path

from billiards_env.studies.run_folder import run_folder

ROOT = Path(__file__).resolve().parents[2]


def test_run_folders_are_new_and_apart(tmp_path):
    a, b = run_folder(tmp_path, "match"), run_folder(tmp_path, "match")
    assert a != b and a.is_dir() and b.is_dir() and not any(a.iterdir())
    assert a.parent == b.parent == tmp_path / "runs" / "match"


def test_match_writes_a_run_folder_by_default(tmp_path, monkeypatch, load_script):
    match = load_script("match")
    monkeypatch.setattr(match, "ROOT", tmp_path)
    assert match.main(["--quick", "--policies", "random", "ghost"]) == 0
    (run,) = (tmp_path / "runs" / "match").iterdir()
    assert (run / "nine_ball_tournament.json").exists() and (run / "nine_ball_tournament.md").exists()
    assert not (tmp_path / "results").exists()


def test_folder_readers_need_out():
    """--summary (match) and --history (benchmark) read a folder: without --out they say so."""
    for script, flag in (("match.py", "--summary"), ("benchmark.py", "--history")):
        out = subprocess.run([sys.executable, str(ROOT / "scripts" / script), flag], capture_output=True, text=True,
                             timeout=300, cwd=ROOT)
        assert out.returncode == 2 and "--out results/" in out.stderr, out.stderr[-2000:]
