"""Distributed evaluation on Ray: the evaluation harness's batches, and the
search baseline's candidate shots, as Ray tasks.

``evaluate_ray`` plays the same batches as ``agents.evaluation.harness.evaluate``
(batch j: ``batch_size`` tables reset with ``seed + j``), each batch a Ray
task, and combines them in batch order, so its results equal the local
evaluation's for the same seed and batch size. The search baseline's cost
is its candidate shots (K per table, simulated in chunks): under Ray each
chunk is a task (``RayChunkMap``), and the chunks' results are joined in
order, so the chosen shots are the same as in one process. ``ray_map``,
under both, runs a list of calls as tasks and runs again those whose worker
died (``agents.evaluation.distributed`` plays match chunks with it).

Work goes to whatever cluster ``agents.rllib.backend.start_ray`` joined (a
local instance by default). Each task uses one CPU and sets numba to one
thread.
"""
from __future__ import annotations

import math
import time
from typing import Callable

from ..evaluation.harness import EvalResult, batch_plan, combine_batches, eval_kwargs, play_batch

_remote_cache: dict = {}


def _remote(fn):
    """``fn`` as a one-CPU Ray remote function (made once per process)."""
    import ray

    if fn not in _remote_cache:
        def run(*args):
            import numba
            numba.set_num_threads(1)
            return fn(*args)
        run.__name__ = run.__qualname__ = fn.__name__
        _remote_cache[fn] = ray.remote(num_cpus=1)(run)
    return _remote_cache[fn]


def _lost(exc: BaseException) -> bool:
    """Whether ``exc`` says a task's worker or node died (not that the task
    raised): such a task is run again from the start, and nothing it did
    before counts."""
    from ray import exceptions as rx

    return isinstance(exc, (rx.WorkerCrashedError, rx.NodeDiedError, rx.ObjectLostError, rx.LocalRayletDiedError))


def ray_map(fn, args: list, retries: int = 3, on_retry=None, on_done=None) -> list:
    """``[fn(*a) for a in args]``, each call a one-CPU Ray task, results in
    ``args`` order. A task whose worker dies (a crashed or killed process, a
    lost node) is submitted again, up to ``retries`` times per task, and
    only its last, complete run's result is kept: a chunk is counted once.
    An exception the task itself raised is raised here. ``on_retry(i,
    error)``: called when task i is submitted again; ``on_done(n, total)``
    after each finished task."""
    import ray

    remote = _remote(fn).options(max_retries=0)  # resubmitted here, so every retry is seen
    pending = {remote.remote(*a): i for i, a in enumerate(args)}
    tries, out = [0] * len(args), [None] * len(args)
    done = 0
    while pending:
        ready, _ = ray.wait(list(pending), num_returns=1)
        i = pending.pop(ready[0])
        try:
            out[i] = ray.get(ready[0])
        except Exception as exc:  # noqa: BLE001 (the task's own errors are raised again below)
            if not _lost(exc) or tries[i] >= retries:
                raise
            tries[i] += 1
            if on_retry is not None:
                on_retry(i, exc)
            pending[remote.remote(*args[i])] = i
            continue
        done += 1
        if on_done is not None:
            on_done(done, len(args))
    return out


class RayChunkMap:
    """``map_chunks`` for ``SearchPolicy``: each chunk of candidate shots is
    simulated by a Ray task; results come back in chunk order (``ray_map``:
    a chunk whose worker died is simulated again)."""

    def __call__(self, fn, args: list) -> list:
        return ray_map(fn, args)


def cluster_cpus() -> int:
    import ray

    return max(1, int(ray.cluster_resources().get("CPU", 1)))


def search_policy_fn(spec: str, seed: int, search_k: int, tables: int) -> Callable:
    """``policy_fn`` of the search baseline ``spec`` (``search`` or
    ``search<K>``) whose candidate chunks run as Ray tasks: about two chunks
    per cluster CPU for ``tables`` tables."""
    from billiards_env.bots.one_player import BotPolicy, SearchPolicy

    from ..interface.game_view import native_env

    k = int(spec[6:]) if spec[6:] else search_k
    chunk = max(1, math.ceil(tables * k / (2 * cluster_cpus())))
    mapper = RayChunkMap()
    return lambda env: BotPolicy(SearchPolicy(k=k, seed=seed, chunk=chunk, map_chunks=mapper), native_env(env))


def evaluate_ray(policy_fn: Callable, env_id: str, n_episodes: int = 1000, seed: int = 0, noise: str = "none",
                 batch_size: int = 1000, max_steps: int = 10_000, env_kwargs: dict | None = None,
                 name: str | None = None, local_batches: bool = False) -> EvalResult:
    """``agents.evaluation.harness.evaluate`` with every batch a Ray task
    (``local_batches``: play the batches here, in order; for policies that
    spread their own work, such as the search baseline's candidates)."""
    import ray

    t0 = time.perf_counter()
    kw = eval_kwargs(noise, env_kwargs)
    plan = batch_plan(n_episodes, seed, batch_size)
    if local_batches:
        batches = [play_batch(policy_fn, env_id, n, s, kw, max_steps, name) for n, s in plan]
    else:
        remote = _remote(play_batch)
        batches = ray.get([remote.remote(policy_fn, env_id, n, s, kw, max_steps, name) for n, s in plan])
    return combine_batches(batches, env_id, n_episodes, seed, noise, time.perf_counter() - t0, name)


def evaluate_spec(spec: str, policy_fn: Callable, env_id: str, n_episodes: int, seed: int, noise: str,
                  batch_size: int, name: str, search_k: int = 256, env_kwargs: dict | None = None) -> EvalResult:
    """One entry of ``agents.evaluation.harness.evaluate_policies(run=evaluate_spec)``
    on Ray: the search baseline plays its batches here with its candidates spread
    over the cluster; every other policy has its batches spread."""
    if spec.startswith("search"):
        fn = search_policy_fn(spec, seed, search_k, min(batch_size, n_episodes))
        return evaluate_ray(fn, env_id, n_episodes, seed, noise, batch_size, name=name, local_batches=True)
    return evaluate_ray(policy_fn, env_id, n_episodes, seed, noise, batch_size, env_kwargs=env_kwargs, name=name)
