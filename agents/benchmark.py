"""The agents' benchmark table (what ``scripts/benchmark_agents.py`` runs).

For every task and algorithm with a block in ``configs/<algo>.yaml``: train
with that config (its own budget, or the ``steps`` given, which the table
then labels as a short budget), evaluating the policy on held seeds during
training (the learning curve, ``HeldOutEvaluation``); then evaluate the
final model on ``episodes`` held tables (``agents.evaluation.harness.evaluate``,
seed ``EVAL_SEED``) without noise and with ``tournament`` noise. One row
per run: config, budget in env steps, training wall time (held-seed
evaluations excluded), env steps/s including the updates, time to beat the
ghost-ball baseline, success with its 95% interval under both noise
settings, mean reward and balls per episode.
"""
from __future__ import annotations

import dataclasses
import json
import time
from pathlib import Path

from .config import CONFIG_DIR, load_config, load_run_config

TASKS = ("Billiards-PotOne-v1", "Billiards-RunOut-v1", "Billiards-NineBall-v1", "Billiards-NineBall2P-v1",
         "Billiards-EightBall-v1")  # the games: against the ghost-ball game policy (configs/ppo_games.yaml)
ALGOS = ("ppo", "sac")


@dataclasses.dataclass(frozen=True)
class Budget:
    """What each row of the table is trained and measured with: ``steps``
    (env steps; None: the config's ``total_timesteps``), ``episodes`` held
    tables of the final evaluation, ``curve_points`` held-seed evaluations
    of ``curve_episodes`` tables during training, and ``extra`` dotted
    config overrides."""

    steps: int | None = None
    episodes: int = 1000
    curve_points: int = 10
    curve_episodes: int = 1000
    extra: tuple = ()
# The configs beside configs/<algo>.yaml whose rows the published table holds (``--all`` trains them too).
TABLE_CONFIGS = ("ppo_direct.yaml", "ppo_nineball.yaml", "ppo_games.yaml")
EVAL_SEED = 12345
NOISES = ("none", "tournament")


def config_file(algo: str, config=None) -> Path:
    """The YAML a run reads: ``config`` if given, else ``configs/<algo>.yaml``."""
    return Path(config) if config is not None else CONFIG_DIR / f"{algo}.yaml"


def config_label(path: Path) -> str:
    """How the table names a config file: relative to the repository when inside it."""
    path = Path(path).resolve()
    root = CONFIG_DIR.resolve().parent
    return str(path.relative_to(root)) if path.is_relative_to(root) else str(path)


def configured(algo: str, env_id: str, config=None) -> bool:
    import yaml
    doc = yaml.safe_load(config_file(algo, config).read_text()) or {}
    return env_id in doc and (doc[env_id] or {}).get("algo", algo) == algo


def run_one(env_id: str, algo: str, out_dir: Path, b: Budget, command: str = "", config=None) -> dict:
    from .sb3.training import train

    steps, episodes, curve_points, curve_episodes, extra = b.steps, b.episodes, b.curve_points, b.curve_episodes, b.extra
    path = config_file(algo, config)
    cfg0 = load_config(path, env_id, list(extra), algo=algo)
    budget = int(steps or cfg0.train.total_timesteps)
    over = [f"train.total_timesteps={budget}", f"train.eval_every={max(budget // curve_points, 1)}",
            f"train.eval_every_episodes={curve_episodes}", "train.eval_episodes=0", "train.progress_bar=false",
            "train.tensorboard=false", "train.checkpoint_every=0", *extra]
    cfg = load_config(path, env_id, over, algo=algo)
    short = env_id.replace("Billiards-", "").replace("-v1", "").lower()
    variant = "" if config is None else "_" + Path(config).stem
    run_dir = out_dir / "runs" / f"{algo}_{short}{variant}"
    s = train(cfg, run_dir, f"benchmark_agents {algo} {env_id} steps={budget}")
    return _row(s, run_dir, run_dir / "evaluations.csv", path, cfg0, out_dir, episodes, extra, command)


def _row(s: dict, run_dir: Path, curve: Path, path: Path, cfg0, out_dir: Path, episodes: int, extra,
         command: str) -> dict:
    """The table's row of a trained run: its summary ``s``, the final model
    of ``run_dir`` evaluated on ``episodes`` held tables under each noise."""
    from .sb3.policy import SB3Policy
    from .evaluation.harness import evaluate, game_opponent

    env_id, algo = s["env_id"], s["algo"]
    pol = SB3Policy.load(run_dir, name=algo)
    kw = game_opponent(env_id, pol.env_kwargs, None)  # a self-play run's games: against ghost
    evals = {nz: evaluate(lambda env: pol.bind(env), env_id, episodes, EVAL_SEED, nz, name=algo,
                          env_kwargs=kw).to_dict()
             for nz in NOISES}
    held = s["held_out"]
    return dict(env_id=env_id, algo=algo, config=config_label(path), overrides=list(extra),
                budget_steps=s["timesteps"], config_budget_steps=int(cfg0.train.total_timesteps),
                train_wall_s=s["train_wall_s"], env_steps_per_s=s["env_steps_per_s"],
                ghost_success=held["ghost_target"], steps_to_beat_ghost=held["steps_to_target"],
                time_to_beat_ghost_s=held["time_to_target_s"], curve=str(curve.relative_to(out_dir)),
                eval=evals, command=command)


def row_from_run(run_dir, out_dir, episodes: int = 1000, command: str = "", config=None) -> dict:
    """The row of a run trained with ``scripts/train.py`` (e.g. one too long
    to repeat): its ``train_summary.json`` and held-seed curve
    (``evaluations.csv``, copied into ``out_dir``; the run needs
    ``train.eval_every`` > 0), the final model evaluated here. ``config``:
    the YAML the run was started from, for the table's label (default: the
    run's resolved ``config.yaml``)."""
    import shutil

    run_dir, out_dir = Path(run_dir), Path(out_dir)
    s = json.loads((run_dir / "train_summary.json").read_text())
    if not s.get("held_out") or not (run_dir / "evaluations.csv").exists():
        raise ValueError(f"{run_dir}: no held-seed curve (train with train.eval_every > 0)")
    path = Path(config) if config is not None else run_dir / "config.yaml"
    cfg0 = load_run_config(run_dir)
    curve = out_dir / "runs" / run_dir.name / "evaluations.csv"
    curve.parent.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(run_dir / "evaluations.csv", curve)
    return _row(s, run_dir, curve, path, cfg0, out_dir, episodes, (), command)


def store_row(out_dir, row: dict) -> list[dict]:
    """Put ``row`` into ``out_dir/benchmark.json`` in place of the row of the
    same (task, algo, config); returns all rows, in the table's order."""
    path = Path(out_dir) / "benchmark.json"
    rows = json.loads(path.read_text()) if path.exists() else []
    key = (row["env_id"], row["algo"], row["config"])
    rows = [r for r in rows if (r["env_id"], r["algo"], r["config"]) != key] + [row]
    rows.sort(key=lambda r: (TASKS.index(r["env_id"]) if r["env_id"] in TASKS else len(TASKS),
                             ALGOS.index(r["algo"]), r["config"] != f"configs/{r['algo']}.yaml", r["config"]))
    path.write_text(json.dumps(rows, indent=2))
    return rows


def table_configs() -> list:
    """Every config of the published table: the default ``configs/<algo>.yaml`` (None), then ``TABLE_CONFIGS``."""
    return [None] + [CONFIG_DIR / name for name in TABLE_CONFIGS]


def run_benchmark(out_dir, tasks=TASKS, algos=ALGOS, budget: Budget = Budget(), command: str = "", config=None,
                  configs: list | None = None) -> list[dict]:
    """Train and evaluate every configured (task, algo) of ``tasks`` x
    ``algos`` (from ``config``, default ``configs/<algo>.yaml``; or from each
    of ``configs``, e.g. ``table_configs()``); the rows replace those of the
    same (task, algo, config) in ``out_dir/benchmark.json`` (the others are
    kept); returns all rows."""
    if configs is not None:
        rows = []
        for c in configs:
            rows = run_benchmark(out_dir, tasks, algos, budget, command, c)
        return rows
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    path = out_dir / "benchmark.json"
    # rows of earlier invocations stay unless this one reruns their (task, algo, config)
    rows = json.loads(path.read_text()) if path.exists() else []
    for env_id in tasks:
        for algo in algos:
            if not configured(algo, env_id, config):
                print(f"skip {algo} on {env_id}: no {algo} block in {config_file(algo, config)}", flush=True)
                continue
            t = time.perf_counter()
            row = run_one(env_id, algo, out_dir, budget, command, config)
            rows = store_row(out_dir, row)
            print(f"{algo} {env_id}: {time.perf_counter() - t:.0f} s", flush=True)
    return rows


def _ci(e: dict) -> str:
    return f"{e['success_rate']:.3f} [{e['success_ci95'][0]:.3f}, {e['success_ci95'][1]:.3f}]"


def curve_reach(curve_csv, target: float) -> tuple[float, int] | None:
    """(training s, env steps) of the first held-seed evaluation of a curve
    (``evaluations.csv``) whose success is at least ``target``; None if none is."""
    import csv

    with open(curve_csv, newline="") as f:
        for p in csv.DictReader(f):
            if float(p["success_rate"]) >= target:
                return float(p["train_s"]), int(p["timesteps"])
    return None


def _when(t_steps) -> str:
    if t_steps is None:
        return "not within the run"
    return "from the start" if t_steps[1] == 0 else f"{t_steps[0]:.0f} s / {t_steps[1]:,} steps"


def markdown_table(rows: list[dict], out_dir) -> str:
    """The table of ``rows`` (their curve paths relative to ``out_dir``)."""
    head = ["task", "algo", "config", "budget (env steps)", "train wall (s)", "env steps/s", "reaches ghost after",
            "beats ghost after", "success, no noise", "success, tournament", "mean reward", "balls/episode"]
    lines = ["| " + " | ".join(head) + " |", "|" + "|".join("---" for _ in head) + "|"]
    for r in rows:
        short = "" if r["budget_steps"] >= r["config_budget_steps"] else \
            f" (short; config: {r['config_budget_steps']:,})"
        reach = _when(curve_reach(Path(out_dir) / r["curve"], r["ghost_success"]))
        ghost = _when(None if r["steps_to_beat_ghost"] is None else
                      (r["time_to_beat_ghost_s"], r["steps_to_beat_ghost"]))
        e0, e1 = r["eval"]["none"], r["eval"]["tournament"]
        cfg = r["config"] + ("".join(f" `{o}`" for o in r["overrides"]) if r["overrides"] else "")
        lines.append("| " + " | ".join([
            r["env_id"].replace("Billiards-", ""), r["algo"].upper(), cfg, f"{r['budget_steps']:,}{short}",
            f"{r['train_wall_s']:.0f}", f"{r['env_steps_per_s']:,.0f}", reach, ghost, _ci(e0), _ci(e1),
            f"{e0['mean_reward']:.3f}", f"{e0['balls_per_episode']:.2f}"]) + " |")
    commands = list(dict.fromkeys(r.get("command", "") for r in rows if r.get("command")))
    if commands:
        lines += ["", "Commands that produced the rows:", "", "```bash", *commands, "```"]
    return "\n".join(lines)


def plot_curves(rows: list[dict], out) -> None:
    """Held-seed success against training time, one panel per task, with the
    ghost-ball baseline's success as a dashed line (``out`` in the directory
    the rows' curve paths are relative to)."""
    import csv

    from .plotting import pyplot, save_figure

    plt = pyplot()

    tasks = list(dict.fromkeys(r["env_id"] for r in rows))
    fig, axes = plt.subplots(1, len(tasks), figsize=(4.5 * len(tasks), 3.6), squeeze=False)
    for ax, env_id in zip(axes[0], tasks):
        for r in (r for r in rows if r["env_id"] == env_id):
            with open(Path(out).parent / r["curve"], newline="") as f:
                pts = list(csv.DictReader(f))
            ax.plot([float(p["train_s"]) for p in pts], [float(p["success_rate"]) for p in pts], marker="o",
                    ms=3, label=r["algo"].upper() + ("" if r["config"] == f"configs/{r['algo']}.yaml"
                                                    else f" ({Path(r['config']).stem})"))
        ghost = next(r for r in rows if r["env_id"] == env_id)["ghost_success"]  # the first row's (the table's order)
        ax.axhline(ghost, ls="--", color="grey", label=f"ghost-ball {ghost:.3f}")
        ax.set_title(env_id.replace("Billiards-", ""))
        ax.set_xlabel("training wall time (s)")
        ax.set_ylabel("held-seed success (no noise)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    save_figure(fig, out)
