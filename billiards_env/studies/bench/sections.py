"""The benchmark's measurements, one function per section, each returning
its rows (dicts; ``report`` tabulates them). Every section takes a
``RunOptions``; ``quick`` is its small size."""
from __future__ import annotations

import os
import statistics
import subprocess
import sys
import tempfile
import time

import numba
import numpy as np

from billiards_env.physics import Effects, PhysicsParams, Table, set_num_threads, simulate

from .. import scenes as _scenes
from .impacts import impact_rows
from .options import RunOptions
from .scenes import SCENES, chosen_scenes
from .timing import simulator_clock, timeit


def _threads() -> int:
    return numba.config.NUMBA_NUM_THREADS


def _solver_label(solver: str, dt) -> str:
    return solver if dt is None else f"step dt={dt:g}"


def solver_rows(opts: RunOptions, P, T) -> list[dict]:
    """Each scene with the event solver and the step solver (dt 1e-3, 1e-4):
    shots/s on 1 and all threads, and one table's latency."""
    rows = []
    solvers = [("event", None), ("step", 1e-3), ("step", 1e-4)]
    for name in chosen_scenes(opts):
        make = SCENES[name]
        for solver, dt in solvers:
            n = opts.batch
            if solver == "step" and dt < 1e-3:
                n = max(16, opts.batch // 16)  # fine steps: a smaller batch keeps the run short
            s = make(n, P, T, np.random.default_rng(0))
            one = s.take([0])
            run = lambda st=s: simulate(st, T, P, solver=solver, dt=dt)
            res = run()
            row = dict(section="solver", scene=name, solver=_solver_label(solver, dt),
                       effects="all", batch=n, events_per_shot=float(np.mean(res.n_events)))
            for threads in (1, _threads()):
                set_num_threads(threads)
                t = timeit(run, opts.repeats)
                row[f"shots_per_s_{threads}t"] = n / t
            set_num_threads(_threads())
            row["latency_ms"] = 1e3 * timeit(lambda: simulate(one, T, P, solver=solver, dt=dt), opts.repeats * 3)
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


def _effects_row(case: dict, run, one_run, repeats: int) -> tuple[dict, float]:
    """One row of ``effects_rows`` (without the speed-up) and its 1-thread
    time: ``run`` simulates the batch, ``one_run`` its first table; ``case``
    holds the row's labels and ``dt``."""
    nt = _threads()
    res = run()
    set_num_threads(1)
    t1 = timeit(run, repeats)
    set_num_threads(nt)
    tall = timeit(run, repeats)
    lat = timeit(one_run, repeats * 3)
    n, dt = case["batch"], case.pop("dt")
    events = float(np.mean(res.n_events))
    sim_s = float(np.mean(res.time))
    units = events if dt is None else sim_s / dt  # events, or steps
    return dict(**case, events_per_shot=events, sim_seconds_per_shot=sim_s, us_per_unit=1e6 * t1 / n / units,
                shots_per_s_1t=n / t1, **{f"shots_per_s_{nt}t": n / tall}, latency_ms=1e3 * lat), t1


def effects_rows(opts: RunOptions, P, T, sets=None, section: str = "effects") -> list[dict]:
    """Each effect switched off alone, and all at once, on the same shots
    (``sets``: label -> Effects, or label -> (Effects, Models); the first is
    the baseline of the speed-up column). Besides shots/s the rows give what
    explains them: events and simulated seconds per shot (the physics of the
    set) and the cost of one event (event solver) or one step (step solver)
    (the kernel's work)."""
    sets = {k: v if isinstance(v, tuple) else (v, None) for k, v in (sets or EFFECT_SETS).items()}
    rows = []
    for scene in chosen_scenes(opts, ("9-ball break (8 m/s)", "two-ball cut (2 m/s, top+side)")):
        for solver, dt in (("event", None), ("step", 1e-3)):
            # the step solver is ~30x slower: a quarter batch keeps the run short
            n = opts.batch if solver == "event" else max(16, opts.batch // 4)
            s = SCENES[scene](n, P, T, np.random.default_rng(1))
            one = s.take([0])
            base = None
            # quick: the step solver with the baseline set only (each set is another kernel to compile, ~5 s;
            # the event rows still run every set, so every code path of the section runs)
            chosen = list(sets.items())[:1] if opts.quick and solver == "step" else sets.items()
            for label, (eff, models) in chosen:
                choice = {} if models is None else {"models": models}  # None: the simulator's default
                run = lambda st=s, e=eff, m=choice: simulate(st, T, P, solver=solver, dt=dt, effects=e, **m)
                one_run = lambda e=eff, m=choice: simulate(one, T, P, solver=solver, dt=dt, effects=e, **m)
                case = dict(section=section, scene=scene, solver=_solver_label(solver, dt), effects=label, batch=n,
                            dt=dt)
                row, t1 = _effects_row(case, run, one_run, opts.repeats)
                base = t1 if base is None else base
                row["speedup_vs_all"] = base / t1
                rows.append(row)
                print(f"  {scene:32s} {solver:6s} {label:20s} x{base / t1:5.2f} vs all", flush=True)
    return rows


# the airborne section's scenes (studies.scenes): a planar break, and two
# scenes of elevated cues that leave the slate
AIRBORNE_SCENES = {"9-ball break (8 m/s)": lambda n, P, T, rng: _scenes.straight_break(T, P, n, rng, layout="nine"),
                   "9-ball break, cue elevated 3-12 deg": lambda n, P, T, rng: _scenes.elevated_break(T, P, n, rng),
                   "jump over a blocker (30-50 deg, 3-6 m/s)": lambda n, P, T, rng: _scenes.jump_over(T, P, n, rng)}


def airborne_rows(opts: RunOptions, P, T) -> list[dict]:
    """What flight costs (issue 46): each scene by the planar kernel (the
    elevated cue's vertical velocity dropped, ``scenes.planar``) and by the
    airborne kernel (``Effects(airborne=True)``), event solver, on the same
    shots: shots/s, events per shot and the cost of one event (target: the
    airborne kernel's per-event cost on the planar break at most 1.5x the
    planar kernel's)."""
    rows = []
    for scene in chosen_scenes(opts, tuple(AIRBORNE_SCENES)):
        s = AIRBORNE_SCENES[scene](opts.batch, P, T, np.random.default_rng(1))
        base = None
        for label, eff, st in (("all (planar)", Effects.all(), _scenes.planar(s)),
                               ("all + airborne", Effects(airborne=True), s)):
            one = st.take([0])
            run = lambda x=st, e=eff: simulate(x, T, P, effects=e)
            one_run = lambda x=one, e=eff: simulate(x, T, P, effects=e)
            case = dict(section="airborne", scene=scene, solver="event", effects=label, batch=opts.batch, dt=None)
            row, t1 = _effects_row(case, run, one_run, opts.repeats)
            base = t1 if base is None else base
            row["speedup_vs_all"] = base / t1
            rows.append(row)
            print(f"  {scene:40s} {label:16s} {row['us_per_unit']:.3f} us/event x{base / t1:5.2f} vs planar",
                  flush=True)
    return rows


def _env_case(env_id: str, n: int, mode: str, opts: RunOptions) -> dict:
    """One row of ``env_rows``: ``n`` tables of ``env_id`` in autoreset ``mode``."""
    import gymnasium as gym
    env = gym.make_vec(env_id, num_envs=n, vectorization_mode="vector_entry_point", autoreset_mode=mode)
    with simulator_clock() as sim_time:
        env.reset(seed=0)
        rng = np.random.default_rng(0)
        acts = rng.uniform(-1, 1, size=(32, n, 4)).astype(np.float32)
        env.step(acts[0])
        steps = max(4, min(64, 20_000 // n)) if not opts.quick else 4
        runs = []
        for _ in range(opts.repeats):
            sim_time[0] = 0.0
            t0 = time.perf_counter()
            for k in range(steps):
                env.step(acts[k % 32])
            runs.append((time.perf_counter() - t0, sim_time[0]))
    dt = statistics.median(r[0] for r in runs)
    env.close()
    return dict(section="env", scene=env_id, solver="event", effects="task", batch=n, autoreset=mode,
                env_steps_per_s=n * steps / dt,
                sim_share=statistics.median(ts / d for d, ts in runs),
                env_overhead_pct=statistics.median(100.0 * (d - ts) / ts for d, ts in runs))


def env_rows(opts: RunOptions) -> list[dict]:
    """Env steps/s through gymnasium.make_vec with random actions. The env's
    own simulator calls (shots and NineBall's break simulations in resets)
    are timed in the same run, so the overhead is the time the env spends
    outside the simulator, over the time inside it."""
    import billiards_env  # noqa: F401  (registers the tasks)
    rows = []
    cases = [(n, "same_step") for n in (1, 64, 1024)] + [(1024, "next_step")]
    for env_id in [e for e in ("Billiards-PotOne-v1", "Billiards-NineBall-v1") if opts.keeps(e)]:
        for n, mode in cases:
            r = _env_case(env_id, n, mode, opts)
            rows.append(r)
            print(f"  {env_id:24s} {n:5d} tables {mode:9s} {r['env_steps_per_s']:10.0f} steps/s, "
                  f"overhead {r['env_overhead_pct']:5.1f}%", flush=True)
    return rows


# The cold-start scene: import and first 9-ball break (also profiled by
# scripts/compile_profile.py); prints its wall time
COLD_START_CODE = ("import time; t0=time.perf_counter(); import numpy as np; "
                   "from billiards_env.physics import *; P=PhysicsParams.standard(); T=Table.pool(9); "
                   "s=strike_velocity(rack(T,P,'nine',1,seed=0), 1.5708, 8.0, params=P); simulate(s,T,P); "
                   "print(time.perf_counter()-t0)")


def cold_start_rows(opts: RunOptions | None = None) -> list[dict]:
    """``COLD_START_CODE`` in a fresh process with an empty numba cache, then
    again with the cache it left (the same at every size: ``quick`` changes
    nothing)."""
    rows = []
    with tempfile.TemporaryDirectory() as cold_dir:
        for label in ("cold (empty numba cache)", "warm (numba cache on disk)"):
            out = subprocess.run([sys.executable, "-c", COLD_START_CODE], capture_output=True, text=True,
                                 env={**os.environ, "NUMBA_CACHE_DIR": cold_dir}, check=True)
            rows.append(dict(section="cold start", scene="import + first 9-ball break", solver="event",
                             effects="all", batch=1, seconds=float(out.stdout.strip().splitlines()[-1]), note=label))
            print(f"  {label}: {rows[-1]['seconds']:.2f} s", flush=True)
    return rows


# Sections measured by code above the library (the RLlib backend lives in the
# checkout's agents/): scripts/benchmark.py plugs them in with ``plug_in``.
PLUGGED: dict = {}


def plug_in(name: str, rows, markdown) -> None:
    """Add a section: ``rows(opts) -> list[dict]`` and ``markdown(rows) -> list[str]``."""
    PLUGGED[name] = (rows, markdown)


def rllib_rows(opts: RunOptions) -> list[dict]:
    """RLlib vs SB3 vs the bare env (plugged in by scripts/benchmark.py from
    ``agents/rllib/bench.py``; needs the ``ray`` extra)."""
    if "rllib" not in PLUGGED:
        raise RuntimeError("the rllib section is measured by agents/rllib/bench.py: run it through "
                           "scripts/benchmark.py --only rllib from a checkout")
    return PLUGGED["rllib"][0](opts)


def games_markdown(opts: RunOptions) -> str:
    """The two-player games' table (``studies.games_bench``): games/s of
    ``opts.batch`` tables over ``3 * batch`` games, and the vector env's
    steps/s, for the games whose specs' presets are benchmarked (``games_bench.benchmarked_games``: 9-ball,
    10-ball and three-cushion, each between its default bots), then three-cushion's shots/s per thread and
    cost per event beside the pool scenes (``games_bench.carom_shots``)."""
    from billiards_env.studies import games_bench
    table = games_bench.markdown(games_bench.rows(games_bench.benchmarked_games(), opts.batch,
                                                  3 * opts.batch, quick=opts.quick))
    return table + "\n" + games_bench.carom_markdown(games_bench.carom_shots(opts.batch, opts.repeats))


# --only name -> (heading printed, rows of the section), in the order they run
_SECTIONS = {
    "solver": ("solvers:", lambda o, P, T: solver_rows(o, P, T)),
    "effects": ("effects:", lambda o, P, T: effects_rows(o, P, T)),
    "models": ("models:", lambda o, P, T: impact_rows(o, P) + effects_rows(o, P, T, model_sets(), "models")),
    "airborne": ("airborne:", lambda o, P, T: airborne_rows(o, P, T)),
    "env": ("environments:", lambda o, P, T: env_rows(o)),
    "cold": ("cold start:", lambda o, P, T: cold_start_rows(o)),
    "rllib": ("rllib:", lambda o, P, T: rllib_rows(o)),  # needs the ray extra; not in the default sections
}


def run_sections(opts: RunOptions, only) -> list[dict]:
    """The rows of every section in ``only`` (``games`` excluded: its own table)."""
    P, T = PhysicsParams.standard(), Table.pool(9)
    rows = []
    print(f"numba threads: {_threads()}, batch {opts.batch}", flush=True)
    for name, (heading, measure) in _SECTIONS.items():
        if name in only:
            print(heading)
            rows += measure(opts, P, T)
    return rows
