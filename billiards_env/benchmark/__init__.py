"""The benchmark: a fixed protocol over the suite's tasks, normalized scores and their aggregate (docs/benchmark.md).

- ``protocol``: the tasks (with their opponents, noise, training budgets and reference bots), the evaluation
  seeds and episodes (``PROTOCOL``, ``QUICK``), as frozen dataclasses;
- ``score``: ``normalized_score(task, score)`` (0 = ``random``, 1 = the task's reference bot), ``REFERENCE``
  (the measured rows), the results files' schema;
- ``aggregate``: interquartile mean, optimality gap, mean, median with stratified-bootstrap 95% intervals and
  performance profiles (Agarwal et al. 2021), in numpy.

Scoring a policy plays it, which for a saved model needs ``agents``: the scoring command is
``python -m agents.evaluation.benchmark score``. Aggregating needs only this package:
``python -m billiards_env.benchmark aggregate FILE...``.
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from . import aggregate
from .protocol import PROTOCOL, QUICK, Protocol, Task
from .score import REFERENCE, Row, check_results, load_results, normalized_score, rows_of

TAUS = np.linspace(0.0, 2.0, 41)  # thresholds of the performance profile (normalized score)

__all__ = ["PROTOCOL", "QUICK", "Protocol", "Task", "REFERENCE", "Row", "normalized_score", "aggregate",
           "aggregate_docs", "aggregate_files", "plot_results", "load_results", "TAUS"]


def _entries(docs, reference) -> dict:
    """algorithm -> {task: [per-run scores]}: the files' runs merged per algorithm (a file per seed is fine),
    then the reference rows of algorithms no file holds."""
    entries: dict = {}
    for doc in docs:
        if doc.get("quick"):
            raise ValueError(f"{doc.get('policy')}: quick results are not scores; aggregate full-protocol files")
        for row in rows_of(doc):
            entries.setdefault(row.algorithm, {}).setdefault(row.task, []).extend(row.scores)
    files = set(entries)
    for row in reference:
        if row.algorithm not in files:
            entries.setdefault(row.algorithm, {}).setdefault(row.task, []).extend(row.scores)
    return entries


def aggregate_docs(docs, reference=None, reps: int = aggregate.REPS) -> dict:
    """The aggregate of results documents and the reference rows: per algorithm its normalized [runs, tasks]
    matrix (runs cut to the fewest any task has), every metric with its 95% interval, the performance profile."""
    reference = REFERENCE if reference is None else reference
    out = {"protocol": PROTOCOL.version, "taus": TAUS.tolist(), "entries": {}}
    order = [t.env_id for t in PROTOCOL.tasks]
    for algo, tasks in _entries(docs, reference).items():
        names = [t for t in order if t in tasks]
        n = min(len(tasks[t]) for t in names)
        m = np.array([normalized_score(t, np.asarray(tasks[t][:n]), reference) for t in names]).T  # [runs, tasks]
        out["entries"][algo] = {"tasks": names, "runs": n, "raw": {t: tasks[t][:n] for t in names},
                                "normalized": m.tolist(), "metrics": aggregate.summarize(m, reps=reps),
                                "profile": aggregate.profile(m, TAUS, reps=reps)}
    return out


def aggregate_files(paths, reference=None, reps: int = aggregate.REPS) -> dict:
    return aggregate_docs([load_results(p) for p in paths], reference, reps)


def table(agg: dict) -> str:
    """A Markdown table of an aggregate."""
    lines = ["| algorithm | tasks | runs | IQM [95% CI] | optimality gap [95% CI] | mean | median |",
             "|---|---|---|---|---|---|---|"]
    for algo, e in agg["entries"].items():
        mt = e["metrics"]
        iq, og = mt["iqm"], mt["optimality_gap"]
        lines.append(f"| {algo} | {len(e['tasks'])} | {e['runs']} | {iq['value']:.3f} [{iq['ci95'][0]:.3f}, "
                     f"{iq['ci95'][1]:.3f}] | {og['value']:.3f} [{og['ci95'][0]:.3f}, {og['ci95'][1]:.3f}] | "
                     f"{mt['mean']['value']:.3f} | {mt['median']['value']:.3f} |")
    return "\n".join(lines)


def plot_aggregate(agg: dict, path) -> Path:
    """Performance profiles (left) and IQM bars with their intervals (right)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.2))
    for algo, e in agg["entries"].items():
        p = e["profile"]
        line, = ax.plot(p["tau"], p["fraction"], label=algo)
        ax.fill_between(p["tau"], p["low"], p["high"], color=line.get_color(), alpha=0.2)
    ax.set_xlabel("normalized score tau (0 = random, 1 = reference bot)")
    ax.set_ylabel("fraction of runs x tasks with score > tau")
    ax.set_title("performance profile")
    ax.legend(fontsize=8)
    algos = list(agg["entries"])
    iq = [agg["entries"][a]["metrics"]["iqm"] for a in algos]
    vals = np.array([d["value"] for d in iq])
    err = np.array([[d["value"] - d["ci95"][0], d["ci95"][1] - d["value"]] for d in iq]).T
    bx.barh(range(len(algos)), vals, xerr=err, capsize=3)
    bx.set_yticks(range(len(algos)))
    bx.set_yticklabels(algos)
    bx.axvline(1.0, color="grey", lw=0.8, ls="--")
    bx.set_xlabel("IQM of normalized scores (95% stratified-bootstrap CI)")
    bx.set_title(f"protocol {agg['protocol']}")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return Path(path)


def plot_results(docs, path) -> Path:
    """The plot of a scoring run: with the reference rows, its aggregate (``plot_aggregate``); in quick mode or
    before reference rows exist, the raw score per task and run."""
    try:
        if any(d.get("quick") for d in docs):
            raise ValueError("quick")
        return plot_aggregate(aggregate_docs(docs, reps=500), path)
    except ValueError:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(9, 3.8))
        for j, doc in enumerate(docs):
            names = list(doc["tasks"])
            for i, t in enumerate(names):
                s = [r["score"] for r in doc["tasks"][t]["runs"]]
                ax.scatter([i + 0.1 * j] * len(s), s, s=14, color=f"C{j}", label=doc["policy"] if i == 0 else None)
            ax.set_xticks(range(len(names)))
            ax.set_xticklabels([n.removeprefix("Billiards-") for n in names], rotation=20, fontsize=8)
        ax.set_ylabel("score per run (success / win rate)")
        ax.set_ylim(-0.02, 1.02)
        ax.set_title("raw scores" + (" (quick mode: not a score)" if any(d.get("quick") for d in docs) else ""))
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(path, dpi=110)
        plt.close(fig)
        return Path(path)


def write_aggregate(agg: dict, out) -> tuple:
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "aggregate.json").write_text(json.dumps(agg, indent=1) + "\n")
    (out / "aggregate.md").write_text(table(agg) + "\n")
    return out / "aggregate.json", plot_aggregate(agg, out / "aggregate.png")
