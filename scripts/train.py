#!/usr/bin/env python
"""Train PPO (default) or SAC on a billiards task and evaluate it against the baselines.

    python scripts/train.py                                   # PotOne PPO, configs/ppo.yaml
    python scripts/train.py --config configs/sac.yaml
    python scripts/train.py --env Billiards-RunOut-v0 --set ppo.learning_rate=1e-4 --set n_envs=64

Writes runs/<name>/: config.yaml (resolved), command.txt, model.zip,
vecnormalize.pkl, checkpoints/, progress.csv, tb/ (TensorBoard),
learning_curve.png, train_summary.json and eval.json / eval.png (the final
evaluation of the model and the baselines on the same seeded episodes).
"""
from __future__ import annotations

import argparse
import json
import shlex
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from agents.config import load_config  # noqa: E402


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--config", default=None, help="YAML of hyper-parameters keyed by env id (default configs/ppo.yaml)")
    ap.add_argument("--env", default=None, help="env id (default: the file's default_env)")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="dotted override, e.g. ppo.learning_rate=1e-4 (repeatable)")
    ap.add_argument("--name", default=None, help="run name (default <algo>_<env>_<time>)")
    ap.add_argument("--runs-dir", default=str(ROOT / "runs"))
    args = ap.parse_args(argv)

    t_start = time.perf_counter()
    cfg = load_config(args.config, args.env, args.set)
    short = cfg.env_id.replace("Billiards-", "").replace("-v0", "").lower()
    name = args.name or f"{cfg.algo}_{short}_{time.strftime('%Y%m%d-%H%M%S')}"
    run_dir = Path(args.runs_dir) / name
    command = "python " + " ".join(shlex.quote(a) for a in [sys.argv[0]] + list(argv if argv is not None else sys.argv[1:]))

    from agents.training import train
    summary = train(cfg, run_dir, command)
    print(f"trained {summary['timesteps']} steps in {summary['train_wall_s']:.1f} s "
          f"({summary['env_steps_per_s']:.0f} env steps/s incl. updates); model: {run_dir / 'model.zip'}")

    sys.path.insert(0, str(ROOT / "scripts"))
    from plot_learning_curve import plot_runs
    plot_runs([run_dir], run_dir / "learning_curve.png")

    results = []
    if cfg.train.eval_episodes > 0:
        from agents.baselines import SB3Policy, make_policy
        from agents.evaluation import evaluate, format_table, save_results

        trained = SB3Policy.load(run_dir, name=cfg.algo)
        ts = cfg.train
        for noise in ts.eval_noise:
            results.append(evaluate(lambda env: trained.bind(env), cfg.env_id, ts.eval_episodes, ts.eval_seed,
                                    noise, name=cfg.algo))
            for b in ts.eval_baselines:
                bname = f"search{ts.search_k}" if b == "search" else b
                results.append(evaluate(lambda env, b=bname: make_policy(b, env, seed=ts.eval_seed), cfg.env_id,
                                        ts.eval_episodes, ts.eval_seed, noise, name=bname))
        print(format_table(results))
        save_results(results, run_dir / "eval.json", run_dir / "eval.png")
    wall = time.perf_counter() - t_start
    summary["total_wall_s"] = wall
    summary["eval"] = [r.to_dict() for r in results]
    (run_dir / "train_summary.json").write_text(json.dumps(summary, indent=2))
    print(f"total wall time (training + evaluation): {wall:.1f} s; run directory: {run_dir}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
