"""Long fuzzing run: random racks, shots and presets, checking every
invariant of billiards_env.testing on every shot; failing shots are saved as
JSON regression cases (replayed by tests/physics/test_regressions.py).

    python scripts/fuzz.py --shots 1000000 --solver event
    python scripts/fuzz.py --shots 20000 --solver step --dt 1e-3
    python scripts/fuzz.py --shots 1000000 --effects each   # every effect set
    python scripts/fuzz.py --shots 200000 --effects each --models cushion=mathavan2010
    python scripts/fuzz.py --shots 1000000 --table snooker   # the 12 ft snooker table, snooker balls
"""
from __future__ import annotations

import argparse
import pathlib
import time

import numpy as np
from tqdm import tqdm

from billiards_env.physics import Effects, Models
from billiards_env.testing import case_dict, random_batch, run_batch, save_case
from billiards_env.testing.fuzzing import TABLE_KINDS, report, table_layout

ROOT = pathlib.Path(__file__).resolve().parents[1]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--shots", type=int, default=1_000_000)
    ap.add_argument("--solver", choices=["event", "step"], default="event")
    ap.add_argument("--dt", type=float, default=1e-3, help="step solver time step (s)")
    ap.add_argument("--effects", default="all",
                    help="an effect set of Effects.each_off() ('all', 'no spin', ..., 'minimal'), "
                         "or 'each': a random one of them per batch")
    ap.add_argument("--models", nargs="*", default=[], metavar="KEY=VALUE",
                    help="model choices, e.g. ball_ball_friction=alciatore cushion=mathavan2010 "
                         "(keys and names: billiards_env.physics.models.REGISTRIES; default: Models())")
    ap.add_argument("--table", choices=TABLE_KINDS, default="pool",
                    help="pool: 9-ball and 8-ball racks and random balls on the 9 ft table (standard and seed "
                         "physics); carom: three balls on the carom match table with carom equipment, frozen "
                         "to each other or to a cushion, extreme spin (testing.fuzzing.carom_batch); snooker: "
                         "the frozen 22-ball opening, random balls and balls in the jaws on the 12 ft snooker "
                         "table (snooker preset)")
    ap.add_argument("--batch", type=int, default=4096)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--regressions", type=pathlib.Path, default=ROOT / "tests" / "regressions")
    ap.add_argument("--summary", type=pathlib.Path, default=None, help="write a JSON summary here")
    ap.add_argument("--max-minutes", type=float, default=None,
                    help="stop after this much wall time (the summary says how many shots ran)")
    args = ap.parse_args(argv)
    effect_sets = Effects.each_off()
    if args.effects != "each" and args.effects not in effect_sets:
        ap.error(f"--effects must be 'each' or one of {sorted(effect_sets)}, got {args.effects!r}")
    names = sorted(effect_sets) if args.effects == "each" else [args.effects]
    try:
        models = Models.from_dict(dict(kv.split("=", 1) for kv in args.models))
    except ValueError as exc:  # also a KEY=VALUE without '='
        ap.error(f"--models: {exc}")

    rng = np.random.default_rng(args.seed)
    done = failures = events = 0
    kinds = {}
    per_set, failures_per_set = {}, {}  # shots and failing shots per effect set
    t0 = time.perf_counter()
    stopped_early = False
    with tqdm(total=args.shots, unit="shot", desc=f"fuzz {args.solver}") as bar:
        while done < args.shots:
            if args.max_minutes is not None and time.perf_counter() - t0 > 60 * args.max_minutes:
                stopped_early = True
                break
            n = min(args.batch, args.shots - done)
            layout, preset, table_name, case_table = table_layout(rng, args.table)
            name = names[int(rng.integers(len(names)))] if len(names) > 1 else names[0]
            effects = effect_sets[name]
            state, table, params = random_batch(rng, n, layout, preset, pockets=effects.pockets, table_name=table_name)
            res, viol = run_batch(state, table, params, args.solver, dt=args.dt, effects=effects,
                                  models=models)
            per_set[name] = per_set.get(name, 0) + n
            events += int(res.n_events.sum())
            for e, v in enumerate(viol):
                if v:
                    failures += 1
                    for m in v:
                        kinds[m.split(" ")[0]] = kinds.get(m.split(" ")[0], 0) + 1
                    failures_per_set[name] = failures_per_set.get(name, 0) + 1
                    if failures <= 50:
                        save_case(case_dict(state, e, params, args.solver, args.dt, v, effects, models,
                                            case_table),
                                  args.regressions, tag="fuzz")
            done += n
            bar.update(n)
            bar.set_postfix(violations=failures)
    wall = time.perf_counter() - t0
    summary = dict(solver=args.solver, dt=args.dt if args.solver == "step" else None, shots=done,
                   shots_requested=args.shots, stopped_by_time_budget=stopped_early,
                   shots_with_violations=failures, violation_kinds=kinds, events=events,
                   wall_s=round(wall, 1), shots_per_s=round(done / wall, 1), seed=args.seed,
                   effects=args.effects, shots_per_effect_set=per_set, table=args.table,
                   violations_per_effect_set=failures_per_set)
    if args.models:  # runs with the default models keep their summary's keys
        summary["models"] = models.to_dict()
    report(summary, args.summary)
    return 1 if failures else 0


if __name__ == "__main__":
    raise SystemExit(main())
