"""The championship protocol (studies.championship, scripts/match.py --protocol championship) and the break
statistics (studies.breaks, scripts/break_stats.py), in their quick modes."""
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from billiards_env.studies.breaks import break_outcomes
from billiards_env.studies.championship import LEVELS, TimedBot, championship

ROOT = Path(__file__).resolve().parents[2]


def test_championship_plays_every_level_with_the_same_racks_and_times_each_entrant():
    levels = championship(["ghost", "random"], n_racks=2, seed=0, max_shots=12)
    assert [lv["noise"] for lv in levels] == list(LEVELS)
    for lv in levels:
        (r,) = lv["results"]
        assert r.n == 4 and r.a_broke.tolist() == [True, True, False, False]   # each rack broken by each side
        c = lv["compute"]
        assert set(c) == {"ghost", "random"} and all(v["shots"] > 0 and v["seconds"] > 0 for v in c.values())
        assert c["ghost"]["shots"] + c["random"]["shots"] >= r.shots.sum()    # every shot was decided by one


def test_timed_bot_counts_tables_and_passes_attributes_through():
    class Stub:
        name, extra = "stub", 7

        def act(self, view):
            return "plan"

    clock = {}
    t = TimedBot(Stub(), "stub", clock)

    class View:
        n = 5

    assert t.act(View()) == "plan" and clock["stub"][0] == 5 and t.extra == 7


def test_championship_script_quick(tmp_path):
    out = subprocess.run([sys.executable, str(ROOT / "scripts" / "match.py"), "--protocol", "championship", "--quick",
                          "--policies", "ghost", "random", "--out", str(tmp_path)],
                         capture_output=True, text=True, cwd=ROOT, timeout=600)
    assert out.returncode == 0, out.stderr[-2000:]
    doc = json.loads((tmp_path / "championship.json").read_text())
    assert [lv["noise"] for lv in doc["levels"]] == list(LEVELS)
    assert all(lv["compute"]["ghost"]["ms_per_shot"] > 0 for lv in doc["levels"])
    for noise in LEVELS:
        assert (tmp_path / f"eight_ball_{noise}.md").exists()
    assert "ms/shot" in (tmp_path / "championship.md").read_text()
    bad = subprocess.run([sys.executable, str(ROOT / "scripts" / "match.py"), "--protocol", "championship",
                          "--game", "nine_ball", "--quick"], capture_output=True, text=True, cwd=ROOT, timeout=300)
    assert bad.returncode != 0 and "plays eight_ball" in bad.stderr


def test_break_outcomes_count_what_the_break_did():
    r = break_outcomes("nine_ball", n_racks=6, seed=0, noise="none")
    assert r["racks"] == 6 and 0 <= r["mean_pocketed"] <= 9
    assert r["breaker wins"]["rate"] <= r["game ball down"]["rate"] + 1e-12
    assert r["legal"]["rate"] > 0.5                                          # the standard break is mostly legal
    spotted = break_outcomes("nine_ball", n_racks=6, seed=0, noise="none", break_nine="spotted")
    assert spotted["breaker wins"]["rate"] == 0.0


def test_break_stats_script_quick():
    out = subprocess.run([sys.executable, str(ROOT / "scripts" / "break_stats.py"), "--quick", "--noise", "none"],
                         capture_output=True, text=True, cwd=ROOT, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    assert "| perfect | none |" in out.stdout and "| realistic | none |" in out.stdout
