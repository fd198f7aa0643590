"""Aggregate scores over a suite the way Agarwal et al. (2021, "Deep RL at the Edge of the Statistical
Precipice") recommend, in numpy (``rliable``'s method, without its dependencies; tests/benchmark compares the two
where ``rliable`` is installed).

Scores are a matrix [runs, tasks] of normalized scores (``score.normalized_score``): run n of task m is one
independently trained (or seeded) policy evaluated on the task.

- ``iqm``: the interquartile mean, the mean of the middle 50% of all runs x tasks scores (scipy's
  ``trim_mean(x, 0.25)`` over the flattened matrix: ``int(0.25 * N)`` scores cut at each end);
- ``optimality_gap``: ``gamma - mean(min(x, gamma))``, how far the runs fall short of ``gamma`` (1: the reference);
- ``mean``, ``median`` (of the per-task means, as rliable);
- ``interval``: the stratified bootstrap: every replicate resamples the runs of each task with replacement,
  independently per task (the tasks stay fixed), and the statistic's 95% interval is the 2.5 and 97.5
  percentiles of its replicates;
- ``performance_profile``: the score distribution, the fraction of all runs x tasks scores above each tau,
  with bootstrap bands.
"""
from __future__ import annotations

import numpy as np

REPS = 2000           # bootstrap replicates: the 95% interval's ends move by < 0.01 normalized score between seeds
CONFIDENCE = 0.95
BOOTSTRAP_SEED = 0    # the intervals are reproducible


def _matrix(scores) -> np.ndarray:
    x = np.asarray(scores, dtype=np.float64)
    if x.ndim == 1:
        x = x[:, None]
    if x.ndim != 2 or x.size == 0:
        raise ValueError(f"scores must be a non-empty [runs, tasks] matrix, got shape {x.shape}")
    if not np.isfinite(x).all():
        raise ValueError("scores must be finite")
    return x


def iqm(scores) -> float:
    """Interquartile mean of every score of the [runs, tasks] matrix (25% trimmed at each end)."""
    x = np.sort(_matrix(scores), axis=None)
    cut = int(0.25 * x.size)
    return float(x[cut:x.size - cut].mean())


def optimality_gap(scores, gamma: float = 1.0) -> float:
    """``gamma`` less the mean of the scores clipped at ``gamma``: 0 when every run reaches the reference."""
    return float(gamma - np.minimum(_matrix(scores), gamma).mean())


def mean(scores) -> float:
    return float(_matrix(scores).mean())


def median(scores) -> float:
    """The median over tasks of each task's mean over runs."""
    return float(np.median(_matrix(scores).mean(axis=0)))


METRICS = {"iqm": iqm, "optimality_gap": optimality_gap, "mean": mean, "median": median}


def score_distribution(scores, taus) -> np.ndarray:
    """The performance profile: for each tau, the fraction of all runs x tasks scores above tau."""
    x = _matrix(scores)
    return np.array([(x > t).mean() for t in np.asarray(taus, dtype=np.float64)])


def bootstrap_indices(n_runs: int, n_tasks: int, reps: int, rng: np.random.Generator) -> np.ndarray:
    """[reps, runs, tasks] run indices of the stratified bootstrap: each task's runs resampled with replacement."""
    return rng.integers(0, n_runs, size=(reps, n_runs, n_tasks))


def interval(scores, statistic, reps: int = REPS, confidence: float = CONFIDENCE,
             seed: int = BOOTSTRAP_SEED) -> tuple:
    """The ``confidence`` percentile interval of ``statistic([runs, tasks]) -> float or array`` under the
    stratified bootstrap (returns (low, high), arrays when the statistic is one)."""
    x = _matrix(scores)
    n, m = x.shape
    idx = bootstrap_indices(n, m, reps, np.random.default_rng(seed))
    tasks = np.arange(m)[None, :]
    values = np.array([statistic(x[i, tasks]) for i in idx])
    a = (1.0 - confidence) / 2.0
    lo, hi = np.percentile(values, [100 * a, 100 * (1 - a)], axis=0)
    return (float(lo), float(hi)) if np.ndim(lo) == 0 else (lo, hi)


def summarize(scores, reps: int = REPS, seed: int = BOOTSTRAP_SEED) -> dict:
    """Every metric with its interval: ``{name: {"value": v, "ci95": [lo, hi]}}``."""
    out = {}
    for name, f in METRICS.items():
        lo, hi = interval(scores, f, reps=reps, seed=seed)
        out[name] = {"value": f(scores), "ci95": [lo, hi]}
    return out


def profile(scores, taus, reps: int = REPS, seed: int = BOOTSTRAP_SEED) -> dict:
    """The performance profile at ``taus`` with its bootstrap band."""
    taus = np.asarray(taus, dtype=np.float64)
    lo, hi = interval(scores, lambda s: score_distribution(s, taus), reps=reps, seed=seed)
    return {"tau": taus.tolist(), "fraction": score_distribution(scores, taus).tolist(),
            "low": np.atleast_1d(lo).tolist(), "high": np.atleast_1d(hi).tolist()}
