"""Simulator and environment throughput, and how it compares across commits.

Compiles before timing, reports medians over repeats and ratios measured in
the same run, prints Markdown tables (one file per section, joined in
benchmark.md), appends rows with the git revision to benchmark.csv and plots
the history of the headline figures (history.png).

    python scripts/benchmark.py                 # full run (a few minutes)
    python scripts/benchmark.py --quick         # smaller batches, fewer repeats
    python scripts/benchmark.py --only solver --against HEAD~1 --quick
    python scripts/benchmark.py --only models   # each non-default model (models.md)
    python scripts/benchmark.py --only rllib    # RLlib vs SB3 vs bare env (docs/distributed.md; needs [ray])
    python scripts/benchmark.py --history       # only redraw history.png
    python scripts/benchmark.py --only games    # two-player games/s and vector-env steps/s (games.md)

``--against REV`` checks REV out in a temporary git worktree, warms both
trees' numba caches, then runs each section in both trees in turn, a fresh
process per run with PYTHONPATH set to the tree and the same seeds, ``--rounds``
times (the order alternating), and writes the medians of both and their
ratio (this tree / REV) to against.md.
"""
from __future__ import annotations

import argparse
import contextlib
import csv
import datetime
import json
import math
import os
import shutil
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


def chosen_scenes(args, names=tuple(SCENES)):
    """The scenes among ``names`` whose name contains one of ``--scene``."""
    return [n for n in names if not args.scene or any(part in n for part in args.scene)]


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
    for name in chosen_scenes(args):
        make = SCENES[name]
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


def model_sets() -> dict:
    """Every effect with each non-default model, against the default models
    (built on demand: a revision older than the model registry, timed with
    --against, has no Models and runs only the other sections)."""
    from billiards_env.physics import Models
    from billiards_env.physics.models import REGISTRIES
    return {"all (= default)": (Effects.all(), Models()),
            **{f"all + {name}": (Effects.all(), Models(**{field: name}))
               for field, registry in REGISTRIES.items() for name in sorted(registry)
               if name != getattr(Models(), field)}}


def effects_rows(args, P, T, sets=None, section="effects"):
    """Each effect switched off alone, and all at once, on the same shots
    (``sets``: label -> Effects, or label -> (Effects, Models); the first is
    the baseline of the speed-up column). Besides shots/s the rows give what
    explains them: events and simulated seconds per shot (the physics of the
    set) and the cost of one event (event solver) or one step (step solver)
    (the kernel's work)."""
    sets = {k: v if isinstance(v, tuple) else (v, None) for k, v in (sets or EFFECT_SETS).items()}
    rows = []
    nt = numba.config.NUMBA_NUM_THREADS
    for scene in chosen_scenes(args, ("9-ball break (8 m/s)", "two-ball cut (2 m/s, top+side)")):
        for solver, dt in (("event", None), ("step", 1e-3)):
            # the step solver is ~30x slower: a quarter batch keeps the run short
            n = args.batch if solver == "event" else max(16, args.batch // 4)
            s = SCENES[scene](n, P, T, np.random.default_rng(1))
            one = s.take([0])
            base = None
            for label, (eff, models) in sets.items():
                choice = {} if models is None else {"models": models}  # None: the simulator's default
                run = lambda st=s, e=eff, m=choice: simulate(st, T, P, solver=solver, dt=dt, effects=e, **m)
                res = run()
                set_num_threads(1)
                t1 = timeit(run, args.repeats)
                set_num_threads(nt)
                tall = timeit(run, args.repeats)
                lat = timeit(lambda e=eff, m=choice: simulate(one, T, P, solver=solver, dt=dt, effects=e, **m),
                             args.repeats * 3)
                base = t1 if base is None else base
                events = float(np.mean(res.n_events))
                sim_s = float(np.mean(res.time))
                units = events if dt is None else sim_s / dt  # events, or steps
                rows.append(dict(section=section, scene=scene, solver=solver if dt is None else f"step dt={dt:g}",
                                 effects=label, batch=n, events_per_shot=events, sim_seconds_per_shot=sim_s,
                                 us_per_unit=1e6 * t1 / n / units, shots_per_s_1t=n / t1,
                                 **{f"shots_per_s_{nt}t": n / tall},
                                 latency_ms=1e3 * lat, speedup_vs_all=base / t1))
                print(f"  {scene:32s} {solver:6s} {label:20s} x{base / t1:5.2f} vs all", flush=True)
    return rows


@contextlib.contextmanager
def simulator_clock():
    """Time every simulator call the env layer makes: rebinds ``simulate`` in
    the loaded ``billiards_env.envs`` modules that imported it to a wrapper
    adding each call's wall time to the yielded one-element list."""
    from billiards_env import physics
    inner = physics.simulate
    total = [0.0]

    def timed(*a, **kw):
        t0 = time.perf_counter()
        out = inner(*a, **kw)
        total[0] += time.perf_counter() - t0
        return out

    mods = [m for name, m in list(sys.modules.items())
            if name.startswith("billiards_env.envs") and getattr(m, "simulate", None) is inner]
    if not mods:
        raise RuntimeError("no billiards_env.envs module calls billiards_env.physics.simulate by that name")
    for m in mods:
        m.simulate = timed
    try:
        yield total
    finally:
        for m in mods:
            m.simulate = inner


def env_rows(args):
    """Env steps/s through gymnasium.make_vec with random actions. The env's
    own simulator calls (shots and NineBall's break simulations in resets)
    are timed in the same run, so the overhead is the time the env spends
    outside the simulator, over the time inside it."""
    import gymnasium as gym
    import billiards_env  # noqa: F401  (registers the tasks)
    rows = []
    cases = [(n, "same_step") for n in (1, 64, 1024)] + [(1024, "next_step")]
    for env_id in [e for e in ("Billiards-PotOne-v0", "Billiards-NineBall-v0")
                   if not args.scene or any(part in e for part in args.scene)]:
        for n, mode in cases:
            env = gym.make_vec(env_id, num_envs=n, vectorization_mode="vector_entry_point", autoreset_mode=mode)
            with simulator_clock() as sim_time:
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


# The cold-start scene: import and first 9-ball break (also profiled by
# scripts/compile_profile.py); prints its wall time
COLD_START_CODE = ("import time; t0=time.perf_counter(); import numpy as np; "
                   "from billiards_env.physics import *; P=PhysicsParams.standard(); T=Table.pool(9); "
                   "s=strike_velocity(rack(T,P,'nine',1,seed=0), 1.5708, 8.0, params=P); simulate(s,T,P); "
                   "print(time.perf_counter()-t0)")


def cold_start_rows():
    code = COLD_START_CODE
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


SECTION_NAMES = {"solver": "solver", "effects": "effects", "models": "models", "env": "env", "cold": "cold start",
                 "rllib": "rllib"}


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
    for eff in ([r for r in rows if r["section"] == k] for k in ("effects", "models")):
        if not eff:
            continue
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
    if any(r["section"] == "rllib" for r in rows):  # the RLlib backend's section (agents/rllib_bench.py)
        from agents.rllib_bench import rllib_markdown
        lines += rllib_markdown([r for r in rows if r["section"] == "rllib"])
    cold = [r for r in rows if r["section"] == "cold start"]
    if cold:
        lines += ["| start | seconds |", "|---|---:|"]
        for r in cold:
            lines.append(f"| {r['note']} | {r['seconds']:.2f} |")
    return "\n".join(lines)


def run_sections(args) -> list[dict]:
    P, T = PhysicsParams.standard(), Table.pool(9)
    rows = []
    print(f"numba threads: {numba.config.NUMBA_NUM_THREADS}, batch {args.batch}", flush=True)
    if "solver" in args.only:
        print("solvers:"); rows += solver_rows(args, P, T)
    if "effects" in args.only:
        print("effects:"); rows += effects_rows(args, P, T)
    if "models" in args.only:
        print("models:"); rows += effects_rows(args, P, T, model_sets(), "models")
    if "env" in args.only:
        print("environments:"); rows += env_rows(args)
    if "cold" in args.only:
        print("cold start:"); rows += cold_start_rows()
    if "rllib" in args.only:  # needs the ray extra; not in the default sections
        from agents.rllib_bench import rllib_rows
        print("rllib:"); rows += rllib_rows(args)
    return rows


# ---------------------------------------------------------------- records --
def revision(tree: Path) -> str:
    """The tree's commit (short hash), ``+dirty`` if tracked files differ from it."""
    try:
        sha = subprocess.run(["git", "-C", str(tree), "rev-parse", "--short=10", "HEAD"], capture_output=True,
                             text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(tree), "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
    return sha + ("+dirty" if dirty else "")


def append_csv(csv_path: Path, rows: list[dict]) -> None:
    """Append ``rows`` to the CSV; when they bring new columns the file is
    rewritten with the union of the columns, so the history stays in one file."""
    old_rows, old_keys = [], []
    if csv_path.exists():
        with csv_path.open(newline="") as f:
            reader = csv.DictReader(f)
            old_keys = list(reader.fieldnames or [])
            old_rows = list(reader)
    keys = sorted(set(old_keys) | {k for r in rows for k in r})
    if old_keys and set(keys) == set(old_keys):
        with csv_path.open("a", newline="") as f:
            csv.DictWriter(f, fieldnames=old_keys).writerows(rows)
        return
    with csv_path.open("w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(old_rows + rows)


# the figures history.png follows: (section, scene, solver, batch, autoreset, column, label)
HEADLINES = (
    ("solver", "9-ball break (8 m/s)", "event", "1024", "", "shots_per_s_1t", "9-ball breaks/s, 1 thread"),
    ("solver", "two-ball cut (2 m/s, top+side)", "event", "1024", "", "shots_per_s_1t",
     "two-ball cut shots/s, 1 thread"),
    ("env", "Billiards-PotOne-v0", "event", "1024", "same_step", "env_steps_per_s", "PotOne env steps/s, 1024 tables"),
    ("env", "Billiards-NineBall-v0", "event", "1024", "same_step", "env_steps_per_s",
     "NineBall env steps/s, 1024 tables"),
)


def history_rows(out_dir: Path) -> list[dict]:
    """Every full-size row of benchmark.csv and of the files older versions of
    this script set aside when the columns changed (benchmark.<stamp>.csv),
    without --quick runs and without the rows of --against comparisons."""
    rows, seen = [], set()
    for path in sorted(out_dir.glob("benchmark*.csv")):
        with path.open(newline="") as f:
            for r in csv.DictReader(f):
                key = (r.get("timestamp"), r.get("section"), r.get("scene"), r.get("solver"), r.get("effects"),
                       r.get("batch"), r.get("autoreset"), r.get("note"))
                if key in seen or r.get("quick") == "True" or r.get("compared_with"):
                    continue
                seen.add(key)
                rows.append(r)
    return rows


def plot_history(out_dir: Path) -> Path | None:
    """history.png: each headline figure against the date of its run."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = history_rows(out_dir)
    if not rows:
        return None
    fig, axes = plt.subplots(2, 2, figsize=(11, 6.5), sharex=True)
    for ax, (section, scene, solver, batch, mode, col, label) in zip(axes.flat, HEADLINES):
        pts = sorted((datetime.datetime.fromisoformat(r["timestamp"]), float(r[col])) for r in rows
                     if r["section"] == section and r["scene"] == scene and r["solver"] == solver
                     and r["batch"] == batch and r.get("autoreset", "") == mode and r.get(col))
        if pts:
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-")
            ax.annotate(f"{pts[-1][1]:,.0f}", pts[-1], textcoords="offset points", xytext=(-10, 6), fontsize=8)
        ax.set_title(label, fontsize=10)
        ax.set_ylim(bottom=0)
        ax.grid(True, alpha=0.3)
    fig.autofmt_xdate()
    fig.suptitle("Benchmark history (results/benchmark/benchmark.csv, full runs)")
    fig.tight_layout()
    path = out_dir / "history.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


# ---------------------------------------------------------------- against --
# per section: the figures compared, as (column, label)
COMPARED = {
    "solver": (("shots_per_s_1t", "shots/s, 1 thread"), ("latency_ms", "single-table latency (ms)")),
    "effects": (("shots_per_s_1t", "shots/s, 1 thread"), ("latency_ms", "single-shot latency (ms)")),
    "models": (("shots_per_s_1t", "shots/s, 1 thread"), ("latency_ms", "single-shot latency (ms)")),
    "env": (("env_steps_per_s", "env steps/s"),),
    "cold": (("seconds", "seconds"),),
}
ROW_KEY = ("section", "scene", "solver", "effects", "batch", "autoreset", "note")


@contextlib.contextmanager
def checked_out(rev: str):
    """A temporary git worktree of ``rev`` (detached), removed afterwards."""
    sha = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--verify", f"{rev}^{{commit}}"],
                         capture_output=True, text=True, check=True).stdout.strip()
    tmp = Path(tempfile.mkdtemp(prefix="billiards-bench-"))
    tree = tmp / "tree"
    subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(tree), sha],
                   capture_output=True, text=True, check=True)
    try:
        yield tree
    finally:
        removed = subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force", str(tree)],
                                 capture_output=True).returncode == 0
        shutil.rmtree(tmp, ignore_errors=True)
        if not removed:  # drop the registration of the deleted directory
            subprocess.run(["git", "-C", str(ROOT), "worktree", "prune"], capture_output=True)


def share_numba_cache(src: Path, dst: Path) -> int:
    """Copy numba's on-disk kernels of ``src``'s package into ``dst`` when every
    source file of the package is byte-identical in both trees (then every
    kernel is the same code; numba keys a cached kernel on its own file only,
    not on the files of the helpers compiled into it, so with any difference
    nothing is shared). Returns the number of files copied."""
    pkg_a, pkg_b = src / "billiards_env", dst / "billiards_env"
    sources_a = sorted(p.relative_to(pkg_a) for p in pkg_a.rglob("*.py"))
    sources_b = sorted(p.relative_to(pkg_b) for p in pkg_b.rglob("*.py"))
    if sources_a != sources_b or any((pkg_a / p).read_bytes() != (pkg_b / p).read_bytes() for p in sources_a):
        return 0
    copied = 0
    for cache_dir in pkg_a.rglob("__pycache__"):
        target = pkg_b / cache_dir.relative_to(pkg_a)
        for f in cache_dir.iterdir():
            if f.suffix in (".nbi", ".nbc"):
                target.mkdir(parents=True, exist_ok=True)
                shutil.copy2(f, target / f.name)
                copied += 1
    return copied


def worker_command(args, section: str, json_path: Path, warm: bool = False) -> list[str]:
    cmd = [sys.executable, str(Path(__file__).resolve()), "--worker", str(json_path), "--only", section,
           "--batch", str(2 if warm else args.batch), "--repeats", str(1 if warm else args.repeats)]
    if args.quick or warm:
        cmd.append("--quick")
    for part in args.scene or []:
        cmd += ["--scene", part]
    return cmd


def run_in_tree(args, tree: Path, section: str, warm: bool = False) -> list[dict]:
    """Run one section in a fresh process that imports ``tree``'s billiards_env."""
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "rows.json"
        others = [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p and Path(p).resolve() != ROOT]
        env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(tree)] + others)}
        out = subprocess.run(worker_command(args, section, path, warm), cwd=tree, env=env, capture_output=True,
                             text=True)
        if out.returncode != 0:
            raise RuntimeError(f"benchmark section {section!r} failed in {tree}:\n{out.stderr[-3000:]}")
        return json.loads(path.read_text())


def against(args) -> list[dict]:
    """Interleaved runs of every chosen section in this tree and in ``args.against``;
    returns both trees' median rows, tagged with their revisions."""
    new_rev = revision(ROOT)
    with checked_out(args.against) as old_tree:
        old_rev = revision(old_tree)
        trees = {"new": (ROOT, new_rev), "old": (old_tree, old_rev)}
        n = share_numba_cache(ROOT, old_tree)
        print(f"this tree {new_rev} against {args.against} = {old_rev} (temporary worktree {old_tree}; "
              f"{n} cached kernel files shared)", flush=True)
        sections = [s for s in args.only if s != "cold"]
        for label, (tree, rev) in trees.items():  # compile (or load) every variant before timing
            t0 = time.perf_counter()
            for section in sections:
                run_in_tree(args, tree, section, warm=True)
            print(f"  warmed {label} tree ({rev}) in {time.perf_counter() - t0:.0f} s", flush=True)
        runs = {"new": [], "old": []}
        for k in range(args.rounds):
            order = ("new", "old") if k % 2 == 0 else ("old", "new")
            for section in args.only:
                for label in order:
                    runs[label] += run_in_tree(args, trees[label][0], section)
            print(f"  round {k + 1}/{args.rounds} done", flush=True)
    out = []
    for label, (_, rev) in trees.items():
        groups = {}
        for r in runs[label]:
            groups.setdefault(tuple(r.get(k) for k in ROW_KEY), []).append(r)
        for rs in groups.values():
            med = dict(rs[0])
            for k, v in rs[0].items():
                if isinstance(v, float):
                    med[k] = statistics.median(r[k] for r in rs)
            med.update(revision=rev, compared_with=trees["old" if label == "new" else "new"][1], tree=label,
                       rounds=len(rs))
            out.append(med)
    return out


def _figure(x) -> str:
    return "-" if not x else f"{x:,.0f}" if x >= 100 else f"{x:.4g}"


def against_markdown(rows: list[dict], rev_spec: str) -> str:
    new = [r for r in rows if r["tree"] == "new"]
    old = {tuple(r.get(k) for k in ROW_KEY): r for r in rows if r["tree"] == "old"}
    if not new:
        return ""
    new_rev, old_rev = new[0]["revision"], new[0]["compared_with"]
    lines = [f"# This tree ({new_rev}) against {rev_spec} ({old_rev})", "",
             f"Medians over {new[0]['rounds']} interleaved rounds (each a fresh process per tree and section, "
             "the same seeds); ratio = this tree / the other. Higher is better for rates, lower for latencies "
             "and seconds.", ""]
    for section, figures in COMPARED.items():
        rs = [r for r in new if r["section"] == SECTION_NAMES[section]]
        if not rs:
            continue
        head = "| scene | solver | effects | tables | " + " | ".join(
            f"{lab}, {old_rev} | {lab}, {new_rev} | ratio" for _, lab in figures) + " |"
        lines += [f"## {SECTION_NAMES[section]}", "", head,
                  "|---|---|---|---:|" + "---:|---:|---:|" * len(figures)]
        for r in rs:
            o = old.get(tuple(r.get(k) for k in ROW_KEY))
            cells = []
            for col, _ in figures:
                a, b = (o or {}).get(col), r.get(col)
                cells += [_figure(a), _figure(b), f"{b / a:.3f}" if a and b else "-"]
            kind = r.get("autoreset") or r.get("note") or r["effects"]
            lines.append(f"| {r['scene']} | {r['solver']} | {kind} | {r['batch']} | " + " | ".join(cells) + " |")
        lines.append("")
    return "\n".join(lines)


# ------------------------------------------------------------------- main --
def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--batch", type=int, default=None, help="tables per simulator call (default 1024, quick 64)")
    ap.add_argument("--repeats", type=int, default=None, help="timed repeats per figure (default 5, quick 2)")
    ap.add_argument("--quick", action="store_true", help="batch 64, 2 repeats, 4 env steps")
    ap.add_argument("--only", nargs="*", default=["solver", "effects", "env", "cold"],
                    choices=list(SECTION_NAMES) + ["games"],
                    help="sections (default: all but models; models: every effect with each non-default "
                         "model, written to models.md)")
    ap.add_argument("--scene", action="append", default=None,
                    help="keep only scenes (or env ids) containing this text (repeatable)")
    ap.add_argument("--out", type=Path, default=ROOT / "results" / "benchmark")
    ap.add_argument("--against", metavar="REV", default=None,
                    help="time this tree and git revision REV (temporary worktree) in turn; writes against.md")
    ap.add_argument("--rounds", type=int, default=3, help="interleaved rounds per tree with --against")
    ap.add_argument("--history", action="store_true", help="only redraw history.png from the CSVs")
    ap.add_argument("--worker", type=Path, default=None, help=argparse.SUPPRESS)  # rows as JSON to this file
    args = ap.parse_args(argv)
    args.batch = args.batch or (64 if args.quick else 1024)
    args.repeats = args.repeats or (2 if args.quick else 5)
    if args.history:
        path = plot_history(args.out)
        print(f"wrote {path}" if path else f"no full-size rows in {args.out}/benchmark*.csv: nothing to plot")
        return
    if args.worker is not None:
        args.worker.write_text(json.dumps(run_sections(args)))
        return
    args.out.mkdir(parents=True, exist_ok=True)
    if "games" in args.only:  # two-player games: billiards_env/studies/games_bench.py, its own table games.md
        from billiards_env.studies import games_bench
        md = games_bench.markdown(games_bench.rows(("nine_ball",), args.batch, 3 * args.batch))
        print(md)
        (args.out / "games.md").write_text(md)
        args.only = [s for s in args.only if s != "games"]
        if not args.only:
            return
    stamp = datetime.datetime.now().isoformat(timespec="seconds")
    common = dict(timestamp=stamp, quick=args.quick)
    if args.against:
        rows = against(args)
        md = against_markdown(rows, args.against)
        print()
        print(md)
        (args.out / "against.md").write_text(md)
        append_csv(args.out / "benchmark.csv", [{**r, **common} for r in rows])
        print(f"\nwrote {args.out / 'against.md'} and appended to {args.out / 'benchmark.csv'}")
        return
    rows = run_sections(args)
    md = markdown(rows)
    print()
    print(md)
    # one Markdown file per section, so a partial run (--only) replaces only
    # its own sections; benchmark.md joins the latest of every section
    for section in args.only:
        part = markdown([r for r in rows if r["section"] == SECTION_NAMES[section]])
        (args.out / f"{section}.md").write_text(part.rstrip("\n") + "\n")
    parts = [(args.out / f"{k}.md").read_text() for k in SECTION_NAMES if (args.out / f"{k}.md").exists()]
    (args.out / "benchmark.md").write_text("\n".join(parts))
    append_csv(args.out / "benchmark.csv", [{**r, **common, "revision": revision(ROOT)} for r in rows])
    history = plot_history(args.out)
    print(f"\nwrote {args.out / 'benchmark.md'}{' and ' + str(history) if history else ''}, appended to "
          f"{args.out / 'benchmark.csv'}")


if __name__ == "__main__":
    main()
