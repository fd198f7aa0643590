"""Event-solver throughput in CPU time, for comparing two trees on a loaded
machine: the scenes of ``scripts/benchmark.py`` at 1024 tables on one
thread, each figure the best of ``--repeats`` runs of the process's CPU time
(other jobs add wall time, and only ever add, so the minimum of the CPU time
is the most repeatable figure). Run it in each tree in turn:

    PYTHONPATH=. python scripts/cpu_bench.py --scene 9-ball --scene two-ball
    PYTHONPATH=/other/tree python scripts/cpu_bench.py --scene 9-ball --scene two-ball
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from benchmark import SCENES  # noqa: E402  (the scenes are defined once, there)

from billiards_env.physics import PhysicsParams, Table, set_num_threads, simulate  # noqa: E402


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", action="append", help="keep scenes whose name contains this (repeatable)")
    ap.add_argument("--batch", type=int, default=1024)
    ap.add_argument("--repeats", type=int, default=7)
    args = ap.parse_args(argv)
    P, T = PhysicsParams.standard(), Table.pool(9)
    set_num_threads(1)
    for name, make in SCENES.items():
        if args.scene and not any(part in name for part in args.scene):
            continue
        s = make(args.batch, P, T, np.random.default_rng(0))
        res = simulate(s, T, P)  # compile or load from the cache
        times = []
        for _ in range(args.repeats):
            t0 = time.process_time()
            simulate(s, T, P)
            times.append(time.process_time() - t0)
        best = min(times)
        print(f"{name:36s} {args.batch / best:10.0f} shots/s  {1e6 * best / res.n_events.sum():6.3f} us/event  "
              f"{np.mean(res.n_events):6.1f} events/shot", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
