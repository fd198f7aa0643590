"""Simulator and environment throughput (issues 3, 4 and 8).

Compiles before timing, reports medians over repeats and ratios measured in
the same run, prints a Markdown table and appends rows to a CSV.

    python scripts/benchmark.py                 # full run (a few minutes)
    python scripts/benchmark.py --quick         # smaller batches, fewer repeats
"""
from __future__ import annotations

import argparse
import csv
import datetime
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numba
import numpy as np

from billiards_env.physics import (BallState, Effects, PhysicsParams, Table, rack, set_num_threads, simulate,
                                   strike_velocity)

ROOT = Path(__file__).resolve().parents[1]


# ------------------------------------------------------------------ scenes --
def scene_nine_break(n, P, T, rng):
    s = rack(T, P, "nine", n, seed=rng)
    return strike_velocity(s, math.pi / 2 + rng.normal(0, 0.01, n), rng.normal(8.0, 0.2, n),
                           0.0, rng.uniform(-0.1, 0.1, n), P)


def scene_fifteen_break(n, P, T, rng):
    s = rack(T, P, "eight", n, seed=rng)
    return strike_velocity(s, math.pi / 2 + rng.normal(0, 0.01, n), rng.normal(8.0, 0.2, n),
                           0.0, rng.uniform(-0.1, 0.1, n), P)


def scene_two_ball_cut(n, P, T, rng):
    cue = np.column_stack([rng.uniform(0.3, 0.9, n), rng.uniform(0.5, 0.9, n)])
    obj = cue + np.column_stack([rng.uniform(-0.15, 0.15, n), rng.uniform(0.5, 0.8, n)])
    s = BallState.from_positions(np.stack([cue, obj], axis=1))
    d = obj - cue
    # aim at a half-ball hit: the cue ball's path passes R beside the object centre
    phi = np.arctan2(d[:, 1], d[:, 0]) + np.arcsin(P.R / np.linalg.norm(d, axis=1))
    return strike_velocity(s, phi, rng.normal(2.0, 0.1, n), 0.2, 0.3, P)


def scene_one_ball_two_cushions(n, P, T, rng):
    s = BallState.from_positions(np.column_stack([rng.uniform(0.5, 0.8, n), rng.uniform(1.5, 1.8, n)])[:, None])
    return strike_velocity(s, math.radians(60) + rng.normal(0, 0.02, n), 3.0, 0.0, 0.4, P)


SCENES = {
    "9-ball break (8 m/s)": scene_nine_break,
    "15-ball break (8 m/s)": scene_fifteen_break,
    "two-ball cut (2 m/s, top+side)": scene_two_ball_cut,
    "one ball, top spin, two cushions": scene_one_ball_two_cushions,
}


def timeit(fn, repeats):
    fn()  # warm-up: compile or load from cache
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def solver_rows(args, P, T):
    rows = []
    solvers = [("event", None), ("step", 1e-3), ("step", 1e-4)]
    for name, make in SCENES.items():
        for solver, dt in solvers:
            n = args.batch
            if solver == "step" and dt < 1e-3:
                n = max(16, args.batch // 16)  # fine steps: a smaller batch keeps the run short
            s = make(n, P, T, np.random.default_rng(0))
            one = s.take([0])
            run = lambda st=s: simulate(st, T, P, solver=solver, dt=dt)
            res = run()
            row = dict(section="solver", scene=name, solver=solver if dt is None else f"step dt={dt:g}",
                       effects="all", batch=n, events_per_shot=float(np.mean(res.n_events)))
            for threads in (1, numba.config.NUMBA_NUM_THREADS):
                set_num_threads(threads)
                t = timeit(run, args.repeats)
                row[f"shots_per_s_{threads}t"] = n / t
            set_num_threads(numba.config.NUMBA_NUM_THREADS)
            row["latency_ms"] = 1e3 * timeit(lambda: simulate(one, T, P, solver=solver, dt=dt), args.repeats * 3)
            rows.append(row)
            print(f"  {name:36s} {row['solver']:14s} {row['shots_per_s_1t']:10.0f} shots/s (1 thread)", flush=True)
    return rows


# "all" is also the default set: both physics presets model every effect
EFFECT_SETS = {("all (= default)" if k == "all" else k): v for k, v in Effects.each_off().items()}


def effects_rows(args, P, T):
    """Each effect switched off alone, and all at once, on the same shots.
    Besides shots/s the rows give what explains them: events and simulated
    seconds per shot (the physics of the set) and the cost of one event
    (event solver) or one step (step solver) (the kernel's work)."""
    rows = []
    nt = numba.config.NUMBA_NUM_THREADS
    for scene in ("9-ball break (8 m/s)", "two-ball cut (2 m/s, top+side)"):
        for solver, dt in (("event", None), ("step", 1e-3)):
            # the step solver is ~30x slower: a quarter batch keeps the run short
            n = args.batch if solver == "event" else max(16, args.batch // 4)
            s = SCENES[scene](n, P, T, np.random.default_rng(1))
            one = s.take([0])
            base = None
            for label, eff in EFFECT_SETS.items():
                run = lambda st=s, e=eff: simulate(st, T, P, solver=solver, dt=dt, effects=e)
                res = run()
                set_num_threads(1)
                t1 = timeit(run, args.repeats)
                set_num_threads(nt)
                tall = timeit(run, args.repeats)
                lat = timeit(lambda e=eff: simulate(one, T, P, solver=solver, dt=dt, effects=e), args.repeats * 3)
                base = t1 if base is None else base
                events = float(np.mean(res.n_events))
                sim_s = float(np.mean(res.time))
                units = events if dt is None else sim_s / dt  # events, or steps
                rows.append(dict(section="effects", scene=scene, solver=solver if dt is None else f"step dt={dt:g}",
                                 effects=label, batch=n, events_per_shot=events, sim_seconds_per_shot=sim_s,
                                 us_per_unit=1e6 * t1 / n / units, shots_per_s_1t=n / t1,
                                 **{f"shots_per_s_{nt}t": n / tall},
                                 latency_ms=1e3 * lat, speedup_vs_all=base / t1))
                print(f"  {scene:32s} {solver:6s} {label:20s} x{base / t1:5.2f} vs all", flush=True)
    return rows


def env_rows(args):
    """Env steps/s through gymnasium.make_vec with random actions. The env's
    own simulator calls (shots and NineBall's break simulations in resets)
    are timed in the same run, so the overhead is the time the env spends
    outside the simulator, over the time inside it."""
    import gymnasium as gym
    import billiards_env  # noqa: F401  (registers the tasks)
    rows = []
    cases = [(n, "same_step") for n in (1, 64, 1024)] + [(1024, "next_step")]
    for env_id in ("Billiards-PotOne-v0", "Billiards-NineBall-v0"):
        for n, mode in cases:
            env = gym.make_vec(env_id, num_envs=n, vectorization_mode="vector_entry_point", autoreset_mode=mode)
            core = env.unwrapped._core
            inner_sim = core._simulate
            sim_time = [0.0]

            def timed(state, _inner=inner_sim, _acc=sim_time):
                t0 = time.perf_counter()
                out = _inner(state)
                _acc[0] += time.perf_counter() - t0
                return out

            core._simulate = timed  # instance attribute: times this env's simulator calls only
            env.reset(seed=0)
            rng = np.random.default_rng(0)
            acts = rng.uniform(-1, 1, size=(32, n, 4)).astype(np.float32)
            env.step(acts[0])
            steps = max(4, min(64, 20_000 // n)) if not args.quick else 4
            runs = []
            for _ in range(args.repeats):
                sim_time[0] = 0.0
                t0 = time.perf_counter()
                for k in range(steps):
                    env.step(acts[k % 32])
                runs.append((time.perf_counter() - t0, sim_time[0]))
            dt = statistics.median(r[0] for r in runs)
            rows.append(dict(section="env", scene=env_id, solver="event", effects="task", batch=n, autoreset=mode,
                             env_steps_per_s=n * steps / dt,
                             sim_share=statistics.median(ts / d for d, ts in runs),
                             env_overhead_pct=statistics.median(100.0 * (d - ts) / ts for d, ts in runs)))
            env.close()
            r = rows[-1]
            print(f"  {env_id:24s} {n:5d} tables {mode:9s} {r['env_steps_per_s']:10.0f} steps/s, "
                  f"overhead {r['env_overhead_pct']:5.1f}%", flush=True)
    return rows


def cold_start_rows():
    code = ("import time; t0=time.perf_counter(); import numpy as np; "
            "from billiards_env.physics import *; P=PhysicsParams.standard(); T=Table.pool(9); "
            "s=strike_velocity(rack(T,P,'nine',1,seed=0), 1.5708, 8.0, params=P); simulate(s,T,P); "
            "print(time.perf_counter()-t0)")
    rows = []
    with tempfile.TemporaryDirectory() as cold_dir:
        for label, env in (("cold (empty numba cache)", {"NUMBA_CACHE_DIR": cold_dir}),
                           ("warm (numba cache on disk)", {"NUMBA_CACHE_DIR": cold_dir})):
            out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                                 env={**os.environ, **env}, check=True)
            rows.append(dict(section="cold start", scene="import + first 9-ball break", solver="event",
                             effects="all", batch=1, seconds=float(out.stdout.strip().splitlines()[-1]), note=label))
            print(f"  {label}: {rows[-1]['seconds']:.2f} s", flush=True)
    return rows


SECTION_NAMES = {"solver": "solver", "effects": "effects", "env": "env", "cold": "cold start"}


def markdown(rows):
    lines = []
    nt = numba.config.NUMBA_NUM_THREADS
    sol = [r for r in rows if r["section"] == "solver"]
    if sol:
        lines += [f"| scene | solver | events/shot | shots/s, 1 thread | shots/s, {nt} threads | single-table latency (ms) |",
                  "|---|---|---:|---:|---:|---:|"]
        for r in sol:
            lines.append(f"| {r['scene']} | {r['solver']} | {r['events_per_shot']:.1f} | {r['shots_per_s_1t']:,.0f} | "
                         f"{r[f'shots_per_s_{nt}t']:,.0f} | {r['latency_ms']:.3f} |")
        lines.append("")
    eff = [r for r in rows if r["section"] == "effects"]
    if eff:
        lines += ["| scene | solver | effects | events/shot | simulated s/shot | µs per event or step | "
                  f"shots/s, 1 thread | shots/s, {nt} threads | single-shot latency (ms) | speed-up vs all |",
                  "|---|---|---|---:|---:|---:|---:|---:|---:|---:|"]
        for r in eff:
            lines.append(f"| {r['scene']} | {r['solver']} | {r['effects']} | {r['events_per_shot']:.1f} | "
                         f"{r['sim_seconds_per_shot']:.2f} | {r['us_per_unit']:.2f} | {r['shots_per_s_1t']:,.0f} | "
                         f"{r[f'shots_per_s_{nt}t']:,.0f} | {r['latency_ms']:.3f} | {r['speedup_vs_all']:.2f}x |")
        lines.append("")
    env = [r for r in rows if r["section"] == "env"]
    if env:
        lines += ["| task | tables | autoreset | env steps/s | time in simulator | env overhead |",
                  "|---|---:|---|---:|---:|---:|"]
        for r in env:
            lines.append(f"| {r['scene']} | {r['batch']} | {r['autoreset']} | {r['env_steps_per_s']:,.0f} | "
                         f"{100 * r['sim_share']:.0f}% | {r['env_overhead_pct']:.0f}% |")
        lines.append("")
    cold = [r for r in rows if r["section"] == "cold start"]
    if cold:
        lines += ["| start | seconds |", "|---|---:|"]
        for r in cold:
            lines.append(f"| {r['note']} | {r['seconds']:.2f} |")
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--batch", type=int, default=1024)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--quick", action="store_true", help="batch 64, 2 repeats")
    ap.add_argument("--only", nargs="*", default=["solver", "effects", "env", "cold"],
                    choices=["solver", "effects", "env", "cold"])
    ap.add_argument("--out", type=Path, default=ROOT / "results" / "benchmark")
    args = ap.parse_args(argv)
    if args.quick:
        args.batch, args.repeats = 64, 2
    P, T = PhysicsParams.standard(), Table.pool(9)
    rows = []
    print(f"numba threads: {numba.config.NUMBA_NUM_THREADS}, batch {args.batch}")
    if "solver" in args.only:
        print("solvers:"); rows += solver_rows(args, P, T)
    if "effects" in args.only:
        print("effects:"); rows += effects_rows(args, P, T)
    if "env" in args.only:
        print("environments:"); rows += env_rows(args)
    if "cold" in args.only:
        print("cold start:"); rows += cold_start_rows()
    md = markdown(rows)
    print()
    print(md)
    # one Markdown file per section, so a partial run (--only) replaces only
    # its own sections; benchmark.md joins the latest of every section
    args.out.mkdir(parents=True, exist_ok=True)
    for section in args.only:
        part = markdown([r for r in rows if r["section"] == SECTION_NAMES[section]])
        (args.out / f"{section}.md").write_text(part.rstrip("\n") + "\n")
    parts = [(args.out / f"{k}.md").read_text() for k in SECTION_NAMES if (args.out / f"{k}.md").exists()]
    (args.out / "benchmark.md").write_text("\n".join(parts))
    stamp = datetime.datetime.now().isoformat(timespec="seconds")
    csv_path = args.out / "benchmark.csv"
    keys = sorted({k for r in rows for k in r} | {"timestamp"})
    new = not csv_path.exists()
    if not new:
        with csv_path.open() as f:
            old_keys = next(csv.reader(f), [])
        if set(old_keys) != set(keys):
            new = True
            csv_path.rename(csv_path.with_suffix(f".{stamp.replace(':', '')}.csv"))
    with csv_path.open("a", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        if new:
            w.writeheader()
        for r in rows:
            w.writerow({**r, "timestamp": stamp})
    print(f"\nwrote {args.out / 'benchmark.md'} and appended to {csv_path}")


if __name__ == "__main__":
    main()
