"""Training PPO / SAC on the native billiards vector env.

``train(cfg, run_dir)`` builds the SB3 adapter (one batched simulator call
per step for all ``n_envs`` tables), optional VecNormalize, the model, and
trains with a progress bar, TensorBoard logging (when installed), a CSV log
of episode statistics (for the learning curve), periodic checkpoints (model +
VecNormalize stats) and the final model saved as ``<run>/model.zip`` with
``<run>/vecnormalize.pkl`` and ``<run>/config.yaml``.

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

from .config import TrainConfig, save_config
from .sb3_vec_env import make_sb3_vec_env


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

    def __init__(self, run_dir: Path, checkpoint_every: int = 0, vecnorm=None):
        super().__init__()
        self.run_dir = run_dir
        self.checkpoint_every = int(checkpoint_every)
        self.vecnorm = vecnorm
        self._next_ckpt = self.checkpoint_every or None
        self._buf = {"success": [], "reward": [], "scratch": [], "foul": []}
        self._ep_ret = None
        self.t0 = time.perf_counter()
        self.rows: list[dict] = []
        self._csv = None

    def _on_training_start(self) -> None:
        self._ep_ret = np.zeros(self.training_env.num_envs)
        self._csv_f = open(self.run_dir / "progress.csv", "w", newline="")
        self._csv = csv.DictWriter(self._csv_f, fieldnames=["timesteps", "time_s", "episodes", "success_rate",
                                                            "mean_reward", "scratch_rate", "foul_rate", "steps_per_s"])
        self._csv.writeheader()

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
            self._buf["success"].append(float(bool(info.get("success", False))))
            self._buf["scratch"].append(float(bool(info.get("scratch", False))))
            self._buf["foul"].append(float(bool(info.get("foul", False))))
            self._buf["reward"].append(float(self._ep_ret[i]))
            self._ep_ret[i] = 0.0
        if self._next_ckpt is not None and self.num_timesteps >= self._next_ckpt:
            ck = self.run_dir / "checkpoints"
            ck.mkdir(exist_ok=True)
            self.model.save(ck / f"model_{self.num_timesteps}_steps.zip")
            if self.vecnorm is not None:
                self.vecnorm.save(str(ck / f"model_{self.num_timesteps}_steps_vecnormalize.pkl"))
            self._next_ckpt += self.checkpoint_every
        return True

    def _on_rollout_end(self) -> None:
        if not self._buf["success"]:
            return
        el = time.perf_counter() - self.t0
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


def build_env(cfg: TrainConfig, seed: int):
    from stable_baselines3.common.vec_env import VecNormalize

    from .features import ShotFeatures

    env = make_sb3_vec_env(cfg.env_id, cfg.n_envs, seed=seed, **cfg.env_kwargs)
    if cfg.features or cfg.aim_scale != 1.0 or cfg.action_mode != "direct":
        env = ShotFeatures(env, env.unwrapped, cfg.features, cfg.aim_scale, cfg.action_mode)
    vecnorm = None
    if cfg.normalize.obs or cfg.normalize.reward:
        n = cfg.normalize
        env = vecnorm = VecNormalize(env, norm_obs=n.obs, norm_reward=n.reward, clip_obs=n.clip_obs,
                                     clip_reward=n.clip_reward, gamma=n.gamma)
    return env, vecnorm


def build_model(cfg: TrainConfig, env, tensorboard_log: str | None):
    from stable_baselines3 import PPO, SAC

    cls = {"ppo": PPO, "sac": SAC}[cfg.algo]
    kw = dict(cfg.algo_kwargs)
    return cls("MlpPolicy", env, policy_kwargs=cfg.policy.policy_kwargs(cfg.algo), seed=cfg.train.seed,
               device=cfg.train.device, tensorboard_log=tensorboard_log, verbose=0, **kw)


def train(cfg: TrainConfig, run_dir, command: str = "") -> dict:
    """Train according to ``cfg``; everything is written to ``run_dir``.
    Returns a summary dict (wall time, throughput, final training success)."""
    import numba
    import torch

    run_dir = Path(run_dir)
    run_dir.mkdir(parents=True, exist_ok=True)
    save_config(cfg, run_dir / "config.yaml")
    (run_dir / "command.txt").write_text(command + "\n")
    torch.set_num_threads(cfg.train.torch_threads)
    numba.set_num_threads(min(cfg.train.numba_threads, numba.config.NUMBA_NUM_THREADS))

    env, vecnorm = build_env(cfg, cfg.train.seed)
    tb = str(run_dir / "tb") if (cfg.train.tensorboard and _has_tensorboard()) else None
    model = build_model(cfg, env, tb)
    cb = EpisodeLogger(run_dir, cfg.train.checkpoint_every, vecnorm)
    callbacks = [cb] + ([ProgressBar(cfg.train.total_timesteps)] if cfg.train.progress_bar else [])
    t0 = time.perf_counter()
    model.learn(total_timesteps=cfg.train.total_timesteps, callback=callbacks, tb_log_name=cfg.algo)
    wall = time.perf_counter() - t0
    model.save(run_dir / "model.zip")
    if vecnorm is not None:
        vecnorm.save(str(run_dir / "vecnormalize.pkl"))
    env.close()
    last = cb.rows[-5:]
    summary = dict(env_id=cfg.env_id, algo=cfg.algo, timesteps=int(model.num_timesteps), train_wall_s=wall,
                   env_steps_per_s=model.num_timesteps / wall,
                   final_train_success=float(np.mean([r["success_rate"] for r in last])) if last else None)
    (run_dir / "train_summary.json").write_text(json.dumps(summary, indent=2))
    return summary


def final_evaluation(cfg: TrainConfig, run_dir) -> list:
    """The trained model of ``run_dir`` and ``cfg.train.eval_baselines`` on
    ``eval_episodes`` seeded episodes per noise setting; prints a Markdown
    table and writes ``eval.json`` / ``eval.png`` into ``run_dir``."""
    from .baselines import make_policy
    from .evaluation import evaluate, format_table, load_trained, save_results

    run_dir = Path(run_dir)
    trained = load_trained(run_dir)  # either backend's run
    ts = cfg.train
    results = []
    for noise in ts.eval_noise:
        results.append(evaluate(lambda env: trained.bind(env), cfg.env_id, ts.eval_episodes, ts.eval_seed,
                                noise, name=trained.name))
        for b in ts.eval_baselines:
            bname = f"search{ts.search_k}" if b == "search" else b
            results.append(evaluate(lambda env, b=bname: make_policy(b, env, seed=ts.eval_seed), cfg.env_id,
                                    ts.eval_episodes, ts.eval_seed, noise, name=bname))
    print(format_table(results))
    save_results(results, run_dir / "eval.json", run_dir / "eval.png")
    return results


def train_and_evaluate(cfg: TrainConfig, run_dir, command: str = "", t_start: float | None = None) -> dict:
    """Train (``train``), plot ``learning_curve.png`` and run the final
    evaluation (``final_evaluation``, skipped when ``eval_episodes`` is 0);
    the summary, with the evaluation and the total wall time since
    ``t_start`` (default: now), is written to ``train_summary.json``."""
    from .plotting import plot_runs

    t_start = time.perf_counter() if t_start is None else t_start
    run_dir = Path(run_dir)
    summary = train(cfg, run_dir, command)
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
