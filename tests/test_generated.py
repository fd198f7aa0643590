"""Every committed generated file that is derived from committed data is current (scripts/regenerate.py --check),
and the check finds a stale one. CI runs the suite, so this is where CI checks the generated tables."""
from __future__ import annotations

import importlib.util
import json
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _regenerate():
    spec = importlib.util.spec_from_file_location("_test_regenerate", ROOT / "scripts" / "regenerate.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod  # its dataclasses look their module up there
    spec.loader.exec_module(mod)
    return mod


def test_every_derived_file_is_current():
    stale = _regenerate().check(ROOT, verbose=False)
    assert not stale, "stale generated files (python scripts/regenerate.py rewrites them):\n" + "\n".join(
        f"{e.path}: {e.command}\n{why}" for e, why in stale)


def test_the_inventory_covers_every_committed_result_and_renders_the_known_tables():
    reg = _regenerate()
    entries = {e.path: e for e in reg.inventory(ROOT)}
    committed = subprocess.run(["git", "ls-files", "results"], cwd=ROOT, capture_output=True, text=True,
                               check=True).stdout.split()
    assert committed and not [f for f in committed if f not in entries]
    derived = {p for p, e in entries.items() if e.kind == reg.CHEAP}
    for path in ("results/benchmark/benchmark.md", "results/ladder/summary.md", "docs/ladder.md",
                 "docs/agents_benchmark.md", "results/matches/summary.md", "results/breaks/nine_ball.md",
                 "results/matches/championship/championship.md", "docs/environments.md"):
        assert path in derived, path
    # a match's JSON is measured, and the inventory says how: the command it records
    doc = json.loads((ROOT / "results/matches/nine_ball_high.json").read_text())
    assert entries["results/matches/nine_ball_high.json"].kind == reg.MEASURED
    assert entries["results/matches/nine_ball_high.json"].command == doc["command"]
    assert entries["results/matches/nine_ball_high.png"].kind == reg.PLOT


def test_a_stale_file_is_found_named_and_fixed(tmp_path, capsys):
    """In a copy of some committed results: a hand-edited match table, a section table re-measured without its
    joined benchmark.md, and an untouched break table."""
    reg = _regenerate()
    for folder in ("results/breaks", "results/matches/championship", "results/benchmark"):
        shutil.copytree(ROOT / folder, tmp_path / folder)
    assert reg.check(tmp_path, verbose=False) == []

    md = tmp_path / "results/matches/championship/eight_ball_high.md"
    md.write_text(md.read_text().replace("| a | b |", "| a | b (edited) |"))
    models = tmp_path / "results/benchmark/models.md"
    models.write_text(models.read_text().replace("| cushion model |", "| cushion model (re-measured) |"))
    stale = reg.check(tmp_path)
    assert sorted(e.path for e, _ in stale) == ["results/benchmark/benchmark.md",
                                                "results/matches/championship/eight_ball_high.md"]
    out = capsys.readouterr().out
    assert "STALE results/matches/championship/eight_ball_high.md" in out and "fix: python scripts/" in out
    assert "(edited)" in dict((e.path, why) for e, why in stale)["results/matches/championship/eight_ball_high.md"]

    changed = reg.regenerate(tmp_path)
    assert sorted(changed) == ["results/benchmark/benchmark.md", "results/matches/championship/eight_ball_high.md"]
    assert "(edited)" not in md.read_text() and "(re-measured)" in (tmp_path / "results/benchmark/benchmark.md").read_text()
    assert reg.check(tmp_path, verbose=False) == []


def test_the_command_lists_checks_and_fails_on_a_stale_file(tmp_path):
    """The CLI: --list prints the inventory; --check exits 0 on a current tree and 1 on a stale one, naming the
    file and the command that fixes it."""
    cmd = [sys.executable, str(ROOT / "scripts" / "regenerate.py")]
    out = subprocess.run(cmd + ["--list", "--only", "results/breaks/*"], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    rows = [line.split("\t") for line in out.stdout.splitlines()]
    assert ["results/breaks/nine_ball.md", "derived"] in [r[:2] for r in rows]
    assert any(r[0] == "results/breaks/nine_ball.json" and r[1] == "measured" and "break_stats.py" in r[2]
               for r in rows)

    shutil.copytree(ROOT / "results/breaks", tmp_path / "results/breaks")
    out = subprocess.run(cmd + ["--check", "--root", str(tmp_path)], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stdout + out.stderr
    md = tmp_path / "results/breaks/ten_ball.md"
    md.write_text(md.read_text().replace("1000 racks", "100 racks", 1))
    out = subprocess.run(cmd + ["--check", "--root", str(tmp_path)], capture_output=True, text=True, timeout=120)
    assert out.returncode == 1 and "STALE results/breaks/ten_ball.md" in out.stdout, out.stdout + out.stderr
    assert "fix: python scripts/regenerate.py" in out.stdout
