#!/usr/bin/env python
"""Tune hyper-parameters with Optuna (TPE sampler, median pruner on held-seed evaluations).

    python scripts/tune.py --env Billiards-PotOne-v1 --algo ppo --trials 30
    python scripts/tune.py --env Billiards-PotOne-v1 --algo ppo --trials 30 --storage postgresql://user@host/db
    python scripts/tune.py --config configs/ppo_direct.yaml --trials 12 --steps 1000000   # another config's block

Each trial trains with hyper-parameters drawn from agents.tuning.SPACES and
is evaluated on held seeds --evals times; trials below the median of earlier
trials at the same evaluation are pruned. The study is stored in
<run-dir>/study.db (SQLite) unless --storage names another database; rerun
the same command to resume it (--trials counts finished trials). Writes
study_summary.json, best_overrides.yaml and importance.png to the run directory.
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--env", default="Billiards-PotOne-v1")
    ap.add_argument("--algo", default="ppo", choices=["ppo", "sac"])
    ap.add_argument("--trials", type=int, default=20, help="finished trials wanted in the study")
    ap.add_argument("--storage", default=None, help="Optuna storage URL (default sqlite:///<run-dir>/study.db)")
    ap.add_argument("--study-name", default=None, help="default <algo>_<env>")
    ap.add_argument("--steps", type=int, default=200_000, help="env steps per trial")
    ap.add_argument("--evals", type=int, default=5, help="held-seed evaluations per trial (pruning points)")
    ap.add_argument("--eval-episodes", type=int, default=1000)
    ap.add_argument("--startup-trials", type=int, default=5, help="random trials before TPE and pruning")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="fixed override for every trial (not sampled; repeatable)")
    ap.add_argument("--run-dir", default=None, help="default runs/tune_<algo>_<env>")
    ap.add_argument("--config", default=None,
                    help="YAML the trials start from (default configs/<algo>.yaml), e.g. configs/ppo_direct.yaml")
    ap.add_argument("--quick", action="store_true",
                    help="smoke test: 2,048 steps per trial, 2 evaluations of 50 episodes, a tiny network")
    a = ap.parse_args(argv)
    if a.quick:
        a.steps, a.evals, a.eval_episodes, a.startup_trials = 2048, 2, 50, 2
        a.set = ["n_envs=64", "policy.net_arch=[16]", "ppo.n_steps=8", "ppo.batch_size=256"] + a.set \
            if a.algo == "ppo" else ["n_envs=64", "policy.net_arch=[16]", "sac.learning_starts=256"] + a.set

    from agents.tuning import Trials, tune

    short = a.env.replace("Billiards-", "").replace("-v1", "").lower()
    run_dir = Path(a.run_dir) if a.run_dir else ROOT / "runs" / f"tune_{a.algo}_{short}"
    t0 = time.perf_counter()
    trials = Trials(a.steps, a.evals, a.eval_episodes, a.seed, tuple(a.set), a.startup_trials)
    summary = tune(a.env, a.algo, a.trials, run_dir, a.storage, a.study_name, trials, a.config)
    print(json.dumps(summary, indent=2, default=float))
    print(f"{summary['finished_trials']} finished trials ({summary['pruned']} pruned) in {run_dir}; "
          f"this run: {time.perf_counter() - t0:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
