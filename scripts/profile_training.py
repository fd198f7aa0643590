#!/usr/bin/env python
"""Where the time of a training run goes: a cProfile of PPO rollouts and updates.

    python scripts/profile_training.py --env Billiards-NineBall2P-v1 --rollouts 4
    python scripts/profile_training.py --quick --out /tmp/prof.txt    # 8 tables, 1 rollout (the test's run)
    python scripts/profile_training.py --compare new --compare "old:n_envs=256,ppo.n_steps=16,ppo.batch_size=1024"

``--compare LABEL[:KEY=VALUE,...]`` (repeatable) skips the profile and
measures the rates of several configs in one process instead: each is
built and warmed up, then ``--rounds`` rounds of about 16,384 env steps
(rollouts and their updates) run interleaved, config after config, so load
changes hit them alike; the medians of the wall rate, of the rate per
CPU-second of the process and its env workers (``train.env_workers``), and
of the rate per critical-path CPU-second (the process and its busiest
worker: about the wall time on idle cores) are printed as a table (and
written to ``--out``).

Trains the config's model (``configs/ppo_games.yaml`` by default) for one
warm-up rollout, then profiles ``--rollouts`` more and splits their wall
time into the PPO updates, the agent's network in the rollouts, the
agent-side features, the opponent's decisions and the simulator (every
``physics.simulate`` call: the shots played and the bots' previews), from
the profile's cumulative times (by default in CPU time of the process:
``--clock wall`` for wall time). With ``train.env_workers`` > 1 each
worker profiles its own part and the profiles are merged: the shares are
then of the CPU of all the processes. Writes the split and the top of the profile
to ``--out`` (default stdout only). The first line also gives the rate per
CPU-second of the process, which a loaded machine changes less than the
wall rate, and how many cores the process kept busy (numba's idle OpenMP
worker spins: with 2 numba threads the process keeps two cores busy).
"""
from __future__ import annotations

import argparse
import cProfile
import io
import re
import pstats
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

from agents.config import load_config  # noqa: E402
from agents.sb3.training import build_env, build_model  # noqa: E402
from agents.sb3.worker_vec_env import cpu_seconds, find_workers, profile_start, profile_stop  # noqa: E402

# (label, file suffix, function name) of the cumulative times the split reads
PARTS = (("updates (PPO train)", "ppo/ppo.py", "train"),
         ("rollouts (collect_rollouts)", "on_policy_algorithm.py", "collect_rollouts"),
         ("env step (all of it in this process)", "vec_env/base_vec_env.py", "step"),
         ("env workers (all of their work)", "sb3/worker_vec_env.py", "_serve"),
         ("simulator (physics.simulate)", "physics/simulate.py", "simulate"),
         ("opponent decisions (bot act)", "envs/games/play.py", "bot_actions"),
         ("agent features", "bots/learned/features.py", "agent_features"),
         ("agent action transform", "bots/learned/features.py", "transform_actions"))


def split(stats: pstats.Stats, wall: float) -> list[tuple[str, float]]:
    """The parts' cumulative seconds (of the profile's clock) and the total."""
    cum = {}
    for (file, _, fn), (_, _, _, ct, _) in stats.stats.items():
        for label, suffix, name in PARTS:
            if fn == name and file.endswith(suffix):
                cum[label] = max(cum.get(label, 0.0), ct)
    rows = [(label, cum.get(label, 0.0)) for label, _, _ in PARTS]
    d = dict(rows)
    rows.append(("agent network in rollouts (rollouts - env step)",
                 d["rollouts (collect_rollouts)"] - d["env step (all of it in this process)"]))
    rows.append(("total", wall))
    return rows


def _threads(cfg) -> None:
    import numba
    import torch
    # the threads training uses (agents.sb3.training.train sets the same)
    torch.set_num_threads(cfg.train.torch_threads)
    numba.set_num_threads(min(cfg.train.numba_threads, numba.config.NUMBA_NUM_THREADS))


def compare(args) -> int:
    """``--compare``: the configs' rates, interleaved rounds in one process."""
    quick = ["n_envs=8", "ppo.batch_size=32"] if args.quick else []
    rounds = 1 if args.quick else args.rounds
    runs = []
    for spec in args.compare:
        label, _, sets = spec.partition(":")
        # commas inside [...] or {...} belong to a value (policy.net_arch=[128,128])
        pairs = [x for x in re.split(r",(?![^\[{]*[\]}])", sets) if x]
        cfg = load_config(args.config, args.env, pairs + list(args.set) + quick)
        _threads(cfg)
        env, _ = build_env(cfg, cfg.train.seed)
        model = build_model(cfg, env, None)
        per = cfg.n_envs * int(cfg.algo_kwargs.get("n_steps", 2048))
        steps = per * (1 if args.quick else max(1, 16384 // per))
        model.learn(steps)  # compiles the kernels, fills the normaliser
        runs.append((label, cfg, model, steps, []))
    for _ in range(rounds):
        for label, cfg, model, steps, rates in runs:
            _threads(cfg)
            t0, (c0, p0) = time.perf_counter(), cpu_seconds(model.get_env())
            model.learn(steps, reset_num_timesteps=False)
            wall, (c1, p1) = time.perf_counter() - t0, cpu_seconds(model.get_env())
            rates.append((steps / wall, steps / (c1 - c0), steps / (p1 - p0)))
            print(f"{label}: {rates[-1][0]:,.0f} env steps/s, {rates[-1][1]:,.0f} per CPU-second, "
                  f"{rates[-1][2]:,.0f} per critical-path CPU-second", flush=True)
    lines = [f"{args.env}: medians of {rounds} interleaved rounds (CPU: this process and its env workers; "
             "critical path: this process and its busiest worker, about the wall time on idle cores)", "",
             "| config | tables x steps | env steps/s (wall) | env steps per CPU-second "
             "| env steps per critical-path CPU-second |", "|---|---|---|---|---|"]
    for label, cfg, model, steps, rates in runs:
        r = np.median(np.array(rates), axis=0)
        lines.append(f"| {label} | {cfg.n_envs} x {cfg.algo_kwargs.get('n_steps')} | {r[0]:,.0f} | {r[1]:,.0f} "
                     f"| {r[2]:,.0f} |")
    print("\n".join(lines))
    if args.out:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text("\n".join(lines) + "\n")
    return 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--config", default=str(ROOT / "configs" / "ppo_games.yaml"))
    ap.add_argument("--env", default="Billiards-NineBall2P-v1")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE")
    ap.add_argument("--rollouts", type=int, default=4)
    ap.add_argument("--out", type=Path, default=None)
    ap.add_argument("--quick", action="store_true", help="8 tables, 1 rollout")
    ap.add_argument("--clock", choices=("cpu", "wall"), default="cpu",
                    help="the profile's timer: the process's CPU time (default; a loaded machine "
                         "stretches wall time unevenly across the parts) or wall time")
    ap.add_argument("--compare", action="append", default=[], metavar="LABEL[:KEY=VALUE,...]",
                    help="rates of configs interleaved in one process, no profile (repeatable)")
    ap.add_argument("--rounds", type=int, default=3, help="--compare: interleaved rounds")
    args = ap.parse_args(argv)
    if args.compare:
        return compare(args)
    sets = list(args.set) + (["n_envs=8", "ppo.batch_size=32"] if args.quick else [])
    rollouts = 1 if args.quick else args.rollouts
    cfg = load_config(args.config, args.env, sets)
    _threads(cfg)
    env, _ = build_env(cfg, cfg.train.seed)
    model = build_model(cfg, env, None)
    per = cfg.n_envs * int(cfg.algo_kwargs.get("n_steps", 2048))
    model.learn(per)  # compiles the kernels, fills the normaliser
    workers = find_workers(env)
    prof = cProfile.Profile(time.process_time if args.clock == "cpu" else time.perf_counter)
    t0, (c0, _) = time.perf_counter(), cpu_seconds(env)
    if workers is not None:  # each worker profiles its own part, merged below
        workers.apply(profile_start, args.clock == "wall")
    prof.enable()
    model.learn(per * rollouts, reset_num_timesteps=False)
    prof.disable()
    with tempfile.TemporaryDirectory() as tmp:
        paths = workers.apply(profile_stop, tmp) if workers is not None else []
        wall, cpu = time.perf_counter() - t0, cpu_seconds(env)[0] - c0
        text = io.StringIO()
        stats = pstats.Stats(prof, stream=text)
        for path in paths:
            stats.add(path)
        stats.sort_stats("cumulative").print_stats(40)
    n_workers = 0 if workers is None else len(paths)
    lines = [f"{args.env}, {cfg.n_envs} tables, {rollouts} rollouts of {per} env steps: "
             f"{per * rollouts / wall:,.0f} env steps/s including updates (under cProfile), "
             f"{per * rollouts / cpu:,.0f} per CPU-second of the process and its {n_workers} env workers "
             f"({cpu / wall:.2f} cores busy; numba threads {cfg.train.numba_threads}, "
             f"torch threads {cfg.train.torch_threads})", "",
             f"| part | {args.clock} seconds | share |", "|---|---|---|"]
    # with workers the parts are summed over the processes: shares of their CPU time
    total = cpu if args.clock == "cpu" else wall
    # four decimals: the quick run's parts last milliseconds, and two would print them as 0.00
    lines += [f"| {label} | {s:.4f} | {s / total:.0%} |" for label, s in split(stats, total)]
    report = "\n".join(lines) + "\n\n```\n" + text.getvalue() + "```\n"
    print("\n".join(lines))
    if args.out:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text(report)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
