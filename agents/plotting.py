"""Learning curves (training success rate and reward vs env steps) from a
run's ``progress.csv`` (written by ``agents.sb3.training.EpisodeLogger``),
with its held-out evaluations (``evaluations.csv``, ``HeldOutEvaluation``)
where it has them: a self-play run has no training success to plot."""
from __future__ import annotations

import csv
from pathlib import Path


def read_progress(run_dir, name: str = "progress.csv") -> dict:
    """A run's csv log as columns of floats ({} when it has no rows or no such file)."""
    path = Path(run_dir) / name
    rows = list(csv.DictReader(open(path))) if path.exists() else []
    return {k: [float(r[k]) for r in rows] for k in (rows[0].keys() if rows else [])}


def smooth(d: dict, min_episodes: int = 2048) -> dict:
    """Merge consecutive rows until each covers >= ``min_episodes`` episodes
    (SAC logs every vector step, 64 episodes: too noisy to read)."""
    out = {k: [] for k in ("timesteps", "success_rate", "mean_reward")}
    acc = {"n": 0.0, "s": 0.0, "r": 0.0}
    for t, n, sr, mr in zip(d["timesteps"], d["episodes"], d["success_rate"], d["mean_reward"]):
        acc["n"] += n; acc["s"] += sr * n; acc["r"] += mr * n
        if acc["n"] >= min_episodes:
            out["timesteps"].append(t)
            out["success_rate"].append(acc["s"] / acc["n"])
            out["mean_reward"].append(acc["r"] / acc["n"])
            acc = {"n": 0.0, "s": 0.0, "r": 0.0}
    return out


def pyplot():
    """matplotlib's pyplot on the file-only Agg backend, imported on first
    use (plotting is optional: nothing imports matplotlib at module level)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save_figure(fig, path) -> None:
    """Lay ``fig`` out, write it to ``path`` (creating the folder) and close it."""
    import matplotlib.pyplot as plt

    fig.tight_layout()
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_runs(run_dirs, out, labels=None) -> None:
    plt = pyplot()

    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
    for k, rd in enumerate(run_dirs):
        d = read_progress(rd)
        if not d:
            continue
        d = smooth(d)
        label = labels[k] if labels else Path(rd).name
        line, = axes[0].plot(d["timesteps"], d["success_rate"], label=label)
        axes[1].plot(d["timesteps"], d["mean_reward"], label=label)
        held = read_progress(rd, "evaluations.csv")
        if held:
            axes[0].plot(held["timesteps"], held["success_rate"], marker="o", ls="--", color=line.get_color(),
                         label=f"{label}, held-out")
    axes[0].set_ylabel("success rate (training: >= 2048 episodes/point)")
    axes[1].set_ylabel("mean episode reward")
    for ax in axes:
        ax.set_xlabel("env steps")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    save_figure(fig, out)


def plot_held_out(run_dirs, out, labels=None) -> None:
    """Held-out success (``evaluations.csv``) with its 95% interval against
    training seconds (evaluations excluded): runs of different paces compared
    at equal wall time."""
    logs = [read_progress(rd, "evaluations.csv") for rd in run_dirs]
    for rd, held in zip(run_dirs, logs):
        if not held:
            raise ValueError(f"{rd} has no evaluations.csv (train with train.eval_every > 0)")
    plt = pyplot()

    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    for k, (rd, held) in enumerate(zip(run_dirs, logs)):
        label = labels[k] if labels else Path(rd).name
        line, = ax.plot(held["train_s"], held["success_rate"], marker="o", label=label)
        ax.fill_between(held["train_s"], held["ci_low"], held["ci_high"], color=line.get_color(), alpha=0.15)
    ax.set_xlabel("training seconds (evaluations excluded)")
    ax.set_ylabel("held-out success rate (95% interval)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    save_figure(fig, out)
