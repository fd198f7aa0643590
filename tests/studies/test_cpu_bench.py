"""scripts/cpu_bench.py in quick mode: the table, the JSON line, and the same
shots from a saved scene file."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _run(*args):
    r = subprocess.run([sys.executable, "scripts/cpu_bench.py", "--quick", *args], cwd=ROOT, capture_output=True,
                       text=True, timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    return r.stdout


def test_cpu_bench_times_effect_sets_and_replays_saved_scenes(tmp_path):
    built = json.loads(_run("--scene", "two-ball", "--effects", "all", "--effects", "no spin", "--effects",
                            "all + airborne", "--latency", "--json"))
    rows = {k: v for k, v in built.items() if k != "tree"}
    assert sorted(k.split(" | ")[1] for k in rows) == ["all", "all + airborne", "no spin"]
    # a planar shot plays the same with the flight switched on (docs/physics.md, what it costs)
    assert rows["two-ball cut (2 m/s, top+side) | all + airborne"]["events_per_shot"] == \
        rows["two-ball cut (2 m/s, top+side) | all"]["events_per_shot"]
    assert all(v["ms"] > 0 and v["latency_us"] > 0 and v["events_per_shot"] > 2 for v in rows.values())
    f = tmp_path / "scenes.npz"
    assert "wrote 1 scenes" in _run("--scene", "two-ball", "--save-scenes", str(f))
    loaded = json.loads(_run("--scenes-from", str(f), "--effects", "all", "--effects", "no spin", "--effects",
                             "all + airborne", "--json"))
    assert {k: v["events_per_shot"] for k, v in loaded.items() if k != "tree"} == \
        {k: v["events_per_shot"] for k, v in rows.items()}
    assert "shots/s" in _run("--scene", "two-ball")


def test_cpu_bench_names_a_scene_that_matches_nothing():
    r = subprocess.run([sys.executable, "scripts/cpu_bench.py", "--quick", "--scene", "no such scene"], cwd=ROOT,
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 2 and "no scene matches" in r.stderr
