#!/usr/bin/env python
"""Evaluate saved models and/or baselines on a task over N seeded episodes.

    python scripts/evaluate.py --policy ghost --policy search --policy runs/<run> \
        --env Billiards-PotOne-v1 --episodes 1000 --seed 12345 --noise none --noise tournament \
        --out results/agents/potone

``--policy``: ``random``, ``ghost``, ``search`` (K from ``--search-k``, or
``search64``), ``lookahead`` (pots that leave a next shot), or a run directory / model .zip (its config.yaml and
vecnormalize.pkl are read). Every policy plays the first episode of the same
seeded tables. On the two-player games (``Billiards-NineBall2P-v1``,
``Billiards-EightBall-v1``) a policy's success is a won game against
``--opponent`` (``ghost-safety`` is a policy there too). Prints a Markdown table (success rate with its 95% Wilson
interval, mean reward, scratch and foul rates, balls per episode) and writes
<out>.json and <out>.png.

``--backend ray`` spreads the batches (and the search baseline's candidate
shots) over Ray tasks, on a local Ray instance or the cluster at
``--address``; results equal the local ones for the same seed and batch size.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--policy", action="append", required=True, help="baseline name or model path (repeatable)")
    ap.add_argument("--name", action="append", default=None, help="display name per --policy (optional)")
    ap.add_argument("--env", default="Billiards-PotOne-v1")
    ap.add_argument("--episodes", type=int, default=1000)
    ap.add_argument("--seed", type=int, default=12345)
    ap.add_argument("--noise", action="append", default=None,
                    help="none | tournament | key=value,... of NoiseConfig, e.g. aim_deg=1 (repeatable; default none)")
    ap.add_argument("--opponent", default=None,
                    help="two-player games: whom every policy plays (ghost, ghost-safety, search<K>, random or a "
                         "game model; default: a trained policy's training opponent, ghost for the baselines)")
    ap.add_argument("--search-k", type=int, default=256)
    ap.add_argument("--batch-size", type=int, default=1000, help="tables simulated together")
    ap.add_argument("--out", default=None, help="output prefix for .json and .png (default results/agents/eval)")
    ap.add_argument("--backend", choices=("local", "ray"), default="local",
                    help="local: this process (default); ray: batches and search candidates as Ray tasks")
    ap.add_argument("--address", default=None, help="ray: cluster to join (auto or HOST:PORT; default: local Ray)")
    a = ap.parse_args(argv)
    if a.address and a.backend != "ray":
        ap.error("--address needs --backend ray")

    from agents.evaluation.harness import evaluate_policies, evaluate_spec, format_table, save_results

    run = evaluate_spec
    if a.backend == "ray":
        from agents.rllib.evaluation import evaluate_spec as run
        from agents.rllib.backend import start_ray
        start_ray(a.address)
    results = evaluate_policies(a.policy, a.env, a.episodes, a.seed, a.noise, a.search_k, a.batch_size, a.name,
                                run=run, opponent=a.opponent)
    print()
    print(format_table(results))
    out = Path(a.out) if a.out else ROOT / "results" / "agents" / "eval"
    save_results(results, out.with_suffix(".json"), out.with_suffix(".png"))
    print(f"\nwrote {out.with_suffix('.json')} and {out.with_suffix('.png')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
