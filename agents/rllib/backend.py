"""Training with Ray RLlib's PPO (new API stack) on the native vector env.

The second training backend next to stable-baselines3 (``agents.sb3.training``),
for runs that outgrow one machine. It reads the same ``TrainConfig`` (the
``rllib:`` block of the env id in ``configs/ppo.yaml``, next to ``ppo:``) and
writes the same run directory: ``config.yaml``, ``command.txt``,
``checkpoints/`` (RLlib checkpoints named by env steps), ``progress.csv``
(same columns), ``tb/`` (TensorBoard), ``learning_curve.png``,
``train_summary.json`` and the final evaluation through the project's harness
(``eval.json``/``eval.png``, ``agents.rllib.policy.RLlibPolicy`` playing the
seeded episodes).

Each EnvRunner is a Ray actor stepping one native vector env of
``num_envs_per_env_runner`` tables: ``make_vector_env`` is the env creator
RLlib registers as a Gymnasium ``vector_entry_point`` inside every worker
process (the driver's Gymnasium registry is not visible there), so one
batched simulator call steps all of a runner's tables. The env is made with
next-step autoreset, the convention RLlib's EnvRunner expects. Each runner
sets numba and torch to one thread per CPU it is given
(``num_cpus_per_env_runner``) and samples lean (``algo_config``: a batched
observation filter, a tuned garbage collector, no second action clip;
``agents.rllib.sampling``).

The ``rllib:`` block: ``num_env_runners``, ``num_envs_per_env_runner``,
``num_cpus_per_env_runner`` (EnvRunners), ``num_learners``,
``num_cpus_per_learner`` (learners), ``max_num_env_runner_restarts`` (fault
tolerance) and any ``PPOConfig.training`` argument (``lr``, ``minibatch_size``,
``num_epochs``, ``train_batch_size_per_learner``, ``lambda_``, ...). The
network comes from ``policy:`` (``net_arch``, ``activation``, and the initial
log-std ``log_std_init`` of a state-independent std, as SB3's PPO has);
``normalize.obs`` adds RLlib's running mean/std observation filter.
"""
from __future__ import annotations

import contextlib
import csv
import json
import os
import time
from pathlib import Path

import gymnasium as gym
import numpy as np

from ..config import TrainConfig, save_config
from .policy import CHECKPOINT_PREFIX, checkpoints, load_run_config

ENV_RUNNER_KEYS = ("num_env_runners", "num_envs_per_env_runner", "num_cpus_per_env_runner")
LEARNER_KEYS = ("num_learners", "num_cpus_per_learner")
FAULT_KEYS = ("max_num_env_runner_restarts",)
PROGRESS_FIELDS = ["timesteps", "time_s", "episodes", "success_rate", "mean_reward", "scratch_rate", "foul_rate",
                   "steps_per_s"]
# A fresh worker compiles (or loads) its numba kernels during its first sample:
# minutes on a loaded machine with a cold cache, far above RLlib's 60 s default.
SAMPLE_TIMEOUT_S = 900.0
RAY_ENV_NAME = "billiards_env_vector"  # make_vector_env's name in Ray's registry (seen by every worker)
WORKER_LOGS_VAR = "BILLIARDS_RAY_LOGS"  # =1: show the Ray workers' output in the driver (hidden by default)
DASHBOARD_VAR = "BILLIARDS_RAY_DASHBOARD"  # =1: a local Ray instance starts its dashboard (off by default)
EPISODE_FLAGS = ("success", "scratch", "foul")


# ------------------------------------------------------------------ env --
def make_vector_env(ctx) -> "gym.vector.VectorEnv":
    """RLlib's env creator: the native vector env of ``ctx["env_id"]`` with
    ``ctx["num_envs"]`` tables (next-step autoreset), with the agent-side
    features and action transform of the config. Runs inside each EnvRunner
    process: importing ``billiards_env`` there registers the ids. In a Ray
    actor (a remote EnvRunner) it also tunes that process's garbage
    collector unless ``ctx["worker_gc"]`` is False
    (``sampling.tune_worker_gc``)."""
    import numba
    import torch

    import billiards_env  # noqa: F401  (registers the env ids in this worker)

    from ..interface.features import VectorShotFeatures

    if ctx.get("worker_gc", True) and _in_ray_actor():
        from .sampling import tune_worker_gc
        tune_worker_gc()  # in EnvRunner processes only, never in the driver
    threads = max(1, int(ctx.get("numba_threads", 1)))  # the CPUs this EnvRunner is given
    numba.set_num_threads(min(threads, numba.config.NUMBA_NUM_THREADS))
    torch.set_num_threads(threads)  # its policy forward passes: no more threads than its CPUs either
    env = gym.make_vec(ctx["env_id"], num_envs=int(ctx["num_envs"]), vectorization_mode="vector_entry_point",
                       autoreset_mode="next_step", **dict(ctx.get("env_kwargs") or {}))
    if ctx.get("features") or ctx.get("aim_scale", 1.0) != 1.0 or ctx.get("action_mode", "direct") != "direct":
        env = VectorShotFeatures(env, bool(ctx.get("features")), float(ctx.get("aim_scale", 1.0)),
                                 ctx.get("action_mode", "direct"))
    return EpisodeFlagTotals(env)


def _in_ray_actor() -> bool:
    """True inside a Ray actor process (a remote EnvRunner)."""
    import ray

    return ray.is_initialized() and ray.get_runtime_context().get_actor_id() is not None


def env_context(cfg: TrainConfig) -> dict:
    """The ``env_config`` RLlib passes to ``make_vector_env`` (plain data)."""
    return dict(env_id=cfg.env_id, env_kwargs=dict(cfg.env_kwargs), features=cfg.features,
                aim_scale=cfg.aim_scale, action_mode=cfg.action_mode,
                numba_threads=int(cfg.rllib.get("num_cpus_per_env_runner", 1)))


class EpisodeFlagTotals(gym.vector.VectorWrapper):
    """Counts finished episodes and their success / scratch / foul flags on
    the vector env, with array operations per step (a per-episode RLlib
    callback costs more than the simulation on one-shot tasks); the
    ``on_sample_end`` callback logs and clears the totals once per sample."""

    def __init__(self, env):
        super().__init__(env)
        self.totals = dict.fromkeys(("episodes",) + EPISODE_FLAGS, 0)

    def step(self, actions):
        obs, rew, term, trunc, info = self.env.step(actions)
        done = np.asarray(term) | np.asarray(trunc)
        if done.any():
            self.totals["episodes"] += int(done.sum())
            for flag in EPISODE_FLAGS:
                if flag in info:
                    mask = np.asarray(info.get("_" + flag, done), dtype=bool)
                    self.totals[flag] += int(np.sum(np.asarray(info[flag], dtype=bool) & mask & done))
        return obs, rew, term, trunc, info

    def pop_totals(self) -> dict:
        out, self.totals = self.totals, dict.fromkeys(self.totals, 0)
        return out

    @staticmethod
    def find(env):
        """The ``EpisodeFlagTotals`` under RLlib's wrappers of ``env`` (or None)."""
        for _ in range(10):
            if isinstance(env, EpisodeFlagTotals) or env is None:
                return env
            env = getattr(env, "env", None)
        return None


def _episode_metrics_callback():
    from ray.rllib.callbacks.callbacks import RLlibCallback

    class EpisodeFlags(RLlibCallback):
        """Per sample: the episodes finished and their success / scratch /
        foul counts (summed over runners; ``progress.csv`` divides them)."""

        def on_sample_end(self, *, env_runner=None, metrics_logger=None, **kwargs):
            env = EpisodeFlagTotals.find(getattr(env_runner, "env", None))
            if env is None or metrics_logger is None:
                return
            for key, value in env.pop_totals().items():
                metrics_logger.log_value(f"billiards_{key}", value, reduce="sum")

    return EpisodeFlags


# --------------------------------------------------------------- config --
def _split_rllib_block(block: dict) -> tuple[dict, dict, dict, dict]:
    """``rllib:`` -> (env_runners, learners, fault_tolerance, training) kwargs;
    unknown keys are an error naming them."""
    from ray.rllib.algorithms.ppo import PPOConfig

    runners = {k: v for k, v in block.items() if k in ENV_RUNNER_KEYS}
    learners = {k: v for k, v in block.items() if k in LEARNER_KEYS}
    fault = {k: v for k, v in block.items() if k in FAULT_KEYS}
    training = {k: v for k, v in block.items() if k not in ENV_RUNNER_KEYS + LEARNER_KEYS + FAULT_KEYS}
    probe = PPOConfig()
    unknown = sorted(k for k in training if not hasattr(probe, k))
    if unknown:
        raise ValueError(f"unknown rllib setting(s) {unknown}: use {list(ENV_RUNNER_KEYS + LEARNER_KEYS + FAULT_KEYS)} "
                         f"or PPOConfig.training arguments (lr, minibatch_size, num_epochs, ...)")
    counts = {**runners, **learners}
    for k, lowest in (("num_env_runners", 0), ("num_learners", 0), ("num_envs_per_env_runner", 1)):
        v = counts.get(k, lowest)
        if isinstance(v, bool) or not isinstance(v, int) or v < lowest:
            raise ValueError(f"rllib.{k} must be an integer >= {lowest}, got {v!r}")
    return runners, learners, fault, training


def algo_config(cfg: TrainConfig, lean: bool = True):
    """The ``PPOConfig`` (new API stack) of ``cfg``. ``lean`` (default):
    the observation filter updates once per vector step
    (``sampling.MeanStdFilter``), EnvRunner processes tune
    their garbage collector (``sampling.tune_worker_gc``) and actions go
    to the env unclipped (the env clips them to its Box [-1, 1], exactly
    RLlib's unsquash for that Box); False gives RLlib's own filter, collector
    and action pass (benchmark comparisons). The Learner gets the same
    episodes either way (observations, sampled actions, log-probs, terminated flags)."""
    from ray.rllib.algorithms.ppo import PPOConfig
    from ray.rllib.core.rl_module.default_model_config import DefaultModelConfig
    from ray.tune.registry import register_env

    if cfg.algo != "ppo":
        raise ValueError(f"the rllib backend trains PPO only, got algo {cfg.algo!r}")
    if cfg.action_mode == "choice":
        raise ValueError("the rllib backend takes continuous actions (action_mode direct or residual); "
                         "action_mode 'choice' trains with the sb3 backend")
    runners, learners, fault, training = _split_rllib_block(cfg.rllib)
    runners.setdefault("num_envs_per_env_runner", cfg.n_envs)
    runners.setdefault("sample_timeout_s", SAMPLE_TIMEOUT_S)
    register_env(RAY_ENV_NAME, make_vector_env)
    config = (PPOConfig()
              .environment(env=RAY_ENV_NAME, env_config={**env_context(cfg), "worker_gc": lean},
                           # RLlib's unsquash for the Box [-1, 1] is a clip to [-1, 1], which the env's action
                           # transform does itself: lean skips RLlib's per-table copy and clip
                           normalize_actions=not lean, clip_actions=False)
              .env_runners(gym_env_vectorize_mode=gym.VectorizeMode.VECTOR_ENTRY_POINT, **runners)
              .learners(**learners)
              .training(**training)
              .rl_module(model_config=DefaultModelConfig(
                  fcnet_hiddens=list(cfg.policy.net_arch), fcnet_activation=cfg.policy.activation,
                  vf_share_layers=False, free_log_std=True))
              .callbacks(_episode_metrics_callback())
              .fault_tolerance(restart_failed_env_runners=True, **fault)
              .debugging(seed=cfg.train.seed)
              .reporting(min_time_s_per_iteration=0, min_sample_timesteps_per_iteration=0))
    if cfg.normalize.obs:
        if lean:
            from .sampling import MeanStdFilter as filter_class
        else:
            from ray.rllib.connectors.env_to_module import MeanStdFilter as filter_class
        clip = cfg.normalize.clip_obs
        config = config.env_runners(env_to_module_connector=lambda env, spaces=None, device=None:
                                    filter_class(clip_by_value=clip, multi_agent=False))
    return config


# ------------------------------------------------------------------ ray --
def start_ray(address: str | None = None, num_cpus: int | None = None) -> None:
    """Join the cluster at ``address`` (``auto`` or ``HOST:PORT``), or start
    a new Ray instance on this machine (``num_cpus``: its CPU count; default
    all cores), even where another one runs: Ray's ``address="local"``
    (a bare ``ray.init()`` would join the newest ``ray start`` or
    ``cluster_utils.Cluster`` head on the machine instead, and refuse
    ``num_cpus``). Workers import the project from the same Python environment
    (``PYTHONPATH`` is passed on when set, so a source checkout works too).
    The workers' output reaches the driver only with ``BILLIARDS_RAY_LOGS=1``;
    a local instance starts Ray's dashboard only with
    ``BILLIARDS_RAY_DASHBOARD=1``."""
    import ray

    if ray.is_initialized():
        return
    env_vars = {k: os.environ[k] for k in ("PYTHONPATH",) if k in os.environ}
    runtime_env = {"env_vars": env_vars} if env_vars else None
    logs = os.environ.get(WORKER_LOGS_VAR) == "1"
    if address:
        ray.init(address=address, runtime_env=runtime_env, log_to_driver=logs)
    else:
        ray.init(address="local", num_cpus=num_cpus, include_dashboard=os.environ.get(DASHBOARD_VAR) == "1",
                 runtime_env=runtime_env, log_to_driver=logs)


# ---------------------------------------------------------------- train --
def _set_log_std(algo, value: float) -> None:
    """Fill the free log-std parameter of the policy (``policy.log_std_init``)
    on the learners and push the weights to the EnvRunners."""
    import torch

    def fill(learner):
        for name, p in learner.module["default_policy"].named_parameters():
            if name.endswith("log_std"):
                with torch.no_grad():
                    p.fill_(value)

    algo.learner_group.foreach_learner(fill)
    algo.env_runner_group.sync_weights(from_worker_or_learner_group=algo.learner_group, inference_only=True)


def env_runner_facts(algo) -> list[dict]:
    """Per remote EnvRunner (the local one when there are none): its node,
    process, vector env class and table count."""
    def facts(runner):
        import ray
        return dict(node_id=ray.get_runtime_context().get_node_id(), pid=os.getpid(),
                    env_class=type(runner.env.unwrapped).__name__, num_envs=int(runner.env.num_envs))

    group = algo.env_runner_group
    return list(group.foreach_env_runner(facts, local_env_runner=group.num_remote_env_runners() == 0))


def _row(result: dict, steps: int, elapsed: float) -> dict | None:
    from ray.rllib.utils.metrics import ENV_RUNNER_RESULTS

    er = result.get(ENV_RUNNER_RESULTS, {})
    n = float(er.get("billiards_episodes", 0) or 0)
    if n <= 0:
        return None
    return dict(timesteps=steps, time_s=round(elapsed, 3), episodes=int(n),
                success_rate=er.get("billiards_success", 0.0) / n,
                mean_reward=float(er.get("episode_return_mean", float("nan"))),
                scratch_rate=er.get("billiards_scratch", 0.0) / n, foul_rate=er.get("billiards_foul", 0.0) / n,
                steps_per_s=steps / max(elapsed, 1e-9))


def _tensorboard(run_dir: Path, enabled: bool):
    if not enabled:
        return None
    try:
        from tensorboardX import SummaryWriter
    except ImportError:
        return None
    return SummaryWriter(str(run_dir / "tb" / "rllib_ppo"))


def train(cfg: TrainConfig, run_dir, command: str = "", address: str | None = None, resume: bool = False,
          num_cpus: int | None = None, stop_after_iterations: int | None = None, lean: bool = True) -> dict:
    """Train ``cfg`` with RLlib's PPO; everything is written to ``run_dir``.
    ``resume``: continue from the run's last checkpoint (progress.csv is
    appended; the env steps since that checkpoint are sampled again).
    ``stop_after_iterations``: stop early (tests). ``lean`` (default):
    ``algo_config``'s lean sampling, and this process's garbage collector
    tuned while it trains (``sampling.tuned_gc``); False: RLlib's own
    settings (benchmark comparisons). Returns the summary dict."""
    import numba
    import torch

    if cfg.self_play:
        raise ValueError(f"{cfg.env_id} with no env_kwargs.opponent trains by self-play, which is the "
                         "stable-baselines3 backend's (agents.sb3.self_play); name an opponent for RLlib")
    run_dir = Path(run_dir)
    run_dir.mkdir(parents=True, exist_ok=True)
    last = checkpoints(run_dir)[-1] if resume and checkpoints(run_dir) else None
    if resume and last is None:
        raise ValueError(f"--resume {run_dir}: no checkpoint in {run_dir / 'checkpoints'}")
    save_config(cfg, run_dir / "config.yaml")
    with open(run_dir / "command.txt", "a" if resume else "w") as f:
        f.write(command + "\n")
    torch.set_num_threads(cfg.train.torch_threads)
    numba.set_num_threads(min(cfg.train.numba_threads, numba.config.NUMBA_NUM_THREADS))
    import ray

    if cfg.normalize.reward:
        print("note: normalize.reward applies to the sb3 backend only; the rllib backend trains on raw rewards")
    from .sampling import tuned_gc

    started_here = not ray.is_initialized()
    start_ray(address, num_cpus)
    try:
        # the learner in this process handles one episode object per env step too
        with tuned_gc() if lean else contextlib.nullcontext():
            return _train(cfg, run_dir, last, stop_after_iterations, lean)
    finally:
        if started_here:
            ray.shutdown()


def _train(cfg: TrainConfig, run_dir: Path, last: Path | None, stop_after_iterations: int | None,
           lean: bool = True) -> dict:
    from ray.rllib.utils.metrics import ENV_RUNNER_RESULTS, NUM_ENV_STEPS_SAMPLED_LIFETIME

    resume = last is not None
    algo = algo_config(cfg, lean).build_algo()
    steps = 0
    if last is not None:
        algo.restore_from_path(str(last))
        steps = int(last.name[len(CHECKPOINT_PREFIX):])
        print(f"resumed from {last} ({steps} env steps)")
    else:
        _set_log_std(algo, cfg.policy.log_std_init)
    every = cfg.train.checkpoint_every
    next_ckpt = (steps // every + 1) * every if every else None
    csv_path = run_dir / "progress.csv"
    append = resume and csv_path.exists()
    prior_time = 0.0
    if append:
        with open(csv_path) as f:
            rows_before = [r for r in csv.DictReader(f) if int(r["timesteps"]) <= steps]
        prior_time = float(rows_before[-1]["time_s"]) if rows_before else 0.0
        with open(csv_path, "w", newline="") as f:  # drop rows after the checkpoint: they are sampled again
            w = csv.DictWriter(f, fieldnames=PROGRESS_FIELDS)
            w.writeheader()
            w.writerows(rows_before)
    csv_f = open(csv_path, "a" if append else "w", newline="")
    writer = csv.DictWriter(csv_f, fieldnames=PROGRESS_FIELDS)
    if not append:
        writer.writeheader()
    tb = _tensorboard(run_dir, cfg.train.tensorboard)
    rows: list[dict] = []
    start_steps = steps
    t0 = time.perf_counter()
    iterations = 0
    try:
        while steps < cfg.train.total_timesteps:
            result = algo.train()
            iterations += 1
            steps = int(result.get(ENV_RUNNER_RESULTS, {}).get(NUM_ENV_STEPS_SAMPLED_LIFETIME, steps))
            elapsed = prior_time + time.perf_counter() - t0
            row = _row(result, steps, elapsed)
            if row is not None:
                row["steps_per_s"] = (steps - start_steps) / max(time.perf_counter() - t0, 1e-9)
                writer.writerow(row)
                csv_f.flush()
                rows.append(row)
                if tb is not None:
                    for k in ("success_rate", "mean_reward", "scratch_rate", "foul_rate", "steps_per_s"):
                        tb.add_scalar(f"rollout/{k}", row[k], steps)
            if cfg.train.progress_bar and row is not None:
                print(f"  {steps:>9d} steps  success {row['success_rate']:.3f}  {row['steps_per_s']:.0f} steps/s",
                      flush=True)
            if next_ckpt is not None and steps >= next_ckpt:
                algo.save_to_path(str(run_dir / "checkpoints" / f"{CHECKPOINT_PREFIX}{steps}"))
                next_ckpt = (steps // every + 1) * every
            if stop_after_iterations is not None and iterations >= stop_after_iterations:
                break
        wall = time.perf_counter() - t0
        final = run_dir / "checkpoints" / f"{CHECKPOINT_PREFIX}{steps}"
        if not final.exists():
            algo.save_to_path(str(final))
        runners = env_runner_facts(algo)
    finally:
        csv_f.close()
        if tb is not None:
            tb.close()
        algo.stop()
    tail = rows[-5:]
    summary = dict(env_id=cfg.env_id, algo=cfg.algo, backend="rllib", timesteps=steps, train_wall_s=wall,
                   env_steps_per_s=(steps - start_steps) / wall, checkpoint=str(final), env_runners=runners,
                   final_train_success=float(np.mean([r["success_rate"] for r in tail])) if tail else None)
    (run_dir / "train_summary.json").write_text(json.dumps(summary, indent=2))
    return summary


def train_and_evaluate(cfg: TrainConfig, run_dir, command: str = "", t_start: float | None = None,
                       address: str | None = None, resume: bool = False) -> dict:
    """``agents.sb3.training.train_and_evaluate`` with this backend: train,
    plot ``learning_curve.png``, evaluate the last checkpoint and the
    baselines through the harness (``final_evaluation``), write the summary."""
    from ..plotting import plot_runs
    from ..sb3.training import final_evaluation

    t_start = time.perf_counter() if t_start is None else t_start
    run_dir = Path(run_dir)
    summary = train(cfg, run_dir, command, address=address, resume=resume)
    print(f"trained {summary['timesteps']} steps in {summary['train_wall_s']:.1f} s "
          f"({summary['env_steps_per_s']:.0f} env steps/s incl. updates); checkpoint: {summary['checkpoint']}")
    plot_runs([run_dir], run_dir / "learning_curve.png")
    results = final_evaluation(cfg, run_dir) if cfg.train.eval_episodes > 0 else []
    summary["total_wall_s"] = time.perf_counter() - t_start
    summary["eval"] = [r.to_dict() for r in results]
    (run_dir / "train_summary.json").write_text(json.dumps(summary, indent=2))
    print(f"total wall time (training + evaluation): {summary['total_wall_s']:.1f} s; run directory: {run_dir}")
    return summary


def resume(run_dir, command: str = "", t_start: float | None = None, address: str | None = None) -> dict:
    """Continue the run ``run_dir`` from its last checkpoint, with the
    config it was started with (``config.yaml``), to its ``total_timesteps``."""
    run_dir = Path(run_dir)
    if not (run_dir / "config.yaml").exists():
        raise ValueError(f"resume {run_dir}: not a run directory (no config.yaml)")
    return train_and_evaluate(load_run_config(run_dir), run_dir, command, t_start, address=address, resume=True)
