"""The benchmark's scoring command: a policy scored under the protocol (``billiards_env.benchmark``).

    python -m agents.evaluation.benchmark score --policy ghost --task all            # a bot
    python -m agents.evaluation.benchmark score --policy mypkg.bots:make --task PotOne
    python -m agents.evaluation.benchmark score --policy runs/ppo_potone --task PotOne --run 0 --budget 500000
    python -m agents.evaluation.benchmark score --policy random --task all --quick   # the pipeline, in seconds
    python -m agents.evaluation.benchmark aggregate runs/benchmark/*/results.json

``--policy``: a bot name (the one-player baselines ``random``, ``ghost``, ``search<K>``, ``lookahead`` on the
one-player tasks; any ``billiards_env.bots.make_bot`` name on the games), a ``module:factory`` (the factory,
called with ``seed=``, returns a bot: a one-player bot on the tasks, a game bot on the games), or a saved model
(a run directory or model file of either training backend, ``harness.load_trained``). Each task is played
through the evaluation harness (``harness.evaluate``: seeded batches of tables, the first episode of each,
success = the task's success or a won game); run k of the protocol seeds the policy k and plays the tables of
``EVAL_SEEDS[k]``. The results JSON (schema: docs/benchmark.md) and a plot go to a new run folder,
``runs/benchmark/<timestamp>/``, unless ``--out`` names one.

Why here and not in ``billiards_env``: scoring a saved model needs stable-baselines3 / RLlib, which live in
``agents`` above the library (tests/test_imports.py), and the harness it reuses is this package's. The library
keeps what needs no agent: the protocol, normalization, reference rows and aggregation
(``python -m billiards_env.benchmark aggregate`` works without torch).
"""
from __future__ import annotations

import argparse
import datetime
import json
import subprocess
import sys
import time
from pathlib import Path

from billiards_env.benchmark import aggregate_files, plot_results
from billiards_env.benchmark.protocol import PROTOCOL, QUICK, Task
from billiards_env.benchmark.score import SCHEMA, normalized_score, write_reference
from billiards_env.studies.run_folder import run_folder

from .harness import evaluate, policy_factory

ROOT = Path(__file__).resolve().parents[2]


def task_policy(spec: str, task: Task, seed: int):
    """(policy_fn(env) -> policy, display name, env kwargs) of ``spec`` on ``task`` with the policy seeded ``seed``."""
    from billiards_env.bots import is_bot_name

    from .policies import GamePolicy, is_policy_name
    from ..interface.game_view import game_view_of

    kw = {"opponent": task.opponent} if task.kind == "game" else {}
    if task.kind == "game" and is_bot_name(spec):
        return (lambda env: GamePolicy(spec, game_view_of(env).env, seed=seed)), spec, kw
    if task.kind == "task" and ":" in spec and not Path(spec).exists():
        from billiards_env.bots import make_bot
        from billiards_env.bots.one_player import BotPolicy
        return (lambda env: BotPolicy(make_bot(spec, seed=seed), env)), spec, kw
    if task.kind == "task" or not is_policy_name(spec):
        fn, name, env_kwargs = policy_factory(spec, seed)
        return fn, (spec if is_policy_name(spec) else name), {**env_kwargs, **kw}
    raise ValueError(f"{spec!r} cannot play {task.env_id}")


def score_task(spec: str, task: Task, runs, eval_seeds, batch_size: int) -> dict:
    """Every run of ``spec`` on ``task``: ``{"runs": [...], "score": mean, "normalized": [...] or None}``."""
    out = []
    for k in runs:
        fn, name, kw = task_policy(spec, task, k)
        r = evaluate(fn, task.env_id, task.episodes, seed=eval_seeds[k], noise=task.noise, batch_size=batch_size,
                     env_kwargs=kw, name=name)
        out.append({"run": k, "eval_seed": eval_seeds[k], "episodes": task.episodes, "score": r.success_rate,
                    "ci95": list(r.success_ci95), "mean_reward": r.mean_reward, "wall_time_s": round(r.wall_time_s, 3)})
        print(f"  {task.env_id:<28s} run {k}  {task.metric:<24s} {r.success_rate:.3f} "
              f"[{r.success_ci95[0]:.3f}, {r.success_ci95[1]:.3f}]  ({r.wall_time_s:.1f} s)", flush=True)
    scores = [r["score"] for r in out]
    try:
        normalized = [float(v) for v in normalized_score(task.env_id, scores)]
    except ValueError:  # no reference rows yet (while measuring them)
        normalized = None
    return {"runs": out, "score": sum(scores) / len(scores), "normalized": normalized}


def _commit() -> str:
    try:
        return subprocess.run(["git", "rev-parse", "HEAD"], cwd=ROOT, capture_output=True, text=True,
                              timeout=10).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return ""


def score(spec: str, tasks: str = "all", quick: bool = False, runs=None, name: str | None = None,
          algorithm: str | None = None, budget: int | None = None, command: str = "") -> dict:
    """The results document of ``spec`` on ``tasks`` under the protocol (or its quick mode)."""
    proto = QUICK if quick else PROTOCOL
    runs = list(range(proto.runs)) if runs is None else list(runs)
    if any(not 0 <= k < len(PROTOCOL.eval_seeds) for k in runs):
        raise ValueError(f"runs are 0..{len(PROTOCOL.eval_seeds) - 1}, got {runs}")
    doc = {"schema": SCHEMA, "protocol": proto.version, "quick": quick, "policy": name or spec,
           "algorithm": algorithm or name or spec, "budget": budget, "command": command, "commit": _commit(),
           "created": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"), "tasks": {}}
    for task in proto.select(tasks):
        t0 = time.perf_counter()
        doc["tasks"][task.env_id] = score_task(spec, task, runs, PROTOCOL.eval_seeds, proto.batch_size)
        doc["tasks"][task.env_id]["wall_time_s"] = round(time.perf_counter() - t0, 3)
    return doc


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    s = sub.add_parser("score", help="score a policy under the protocol")
    s.add_argument("--policy", required=True, help="bot name, module:factory, or saved model path")
    s.add_argument("--task", default="all", help="all, or comma-separated ids / short names (PotOne,NineBall2P)")
    s.add_argument("--quick", action="store_true", help="a few episodes and two runs: the pipeline, not a score")
    s.add_argument("--run", type=int, action="append", default=None,
                   help="protocol run(s) to play (0-4; repeatable; default all): a trained agent's seed k is run k")
    s.add_argument("--name", default=None, help="the policy's name in the results (default: --policy)")
    s.add_argument("--algorithm", default=None, help="the algorithm its row is filed under (default: the name)")
    s.add_argument("--budget", type=int, default=None, help="env steps the policy trained (agents)")
    s.add_argument("--out", default=None, help="folder for results.json and results.png "
                                               "(default: a new runs/benchmark/<timestamp>/)")
    s.add_argument("--reference", action="store_true",
                   help="also merge these rows into billiards_env/benchmark/reference.json (full protocol only)")
    g = sub.add_parser("aggregate", help="aggregate results files with the reference rows")
    g.add_argument("files", nargs="+")
    g.add_argument("--out", default=None, help="folder for aggregate.json and aggregate.png (default: print only)")
    a = ap.parse_args(argv)
    if a.cmd == "aggregate":
        from billiards_env.benchmark.__main__ import main as lib_main
        return lib_main(["aggregate", *a.files] + (["--out", a.out] if a.out else []))
    if a.reference and a.quick:
        ap.error("--reference takes full-protocol scores, not --quick ones")
    command = "python -m agents.evaluation.benchmark " + " ".join(sys.argv[1:] if argv is None else argv)
    doc = score(a.policy, a.task, a.quick, a.run, a.name, a.algorithm, a.budget, command)
    out = Path(a.out) if a.out else run_folder(ROOT, "benchmark")
    out.mkdir(parents=True, exist_ok=True)
    (out / "results.json").write_text(json.dumps(doc, indent=1) + "\n")
    plot_results([doc], out / "results.png")
    print(f"wrote {out / 'results.json'} and {out / 'results.png'}")
    if a.reference:
        from billiards_env.benchmark.score import REFERENCE_FILE, rows_of, load_reference
        keep = [r for r in load_reference() if (r.task, r.algorithm) not in {(x.task, x.algorithm) for x in rows_of(doc)}]
        old = {"schema": SCHEMA, "protocol": PROTOCOL.version, "quick": False, "policy": "", "algorithm": "",
               "tasks": {}}
        docs = [doc] + [dict(old, algorithm=r.algorithm, budget=r.budget,
                             tasks={r.task: {"runs": [{"score": s} for s in r.scores]}}) for r in keep]
        print(f"wrote {write_reference(docs, REFERENCE_FILE)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
