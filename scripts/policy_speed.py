#!/usr/bin/env python
"""Decisions per second of a baseline policy on N tables at once.

    python scripts/policy_speed.py --policy lookahead --env Billiards-NineBall-v1 --tables 1024

Resets N seeded tables, lets the policy choose one shot for each (after a
warm-up call on a few tables, which compiles the kernels), and reports the
wall time of the decision, N / time, and for lookahead the shots it simulated.
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
    ap.add_argument("--policy", default="lookahead")
    ap.add_argument("--env", default="Billiards-RunOut-v1")
    ap.add_argument("--tables", type=int, default=1024)
    ap.add_argument("--repeats", type=int, default=1, help="decisions timed (the median is reported)")
    ap.add_argument("--seed", type=int, default=12345)
    a = ap.parse_args(argv)

    import numpy as np

    from agents.evaluation.policies import make_policy
    from agents.sb3.vec_env import make_sb3_vec_env

    warm = make_sb3_vec_env(a.env, 4, seed=a.seed)
    make_policy(a.policy, warm).act(warm.reset())
    env = make_sb3_vec_env(a.env, a.tables, seed=a.seed)
    obs = env.reset()
    times, sims = [], []
    for _ in range(a.repeats):
        pol = make_policy(a.policy, env, seed=a.seed)
        t = time.perf_counter()
        pol.act(obs)
        times.append(time.perf_counter() - t)
        sims.append(getattr(pol, "sims", None))
    dt = float(np.median(times))
    out = dict(policy=a.policy, env=a.env, tables=a.tables, decision_s=dt, decisions_per_s=a.tables / dt,
               simulated_shots=sims[0], simulated_shots_per_s=(sims[0] / dt) if sims[0] else None)
    print(json.dumps(out, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
