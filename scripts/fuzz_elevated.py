"""Fuzz the simulator after elevated cue strikes (issue 46): random
racks and balls (billiards_env.testing's layouts, standard and seed physics),
each cue ball struck again with any aim, draw, tip offset in the miscue disc
and cue elevation uniform over [0, theta_max]; every invariant of
billiards_env.testing checked on every shot (no NaN, no energy gain counting
the height's, no overlap in 3D, no ball below the slate or off the table but
through a pocket or over a rail, every ball at rest on the slate at the end).
Planar (the default): the velocity into the slate is dropped. ``--airborne``:
``Effects(airborne=True)``, the cue ball jumping off the slate (both solvers;
the step solver at dt = 1e-3 s). Failing shots are saved as regression cases (the struck state,
its vertical velocity with ``--airborne``).

    python scripts/fuzz_elevated.py --shots 100000 --summary results/physics3d/fuzz_elevated.json
    python scripts/fuzz_elevated.py --airborne --shots 100000 --summary results/physics3d/fuzz_airborne.json
"""
from __future__ import annotations

import argparse
import pathlib
import time

import numpy as np

from billiards_env.physics import BallState, Effects, strike
from billiards_env.physics import constants as C
from billiards_env.physics.strike import MAX_ELEVATION
from billiards_env.testing import case_dict, random_batch, run_batch, save_case
from billiards_env.testing.fuzzing import TABLE_KINDS, report, table_layout

ROOT = pathlib.Path(__file__).resolve().parents[1]


def elevated(state, rng, params, theta_max):
    """``state`` with its cue ball struck again, the cue elevated at random."""
    n = state.n_envs
    r = params.miscue_limit * np.sqrt(rng.uniform(0, 1, n)) * (1 - 1e-12)
    ang = rng.uniform(0, 2 * np.pi, n)
    return strike(state, rng.uniform(0, 2 * np.pi, n), params.max_draw * rng.uniform(0, 1, n) ** 0.5,
                  r * np.cos(ang), r * np.sin(ang), params, theta=rng.uniform(0, theta_max, n))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--shots", type=int, default=100_000)
    ap.add_argument("--solver", choices=["event", "step"], default="event")
    ap.add_argument("--theta-max", type=float, default=MAX_ELEVATION, help="largest elevation (rad)")
    ap.add_argument("--table", choices=TABLE_KINDS, default="pool",
                    help="the table and its layouts (as scripts/fuzz.py --table)")
    ap.add_argument("--airborne", action="store_true", help="simulate the flight (Effects(airborne=True))")
    ap.add_argument("--batch", type=int, default=2048)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--regressions", type=pathlib.Path, default=ROOT / "tests" / "regressions")
    ap.add_argument("--summary", type=pathlib.Path, default=None)
    args = ap.parse_args(argv)
    effects = Effects(airborne=True) if args.airborne else Effects()
    rng = np.random.default_rng(args.seed)
    done = failing = events = off = off_object = 0
    t0 = time.perf_counter()
    while done < args.shots:
        n = min(args.batch, args.shots - done)
        layout, preset, table_name, case_table = table_layout(rng, args.table)
        state, table, params = random_batch(rng, n, layout, preset, table_name=table_name)
        if args.airborne:  # every ball on the slate, with a vertical velocity the strike can set
            state = BallState(state.pos, state.vel, state.omega, state.pocket, np.zeros(state.pos.shape[:2] + (2,)))
        state = elevated(state, rng, params, args.theta_max)
        res, violations = run_batch(state, table, params, args.solver, effects=effects)
        events += int(res.n_events.sum())
        off += int((res.state.pocket >= C.OFF_TABLE).sum())
        off_object += int((res.state.pocket[:, 1:] >= C.OFF_TABLE).sum())  # ball 0 is the cue ball
        for e, v in enumerate(violations):
            if v:
                failing += 1
                save_case(case_dict(state, e, params, args.solver, 1e-3, v, effects=effects, table_name=case_table),
                          args.regressions,
                          tag="airborne" if args.airborne else "elevated")
        done += n
    summary = {"solver": args.solver, "airborne": args.airborne, "table": args.table, "shots": done,
               "shots_with_violations": failing, "events": events, "balls_off_table": off,
               "object_balls_off_table": off_object,
               "theta_max": args.theta_max, "seed": args.seed, "wall_s": round(time.perf_counter() - t0, 1)}
    report(summary, args.summary)
    return 1 if failing else 0


if __name__ == "__main__":
    raise SystemExit(main())
