"""The ``rllib`` section of ``scripts/benchmark.py``: sampling and training
throughput of the Ray RLlib backend against the stable-baselines3 backend
and the bare vector env, all measured in one run on PotOne.

Sampling (env steps/s, one numba thread per env stepper):

- ``bare env``: the vector env exactly as an EnvRunner builds it
  (``rllib_backend.make_vector_env``: native env, next-step autoreset, agent
  features, residual actions) stepped in a loop with random actions; only
  real shots count (the autoreset steps in between cost time, count nothing);
- ``sb3 rollout``: SB3 PPO's ``collect_rollouts`` on the default config's env
  (the same tables in one process, VecNormalize, policy forward passes);
- ``rllib N runners``: N remote EnvRunners (``num_envs_per_env_runner``
  tables each) sampling at once; steps of all runners over the wall time
  (1 and 2 runners interleaved in each repeat).

RLlib's sampling overhead is ``1 - rllib 1 runner / bare env`` at the same
table count; the 2-runner scaling is ``rllib 2 runners / rllib 1 runner``.
The runners also report their processes' CPU time: steps per runner
CPU-second show what each core does whether or not the machine gave the
runners whole cores (on a shared machine it may not).

Training (env steps/s including updates): each backend's ``train`` on the
default PotOne config for ``train_steps`` env steps (no evaluation), the
rate measured from the first to the last iteration, so Ray's start-up and
the first sample's kernel loading are not counted.
"""
from __future__ import annotations

import statistics
import time

import numpy as np

ENV_ID = "Billiards-PotOne-v0"


def _cfg(overrides=()):
    from .config import load_config

    return load_config(None, ENV_ID, list(overrides))


def bare_env_rate(tables: int, shots: int, repeats: int) -> float:
    """Env steps/s of the runner's vector env with random actions (median)."""
    import numba

    from .rllib_backend import env_context, make_vector_env

    cfg = _cfg()
    ctx = {**env_context(cfg), "num_envs": tables, "numba_threads": 1}
    env = make_vector_env(ctx)
    acts = np.random.default_rng(0).uniform(-1, 1, (8, tables, 4)).astype(np.float32)
    env.reset(seed=0)
    env.step(acts[0]); env.step(acts[1])  # warm (kernels loaded)
    rates = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        real = 0
        for k in range(2 * shots):  # one shot, then the autoreset step, as an EnvRunner steps it
            _, _, term, trunc, _ = env.step(acts[k % 8])
            real += int(np.sum(term | trunc)) if k % 2 == 0 else 0
        rates.append(real / (time.perf_counter() - t0))
    env.close()
    numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
    return statistics.median(rates)


def sb3_rollout_rate(repeats: int) -> float:
    """Env steps/s of SB3 PPO's rollout collection (``n_steps`` x ``n_envs``
    of the default config) with one numba thread (median)."""
    import numba
    import torch

    from .training import build_env, build_model

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


def rllib_sample_rates(tables: int, shots: int, repeats: int) -> dict:
    """Env steps/s of one and of two remote EnvRunners sampling ``shots``
    steps of ``tables`` tables each at once: one algorithm with two runners,
    the two cases interleaved in each repeat (medians), so load from other
    processes hits both alike."""
    from .rllib_backend import algo_config

    cfg = _cfg(["rllib.num_env_runners=2", f"rllib.num_envs_per_env_runner={tables}",
                f"rllib.train_batch_size_per_learner={2 * tables}", f"rllib.minibatch_size={2 * tables}"])
    algo = algo_config(cfg).build_algo()
    group = algo.env_runner_group
    def sample(runner):  # (env steps, CPU seconds of the runner process)
        c0 = time.process_time()
        steps = sum(len(e) for e in runner.sample(num_timesteps=tables * shots))
        return steps, time.process_time() - c0

    ids = {1: [1], 2: [1, 2]}
    try:
        group.foreach_env_runner(sample, local_env_runner=False)  # warm
        rates = {1: [], 2: []}
        cpu_rates = {1: [], 2: []}
        for _ in range(repeats):
            for n, workers in ids.items():
                t0 = time.perf_counter()
                out = group.foreach_env_runner(sample, local_env_runner=False, remote_worker_ids=workers)
                steps = sum(o[0] for o in out)
                rates[n].append(steps / (time.perf_counter() - t0))
                cpu_rates[n].append(steps / sum(o[1] for o in out))
    finally:
        algo.stop()
    return {**{n: statistics.median(r) for n, r in rates.items()},
            **{f"{n} per cpu": statistics.median(r) for n, r in cpu_rates.items()}}


def _iteration_rate(progress_csv) -> float:
    """Env steps/s between the first and the last logged iteration."""
    import csv

    with open(progress_csv) as f:
        rows = list(csv.DictReader(f))
    a, b = rows[0], rows[-1]
    return (int(b["timesteps"]) - int(a["timesteps"])) / (float(b["time_s"]) - float(a["time_s"]))


def train_rates(train_steps: int, tmp) -> dict:
    """Env steps/s including updates of both backends on the default config."""
    from pathlib import Path

    from . import rllib_backend
    from .training import train

    tmp = Path(tmp)
    common = [f"train.total_timesteps={train_steps}", "train.checkpoint_every=0", "train.progress_bar=false",
              "train.tensorboard=false", "train.eval_episodes=0"]
    train(_cfg(common), tmp / "sb3")
    rllib_backend.train(_cfg(common), tmp / "rllib")
    return dict(sb3=_iteration_rate(tmp / "sb3" / "progress.csv"),
                rllib=_iteration_rate(tmp / "rllib" / "progress.csv"))


def rllib_rows(args) -> list[dict]:
    """The section's rows (``scripts/benchmark.py --only rllib``); starts a
    local Ray instance with 2 CPUs and shuts it down."""
    import tempfile

    import ray

    from .rllib_backend import start_ray

    tables = 64 if args.quick else 256
    shots = 4 if args.quick else 16
    repeats = args.repeats
    train_steps = 4 * 2048 if args.quick else 16 * 2048
    rows = []

    def add(kind, steps_per_s, **kw):
        rows.append(dict(section="rllib", scene=ENV_ID, solver="event", effects="task", kind=kind,
                         env_steps_per_s=steps_per_s, **kw))
        print(f"  {kind:34s} {steps_per_s:10.0f} env steps/s", flush=True)

    add("sampling: bare env", bare_env_rate(tables, shots, repeats), batch=tables, runners=1)
    add("sampling: sb3 rollout", sb3_rollout_rate(repeats), batch=256, runners=1)
    ray.shutdown()
    start_ray(num_cpus=2)
    try:
        sampled = rllib_sample_rates(tables, shots, repeats)
        for n in (1, 2):
            add(f"sampling: rllib {n} runner{'s' * (n > 1)}", sampled[n], batch=tables, runners=n)
        for n in (1, 2):
            add(f"sampling: rllib {n} runner{'s' * (n > 1)}, per runner CPU-second", sampled[f"{n} per cpu"],
                batch=tables, runners=n)
        with tempfile.TemporaryDirectory() as tmp:
            rates = train_rates(train_steps, tmp)
    finally:
        ray.shutdown()
    add("training: sb3 (default config)", rates["sb3"], batch=256, runners=1)
    add("training: rllib (default config)", rates["rllib"], batch=256, runners=2)
    return rows


def rllib_markdown(rows: list[dict]) -> list[str]:
    """The section's table, with the derived ratios."""
    if not rows:
        return []
    by = {r["kind"]: r for r in rows}
    lines = ["| measurement | tables per stepper | steppers | env steps/s |", "|---|---:|---:|---:|"]
    for r in rows:
        lines.append(f"| {r['kind']} | {r['batch']} | {r['runners']} | {r['env_steps_per_s']:,.0f} |")
    bare, one, two = (by.get(k, {}).get("env_steps_per_s") for k in
                      ("sampling: bare env", "sampling: rllib 1 runner", "sampling: rllib 2 runners"))
    lines.append("")
    if bare and one:
        lines.append(f"RLlib sampling overhead over the bare env (1 runner): {100 * (1 - one / bare):.0f}%")
    if one and two:
        lines.append(f"2 runners / 1 runner: {two / one:.2f}x")
    c1, c2 = (by.get(f"sampling: rllib {k}, per runner CPU-second", {}).get("env_steps_per_s")
              for k in ("1 runner", "2 runners"))
    if c1 and c2:
        lines.append(f"steps per runner CPU-second, 2 runners / 1 runner: {c2 / c1:.2f} "
                     f"(1.00: each runner does the same work per core as one alone)")
    lines.append("")
    return lines
