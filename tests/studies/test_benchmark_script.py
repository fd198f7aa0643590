"""scripts/benchmark.py runs end to end (small sizes) and writes its tables:
every section in its quick mode (a moved or broken function fails here, not
in a headline figure), --against HEAD, --history; and the benchmark's scenes
draw the same shots as on every earlier commit."""
import csv
import importlib.util
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "scripts" / "benchmark.py"
TINY = ["--quick", "--batch", "8", "--repeats", "1"]


def _run(tmp_path, *args, timeout=600):
    out = subprocess.run([sys.executable, str(SCRIPT), *args, "--out", str(tmp_path)], capture_output=True,
                         text=True, timeout=timeout, cwd=ROOT)
    assert out.returncode == 0, out.stderr[-3000:]
    return out


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


def _ray_or_skip():
    if importlib.util.find_spec("ray") is None:
        msg = "the rllib section needs ray (pip install -e '.[ray]')"
        if os.environ.get("CI"):
            pytest.fail(msg + " (required under CI)")
        pytest.skip(msg)


def _model_labels():
    from billiards_env.studies.bench.sections import model_sets
    return list(model_sets())


# each section (but env, above) -> what its table must name
SECTION_TABLES = {
    "solver": lambda: ["9-ball break (8 m/s)", "15-ball break (8 m/s)", "two-ball cut (2 m/s, top+side)",
                       "one ball, top spin, two cushions", "| event |", "| step dt=0.001 |", "| step dt=0.0001 |",
                       "single-table latency (ms)"],
    "effects": lambda: ["9-ball break (8 m/s)", "two-ball cut (2 m/s, top+side)", "all (= default)", "no spin",
                        "no pockets", "minimal", "µs per event or step", "speed-up vs all"],
    "models": lambda: ["9-ball break (8 m/s)", "two-ball cut (2 m/s, top+side)", *_model_labels(),
                       "speed-up vs all"],
    "airborne": lambda: ["9-ball break (8 m/s)", "9-ball break, cue elevated 3-12 deg",
                         "jump over a blocker (30-50 deg, 3-6 m/s)", "all (planar)", "all + airborne"],
    "cold": lambda: ["cold (empty numba cache)", "warm (numba cache on disk)"],
    "games": lambda: ["games/s, ghost vs ghost", "vector env steps/s, random actions", "nine_ball", "ten_ball",
                      "games/s, carom vs carom", "three_cushion", "three-cushion shot (carom table, contacts kept)",
                      "9-ball break (8 m/s)", "us per event"],
    "snooker": lambda: ["snooker opening (22 balls, 8 m/s)", "pool 15-ball break (8 m/s)", "per-event cost vs pool",
                        "frames, snooker vs snooker", "shots per frame"],
    "rllib": lambda: ["sampling: bare env", "sampling: sb3 rollout", "sampling: rllib 1 runner",
                      "sampling: rllib 2 runners", "training: sb3 (default config)", "one EnvRunner, CPU per env step"],
}


def test_every_section_has_a_quick_test():
    from billiards_env.studies.bench.options import SECTION_NAMES
    assert set(SECTION_TABLES) | {"env"} == set(SECTION_NAMES) | {"games", "snooker"}


# rllib starts Ray and trains both backends for 8,192 steps: about a minute
@pytest.mark.parametrize("section", [pytest.param(k, marks=[pytest.mark.slow, pytest.mark.xdist_group("ray")])
                                     if k == "rllib" else k for k in SECTION_TABLES])
def test_benchmark_section_quick(section, tmp_path):
    """``--only SECTION --quick`` at the smallest sizes writes SECTION.md naming
    its rows (and, but for games, benchmark.md and the CSV rows)."""
    if section == "rllib":
        _ray_or_skip()
    _run(tmp_path, "--only", section, *TINY)
    table = (tmp_path / f"{section}.md").read_text()
    missing = [name for name in SECTION_TABLES[section]() if name not in table]
    assert not missing, table
    if section in ("games", "snooker"):
        return
    assert (tmp_path / "benchmark.md").read_text().strip() == table.strip()
    recorded = list(csv.DictReader((tmp_path / "benchmark.csv").open()))
    assert recorded and all(r["quick"] == "True" and r["revision"] for r in recorded)


def test_benchmark_history_plot(tmp_path):
    """--history draws history.png from the full-size CSV rows (none: nothing to plot)."""
    pytest.importorskip("matplotlib")
    out = _run(tmp_path, "--history")
    assert "nothing to plot" in out.stdout and not (tmp_path / "history.png").exists()
    cols = ["timestamp", "section", "scene", "solver", "batch", "autoreset", "quick", "shots_per_s_1t"]
    with (tmp_path / "benchmark.csv").open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow(cols)
        for day, rate in ((1, 7000.0), (2, 7500.0)):
            w.writerow([f"2026-01-0{day}T00:00:00", "solver", "9-ball break (8 m/s)", "event", "1024", "", "False",
                        rate])
    _run(tmp_path, "--history")
    assert (tmp_path / "history.png").stat().st_size > 0


# per scene, for 4 tables from default_rng(0): weighted means of pos, vel and
# omega, and the generator's next draw, as the scenes gave before they moved
# into the library (the same draws in the same order keep figures comparable)
SCENE_FINGERPRINTS = {
    "9-ball break (8 m/s)": (51.62313654531181, 12.824089167333403, -48.015976785037324, 0.6884467305709401),
    "15-ball break (8 m/s)": (84.33753666136658, 12.585753441928652, -40.90347602302524, 0.23936944299295215),
    "two-ball cut (2 m/s, top+side)": (6.558318998656141, 3.684075659936734, -23.750932600987767,
                                       0.028319671145462966),
    "one ball, top spin, two cushions": (5.369508731011759, 9.504832790541434, -50.24073653412285,
                                         0.8574042765875693),
}


def test_benchmark_scenes_draw_the_same_shots():
    from billiards_env.physics import PhysicsParams, Table
    from billiards_env.studies.bench.scenes import SCENES
    P, T = PhysicsParams.standard(), Table.pool(9)

    def fingerprint(a):
        return float((a * np.arange(1, a.size + 1).reshape(a.shape)).sum() / a.size)

    assert list(SCENES) == list(SCENE_FINGERPRINTS)
    for name, make in SCENES.items():
        rng = np.random.default_rng(0)
        s = make(4, P, T, rng)
        got = (fingerprint(s.pos), fingerprint(s.vel), fingerprint(s.omega), float(rng.random()))
        assert got[3] == SCENE_FINGERPRINTS[name][3], name  # the same number of draws
        np.testing.assert_allclose(got[:3], SCENE_FINGERPRINTS[name][:3], rtol=1e-12, err_msg=name)
