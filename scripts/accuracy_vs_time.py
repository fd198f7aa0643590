#!/usr/bin/env python
"""What accuracy costs in time: the step solver at a list of time steps
against the exact event solver, on seeded two-ball shots, 9-ball breaks and
shots on the tables breaks leave; also physics effects switched off and the
event solver's sensitivity to a 1e-6 change of the shot; and each
non-default model choice against the default models
(``billiards_env.studies.accuracy`` does the work).

Writes to ``--out`` (default results/accuracy/): accuracy.md, accuracy.csv,
effects.csv, sensitivity.csv and accuracy.png; with ``--models``:
models.md and models.csv (the model part only).

    python scripts/accuracy_vs_time.py                 # 200 shots per scene
    python scripts/accuracy_vs_time.py --shots 50
    python scripts/accuracy_vs_time.py --quick --out /tmp/acc
    python scripts/accuracy_vs_time.py --models         # model choices only
"""
from __future__ import annotations

import argparse
import sys

from billiards_env.studies import accuracy


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--shots", type=int, default=200, help="shots per scene (default 200)")
    ap.add_argument("--quick", action="store_true", help="4 shots per scene, dt in (1e-2, 1e-3, 1e-4)")
    ap.add_argument("--out", default="results/accuracy", help="output directory")
    ap.add_argument("--seed", type=int, default=0, help="offset added to every scene seed")
    ap.add_argument("--dt", type=float, nargs="*", help="step-solver time steps (s)")
    ap.add_argument("--single", type=int, default=5, help="shots timed one table at a time (median)")
    ap.add_argument("--budget", type=float, default=120.0,
                    help="wall seconds per (scene, dt) cell: finer dt run on the first shots that fit "
                         "(at least --min-shots); 0 = no limit")
    ap.add_argument("--min-shots", type=int, default=20)
    ap.add_argument("--models", action="store_true",
                    help="run only the model part: each non-default model against the default models")
    args = ap.parse_args(argv)
    if args.quick:
        args.shots = 4 if "--shots" not in (argv or sys.argv) else args.shots
        args.single = min(args.single, 2)
    if args.shots < 1:
        ap.error("--shots must be >= 1")
    if args.models:
        out = accuracy.run_models(shots=args.shots, seed=args.seed, single=max(args.single, 20))
        paths = accuracy.write_models(out, args.out)
        print(f"wrote {', '.join(map(str, paths))} in {out['total']:.0f} s")
        return
    dts = accuracy.QUICK_DTS if args.quick else tuple(args.dt or accuracy.DTS)
    out = accuracy.run(shots=args.shots, dts=dts, seed=args.seed, single=args.single, budget=args.budget,
                       min_shots=args.min_shots)
    accuracy.write(out, args.out)
    print(f"wrote {args.out}/accuracy.md, accuracy.csv, effects.csv, sensitivity.csv, accuracy.png "
          f"in {out['total']:.0f} s")


if __name__ == "__main__":
    main()
