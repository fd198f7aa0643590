"""The league's bookkeeping (agents.league) and play_jobs (agents.evaluation.distributed)."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from agents.evaluation.distributed import MatchJob
from agents.league.games import play_league_jobs
from agents.league import LeagueConfig, fit_value, load_state, run_league
from agents.league.fit import FitConfig, log_loss

ROOT = Path(__file__).resolve().parents[2]
TINY = dict(game="nine_ball", generations=2, racks=1, opponents=["ghost"], noises=["tournament", "variable"],
            max_shots=10, fit=dict(hidden=[6], epochs=2), max_snapshots=1)


def test_resumed_league_ends_as_an_uninterrupted_one(tmp_path):
    cfg = LeagueConfig.from_dict(TINY)
    quiet = lambda s: None
    whole = run_league(tmp_path / "whole", cfg, log=quiet)
    run_league(tmp_path / "parts", cfg, generations=1, log=quiet)
    assert load_state(tmp_path / "parts")["generation"] == 1
    parts = run_league(tmp_path / "parts", resume=True, log=quiet)
    assert [s["sha256"] for s in parts["snapshots"]] == [s["sha256"] for s in whole["snapshots"]]
    assert parts["games"] == whole["games"] and parts["seeds"] == whole["seeds"] and parts["rng"] == whole["rng"]
    assert len(parts["snapshots"]) == 2 and sum(c["games"] for c in parts["games"].values()) == 8
    # generation 1's learner is generation 0's snapshot
    assert any(k.startswith("snapshots/gen_001 | ghost") for k in parts["games"])
    with pytest.raises(FileExistsError, match="--resume"):
        run_league(tmp_path / "whole", cfg, log=quiet)


def test_league_jobs_record_every_decision_with_its_shooters_result():
    """Through play_jobs: one sample per shot but the breaks, labelled by the shooter's game; the same in
    chunks of one rack as in one batch of the job's racks, apart from the order of the samples."""
    from billiards_env.studies.matches import play_pairing
    job = MatchJob("lookahead", "ghost-safety", "nine_ball", racks=2, seed=5, noise="tournament", max_shots=14)
    r, again = play_league_jobs([job]), play_league_jobs([job])
    r, again = r[0], again[0]
    ref = play_pairing("lookahead", "ghost-safety", "nine_ball", 2, 5, "tournament", max_shots=14)
    assert np.array_equal(r.winner, ref.winner) and np.array_equal(r.winner, again.winner)
    s = r.samples
    assert np.array_equal(s.x, again.samples.x)
    assert len(s.y) == int(ref.shots.sum()) - 4
    assert set(np.unique(s.y)) <= {0.0, 0.5, 1.0} and set(s.table) <= set(range(4))
    w = ref.winner[s.table]
    assert np.all((s.y == 0.5) == (w < 0))
    # the lookahead's decisions carry its search value, ghost-safety's do not
    assert np.isfinite(s.search).any() and np.isnan(s.search).any()
    chunked = play_league_jobs([MatchJob("ghost", "ghost-safety", "nine_ball", racks=2, seed=5, max_shots=14,
                                         chunk_racks=1)])[0]
    assert len(chunked.samples.y) == len(chunked.samples.table) and set(chunked.samples.table) <= set(range(4))


def test_fit_learns_a_planted_value():
    rng = np.random.default_rng(0)
    x = rng.normal(size=(3000, 9))   # the feature rows of a one-ball table: column 7 is the ease
    x[:, 7] = 0.0                     # the starting (hand-made) value: 1/2 everywhere
    p = 1 / (1 + np.exp(-3 * x[:, 0]))
    y = (rng.random(3000) < p).astype(float)
    net, rep = fit_value(x, y, FitConfig(hidden=(8,), epochs=20, lr=1e-2, val_frac=0.2), np.random.default_rng(1),
                         groups=np.arange(3000) // 3)
    assert rep["val_log_loss_start"] == pytest.approx(np.log(2))
    assert rep["val_log_loss"] < rep["val_log_loss_constant"] - 0.15 and rep["best_epoch"] > 0
    assert log_loss(net(x), y) < log_loss(np.full(len(y), y.mean()), y)


def test_config_errors_name_the_key():
    with pytest.raises(ValueError, match="unknown league config keys \\['rackz'\\]"):
        LeagueConfig.from_dict(dict(rackz=3))
    with pytest.raises(ValueError, match="the league trains"):
        LeagueConfig(game="snooker")


def test_league_script_quick(tmp_path):
    res = subprocess.run([sys.executable, "scripts/league.py", "--quick", "--run", str(tmp_path / "q")], cwd=ROOT,
                         capture_output=True, text=True, timeout=600, env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"})
    assert res.returncode == 0, res.stderr[-2000:]
    assert "generation 0 done" in res.stdout
    state = json.loads((tmp_path / "q" / "league.json").read_text())
    assert state["generation"] == 1 and (tmp_path / "q" / "snapshots" / "gen_001.npz").exists()


def test_value_networks_are_entrants_by_stem():
    """``value@<stem>`` and ``value-all@<stem>`` (a league snapshot, here the shipped 9-ball value) play as
    value-lookahead with that network on the blind leaves or on every leaf; a missing stem is a clear error."""
    from agents.evaluation.entrants import bot_factory
    from billiards_env.bots.learned.value import VALUE_DIR, ValueLookahead, load_value
    stem = str(VALUE_DIR / "nine_ball")
    net = load_value(stem)[0]
    for prefix, where in (("value@", "blind"), ("value-all@", "all")):
        bot = bot_factory(prefix + stem, seed=1)
        assert isinstance(bot, ValueLookahead) and bot.name == prefix + stem and bot.leaf_value.where == where
        assert np.array_equal(bot.leaf_value.net("nine_ball").weights[0], net.weights[0])
    with pytest.raises(ValueError, match="no value network"):
        bot_factory("value@" + str(ROOT / "missing"))


def test_a_league_fits_the_balls_eases_when_asked(tmp_path):
    """``ball_eases: true``: the samples carry the balls' eases, the snapshots are networks that see them, and the
    next generation's learner searches with them."""
    from billiards_env.bots.learned.value import feature_size, load_value
    cfg = LeagueConfig.from_dict({**TINY, "ball_eases": True})
    state = run_league(tmp_path / "b", cfg, log=lambda s: None)
    for snap in state["snapshots"]:
        net, doc = load_value(tmp_path / "b" / snap["stem"])
        assert net.ball_eases and doc["ball_eases"] and net.in_dim == feature_size(10, ball_eases=True)
    with np.load(tmp_path / "b" / "data" / "gen_000.npz") as z:
        assert z["balls"].shape == (len(z["y"]), 20)
    assert any(k.startswith("snapshots/gen_001 | ghost") for k in state["games"])
