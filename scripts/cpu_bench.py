"""Event-solver throughput in CPU time, for comparing trees on a loaded
machine: the scenes of ``scripts/benchmark.py`` at 1024 tables on one
thread, each figure the best of ``--repeats`` runs of the process's CPU time
(other jobs add wall time, and only ever add, so the minimum of the CPU time
is the most repeatable figure), for each effect set asked for, and with
``--latency`` the best per-call time of the scene's first table alone.

    PYTHONPATH=. python scripts/cpu_bench.py --scene 9-ball --scene two-ball
    PYTHONPATH=/other/tree python scripts/cpu_bench.py --scene 9-ball --scene two-ball

Trees older than the scene builders time the same shots from a file:
``--save-scenes F`` (in this tree) writes the struck states, ``--scenes-from
F`` reads them instead of building them. ``--json`` prints one line per
process (the tree, then per scene and effect set: ms per call, and us per
single-table call), for a loop that runs the trees in turn, many times::

    python scripts/cpu_bench.py --save-scenes /tmp/scenes.npz --scene two-ball
    for r in 1 2 3 4 5 6 7 8; do for t in /old/tree .; do
      PYTHONPATH=$t python scripts/cpu_bench.py --scenes-from /tmp/scenes.npz --effects "no spin" --latency --json
    done; done
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from billiards_env.physics import BallState, Effects, PhysicsParams, Table, set_num_threads, simulate

FIELDS = ("pos", "vel", "omega", "pocket")
# each effect switched off alone (Effects.each_off), and the opt-in flight on top of all of them
EFFECT_SETS = {**Effects.each_off(), "all + airborne": Effects(airborne=True)}
LATENCY_CALLS = 200  # single-table calls per timed run (one call lasts tens of microseconds)


def scenes(args, P, T) -> dict:
    """The scenes' struck states by name: built here, or read from ``--scenes-from``."""
    if args.scenes_from:
        z = np.load(args.scenes_from)
        names = sorted({k.rsplit("/", 1)[0] for k in z.files})
        return {n: BallState(*(z[f"{n}/{f}"].copy() for f in FIELDS)) for n in names
                if not args.scene or any(part in n for part in args.scene)}
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from benchmark import SCENES  # the scenes are defined once, there
    return {name: make(args.batch, P, T, np.random.default_rng(0)) for name, make in SCENES.items()
            if not args.scene or any(part in name for part in args.scene)}


def best_ms(fn, repeats: int, calls: int) -> float:
    """The minimum over ``repeats`` runs of ``calls`` calls of the CPU time per call (ms)."""
    times = []
    for _ in range(repeats):
        t0 = time.process_time()
        for _ in range(calls):
            fn()
        times.append((time.process_time() - t0) / calls * 1e3)
    return min(times)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", action="append", help="keep scenes whose name contains this (repeatable)")
    ap.add_argument("--effects", action="append", choices=list(EFFECT_SETS),
                    help="effect sets to time (repeatable; default 'all')")
    ap.add_argument("--batch", type=int, default=1024)
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--latency", action="store_true", help="also the first table alone, per call")
    ap.add_argument("--json", action="store_true", help="one JSON line instead of the table")
    ap.add_argument("--save-scenes", type=Path, default=None, help="write the scenes' struck states and exit")
    ap.add_argument("--scenes-from", type=Path, default=None, help="read the scenes' states from this file")
    ap.add_argument("--quick", action="store_true", help="64 tables, 1 repeat (the test's run)")
    args = ap.parse_args(argv)
    if args.quick:
        args.batch, args.repeats = 64, 1
    if args.batch < 1 or args.repeats < 1:
        ap.error(f"--batch and --repeats must be at least 1, got {args.batch} and {args.repeats}")
    P, T = PhysicsParams.standard(), Table.pool(9)
    found = scenes(args, P, T)
    if not found:
        ap.error(f"no scene matches {args.scene}")
    if args.save_scenes:
        np.savez(args.save_scenes, **{f"{n}/{f}": getattr(s, f) for n, s in found.items() for f in FIELDS})
        print(f"wrote {len(found)} scenes to {args.save_scenes}")
        return 0
    set_num_threads(1)
    sets = EFFECT_SETS
    out = {"tree": str(Path(sys.modules["billiards_env"].__file__).resolve().parents[1])}
    for name, s in found.items():
        one = s.take([0])
        for label in args.effects or ["all"]:
            eff = sets[label]
            res = simulate(s, T, P, effects=eff)  # compile or load from the cache
            ms = best_ms(lambda: simulate(s, T, P, effects=eff), args.repeats, 1)
            row = {"ms": ms, "events_per_shot": float(np.mean(res.n_events))}
            if args.latency:
                simulate(one, T, P, effects=eff)
                row["latency_us"] = 1e3 * best_ms(lambda: simulate(one, T, P, effects=eff), args.repeats,
                                                  LATENCY_CALLS)
            out[f"{name} | {label}"] = row
            if not args.json:
                lat = f"  {row['latency_us']:7.1f} us one table" if args.latency else ""
                print(f"{name:36s} {label:20s} {s.n_envs / ms * 1e3:10.0f} shots/s  "
                      f"{1e6 * ms / 1e3 / res.n_events.sum():6.3f} us/event  {row['events_per_shot']:6.1f} "
                      f"events/shot{lat}", flush=True)
    if args.json:
        print(json.dumps(out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
