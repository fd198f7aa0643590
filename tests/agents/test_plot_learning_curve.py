"""scripts/plot_learning_curve.py: both figures from a run's csv logs, and
the errors that name what is missing."""
from __future__ import annotations

import csv
from pathlib import Path

import pytest

pytest.importorskip("matplotlib")


def _write(path: Path, fields: list[str], rows: list[list]) -> None:
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(fields)
        w.writerows(rows)


def _run(tmp_path: Path, name: str, held: bool = True) -> Path:
    """A run folder with the two logs training writes (EpisodeLogger, HeldOutEvaluation)."""
    rd = tmp_path / name
    rd.mkdir()
    _write(rd / "progress.csv", ["timesteps", "time_s", "episodes", "success_rate", "mean_reward", "scratch_rate",
                                 "foul_rate", "steps_per_s"],
           [[4096 * k, 1.0 * k, 2048, 0.1 * k, -1 + 0.2 * k, 0.1, 0.2, 4096.0] for k in range(1, 5)])
    if held:
        _write(rd / "evaluations.csv", ["timesteps", "train_s", "success_rate", "ci_low", "ci_high"],
               [[0, 0.0, 0.1, 0.08, 0.12], [8192, 2.0, 0.4, 0.37, 0.43], [16384, 4.0, 0.5, 0.47, 0.53]])
    return rd


def test_both_figures_are_written(tmp_path, load_script):
    main = load_script("plot_learning_curve").main
    a, b = _run(tmp_path, "a"), _run(tmp_path, "b")
    for flags, out in (([], "curve.png"), (["--held-out"], "held.png")):
        assert main([str(a), str(b), "--labels", "A", "B", "--out", str(tmp_path / out)] + flags) == 0
        assert (tmp_path / out).stat().st_size > 10_000


def test_a_run_without_held_out_evaluations_is_named(tmp_path, load_script):
    main = load_script("plot_learning_curve").main
    rd = _run(tmp_path, "no_evals", held=False)
    with pytest.raises(ValueError, match="no_evals has no evaluations.csv"):
        main([str(rd), "--held-out", "--out", str(tmp_path / "x.png")])
    assert not (tmp_path / "x.png").exists()


def test_labels_must_match_runs(tmp_path, load_script):
    main = load_script("plot_learning_curve").main
    rd = _run(tmp_path, "a")
    with pytest.raises(SystemExit):
        main([str(rd), "--labels", "A", "B", "--out", str(tmp_path / "x.png")])
    assert not (tmp_path / "x.png").exists()
