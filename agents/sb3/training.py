"""Training PPO / SAC on the native billiards vector env.

``train(cfg, run_dir)`` builds the SB3 adapter (one batched simulator call
per step for all ``n_envs`` tables), optional VecNormalize, the model, and
trains with a progress bar, TensorBoard logging (when installed), a CSV log
of episode statistics (for the learning curve), periodic checkpoints
(``agents.sb3.checkpoints``: model, normaliser statistics as plain arrays, step
counter, random state) and the final model saved as ``<run>/model.zip`` with
``<run>/vecnormalize.pkl`` and ``<run>/config.yaml``. ``train(cfg, run_dir,
resume=True)`` continues a stopped or killed run from its newest checkpoint.

``train_and_evaluate(cfg, run_dir, command)`` (what ``scripts/train.py``
runs) also plots the learning curve and evaluates the trained model against
the baselines on the same seeded episodes (``eval.json``, ``eval.png``).
"""
from __future__ import annotations

import csv
import json
import time
from pathlib import Path

import numpy as np
from stable_baselines3.common.callbacks import BaseCallback

from .checkpoints import last_logged_steps, latest_checkpoint, load_checkpoint, save_checkpoint
from ..config import TrainConfig, load_run_config, save_config


def _has_tensorboard() -> bool:
    try:
        import tensorboard  # noqa: F401
        return True
    except ImportError:
        return False


class ProgressBar(BaseCallback):
    """A plain tqdm progress bar (SB3's own needs ``rich``), showing the
    recent training success rate."""

    def __init__(self, total: int):
        super().__init__()
        self.total = total
        self.pbar = None

    def _on_training_start(self) -> None:
        from tqdm.auto import tqdm
        self.pbar = tqdm(total=self.total, unit="step", unit_scale=True, dynamic_ncols=True, mininterval=1.0)

    def _on_step(self) -> bool:
        self.pbar.update(self.training_env.num_envs)
        return True

    def _on_rollout_end(self) -> None:
        sr = self.logger.name_to_value.get("rollout/success_rate")
        if sr is not None:
            self.pbar.set_postfix(success=f"{sr:.3f}", refresh=False)

    def _on_training_end(self) -> None:
        self.pbar.close()


class EpisodeLogger(BaseCallback):
    """Logs finished episodes' success / reward / scratch / foul, averaged
    over each rollout, to ``progress.csv`` and to the SB3 logger
    (TensorBoard ``rollout/success_rate`` etc.); saves checkpoints."""

    FIELDS = ["timesteps", "time_s", "episodes", "success_rate", "mean_reward", "scratch_rate", "foul_rate",
              "steps_per_s"]

    def __init__(self, run_dir: Path, checkpoint_every: int = 0, vecnorm=None, start_steps: int = 0,
                 start_elapsed_s: float = 0.0):
        super().__init__()
        self.run_dir = run_dir
        self.checkpoint_every = int(checkpoint_every)
        self.vecnorm = vecnorm
        self._next_ckpt = (start_steps // self.checkpoint_every + 1) * self.checkpoint_every \
            if self.checkpoint_every else None
        self._buf = {"success": [], "reward": [], "scratch": [], "foul": []}
        self._ep_ret = None
        # a resumed run continues the clock and the log of its checkpoint
        self.start_steps, self.start_elapsed_s = int(start_steps), float(start_elapsed_s)
        self.t0 = time.perf_counter() - self.start_elapsed_s
        self.rows: list[dict] = []
        self._csv = None

    def _on_training_start(self) -> None:
        self._ep_ret = np.zeros(self.training_env.num_envs)
        path = self.run_dir / "progress.csv"
        kept = []
        if self.start_steps and path.exists():  # keep the rows up to the checkpoint
            with open(path, newline="") as f:
                kept = [r for r in csv.DictReader(f) if int(r["timesteps"]) <= self.start_steps]
        self._csv_f = open(path, "w", newline="")
        self._csv = csv.DictWriter(self._csv_f, fieldnames=self.FIELDS)
        self._csv.writeheader()
        self._csv.writerows(kept)

    def checkpoint_due(self, num_timesteps: int) -> bool:
        """Whether a rollout starting at ``num_timesteps`` starts with a checkpoint
        (``OverlappedPPO`` finishes its update before such a rollout)."""
        return self._next_ckpt is not None and num_timesteps >= self._next_ckpt

    def _on_rollout_start(self) -> None:
        # after the previous update and before new steps: the state a resumed
        # run restarts from exactly (checkpoint steps are rollout boundaries)
        if self.checkpoint_due(self.num_timesteps):
            save_checkpoint(self.run_dir, self.model, self.vecnorm, time.perf_counter() - self.t0)
            while self._next_ckpt <= self.num_timesteps:
                self._next_ckpt += self.checkpoint_every

    def _on_step(self) -> bool:
        rewards = self.locals["rewards"]
        dones = self.locals["dones"]
        infos = self.locals["infos"]
        # un-normalised rewards: VecNormalize keeps the originals
        if self.vecnorm is not None and self.vecnorm.norm_reward:
            rewards = self.vecnorm.get_original_reward()
        self._ep_ret += rewards
        for i in np.flatnonzero(dones):
            info = infos[i]
            # a self-play game has no agent to succeed: its rows log success as NaN
            self._buf["success"].append(float(bool(info["success"])) if "success" in info else np.nan)
            self._buf["scratch"].append(float(bool(info.get("scratch", False))))
            self._buf["foul"].append(float(bool(info.get("foul", False))))
            self._buf["reward"].append(float(self._ep_ret[i]))
            self._ep_ret[i] = 0.0
        return True

    def _on_rollout_end(self) -> None:
        if not self._buf["success"]:
            return
        el = time.perf_counter() - self.t0
        # a self-play window's successes are all NaN, and so is their mean
        row = dict(timesteps=self.num_timesteps, time_s=round(el, 3), episodes=len(self._buf["success"]),
                   success_rate=float(np.mean(self._buf["success"])), mean_reward=float(np.mean(self._buf["reward"])),
                   scratch_rate=float(np.mean(self._buf["scratch"])), foul_rate=float(np.mean(self._buf["foul"])),
                   steps_per_s=self.num_timesteps / max(el, 1e-9))
        self.logger.record("rollout/success_rate", row["success_rate"])
        self.logger.record("rollout/scratch_rate", row["scratch_rate"])
        self.logger.record("rollout/foul_rate", row["foul_rate"])
        self.logger.record("rollout/episode_reward", row["mean_reward"])
        self.logger.record("time/env_steps_per_s", row["steps_per_s"])
        self._csv.writerow(row)
        self._csv_f.flush()
        self.rows.append(row)
        for v in self._buf.values():
            v.clear()

    def _on_training_end(self) -> None:
        self._on_rollout_end()
        if self._csv is not None:
            self._csv_f.close()


class HeldOutEvaluation(BaseCallback):
    """Evaluates the policy on the held seeds (``agents.evaluation.harness.evaluate``,
    ``episodes`` tables of seed ``seed``, noise ``train.eval_every_noise``) every ``every`` env steps,
    at rollout boundaries, and once at the end. The clock of the training time
    (``train_s``) stops while it evaluates. Rows (steps, train_s, success,
    95% interval) go to ``<run>/evaluations.csv`` and ``self.rows``, the
    first at step 0. The first row whose 95% interval lies above ``target``
    (default: the ghost-ball baseline's success on the same tables, evaluated
    once at the start) gives ``steps_to_target`` / ``time_to_target_s``: a
    residual policy starts *at* the ghost-ball shot, so merely matching the
    baseline says nothing. ``report(row)`` (optional) sees every row and may
    return False to stop training (used for pruning)."""

    FIELDS = ["timesteps", "train_s", "success_rate", "ci_low", "ci_high"]

    def __init__(self, cfg: TrainConfig, run_dir: Path, every: int, episodes: int, seed: int,
                 target: float | None = None, report=None):
        super().__init__()
        self.cfg, self.run_dir, self.every, self.episodes, self.seed = cfg, Path(run_dir), int(every), episodes, seed
        self.target, self.report = target, report
        self.rows: list[dict] = []
        self.steps_to_target = self.time_to_target_s = None
        self._next = self.every
        self._eval_s = 0.0
        self._t0 = None
        self._stop = False

    def _evaluate(self, policy) -> object:
        from ..evaluation.harness import evaluate
        return evaluate(policy, self.cfg.env_id, self.episodes, self.seed, self.cfg.train.eval_every_noise,
                        env_kwargs=self.cfg.eval_env_kwargs, name=self.cfg.algo)

    def _on_training_start(self) -> None:
        from ..evaluation.policies import make_policy
        name = self.cfg.train.eval_target
        if self.target is None and name:
            self.target = self._evaluate(lambda env: make_policy(name, env)).success_rate
        self._f = open(self.run_dir / "evaluations.csv", "w", newline="")
        self._csv = csv.DictWriter(self._f, fieldnames=self.FIELDS)
        self._csv.writeheader()
        self._t0 = time.perf_counter()   # the baseline's evaluation ran before the clock started
        self._run()

    def _run(self) -> None:
        from .policy import SB3Policy
        t = time.perf_counter()
        train_s = t - self._t0 - self._eval_s
        cfg = self.cfg
        pol = SB3Policy(self.model, _find_vecnorm(self.training_env), cfg.algo, cfg.features, cfg.aim_scale,
                        None, cfg.action_mode)
        r = self._evaluate(lambda env: pol.bind(env))
        row = dict(timesteps=int(self.num_timesteps), train_s=round(train_s, 3), success_rate=r.success_rate,
                   ci_low=r.success_ci95[0], ci_high=r.success_ci95[1])
        self.rows.append(row)
        self._csv.writerow(row)
        self._f.flush()
        if self.steps_to_target is None and self.target is not None and r.success_ci95[0] > self.target:
            self.steps_to_target, self.time_to_target_s = row["timesteps"], row["train_s"]
        if self.report is not None and self.report(row) is False:
            self._stop = True
        self._eval_s += time.perf_counter() - t

    def _on_rollout_start(self) -> None:
        if self.every and self.num_timesteps >= self._next:
            self._run()
            while self._next <= self.num_timesteps:
                self._next += self.every

    def _on_step(self) -> bool:
        return not self._stop

    def _on_training_end(self) -> None:
        if not self.rows or self.rows[-1]["timesteps"] != self.num_timesteps:
            self._run()
        self._f.close()

    def summary(self) -> dict:
        return dict(ghost_target=self.target, steps_to_target=self.steps_to_target,
                    time_to_target_s=self.time_to_target_s, train_s_excluding_evaluations=self.rows[-1]["train_s"],
                    held_success=self.rows[-1]["success_rate"])


def _find_vecnorm(env):
    from stable_baselines3.common.vec_env import VecNormalize
    while env is not None:
        if isinstance(env, VecNormalize):
            return env
        env = getattr(env, "venv", None)
    return None


def table_spec(cfg: TrainConfig):
    """What the training tables are: the env, its kwargs, the agent-side features and action mode."""
    from .worker_vec_env import TableEnvSpec
    return TableEnvSpec(cfg.env_id, dict(cfg.env_kwargs), cfg.features, cfg.aim_scale, cfg.action_mode,
                        cfg.train.numba_threads, "next_step" if cfg.self_play else "same_step")


def build_env(cfg: TrainConfig, seed: int):
    """The training env: ``cfg.n_envs`` tables (in this process, or split over
    ``train.env_workers`` processes: ``agents.sb3.worker_vec_env``) with the
    agent-side features, under VecNormalize when the config normalises."""
    from stable_baselines3.common.vec_env import VecNormalize

    from .worker_vec_env import WorkerVecEnv

    spec = table_spec(cfg)
    if cfg.train.env_workers > 1:
        env = WorkerVecEnv(spec, cfg.n_envs, cfg.train.env_workers)
        env.seed(seed)
    else:
        env = spec.build(cfg.n_envs, seed)
    vecnorm = None
    if cfg.normalize.obs or cfg.normalize.reward:
        n = cfg.normalize
        env = vecnorm = VecNormalize(env, norm_obs=n.obs, norm_reward=n.reward, clip_obs=n.clip_obs,
                                     clip_reward=n.clip_reward, gamma=n.gamma)
    return env, vecnorm


def schedule(value):
    """A constant, or ``"lin_<v>"``: linear from ``v`` at the start to 0 at
    the end of the run (RL-Zoo's notation)."""
    if isinstance(value, str):
        if not value.startswith("lin_"):
            raise ValueError(f"schedule {value!r}: expected a number or lin_<number>")
        v0 = float(value[4:])
        return lambda progress_remaining: progress_remaining * v0
    return value


def model_class(cfg: TrainConfig):
    """SB3's PPO or SAC, or ``OverlappedPPO`` with ``train.overlap_updates``."""
    from stable_baselines3 import PPO, SAC

    if cfg.train.overlap_updates:
        from .overlap import OverlappedPPO
        return OverlappedPPO
    return {"ppo": PPO, "sac": SAC}[cfg.algo]


def build_model(cfg: TrainConfig, env, tensorboard_log: str | None):
    cls = model_class(cfg)
    kw = dict(cfg.algo_kwargs)
    if cfg.self_play:
        from .self_play import TurnRolloutBuffer
        kw["rollout_buffer_class"] = TurnRolloutBuffer
    for key in ("learning_rate", "clip_range"):
        if key in kw:
            kw[key] = schedule(kw[key])
    return cls("MlpPolicy", env, policy_kwargs=cfg.policy.policy_kwargs(cfg.algo), seed=cfg.train.seed,
               device=cfg.train.device, tensorboard_log=tensorboard_log, verbose=0, **kw)


def train(cfg: TrainConfig, run_dir, command: str = "", resume: bool = False, report=None) -> dict:
    """Train according to ``cfg``; everything is written to ``run_dir``.
    Returns a summary dict (wall time, throughput, final training success).

    ``resume``: continue the run in ``run_dir`` from its newest checkpoint
    (``agents.sb3.checkpoints``) up to ``cfg.train.total_timesteps``; the summary's
    ``resumed`` entry gives the checkpoint's step, the steps the stopped run
    had logged past it (``steps_redone``) and the earlier training time.
    With ``train.eval_every`` > 0 (or a ``report`` callable, see
    ``HeldOutEvaluation``) the policy is evaluated on held seeds during
    training; the summary then has ``held_out`` (time to the ghost-ball
    baseline's success) and its throughput excludes the evaluations."""
    import numba
    import torch

    run_dir = Path(run_dir)
    run_dir.mkdir(parents=True, exist_ok=True)
    ck = latest_checkpoint(run_dir) if resume else None
    if resume and ck is None:
        raise FileNotFoundError(f"{run_dir}: no complete checkpoint to resume from")
    if ck is None:
        save_config(cfg, run_dir / "config.yaml")
        (run_dir / "command.txt").write_text(command + "\n")
    else:
        with open(run_dir / "command.txt", "a") as f:
            f.write(command + "\n")
    torch.set_num_threads(cfg.train.torch_threads)
    numba.set_num_threads(min(cfg.train.numba_threads, numba.config.NUMBA_NUM_THREADS))

    env, vecnorm = build_env(cfg, cfg.train.seed)
    tb = str(run_dir / "tb") if (cfg.train.tensorboard and _has_tensorboard()) else None
    resumed = None
    if ck is None:
        model = build_model(cfg, env, tb)
        cb = EpisodeLogger(run_dir, cfg.train.checkpoint_every, vecnorm)
    else:
        logged = last_logged_steps(run_dir)
        model = load_checkpoint(ck, model_class(cfg), env, vecnorm, cfg.train.device, tb)
        prev = ck.state()["elapsed_s"]
        resumed = dict(checkpoint=str(ck.model_path.relative_to(run_dir)), from_step=ck.steps,
                       steps_redone=max(0, logged - ck.steps), previous_train_wall_s=prev)
        cb = EpisodeLogger(run_dir, cfg.train.checkpoint_every, vecnorm, ck.steps, prev)
    start = int(model.num_timesteps)
    remaining = max(cfg.train.total_timesteps - start, 0)
    callbacks = [cb] + ([ProgressBar(remaining)] if cfg.train.progress_bar else [])
    if cfg.self_play:
        from .self_play import TurnRecorder
        callbacks.insert(0, TurnRecorder())
    held = None
    if cfg.train.eval_every > 0 or report is not None:
        held = HeldOutEvaluation(cfg, run_dir, cfg.train.eval_every, cfg.train.eval_every_episodes,
                                 cfg.train.eval_seed, report=report)
        callbacks.append(held)
    t0 = time.perf_counter()
    model.learn(total_timesteps=remaining, callback=callbacks, tb_log_name=cfg.algo,
                reset_num_timesteps=ck is None)
    wall = time.perf_counter() - t0
    if held is not None:
        wall = held.rows[-1]["train_s"]
    model.save(run_dir / "model.zip")
    if vecnorm is not None:
        vecnorm.save(str(run_dir / "vecnormalize.pkl"))
    env.close()
    last = cb.rows[-5:]
    summary = dict(env_id=cfg.env_id, algo=cfg.algo, timesteps=int(model.num_timesteps), train_wall_s=wall,
                   env_steps_per_s=(model.num_timesteps - start) / wall,
                   final_train_success=float(np.mean([r["success_rate"] for r in last])) if last else None)
    if resumed is not None:
        summary["resumed"] = resumed
    if held is not None:
        summary["held_out"] = held.summary()
    (run_dir / "train_summary.json").write_text(json.dumps(summary, indent=2))
    return summary


def final_evaluation(cfg: TrainConfig, run_dir) -> list:
    """The trained model of ``run_dir`` and ``cfg.train.eval_baselines`` on
    ``eval_episodes`` seeded episodes per noise setting, on the env of
    ``cfg.env_kwargs`` (the one the model was trained on); prints a Markdown
    table and writes ``eval.json`` / ``eval.png`` into ``run_dir``."""
    from ..evaluation.harness import evaluate, format_table, load_trained, save_results
    from ..evaluation.policies import make_policy

    run_dir = Path(run_dir)
    trained = load_trained(run_dir)  # either backend's run
    ts = cfg.train
    results = []
    for noise in ts.eval_noise:
        results.append(evaluate(lambda env: trained.bind(env), cfg.env_id, ts.eval_episodes, ts.eval_seed,
                                noise, env_kwargs=cfg.eval_env_kwargs, name=trained.name))
        for b in ts.eval_baselines:
            bname = f"search{ts.search_k}" if b == "search" else b
            results.append(evaluate(lambda env, b=bname: make_policy(b, env, seed=ts.eval_seed), cfg.env_id,
                                    ts.eval_episodes, ts.eval_seed, noise, env_kwargs=cfg.eval_env_kwargs, name=bname))
    print(format_table(results))
    save_results(results, run_dir / "eval.json", run_dir / "eval.png")
    return results


def train_and_evaluate(cfg: TrainConfig | None, run_dir, command: str = "", t_start: float | None = None,
                       resume: bool = False) -> dict:
    """Train (``train``), plot ``learning_curve.png`` and run the final
    evaluation (``final_evaluation``, skipped when ``eval_episodes`` is 0);
    the summary, with the evaluation and the total wall time since
    ``t_start`` (default: now), is written to ``train_summary.json``.
    ``resume``: continue the run in ``run_dir`` (``cfg`` None: its own
    ``config.yaml``)."""
    from ..plotting import plot_runs

    t_start = time.perf_counter() if t_start is None else t_start
    run_dir = Path(run_dir)
    if cfg is None:
        cfg = load_run_config(run_dir)
    summary = train(cfg, run_dir, command, resume=resume)
    if "resumed" in summary:
        r = summary["resumed"]
        print(f"resumed from {r['checkpoint']} (step {r['from_step']}); {r['steps_redone']} steps redone")
    print(f"trained {summary['timesteps']} steps in {summary['train_wall_s']:.1f} s "
          f"({summary['env_steps_per_s']:.0f} env steps/s incl. updates); model: {run_dir / 'model.zip'}")
    plot_runs([run_dir], run_dir / "learning_curve.png")
    results = final_evaluation(cfg, run_dir) if cfg.train.eval_episodes > 0 else []
    wall = time.perf_counter() - t_start
    summary["total_wall_s"] = wall
    summary["eval"] = [r.to_dict() for r in results]
    (run_dir / "train_summary.json").write_text(json.dumps(summary, indent=2))
    print(f"total wall time (training + evaluation): {wall:.1f} s; run directory: {run_dir}")
    return summary
