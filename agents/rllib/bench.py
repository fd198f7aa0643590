"""The ``rllib`` section of ``scripts/benchmark.py``: sampling and training
throughput of the Ray RLlib backend against the stable-baselines3 backend
and the bare vector env, all measured in one run on PotOne.

Sampling (env steps/s, one numba thread per env stepper):

- ``bare env``: the vector env exactly as an EnvRunner builds it
  (``backend.make_vector_env``: native env, next-step autoreset, agent
  features, residual actions) stepped in a loop with random actions; only
  real shots count (the autoreset steps in between cost time, count nothing);
- ``sb3 rollout``: SB3 PPO's ``collect_rollouts`` on the default config's env
  (the same tables in one process, VecNormalize, policy forward passes);
- ``rllib N runners``: N remote EnvRunners (``num_envs_per_env_runner``
  tables each) sampling at once; steps of all runners over the wall time
  (1 and 2 runners interleaved in each repeat), with the backend's lean
  sampling (``backend.algo_config(lean=True)``, the default) and
  with RLlib's own observation filter, collector and action pass.

RLlib's sampling overhead is ``1 - rllib 1 runner / bare env`` at the same
table count; the 2-runner scaling is ``rllib 2 runners / rllib 1 runner``.
On a shared machine wall-clock ratios measure the other jobs too, so every
sampling interval is also CPU-accounted from ``/proc`` (Linux): the CPU
seconds of the driver, of each runner and of every Ray daemon (gcs_server,
raylet, dashboard and agents, log monitor), and the time each runner was
runnable but waiting for a core (``schedstat``). From these: steps per
runner CPU-second, steps per wall second without the runners' run-queue
wait, and the cores each kind of process used.

Where a runner's CPU goes (``sample_breakdown``): one EnvRunner built in the
benchmark's process, its env step, module forward pass and connector
pipelines timed with ``time.process_time``; the rest of ``sample()`` is the
runner's loop over tables and its episode objects, whose cost alone is
``episode_object_us``.

Training (env steps/s including updates): each backend's ``train`` on the
default PotOne config for ``train_steps`` env steps (no evaluation), the
rate measured from the first to the last iteration, so Ray's start-up and
the first sample's kernel loading are not counted.
"""
from __future__ import annotations

import gc
import os
import statistics
import time

import numpy as np

ENV_ID = "Billiards-PotOne-v1"


def _cfg(overrides=()):
    from ..config import load_config

    return load_config(None, ENV_ID, list(overrides))


def bare_env_rate(tables: int, shots: int, repeats: int) -> tuple[float, float]:
    """Env steps/s of the runner's vector env with random actions, per wall
    second and per CPU-second of this process (medians)."""
    import numba

    from .backend import env_context, make_vector_env

    cfg = _cfg()
    ctx = {**env_context(cfg), "num_envs": tables, "numba_threads": 1}
    env = make_vector_env(ctx)
    acts = np.random.default_rng(0).uniform(-1, 1, (8, tables, 4)).astype(np.float32)
    env.reset(seed=0)
    env.step(acts[0]); env.step(acts[1])  # warm (kernels loaded)
    rates, cpu_rates = [], []
    for _ in range(repeats):
        t0, c0 = time.perf_counter(), time.process_time()
        real = 0
        for k in range(2 * shots):  # one shot, then the autoreset step, as an EnvRunner steps it
            _, _, term, trunc, _ = env.step(acts[k % 8])
            real += int(np.sum(term | trunc)) if k % 2 == 0 else 0
        rates.append(real / (time.perf_counter() - t0))
        cpu_rates.append(real / (time.process_time() - c0))
    env.close()
    numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
    return statistics.median(rates), statistics.median(cpu_rates)


def sb3_rollout_rate(repeats: int) -> float:
    """Env steps/s of SB3 PPO's rollout collection (``n_steps`` x ``n_envs``
    of the default config) with one numba thread (median)."""
    import numba
    import torch

    from ..sb3.training import build_env, build_model

    cfg = _cfg(["train.tensorboard=false"])
    torch.set_num_threads(cfg.train.torch_threads)
    numba.set_num_threads(1)
    env, _ = build_env(cfg, 0)
    model = build_model(cfg, env, None)
    _, callback = model._setup_learn(10 ** 9, callback=None)
    callback.on_training_start(locals(), globals())
    rates = []
    for r in range(repeats + 1):
        t0 = time.perf_counter()
        model.collect_rollouts(model.env, callback, model.rollout_buffer, n_rollout_steps=model.n_steps)
        if r:  # the first collection warms up
            rates.append(model.n_steps * env.num_envs / (time.perf_counter() - t0))
    env.close()
    numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
    return statistics.median(rates)


# --------------------------------------------------- CPU accounting --
CLOCK_TICKS = os.sysconf("SC_CLK_TCK") if hasattr(os, "sysconf") else 100


def _proc_cpu(pid: int) -> tuple[str, float, float]:
    """(command line, CPU seconds of all its threads, seconds its main thread
    was runnable but waiting for a core) of process ``pid`` over its life
    (Linux ``/proc``: ``stat`` utime + stime, the main thread's ``schedstat``
    run-queue wait; an EnvRunner samples in its main thread, while Ray's
    helper threads wake often and would add waits that overlap it)."""
    with open(f"/proc/{pid}/cmdline", "rb") as f:
        cmd = f.read().replace(b"\0", b" ").decode(errors="replace").strip()
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    cpu = (int(fields[11]) + int(fields[12])) / CLOCK_TICKS
    try:
        with open(f"/proc/{pid}/task/{pid}/schedstat") as f:
            wait = int(f.read().split()[1]) / 1e9
    except OSError:
        wait = 0.0
    return cmd, cpu, wait


def process_tree_cpu(root: int) -> dict[int, tuple[str, float, float]]:
    """``_proc_cpu`` of ``root`` and all its descendants: for a driver that
    started a local Ray instance, that is every Ray process (gcs_server,
    raylet, dashboard and its agents, log monitor, workers and EnvRunner
    actors). Empty where ``/proc`` is missing (not Linux)."""
    if not os.path.isdir("/proc"):
        return {}
    parent = {}
    for d in os.listdir("/proc"):
        if d.isdigit():
            try:
                with open(f"/proc/{d}/stat") as f:
                    parent[int(d)] = int(f.read().rsplit(")", 1)[1].split()[1])
            except OSError:
                pass
    children: dict[int, list[int]] = {}
    for pid, pp in parent.items():
        children.setdefault(pp, []).append(pid)
    out, todo = {}, [root]
    while todo:
        pid = todo.pop()
        try:
            out[pid] = _proc_cpu(pid)
        except OSError:
            continue
        todo += children.get(pid, [])
    return out


def ray_process_kind(cmd: str) -> str:
    """A Ray process's role from its command line (for the CPU account)."""
    for key, kind in (("gcs_server", "gcs_server"), ("raylet", "raylet"), ("dashboard/agent", "dashboard agent"),
                      ("DashboardAgent", "dashboard agent"), ("RuntimeEnvAgent", "runtime env agent"),
                      ("dashboard", "dashboard"), ("log_monitor", "log monitor"), ("monitor.py", "monitor"),
                      ("ray::", "other Ray workers")):
        if key in cmd:
            return kind
    return "other"


def cpu_account(before: dict, after: dict, driver: int, runners: set) -> tuple[dict, dict]:
    """CPU seconds per kind of process between two ``process_tree_cpu``
    snapshots (``driver``, ``runner`` for the pids in ``runners``, Ray's
    daemons by ``ray_process_kind``), and the run-queue wait of each runner."""
    cpu: dict[str, float] = {}
    waits = {}
    for pid, (cmd, c, w) in after.items():
        _, c0, w0 = before.get(pid, (cmd, 0.0, 0.0))
        kind = "driver" if pid == driver else "runner" if pid in runners else ray_process_kind(cmd)
        cpu[kind] = cpu.get(kind, 0.0) + c - c0
        if pid in runners:
            waits[pid] = w - w0
    return cpu, waits


def rllib_sample_rates(tables: int, shots: int, repeats: int, lean: bool = True) -> dict:
    """One and two remote EnvRunners sampling ``shots`` steps of ``tables``
    tables each at once: one algorithm with two runners, the two cases
    interleaved in each repeat (medians), so load from other processes hits
    both alike. Per case: env steps/s over the wall time (``wall``), per
    CPU-second of the sampling runners (``per_cpu``), over the wall time
    minus the longest run-queue wait of a runner (``unqueued``: what the
    runners did while they held a core; on an idle machine with a core per
    runner that is the wall time), and the cores each kind of process used
    (``cores``: CPU seconds over wall seconds; Ray's daemons, the driver,
    the runners). ``lean``: ``algo_config``'s lean sampling or RLlib's own."""
    from .backend import algo_config

    cfg = _cfg(["rllib.num_env_runners=2", f"rllib.num_envs_per_env_runner={tables}",
                f"rllib.train_batch_size_per_learner={2 * tables}", f"rllib.minibatch_size={2 * tables}"])
    algo = algo_config(cfg, lean=lean).build_algo()
    group = algo.env_runner_group
    driver = os.getpid()

    def sample(runner):  # (env steps, runner pid)
        return sum(len(e) for e in runner.sample(num_timesteps=tables * shots)), os.getpid()

    ids = {1: [1], 2: [1, 2]}
    per = {n: dict(wall=[], per_cpu=[], unqueued=[], cores=[]) for n in ids}
    try:
        group.foreach_env_runner(sample, local_env_runner=False)  # warm
        for _ in range(repeats):
            for n, workers in ids.items():
                before = process_tree_cpu(driver)
                t0 = time.perf_counter()
                out = group.foreach_env_runner(sample, local_env_runner=False, remote_worker_ids=workers)
                wall = time.perf_counter() - t0
                cpu, waits = cpu_account(before, process_tree_cpu(driver), driver, {o[1] for o in out})
                steps = sum(o[0] for o in out)
                per[n]["wall"].append(steps / wall)
                if cpu.get("runner"):
                    per[n]["per_cpu"].append(steps / cpu["runner"])
                    per[n]["unqueued"].append(steps / max(wall - max(waits.values()), 1e-9))
                    per[n]["cores"].append({k: v / wall for k, v in cpu.items()})
    finally:
        algo.stop()
    result = {}
    for n, d in per.items():
        kinds = sorted({k for c in d["cores"] for k in c})
        result[n] = dict(wall=statistics.median(d["wall"]),
                         per_cpu=statistics.median(d["per_cpu"]) if d["per_cpu"] else None,
                         unqueued=statistics.median(d["unqueued"]) if d["unqueued"] else None,
                         cores={k: statistics.median(c.get(k, 0.0) for c in d["cores"]) for k in kinds})
    return result


def sample_breakdown(tables: int, shots: int, lean: bool = True, repeats: int = 3) -> dict:
    """CPU seconds per env step of one EnvRunner built in this process (no
    Ray actor), split by where ``sample()`` spends them: the env's step,
    the module's forward pass, the env-to-module and module-to-env
    connectors, and the rest of the runner's loop (episode objects: creation,
    ``add_env_reset``/``add_env_step``, callbacks, ``validate``/``to_numpy``
    of the finished ones). Timed with ``time.process_time`` around each part
    (medians of ``repeats`` samples of ``shots`` steps of ``tables`` tables)."""
    import torch
    from ray.rllib.env.single_agent_env_runner import SingleAgentEnvRunner

    from .backend import algo_config
    from .sampling import tune_worker_gc

    torch.set_num_threads(1)
    cfg = _cfg(["rllib.num_env_runners=0", f"rllib.num_envs_per_env_runner={tables}"])
    runner = SingleAgentEnvRunner(config=algo_config(cfg, lean=lean))
    spent = dict.fromkeys(("env step", "module forward", "env-to-module connectors", "module-to-env connectors"), 0.0)

    def timed(part, fn):
        def call(*a, **kw):
            c0 = time.process_time()
            try:
                return fn(*a, **kw)
            finally:
                spent[part] += time.process_time() - c0
        return call

    runner.env.step = timed("env step", runner.env.step)
    runner.module.forward_exploration = timed("module forward", runner.module.forward_exploration)
    runner._env_to_module = timed("env-to-module connectors", runner._env_to_module)
    runner._module_to_env = timed("module-to-env connectors", runner._module_to_env)
    runner.sample(num_timesteps=2 * tables)  # warm
    gc_state = gc.get_threshold(), gc.isenabled()
    if lean:
        tune_worker_gc()  # what a remote lean runner does in its own process
    rows = []
    try:
        for _ in range(repeats):
            for k in spent:
                spent[k] = 0.0
            c0 = time.process_time()
            steps = sum(len(e) for e in runner.sample(num_timesteps=tables * shots))
            total = time.process_time() - c0
            row = {k: 1e6 * v / steps for k, v in spent.items()}
            row["episode bookkeeping and the runner's loop"] = 1e6 * (total - sum(spent.values())) / steps
            row["total"] = 1e6 * total / steps
            rows.append(row)
    finally:
        gc.unfreeze()
        gc.set_threshold(*gc_state[0])
        runner.stop()
    return {k: statistics.median(r[k] for r in rows) for k in rows[0]}


def runner_cpu_rate(tables: int = 256, shots: int = 16, repeats: int = 5, lean: bool = True,
                    explore: bool | None = None, **env_runner_settings) -> float:
    """Env steps per CPU-second of one EnvRunner built in this process with
    ``algo_config(cfg, lean)`` plus ``PPOConfig.env_runners`` settings (for
    example ``episodes_to_numpy=False``, ``batch_mode="complete_episodes"``,
    ``add_default_connectors_to_env_to_module_pipeline=False``), sampling
    ``shots`` steps of ``tables`` tables (median of ``repeats``), with the
    collector tuned as in a remote lean runner. ``explore=False`` samples
    with the deterministic forward pass (not usable for PPO's training: no
    exploration; shown for the forward pass's cost)."""
    import torch
    from ray.rllib.env.single_agent_env_runner import SingleAgentEnvRunner

    from .backend import algo_config
    from .sampling import tune_worker_gc

    torch.set_num_threads(1)
    cfg = _cfg(["rllib.num_env_runners=0", f"rllib.num_envs_per_env_runner={tables}"])
    config = algo_config(cfg, lean=lean)
    if env_runner_settings:
        config = config.env_runners(**env_runner_settings)
    runner = SingleAgentEnvRunner(config=config)
    runner.sample(num_timesteps=2 * tables, explore=explore)  # warm
    threshold = gc.get_threshold()
    if lean:
        tune_worker_gc()
    rates = []
    try:
        for _ in range(repeats):
            c0 = time.process_time()
            steps = sum(len(e) for e in runner.sample(num_timesteps=tables * shots, explore=explore))
            rates.append(steps / (time.process_time() - c0))
    finally:
        gc.unfreeze()
        gc.set_threshold(*threshold)
        runner.stop()
    return statistics.median(rates)


def gc_sample_rates(tables: int = 256, shots: int = 16, samples: int = 6) -> dict:
    """Env steps per CPU-second of each of ``samples`` consecutive samples of
    one EnvRunner built in this process with RLlib's own filter and action
    pass (``lean=False``), first with CPython's default collector, then with
    ``tune_worker_gc``: what the collector alone costs a runner."""
    import torch
    from ray.rllib.env.single_agent_env_runner import SingleAgentEnvRunner

    from .backend import algo_config
    from .sampling import tune_worker_gc

    torch.set_num_threads(1)
    cfg = _cfg(["rllib.num_env_runners=0", f"rllib.num_envs_per_env_runner={tables}"])
    runner = SingleAgentEnvRunner(config=algo_config(cfg, lean=False))
    runner.sample(num_timesteps=2 * tables)  # warm
    threshold = gc.get_threshold()
    out = {}
    try:
        for name in ("default collector", "tuned collector"):
            if name == "tuned collector":
                tune_worker_gc()
            rates = []
            for _ in range(samples):
                c0 = time.process_time()
                steps = sum(len(e) for e in runner.sample(num_timesteps=tables * shots))
                rates.append(steps / (time.process_time() - c0))
            out[name] = rates
    finally:
        gc.unfreeze()
        gc.set_threshold(*threshold)
        runner.stop()
    return out


def episode_object_us(n: int = 4000) -> dict:
    """CPU microseconds per one-step episode of RLlib's ``SingleAgentEpisode``
    alone (no env, no module): an empty one, and the runner's full path
    (create, ``add_env_reset``, ``add_env_step``, ``validate``,
    ``to_numpy``) with PotOne's observation and action sizes."""
    from ray.rllib.env.single_agent_episode import SingleAgentEpisode

    from .backend import env_context, make_vector_env

    env = make_vector_env({**env_context(_cfg()), "num_envs": 1})
    obs_space, act_space = env.single_observation_space, env.single_action_space
    env.close()
    o0 = np.zeros(obs_space.shape, np.float32)
    a = np.zeros(act_space.shape, np.float32)
    extra = {"action_logp": np.float32(0.0), "action_dist_inputs": np.zeros(2 * a.size, np.float32),
             "vf_preds": np.float32(0.0)}

    def full():
        e = SingleAgentEpisode(observation_space=obs_space, action_space=act_space)
        e.add_env_reset(observation=o0, infos={})
        e.add_env_step(observation=o0, action=a, reward=1.0, infos={}, terminated=True, truncated=False,
                       extra_model_outputs=extra)
        e.validate()
        return e.to_numpy()

    out = {}
    for name, fn in (("empty SingleAgentEpisode", lambda: SingleAgentEpisode(observation_space=obs_space,
                                                                              action_space=act_space)),
                     ("one-step episode, the runner's path", full)):
        fn()
        c0 = time.process_time()
        for _ in range(n):
            fn()
        out[name] = 1e6 * (time.process_time() - c0) / n
    return out


def _iteration_rate(progress_csv) -> float:
    """Env steps/s between the first and the last logged iteration."""
    import csv

    with open(progress_csv) as f:
        rows = list(csv.DictReader(f))
    a, b = rows[0], rows[-1]
    return (int(b["timesteps"]) - int(a["timesteps"])) / (float(b["time_s"]) - float(a["time_s"]))


def train_rates(train_steps: int, tmp) -> dict:
    """Env steps/s including updates of both backends on the default config,
    RLlib's with lean sampling (``rllib``) and with RLlib's own settings
    (``rllib own``), and the driver's CPU seconds over each RLlib run (its
    learner; start-up included: ``... driver cpu``)."""
    from pathlib import Path

    from ..sb3.training import train
    from .backend import train as rllib_train

    tmp = Path(tmp)
    common = [f"train.total_timesteps={train_steps}", "train.checkpoint_every=0", "train.progress_bar=false",
              "train.tensorboard=false", "train.eval_episodes=0"]
    train(_cfg(common), tmp / "sb3")
    out = dict(sb3=_iteration_rate(tmp / "sb3" / "progress.csv"))
    for name, lean in (("rllib", True), ("rllib own", False)):
        c0 = time.process_time()
        rllib_train(_cfg(common), tmp / name, lean=lean)
        out[name + " driver cpu"] = time.process_time() - c0
        out[name] = _iteration_rate(tmp / name / "progress.csv")
    return out


LEAN_LABELS = {True: "", False: " (RLlib's filter, GC, action pass)"}


def rllib_rows(args) -> list[dict]:
    """The section's rows (``scripts/benchmark.py --only rllib``); starts a
    local Ray instance with 2 CPUs and shuts it down."""
    import tempfile

    import ray

    from .backend import start_ray

    tables = 64 if args.quick else 256
    shots = 4 if args.quick else 16
    repeats = args.repeats
    train_steps = 4 * 2048 if args.quick else 16 * 2048
    rows = []

    def add(kind, steps_per_s, **kw):
        rows.append(dict(section="rllib", scene=ENV_ID, solver="event", effects="task", kind=kind,
                         env_steps_per_s=steps_per_s, **kw))
        print(f"  {kind:60s} {steps_per_s:10.0f} env steps/s", flush=True)

    bare, bare_cpu = bare_env_rate(tables, shots, repeats)
    add("sampling: bare env", bare, batch=tables, runners=1)
    add("sampling: bare env, per CPU-second", bare_cpu, batch=tables, runners=1)
    add("sampling: sb3 rollout", sb3_rollout_rate(repeats), batch=256, runners=1)
    for lean in (True, False):  # one EnvRunner in this process: CPU microseconds per env step by part
        for part, us in sample_breakdown(tables, shots, lean, repeats).items():
            rows.append(dict(section="rllib", scene=ENV_ID, kind=f"runner CPU per env step{LEAN_LABELS[lean]}: {part}",
                             us_per_step=us, batch=tables, runners=1))
            print(f"  runner CPU per env step{LEAN_LABELS[lean]}: {part:45s} {us:8.1f} us", flush=True)
    for name, us in episode_object_us().items():
        rows.append(dict(section="rllib", scene=ENV_ID, kind=f"episode object: {name}", us_per_step=us))
        print(f"  episode object: {name:45s} {us:8.1f} us", flush=True)
    ray.shutdown()
    start_ray(num_cpus=2)
    try:
        for lean in (True, False):
            sampled = rllib_sample_rates(tables, shots, repeats, lean)
            for n in (1, 2):
                r = sampled[n]
                name = f"sampling: rllib {n} runner{'s' * (n > 1)}{LEAN_LABELS[lean]}"
                cores = {f"cores_{k.replace(' ', '_')}": round(v, 3) for k, v in r["cores"].items()}
                add(name, r["wall"], batch=tables, runners=n, **cores)
                if r["per_cpu"]:
                    add(name + ", per runner CPU-second", r["per_cpu"], batch=tables, runners=n)
                    add(name + ", without run-queue wait", r["unqueued"], batch=tables, runners=n)
                    print("    cores used: " + ", ".join(f"{k} {v:.3f}" for k, v in r["cores"].items()))
        with tempfile.TemporaryDirectory() as tmp:
            rates = train_rates(train_steps, tmp)
    finally:
        ray.shutdown()
    add("training: sb3 (default config)", rates["sb3"], batch=256, runners=1)
    for name, lean in (("rllib", True), ("rllib own", False)):
        add(f"training: rllib (default config){LEAN_LABELS[lean]}", rates[name], batch=256, runners=2,
            driver_cpu_s=round(rates[name + " driver cpu"], 2), train_steps=train_steps)
        print(f"    driver CPU {rates[name + ' driver cpu']:.1f} s for {train_steps} env steps (start-up included)")
    return rows


def rllib_markdown(rows: list[dict]) -> list[str]:
    """The section's tables, with the derived ratios."""
    if not rows:
        return []
    by = {r["kind"]: r for r in rows}
    rate = [r for r in rows if r.get("env_steps_per_s") not in (None, "")]
    lines = ["| measurement | tables per stepper | steppers | env steps/s |", "|---|---:|---:|---:|"]
    for r in rate:
        lines.append(f"| {r['kind']} | {r['batch']} | {r['runners']} | {float(r['env_steps_per_s']):,.0f} |")
    lines.append("")

    def val(kind):
        v = by.get(kind, {}).get("env_steps_per_s")
        return float(v) if v not in (None, "") else None

    bare, bare_cpu = val("sampling: bare env"), val("sampling: bare env, per CPU-second")
    for lean, label in LEAN_LABELS.items():
        one, two = val(f"sampling: rllib 1 runner{label}"), val(f"sampling: rllib 2 runners{label}")
        c1, c2 = (val(f"sampling: rllib {k}{label}, per runner CPU-second") for k in ("1 runner", "2 runners"))
        u1, u2 = (val(f"sampling: rllib {k}{label}, without run-queue wait") for k in ("1 runner", "2 runners"))
        name = "lean sampling (the backend's default)" if lean else "RLlib's own filter, GC and action pass"
        if bare and one:
            lines.append(f"{name}: RLlib sampling overhead over the bare env (1 runner, wall): {100 * (1 - one / bare):.0f}%")
        if bare_cpu and c1:
            lines.append(f"{name}: overhead per CPU-second (runner against bare env): {100 * (1 - c1 / bare_cpu):.0f}%")
        if one and two:
            lines.append(f"{name}: 2 runners / 1 runner: {two / one:.2f}x wall, "
                         + (f"{u2 / u1:.2f}x without run-queue wait, " if u1 and u2 else "")
                         + (f"{c2 / c1:.2f} per runner CPU-second" if c1 and c2 else ""))
        lines.append("")
    for r in rows:
        if str(r["kind"]).startswith("training: rllib") and r.get("driver_cpu_s") not in (None, ""):
            lines.append(f"{r['kind']}: driver (learner) CPU {float(r['driver_cpu_s']):.1f} s for "
                         f"{int(float(r['train_steps'])):,} env steps, start-up included")
    lines.append("")
    parts = [r for r in rows if str(r["kind"]).startswith("runner CPU per env step")]
    if parts:
        lines += ["| one EnvRunner, CPU per env step | microseconds |", "|---|---:|"]
        lines += [f"| {r['kind'][len('runner CPU per env step'):].lstrip(': ')} | {float(r['us_per_step']):.1f} |"
                  for r in parts]
        lines.append("")
    eps = [r for r in rows if str(r["kind"]).startswith("episode object")]
    if eps:
        lines += ["| RLlib episode object alone | microseconds per episode |", "|---|---:|"]
        lines += [f"| {r['kind'][len('episode object: '):]} | {float(r['us_per_step']):.1f} |" for r in eps]
        lines.append("")
    return lines
