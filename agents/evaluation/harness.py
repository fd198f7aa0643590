"""Seeded evaluation of policies on the billiards tasks, and the Wilson interval.

``evaluate(policy_fn, env_id, n_episodes, seed, noise)`` plays the *first*
episode of each of ``n_episodes`` tables (in batches of at most
``batch_size`` tables; batch j is reset with seed ``seed + j``), so every
policy sees exactly the same initial tables for the same seed, whatever the
episode lengths. Metrics per episode: success, return, scratch (any shot
scratched), foul (any foul), balls pocketed, shots.
"""
from __future__ import annotations

import json
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np

from ..sb3.vec_env import NativeVecEnv, make_sb3_vec_env

from billiards_env.studies.stats import Z95, wilson_interval  # noqa: E402,F401 (re-exported)


@dataclass
class EvalResult:
    policy: str
    env_id: str
    noise: str
    n_episodes: int
    seed: int
    success_rate: float
    success_ci95: tuple
    mean_reward: float
    std_reward: float
    scratch_rate: float
    foul_rate: float
    balls_per_episode: float
    shots_per_episode: float
    wall_time_s: float
    per_episode: dict = field(default_factory=dict, repr=False)

    def to_dict(self, with_episodes: bool = False) -> dict:
        d = asdict(self)
        d["success_ci95"] = list(self.success_ci95)
        if not with_episodes:
            d.pop("per_episode")
        return d


def _flag(info: dict, *names) -> bool:
    for n in names:
        if n in info:
            return bool(info[n])
    return False


def _count(info: dict, *names) -> int:
    for n in names:
        if n in info:
            v = info[n]
            return int(np.sum(v)) if np.ndim(v) else int(v)
    return 0


def parse_noise(spec: str | None):
    """A ``--noise`` value: a preset name (``none``, ``tournament``) or
    ``key=value`` pairs of ``NoiseConfig`` separated by commas, optionally
    with ``preset=...`` (``aim_deg=1`` or ``preset=tournament,aim_deg=0.5``).
    Returns what the env's ``noise`` option takes; errors name the bad part."""
    if spec is None or "=" not in spec:
        return spec
    d = {}
    for part in spec.split(","):
        key, sep, value = part.partition("=")
        key = key.strip()
        if not sep or not key:
            raise ValueError(f"noise spec {spec!r}: expected key=value, got {part!r}")
        if key == "preset":
            d[key] = value.strip()
            continue
        try:
            d[key] = float(value)
        except ValueError:
            raise ValueError(f"noise spec {spec!r}: {key} must be a number, got {value!r}") from None
    from billiards_env.envs.config import NoiseConfig
    NoiseConfig.from_any(d)  # validates names and values before any env is built
    return d


def play_batch(policy_fn: Callable, env_id: str, n: int, seed: int, env_kwargs: dict | None = None,
               max_steps: int = 10_000, name: str | None = None) -> dict:
    """Play the first episode of ``n`` tables reset with ``seed``; per-episode
    arrays (success, reward, scratch, foul, balls, shots) and the policy's name.
    One batch of ``evaluate``; a unit of work for distributed evaluation."""
    env: NativeVecEnv = make_sb3_vec_env(env_id, n, **dict(env_kwargs or {}))
    env.seed(seed)
    policy = policy_fn(env)
    pname = name or getattr(policy, "name", "policy")
    obs = env.reset()
    finished = np.zeros(n, dtype=bool)
    ep_ret = np.zeros(n)
    ep_scratch = np.zeros(n, dtype=bool)
    ep_foul = np.zeros(n, dtype=bool)
    ep_balls = np.zeros(n, dtype=np.int64)
    ep_shots = np.zeros(n, dtype=np.int64)
    ep_succ = np.zeros(n, dtype=bool)
    steps = 0
    while not finished.all():
        steps += 1
        if steps > max_steps:
            raise RuntimeError(f"evaluation of {pname} on {env_id}: episodes did not end in {max_steps} steps")
        actions = policy.act(obs)
        obs, rewards, dones, infos = env.step(actions)
        live = ~finished
        ep_ret[live] += rewards[live]
        ep_shots[live] += 1
        for i in np.flatnonzero(live):
            info = infos[i]
            ep_scratch[i] |= _flag(info, "scratch")
            ep_foul[i] |= _flag(info, "foul")
            ep_balls[i] += _count(info, "n_pocketed", "balls_pocketed", "legal_pocketed")
            if dones[i]:
                ep_succ[i] = _flag(info, "success", "is_success")
        finished |= dones
    env.close()
    return dict(name=pname, success=ep_succ, reward=ep_ret, scratch=ep_scratch, foul=ep_foul, balls=ep_balls,
                shots=ep_shots)


def batch_plan(n_episodes: int, seed: int, batch_size: int) -> list[tuple[int, int]]:
    """(tables, reset seed) of each batch: batch j holds ``batch_size`` tables
    (the last one the rest) reset with ``seed + j``."""
    plan, done = [], 0
    while done < n_episodes:
        n = min(batch_size, n_episodes - done)
        plan.append((n, seed + len(plan)))
        done += n
    return plan


def eval_kwargs(noise: str | None, env_kwargs: dict | None = None) -> dict:
    """The env arguments of an evaluation under ``noise``."""
    kw = dict(env_kwargs or {})
    if noise and noise != "none":
        kw["noise"] = parse_noise(noise)
    return kw


def combine_batches(batches: list[dict], env_id: str, n_episodes: int, seed: int, noise: str | None,
                    wall_time_s: float, name: str | None = None) -> EvalResult:
    """One ``EvalResult`` from the ``play_batch`` outputs, in batch order."""
    succ, ret, scratch, foul, balls, shots = (np.concatenate([b[k] for b in batches])
                                              for k in ("success", "reward", "scratch", "foul", "balls", "shots"))
    k = int(succ.sum())
    return EvalResult(
        policy=name or batches[0]["name"], env_id=env_id, noise=noise or "none", n_episodes=int(n_episodes),
        seed=int(seed), success_rate=k / n_episodes, success_ci95=wilson_interval(k, n_episodes),
        mean_reward=float(ret.mean()), std_reward=float(ret.std()),
        scratch_rate=float(scratch.mean()), foul_rate=float(foul.mean()),
        balls_per_episode=float(balls.mean()), shots_per_episode=float(shots.mean()),
        wall_time_s=wall_time_s,
        per_episode=dict(success=succ.tolist(), reward=ret.tolist()))


def evaluate(policy_fn: Callable, env_id: str, n_episodes: int = 1000, seed: int = 0, noise: str = "none",
             batch_size: int = 1000, max_steps: int = 10_000, env_kwargs: dict | None = None,
             name: str | None = None, numba_threads: int | None = None) -> EvalResult:
    """Evaluate ``policy_fn(env) -> policy`` (a policy built on the SB3
    adapter ``env``; it may read the native env through it)."""
    t0 = time.perf_counter()
    kw = eval_kwargs(noise, env_kwargs)
    batches = []
    for n, batch_seed in batch_plan(n_episodes, seed, batch_size):
        batches.append(play_batch(policy_fn, env_id, n, batch_seed, kw, max_steps, name))
        name = name or batches[0]["name"]
    return combine_batches(batches, env_id, n_episodes, seed, noise, time.perf_counter() - t0, name)


def load_trained(path, name: str | None = None):
    """A trained policy from a run directory or model file of either backend:
    stable-baselines3 (``model.zip``) or RLlib (``agents.rllib.policy``)."""
    from ..sb3.policy import SB3Policy
    from ..rllib.policy import RLlibPolicy, is_rllib_run

    if is_rllib_run(path):
        return RLlibPolicy.load(path, name=name)
    return SB3Policy.load(path, name=name)


def policy_factory(spec: str, seed: int = 0, search_k: int = 256) -> tuple[Callable, str, dict]:
    """``(policy_fn, display name, env_kwargs)`` of a policy spec: ``random``,
    ``ghost``, ``search`` (K = ``search_k``), ``search<K>``, ``lookahead``, or
    a run directory / model file of either training backend. ``env_kwargs``
    are the env options the policy plays with: a trained policy's are its
    run's (``env_kwargs`` of its config.yaml: its observation and action
    mapping), a baseline's none."""
    from .policies import is_policy_name, make_policy

    if is_policy_name(spec):
        if spec == "search":
            spec = f"search{search_k}"
        return (lambda env, s=spec: make_policy(s, env, seed=seed)), spec, {}  # noqa: E731
    loaded = load_trained(spec)
    return (lambda env, p=loaded: p.bind(env)), f"{loaded.name}:{Path(spec).name}", dict(loaded.env_kwargs)  # noqa: E731


def evaluate_spec(spec: str, policy_fn: Callable, env_id: str, n_episodes: int, seed: int, noise: str,
                  batch_size: int, name: str, search_k: int = 256, env_kwargs: dict | None = None) -> EvalResult:
    """One entry of ``evaluate_policies``, in this process."""
    return evaluate(policy_fn, env_id, n_episodes, seed, noise, batch_size=batch_size, name=name,
                    env_kwargs=env_kwargs)


def game_opponent(env_id: str, env_kwargs: dict, opponent: str | None) -> dict:
    """The env arguments of a policy on ``env_id``: on a two-player game id
    with ``opponent`` (else the one its run trained against, else ``ghost``);
    ``opponent`` on a one-player task is an error."""
    from billiards_env.envs.registration import GAME_IDS

    if env_id not in GAME_IDS:
        if opponent is not None:
            raise ValueError(f"an opponent applies to the two-player games ({', '.join(GAME_IDS)}), not {env_id}")
        return env_kwargs
    return {**env_kwargs, "opponent": opponent or env_kwargs.get("opponent", "ghost")}


def evaluate_policies(specs: list[str], env_id: str, n_episodes: int = 1000, seed: int = 0,
                      noises: list | None = None, search_k: int = 256, batch_size: int = 1000,
                      names: list[str] | None = None, run: Callable = evaluate_spec,
                      opponent: str | None = None) -> list[EvalResult]:
    """Evaluate every policy of ``specs`` (see ``policy_factory``) under
    every noise setting of ``noises`` (default ``["none"]``) on the same
    seeded episodes, printing one line per result. ``names``: display names
    per spec (optional). ``run``: how one entry is evaluated (``evaluate_spec``
    here; ``agents.rllib.evaluation.evaluate_spec`` on Ray, with the same results).
    ``opponent``: on a two-player game, whom every policy plays (default:
    a trained policy's training opponent, ``ghost`` for the baselines)."""
    game_opponent(env_id, {}, opponent)  # a misplaced opponent fails before anything runs
    results = []
    for j, spec in enumerate(specs):
        fn, display, env_kwargs = policy_factory(spec, seed, search_k)
        env_kwargs = game_opponent(env_id, env_kwargs, opponent)
        display = names[j] if names and j < len(names) and names[j] else display
        for nz in noises or ["none"]:
            r = run(spec, fn, env_id, n_episodes, seed, nz, batch_size, display, search_k, env_kwargs=env_kwargs)
            against = f" against {env_kwargs['opponent']}" if "opponent" in env_kwargs else ""
            print(f"{display:>20s}{against} noise={nz:<10s} success {r.success_rate:.3f} "
                  f"[{r.success_ci95[0]:.3f}, {r.success_ci95[1]:.3f}]  ({r.wall_time_s:.1f} s)", flush=True)
            results.append(r)
    return results


def format_table(results: list[EvalResult]) -> str:
    """A Markdown table of results."""
    multi = any(r.env_id not in ("Billiards-PotOne-v1",) for r in results)
    head = ["policy", "task", "noise", "episodes", "success", "95% CI", "mean reward", "scratch", "foul"]
    if multi:
        head += ["balls/episode"]
    lines = ["| " + " | ".join(head) + " |", "|" + "|".join("---" for _ in head) + "|"]
    for r in results:
        row = [r.policy, r.env_id, r.noise, str(r.n_episodes), f"{r.success_rate:.3f}",
               f"[{r.success_ci95[0]:.3f}, {r.success_ci95[1]:.3f}]", f"{r.mean_reward:.3f}",
               f"{r.scratch_rate:.3f}", f"{r.foul_rate:.3f}"]
        if multi:
            row.append(f"{r.balls_per_episode:.2f}")
        lines.append("| " + " | ".join(row) + " |")
    return "\n".join(lines)


def save_results(results: list[EvalResult], json_path, png_path=None, title: str = "") -> None:
    json_path = Path(json_path)
    json_path.parent.mkdir(parents=True, exist_ok=True)
    json_path.write_text(json.dumps([r.to_dict() for r in results], indent=2))
    if png_path is not None:
        bar_chart(results, png_path, title)


def bar_chart(results: list[EvalResult], png_path, title: str = "") -> None:
    from ..plotting import pyplot, save_figure

    plt = pyplot()

    noises = sorted({r.noise for r in results}, key=lambda s: (s != "none", s))
    policies = list(dict.fromkeys(r.policy for r in results))
    width = 0.8 / max(len(noises), 1)
    fig, ax = plt.subplots(figsize=(max(5, 1.3 * len(policies) + 2), 4))
    for j, nz in enumerate(noises):
        xs, ys, lo, hi = [], [], [], []
        for i, p in enumerate(policies):
            r = next((r for r in results if r.policy == p and r.noise == nz), None)
            if r is None:
                continue
            xs.append(i + (j - (len(noises) - 1) / 2) * width)
            ys.append(r.success_rate)
            lo.append(r.success_rate - r.success_ci95[0])
            hi.append(r.success_ci95[1] - r.success_rate)
        bars = ax.bar(xs, ys, width, yerr=[lo, hi], capsize=3, label=f"noise: {nz}")
        for x, y in zip(xs, ys):
            ax.text(x, y + 0.02, f"{y:.2f}", ha="center", fontsize=8)
    ax.set_xticks(range(len(policies)))
    ax.set_xticklabels(policies)
    ax.set_ylim(0, 1.1)
    ax.set_ylabel("success rate (95% Wilson CI)")
    env_ids = sorted({r.env_id for r in results})
    ax.set_title(title or f"{', '.join(env_ids)}: {results[0].n_episodes} seeded episodes")
    ax.legend(loc="lower right", fontsize=8)
    save_figure(fig, png_path)
