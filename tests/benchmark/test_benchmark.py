"""The benchmark (billiards_env/benchmark, agents/evaluation/benchmark.py): the aggregate against hand-computed
values and against rliable where it is installed, normalization, the protocol, and the quick scoring run end to
end (a few seconds once the kernels are compiled)."""
from __future__ import annotations

import dataclasses
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from billiards_env.benchmark import PROTOCOL, QUICK, REFERENCE, Row, aggregate as A, aggregate_docs, normalized_score
from billiards_env.benchmark.score import SCHEMA, check_results

ROOT = Path(__file__).resolve().parents[2]


# -- the aggregate, by hand ----------------------------------------------------------------------------------------

def test_iqm_by_hand():
    x = np.array([[0, 1, 2, 3], [4, 5, 6, 7]], dtype=float)  # 8 scores: cut int(0.25 * 8) = 2 at each end
    assert A.iqm(x) == pytest.approx((2 + 3 + 4 + 5) / 4)
    assert A.iqm(np.array([[1.0, 100.0, -50.0, 2.0, 3.0]])) == pytest.approx(2.0)  # 5 scores: cut 1 at each end


def test_optimality_gap_mean_median_by_hand():
    x = np.array([[0.5, 1.5], [1.0, 0.0]])
    assert A.optimality_gap(x) == pytest.approx(1 - (0.5 + 1.0 + 1.0 + 0.0) / 4)
    assert A.optimality_gap(x, gamma=2.0) == pytest.approx(2 - 3.0 / 4)
    assert A.mean(x) == pytest.approx(0.75)
    x3 = np.array([[0.0, 1.0, 3.0], [0.2, 1.0, 5.0]])  # task means 0.1, 1, 4
    assert A.median(x3) == pytest.approx(1.0)


def test_performance_profile_by_hand():
    x = np.array([[0.5, 1.5], [1.0, 0.0]])
    assert A.score_distribution(x, [0.0, 0.5, 1.0, 2.0]).tolist() == [0.75, 0.5, 0.25, 0.0]


def test_stratified_bootstrap_resamples_runs_within_tasks():
    # every run of a task equal: any resample of runs gives the same matrix, so every interval is a point
    x = np.array([[0.1, 0.9, 0.4]] * 5)
    for f in (A.iqm, A.mean, A.optimality_gap):
        lo, hi = A.interval(x, f, reps=200)
        assert lo == pytest.approx(f(x)) and hi == pytest.approx(f(x))
    # two runs 0 and 1 of one task: the mean of a resample of 2 is 0, 0.5 or 1 with odds 1/4, 1/2, 1/4
    y = np.array([[0.0], [1.0]])
    idx = A.bootstrap_indices(2, 1, 20000, np.random.default_rng(1))
    means = y[idx, np.arange(1)[None, :]].mean(axis=(1, 2))
    assert np.mean(means == 0.5) == pytest.approx(0.5, abs=0.02) and np.mean(means == 0.0) == pytest.approx(0.25, abs=0.02)
    assert A.interval(y, A.mean, reps=2000) == (0.0, 1.0)
    assert A.interval(y, A.mean, reps=500, seed=3) == A.interval(y, A.mean, reps=500, seed=3)  # reproducible


def test_bad_scores_are_refused():
    with pytest.raises(ValueError, match="finite"):
        A.iqm(np.array([[np.nan, 1.0]]))
    with pytest.raises(ValueError, match="non-empty"):
        A.iqm(np.zeros((0, 3)))


# -- the aggregate against rliable ---------------------------------------------------------------------------------

def _scores(seed=0, runs=5, tasks=8):
    return np.random.default_rng(seed).normal(0.7, 0.4, size=(runs, tasks))


def test_point_metrics_match_rliable():
    metrics = pytest.importorskip("rliable.metrics", reason="rliable is not installed (pip install rliable: an "
                                                            "optional extra, [benchmark])")
    for seed in range(3):
        x = _scores(seed)
        assert A.iqm(x) == pytest.approx(metrics.aggregate_iqm(x), abs=1e-12)
        assert A.optimality_gap(x) == pytest.approx(metrics.aggregate_optimality_gap(x), abs=1e-12)
        assert A.mean(x) == pytest.approx(metrics.aggregate_mean(x), abs=1e-12)
        assert A.median(x) == pytest.approx(metrics.aggregate_median(x), abs=1e-12)


def test_profile_matches_rliable():
    library = pytest.importorskip("rliable.library", reason="rliable (or arch, which it imports) is not installed")
    x, taus = _scores(4), np.linspace(0, 2, 21)
    assert np.allclose(A.score_distribution(x, taus), library.score_distributions(x, taus))


def test_bootstrap_intervals_match_rliable(monkeypatch):
    library = pytest.importorskip("rliable.library", reason="rliable (or arch, which it imports) is not installed")
    from rliable import metrics
    init = library.arch_bs.IIDBootstrap.__init__
    if "random_state" not in __import__("inspect").signature(init).parameters:
        # rliable 1.2.0 passes random_state=, which arch >= 6 calls seed= (arch 7.2, which rliable pins below 8,
        # does not import with pandas 3): translate, so the comparison runs with the installed arch
        monkeypatch.setattr(library.arch_bs.IIDBootstrap, "__init__",
                            lambda self, *a, random_state=None, **kw: init(self, *a, seed=random_state, **kw))
    for seed, f, rf in ((5, A.iqm, metrics.aggregate_iqm), (6, A.optimality_gap, metrics.aggregate_optimality_gap)):
        x = _scores(seed)
        np.random.seed(0)  # rliable resamples with numpy's global generator
        _, ci = library.get_interval_estimates({"a": x}, lambda s: np.array([rf(s)]), reps=4000)
        lo, hi = A.interval(x, f, reps=4000)
        # two Monte-Carlo estimates of the same percentiles: within 0.02 (the interval is ~0.2 wide)
        assert lo == pytest.approx(ci["a"][0, 0], abs=0.02) and hi == pytest.approx(ci["a"][1, 0], abs=0.02)


# -- normalization and the protocol --------------------------------------------------------------------------------

def test_normalized_score():
    rows = (Row("Billiards-PotOne-v1", "random", None, (0.1, 0.1)), Row("Billiards-PotOne-v1", "lookahead", None,
                                                                        (0.5, 0.7)))
    assert normalized_score("PotOne", 0.35, rows) == pytest.approx(0.5)
    assert normalized_score("Billiards-PotOne-v1", 0.6, rows) == pytest.approx(1.0)
    assert np.allclose(normalized_score("PotOne", [0.1, 0.6], rows), [0.0, 1.0])
    with pytest.raises(ValueError, match="no reference row of 'random' on Billiards-RunOut-v1"):
        normalized_score("RunOut", 0.5, rows)
    with pytest.raises(ValueError, match="not a task of the benchmark"):
        normalized_score("Billiards-ThreeCushionPoint-v1", 0.5, rows)


def test_protocol_is_frozen_and_complete():
    import billiards_env  # noqa: F401
    from billiards_env.envs.registration import ENV_IDS, GAME_IDS
    with pytest.raises(dataclasses.FrozenInstanceError):
        PROTOCOL.tasks[0].budget = 1
    ids = [t.env_id for t in PROTOCOL.tasks]
    assert set(ids) <= set(ENV_IDS) | set(GAME_IDS) and set(GAME_IDS) <= set(ids)
    assert len(PROTOCOL.eval_seeds) == 5 and all(t.episodes <= 10_000 for t in PROTOCOL.tasks)
    assert QUICK.runs == 2 and [t.env_id for t in QUICK.tasks] == ids


def test_reference_rows_anchor_every_task():
    """REFERENCE holds, for every task, the random policy's and the reference bot's per-run scores, measured
    under the full protocol (one score per run), and the reference beats random."""
    for t in PROTOCOL.tasks:
        for name in (t.baseline, t.reference):
            rows = [r for r in REFERENCE if r.task == t.env_id and r.algorithm == name]
            assert len(rows) == 1 and len(rows[0].scores) == PROTOCOL.runs, (t.env_id, name)
        assert normalized_score(t.env_id, [r for r in REFERENCE if r.task == t.env_id
                                           and r.algorithm == t.reference][0].mean) == pytest.approx(1.0)


# -- the commands, end to end --------------------------------------------------------------------------------------

def _run(*args, timeout=600):
    out = subprocess.run([sys.executable, "-m", *args], capture_output=True, text=True, timeout=timeout, cwd=ROOT)
    assert out.returncode == 0, out.stdout[-2000:] + out.stderr[-3000:]
    return out.stdout


def test_quick_score_and_aggregate_end_to_end(tmp_path):
    """The quick mode: random on every task (two runs of a few episodes), a results file of the documented
    schema and a plot; then the aggregate of that file (marked full-protocol here, as a real run's would be)
    with the reference rows."""
    _run("agents.evaluation.benchmark", "score", "--policy", "random", "--task", "all", "--quick",
         "--out", str(tmp_path / "q"))
    doc = check_results(json.loads((tmp_path / "q" / "results.json").read_text()))
    assert doc["schema"] == SCHEMA and doc["quick"] and doc["policy"] == "random"
    assert list(doc["tasks"]) == [t.env_id for t in PROTOCOL.tasks]
    for t in QUICK.tasks:
        runs = doc["tasks"][t.env_id]["runs"]
        assert [r["run"] for r in runs] == [0, 1] and all(r["episodes"] == t.episodes for r in runs)
        assert all(0 <= r["score"] <= 1 for r in runs)
    assert (tmp_path / "q" / "results.png").stat().st_size > 1000
    doc["quick"], doc["policy"], doc["algorithm"] = False, "random-quick", "random-quick"
    (tmp_path / "full.json").write_text(json.dumps(doc))
    out = _run("billiards_env.benchmark", "aggregate", str(tmp_path / "full.json"), "--out", str(tmp_path / "agg"))
    assert "| random-quick | 8 | 2 |" in out and "| lookahead | 3 | 5 |" in out
    agg = json.loads((tmp_path / "agg" / "aggregate.json").read_text())
    assert agg["entries"]["lookahead"]["metrics"]["mean"]["value"] == pytest.approx(1.0)  # the reference: 1
    assert agg["entries"]["random"]["metrics"]["mean"]["value"] == pytest.approx(0.0)     # the baseline: 0
    assert (tmp_path / "agg" / "aggregate.png").stat().st_size > 1000


def test_a_module_factory_policy_and_quick_files_refused(tmp_path):
    _run("agents.evaluation.benchmark", "score", "--policy", "billiards_env.bots.random_bot:RandomBot",
         "--task", "NineBall2P", "--quick", "--run", "1", "--out", str(tmp_path))
    doc = json.loads((tmp_path / "results.json").read_text())
    assert list(doc["tasks"]) == ["Billiards-NineBall2P-v1"] and doc["tasks"]["Billiards-NineBall2P-v1"]["runs"][0]["run"] == 1
    with pytest.raises(ValueError, match="quick results are not scores"):
        aggregate_docs([doc])
