#!/usr/bin/env python
"""Train PPO (default) or SAC on a billiards task and evaluate it against the baselines.

    python scripts/train.py                                   # PotOne PPO, configs/ppo.yaml
    python scripts/train.py --config configs/sac.yaml
    python scripts/train.py --env Billiards-RunOut-v1 --set ppo.learning_rate=1e-4 --set n_envs=64
    python scripts/train.py --resume runs/<name>              # continue a stopped run (either backend)
    python scripts/train.py --backend rllib --set rllib.num_env_runners=4   # Ray RLlib (docs/distributed.md)
    python scripts/train.py --backend rllib --address auto                   # on a running Ray cluster

Writes runs/<name>/: config.yaml (resolved), command.txt, model.zip,
vecnormalize.pkl, checkpoints/, progress.csv, tb/ (TensorBoard),
learning_curve.png, train_summary.json and eval.json / eval.png (the final
evaluation of the model and the baselines on the same seeded episodes).
"""
from __future__ import annotations

import argparse
import shlex
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from agents.config import load_config  # noqa: E402
from agents.sb3.training import train_and_evaluate  # noqa: E402


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--config", default=None, help="YAML of hyper-parameters keyed by env id (default configs/ppo.yaml)")
    ap.add_argument("--env", default=None, help="env id (default: the file's default_env)")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="dotted override, e.g. ppo.learning_rate=1e-4 (repeatable)")
    ap.add_argument("--name", default=None, help="run name (default <algo>_<env>_<time>)")
    ap.add_argument("--runs-dir", default=str(ROOT / "runs"))
    ap.add_argument("--resume", default=None, metavar="RUN_DIR",
                    help="continue a stopped run (either backend) from its newest checkpoint, with its own config.yaml")
    ap.add_argument("--backend", choices=("sb3", "rllib"), default="sb3",
                    help="sb3: stable-baselines3 on this machine (default); rllib: Ray RLlib (the rllib: block)")
    ap.add_argument("--address", default=None,
                    help="rllib: Ray cluster to join (auto or HOST:PORT; default: a local Ray instance)")
    args = ap.parse_args(argv)
    if args.address and args.backend != "rllib" and not args.resume:
        ap.error("--address needs --backend rllib")

    t_start = time.perf_counter()
    command = "python " + " ".join(shlex.quote(a) for a in [sys.argv[0]] + list(argv if argv is not None else sys.argv[1:]))
    if args.resume:  # the run's own config.yaml; the command is appended to its command.txt
        from agents.rllib.policy import is_rllib_run
        if is_rllib_run(args.resume):
            from agents.rllib import backend as rllib_backend
            rllib_backend.resume(args.resume, command, t_start, address=args.address)
        else:
            train_and_evaluate(None, args.resume, command, t_start, resume=True)
        return 0
    cfg = load_config(args.config, args.env, args.set)
    short = cfg.env_id.replace("Billiards-", "").replace("-v1", "").lower()
    prefix = cfg.algo if args.backend == "sb3" else f"rllib_{cfg.algo}"
    name = args.name or f"{prefix}_{short}_{time.strftime('%Y%m%d-%H%M%S')}"
    run_dir = Path(args.runs_dir) / name
    if args.backend == "rllib":
        from agents.rllib import backend as rllib_backend
        rllib_backend.train_and_evaluate(cfg, run_dir, command, t_start, address=args.address)
        return 0
    train_and_evaluate(cfg, run_dir, command, t_start)
    return 0


if __name__ == "__main__":
    sys.exit(main())
