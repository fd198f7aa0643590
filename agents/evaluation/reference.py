"""The reference agents of the benchmark: PPO and SAC trained on every task of the protocol, one run per
evaluation seed, each scored under the protocol, then aggregated with the reference bots' rows.

    python -m agents.evaluation.reference --out results/suite/agents          # the whole table (resumable)
    python -m agents.evaluation.reference --algo ppo --task PotOne --seed 0    # one cell
    python -m agents.evaluation.reference --quick                              # the pipeline, about a minute
    python -m agents.evaluation.reference --out results/suite/agents --reference   # and file the rows

Each (algorithm, task, seed) is one unit: ``scripts/train.py``'s training (``agents.sb3.training``) with the
task's block of ``configs/benchmark_<algo>.yaml`` at the budget (the protocol's, or the block's own
``train.total_timesteps`` where it is smaller: SAC), the seed as the training seed, a held-seed evaluation at the
protocol's noise every ``1 / CURVE_POINTS`` of the budget (the learning curve); then the scoring command's
``score`` of the trained model as run ``seed`` (its held tables, ``EVAL_SEEDS[seed]``). Units are done in
order, algorithm by algorithm and task by task; a unit whose results file exists is skipped, a unit whose
training stopped resumes from its newest checkpoint, so the command picks up where a stopped run left off.
Training runs live under ``--work`` (default ``runs/reference``); ``--out`` (default a new run folder
``runs/reference_<timestamp>``, never the committed ``results/`` unless named) gets the results files
(``<algo>/<Task>/seed<k>.json``, each with its training's figures, learning curve and wall times), ``table.md``
(the generated table docs/benchmark.md links), ``aggregate.json``/``aggregate.png`` and ``curves.png``.
``--jobs 2`` trains the algorithms side by side in two processes (SAC's updates keep one core busy, PPO's
self-play tables the other).
"""
from __future__ import annotations

import argparse
import json
import shutil
import sys
import time
from pathlib import Path

import yaml

from billiards_env.benchmark import aggregate_docs, plot_aggregate, table
from billiards_env.benchmark.protocol import PROTOCOL, QUICK, Task
from billiards_env.benchmark.score import check_results, rows_of

ROOT = Path(__file__).resolve().parents[2]
ALGOS = ("ppo", "sac")
SEEDS = tuple(range(PROTOCOL.runs))   # training seed k is scored as protocol run k
CURVE_POINTS = 4                      # held-seed evaluations per training run (plus the one at step 0)
CURVE_EPISODES = {"task": 100, "game": 50}  # tables per curve point: a curve, not a score (games cost more)
QUICK_TASKS = "PotOne,NineBall2P"     # quick mode: one one-player task and one game ...
QUICK_SEEDS = (0, 1)                  # ... two seeds (QUICK's two runs) ...
QUICK_STEPS = {"ppo": 4096, "sac": 512}  # ... a few thousand env steps: the pipeline, not a score
QUICK_SETTINGS = {"ppo": ["n_envs=64", "train.env_workers=1", "train.overlap_updates=false", "ppo.n_steps=32",
                          "ppo.batch_size=512", "train.eval_every_episodes=8",
                          "train.checkpoint_every=2048"],
                  "sac": ["n_envs=16", "sac.learning_starts=128", "sac.batch_size=64", "train.eval_every_episodes=8",
                          "train.checkpoint_every=256"]}


def config_path(algo: str) -> Path:
    return ROOT / "configs" / f"benchmark_{algo}.yaml"


def budget_of(algo: str, task: Task, quick: bool = False) -> int:
    """The env steps ``algo`` trains on ``task``: the block's ``train.total_timesteps`` if it names one (it may
    not exceed the protocol's budget), else the protocol's."""
    if quick:
        return QUICK_STEPS[algo]
    doc = yaml.safe_load(config_path(algo).read_text())
    if task.env_id not in doc:
        raise ValueError(f"{config_path(algo)} has no block for {task.env_id}")
    own = (doc[task.env_id].get("train") or {}).get("total_timesteps")
    if own is not None and own > task.budget:
        raise ValueError(f"{config_path(algo)} [{task.env_id}]: train.total_timesteps {own:,} exceeds the "
                         f"protocol's budget {task.budget:,}")
    return int(own) if own is not None else task.budget


def train_unit(algo: str, task: Task, seed: int, run_dir: Path, quick: bool) -> dict:
    """Train (or resume) one unit; the run's ``train_summary.json``."""
    from agents.config import load_config
    from agents.sb3.training import train_and_evaluate

    summary = run_dir / "train_summary.json"
    if summary.exists():
        return json.loads(summary.read_text())
    command = f"python -m agents.evaluation.reference --algo {algo} --task {task.name} --seed {seed}"
    if (run_dir / "checkpoints").is_dir() and any((run_dir / "checkpoints").iterdir()):
        print(f"  resuming {run_dir}", flush=True)
        train_and_evaluate(None, run_dir, command, time.perf_counter(), resume=True)
        return json.loads(summary.read_text())
    if run_dir.exists():   # stopped before its first checkpoint: nothing to resume
        shutil.rmtree(run_dir)
    budget = budget_of(algo, task, quick)
    overrides = [f"train.total_timesteps={budget}", f"train.seed={seed}",
                 f"train.eval_every={max(budget // CURVE_POINTS, 1)}",
                 f"train.eval_every_episodes={CURVE_EPISODES[task.kind]}",
                 f"train.eval_opponent={task.opponent or 'ghost'}"] + (QUICK_SETTINGS[algo] if quick else [])
    cfg = load_config(config_path(algo), task.env_id, overrides)
    train_and_evaluate(cfg, run_dir, command, time.perf_counter())
    return json.loads(summary.read_text())


def score_unit(algo: str, task: Task, seed: int, run_dir: Path, budget: int, quick: bool) -> dict:
    from .benchmark import score
    doc = score(str(run_dir), task.env_id, quick=quick, runs=[seed], name=f"{algo.upper()} seed {seed}",
                algorithm=algo.upper(), budget=budget,
                command=f"python -m agents.evaluation.benchmark score --policy {run_dir} --task {task.name} "
                        f"--run {seed} --algorithm {algo.upper()} --budget {budget}")
    return doc


def run(algos, tasks, seeds, work: Path, out: Path, quick: bool = False) -> None:
    """Train and score every unit not done yet (``collect`` reads them all back for the table)."""
    units = [(a, t, s) for a in algos for t in tasks for s in seeds]
    for i, (algo, task, seed) in enumerate(units):
        path = out / algo / task.name / f"seed{seed}.json"
        key = f"{algo}/{task.name}/seed{seed}"
        if path.exists():
            continue
        print(f"[{i + 1}/{len(units)}] {key}: training", flush=True)
        t0 = time.perf_counter()
        run_dir = work / algo / task.name / f"seed{seed}"
        summary = train_unit(algo, task, seed, run_dir, quick)
        t1 = time.perf_counter()
        doc = score_unit(algo, task, seed, run_dir, int(summary["timesteps"]), quick)
        doc["training"] = {"run_dir": str(run_dir), "timesteps": summary["timesteps"],
                           "train_wall_s": summary["train_wall_s"], "env_steps_per_s": summary["env_steps_per_s"],
                           "curve": _curve(run_dir), "unit_train_s": round(t1 - t0, 1),
                           "unit_score_s": round(time.perf_counter() - t1, 1)}
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(doc, indent=1) + "\n")


def _curve(run_dir: Path) -> list:
    """The learning curve: (env steps, success or win rate) of the held-seed evaluations."""
    import csv
    path = run_dir / "evaluations.csv"
    if not path.exists():
        return []
    with open(path) as f:
        return [[int(r["timesteps"]), float(r["success_rate"])] for r in csv.DictReader(f)]


def plot_curves(docs, path) -> Path:
    """Learning curves per task: each seed's held-seed evaluations (thin) and their mean (thick), per algorithm."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    tasks = [t.env_id for t in PROTOCOL.tasks if any(t.env_id in d["tasks"] for d in docs)]
    cols = 4
    rows = max(1, -(-len(tasks) // cols))
    fig, axes = plt.subplots(rows, cols, figsize=(3.4 * cols, 2.7 * rows), squeeze=False)
    for ax, task in zip(axes.flat, tasks):
        for j, algo in enumerate(sorted({d["algorithm"] for d in docs})):
            curves = [d["training"]["curve"] for d in docs if d["algorithm"] == algo and task in d["tasks"]
                      and d.get("training", {}).get("curve")]
            for c in curves:
                ax.plot(*np.array(c).T, color=f"C{j}", lw=0.6, alpha=0.4)
            if curves and len({len(c) for c in curves}) == 1:
                a = np.array(curves)   # [seeds, points, 2]
                ax.plot(a[0, :, 0], a[:, :, 1].mean(0), color=f"C{j}", lw=2, label=algo)
        ax.set_title(task.removeprefix("Billiards-"), fontsize=9)
        ax.set_xlabel("env steps", fontsize=8)
        ax.set_ylabel("success / win rate", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.legend(fontsize=7)
    for ax in list(axes.flat)[len(tasks):]:
        ax.axis("off")
    fig.suptitle("learning curves: held tables at the protocol's noise (games: against its opponent)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return Path(path)


def _wall(doc) -> float:
    """Wall time of a unit: its training (with the learning curve's evaluations) and its scoring."""
    t = doc.get("training", {})
    return t.get("unit_train_s", 0.0) + t.get("unit_score_s", 0.0)


def per_task_table(docs) -> str:
    """Markdown: per task and algorithm, the budget, the five runs' scores, their mean and normalized mean,
    env steps/s and wall time."""
    from billiards_env.benchmark.score import normalized_score
    lines = ["| task | algorithm | budget (env steps) | score per run (seed 0-4) | mean | normalized | "
             "env steps/s (median) | train + score wall (s) |", "|---|---|---|---|---|---|---|---|"]
    for task in PROTOCOL.tasks:
        for algo in ALGOS:
            mine = sorted((d for d in docs if d["algorithm"] == algo.upper() and task.env_id in d["tasks"]),
                          key=lambda d: d["tasks"][task.env_id]["runs"][0]["run"])
            if not mine:
                continue
            scores = [d["tasks"][task.env_id]["runs"][0]["score"] for d in mine]
            mean = sum(scores) / len(scores)
            try:
                norm = f"{float(normalized_score(task.env_id, mean)):.2f}"
            except ValueError:
                norm = "-"
            rates = sorted(d["training"]["env_steps_per_s"] for d in mine)
            wall = sum(_wall(d) for d in mine)
            lines.append(f"| `{task.env_id}` | {algo.upper()} | {mine[0]['budget']:,} | "
                         f"{', '.join(f'{s:.3f}' for s in scores)} | {mean:.3f} | {norm} | "
                         f"{rates[len(rates) // 2]:,.0f} | {wall:,.0f} |")
    return "\n".join(lines)


def collect(out: Path, quick: bool = False) -> list:
    """Every unit's results file in ``out`` (of the protocol's tasks, in the protocol's order): what the table
    covers, whichever call trained the units (a rerun of one task rewrites the whole table)."""
    proto = QUICK if quick else PROTOCOL
    docs = []
    for algo in ALGOS:
        for task in proto.tasks:
            for path in sorted((out / algo / task.name).glob("seed*.json")):
                docs.append(check_results(json.loads(path.read_text())))
    return docs


def table_text(docs, quick: bool = False) -> str:
    """``table.md``'s text: the per-task table, the aggregate with the reference bots (full protocol) and the
    units' wall time (scripts/regenerate.py renders it from the committed unit files with this function)."""
    parts = [f"<!-- generated by python -m agents.evaluation.reference (protocol {PROTOCOL.version}); "
             f"do not edit -->", "", per_task_table(docs), ""]
    if not quick:
        parts += ["Aggregate with the reference bots (normalized scores; IQM and optimality gap with 95% "
                  "stratified-bootstrap intervals):", "", table(aggregate_docs(docs)), ""]
    total = sum(_wall(d) for d in docs)
    parts += [f"Wall time of the {len(docs)} units, added up: {total / 3600:.2f} h (training with its learning "
              f"curve, and scoring; side by side with `--jobs 2` the table takes less; see docs/benchmark.md)."]
    return "\n".join(parts) + "\n"


def report(docs, out: Path, quick: bool) -> None:
    """``table.md``, ``curves.png`` and (full protocol) ``aggregate.json``/``aggregate.png`` in ``out``."""
    if not quick:
        agg = aggregate_docs(docs)
        (out / "aggregate.json").write_text(json.dumps(agg, indent=1) + "\n")
        plot_aggregate(agg, out / "aggregate.png")
    (out / "table.md").write_text(table_text(docs, quick))
    plot_curves(docs, out / "curves.png")


def file_reference(docs) -> Path:
    """Merge the agents' rows (one per algorithm and task, its runs in seed order) into reference.json."""
    from billiards_env.benchmark.score import REFERENCE_FILE, SCHEMA, load_reference, write_reference
    merged: dict = {}
    for d in docs:
        for row in rows_of(d):
            m = merged.setdefault((row.task, row.algorithm), {"budget": row.budget, "runs": {}})
            m["runs"][d["tasks"][row.task]["runs"][0]["run"]] = row.scores[0]
    keep = [r for r in load_reference() if (r.task, r.algorithm) not in merged]
    base = {"schema": SCHEMA, "protocol": PROTOCOL.version, "quick": False, "policy": ""}
    out = [dict(base, algorithm=a, budget=m["budget"],
                tasks={t: {"runs": [{"score": m["runs"][k]} for k in sorted(m["runs"])]}})
           for (t, a), m in merged.items()]
    out += [dict(base, algorithm=r.algorithm, budget=r.budget, tasks={r.task: {"runs": [{"score": s}
                                                                                        for s in r.scores]}})
            for r in keep]
    return write_reference(out, REFERENCE_FILE)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--algo", default="ppo,sac", help="ppo, sac or both (comma-separated)")
    ap.add_argument("--task", default=None, help="all (default), or ids / short names, comma-separated")
    ap.add_argument("--seed", type=int, action="append", default=None, help="seeds 0-4 (repeatable; default all)")
    ap.add_argument("--quick", action="store_true", help="two tasks, two seeds, a few thousand steps: the pipeline")
    ap.add_argument("--work", default=None, help="training runs (default runs/reference, quick: runs/reference_quick)")
    ap.add_argument("--out", default=None, help="results, table and plots (default a new runs/reference_<time>/)")
    ap.add_argument("--reference", action="store_true", help="merge the rows into billiards_env/benchmark/reference.json")
    ap.add_argument("--jobs", type=int, default=1, help="algorithms trained side by side, one process each")
    ap.add_argument("--units-only", action="store_true", help=argparse.SUPPRESS)  # --jobs' children
    a = ap.parse_args(argv)
    algos = tuple(x.strip() for x in a.algo.split(",") if x.strip())
    if not algos or any(x not in ALGOS for x in algos):
        ap.error(f"--algo takes {', '.join(ALGOS)}, got {a.algo!r}")
    proto = QUICK if a.quick else PROTOCOL
    tasks = proto.select(a.task or (QUICK_TASKS if a.quick else "all"))
    seeds = tuple(a.seed) if a.seed else (QUICK_SEEDS if a.quick else SEEDS)
    if any(not 0 <= s < PROTOCOL.runs for s in seeds):
        ap.error(f"--seed takes 0..{PROTOCOL.runs - 1}")
    if a.reference and a.quick:
        ap.error("--reference takes full-protocol rows, not --quick ones")
    work = Path(a.work) if a.work else ROOT / "runs" / ("reference_quick" if a.quick else "reference")
    out = Path(a.out) if a.out else ROOT / "runs" / time.strftime("reference_%Y%m%d-%H%M%S")
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    if a.jobs > 1 and len(algos) > 1:   # one child per algorithm, then the report over all of them
        import subprocess
        base = [sys.executable, "-m", "agents.evaluation.reference", "--work", str(work), "--out", str(out),
                "--units-only"]
        base += (["--quick"] if a.quick else []) + (["--task", a.task] if a.task else [])
        base += [f"--seed={s}" for s in (a.seed or [])]
        procs = [subprocess.Popen(base + ["--algo", algo], cwd=ROOT) for algo in algos]
        if any([p.wait() for p in procs]):  # wait for every child, not only up to the first that failed
            print("a child failed; rerun the same command to resume", file=sys.stderr)
            return 1
    run(algos, tasks, seeds, work, out, a.quick)
    if a.units_only:
        return 0
    docs = collect(out, a.quick)
    report(docs, out, a.quick)
    print(f"{len(docs)} units; wrote {out / 'table.md'} and {out / 'curves.png'} "
          f"({time.perf_counter() - t0:.0f} s this call)")
    if a.reference:
        print(f"wrote {file_reference(docs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
