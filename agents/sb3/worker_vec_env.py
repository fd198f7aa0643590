"""The training tables split over worker processes, stepping at once.

``WorkerVecEnv`` is an SB3 ``VecEnv`` of ``n_envs`` tables held by
``workers`` processes, ``n_envs / workers`` tables each: every worker builds
the same env the single-process path builds (``TableEnvSpec.build``: the
native vector env in the SB3 adapter, with the agent-side features and the
action transform), and a step sends each worker its slice of the actions,
then collects the slices in table order. The workers step at the same time,
one core each, while the learner (VecNormalize, the network, the updates)
stays in this process; the env step (the simulator, the opponent's
decisions, the rules, the features) is most of a game step's CPU
(docs/agents_benchmark.md, "Where the games' training time goes").

Table ``i`` of the whole batch is table ``i - j * n_envs / workers`` of
worker ``j``, seeded ``seed + i`` as in one process (``seed``/``reset``).
``apply(fn, *args)`` runs a module-level function ``fn(env, *args)`` in
every worker on its env and returns the workers' results in order (the
checkpoints read and restore the tables' random streams with it;
``worker_cpu_seconds`` gives each worker's CPU time). Workers are started with
``spawn`` (a fork would copy the parent's OpenMP and torch thread state)
and leave when their pipe closes, so a killed trainer leaves none behind.
"""
from __future__ import annotations

import multiprocessing as mp
import time
import traceback
from collections.abc import Sequence
from typing import Any, NamedTuple

import numpy as np
from stable_baselines3.common.vec_env.base_vec_env import VecEnv, VecEnvIndices

from .infos import VecInfos
from .vec_env import env_indices, native_vec_env

START_TIMEOUT_S = 600.0  # a worker's first reply: imports plus, in a fresh tree, compiling the numba kernels


class TableEnvSpec(NamedTuple):
    """What a worker (or the single-process path) builds for its tables."""
    env_id: str
    env_kwargs: dict
    features: bool
    aim_scale: float
    action_mode: str
    numba_threads: int = 1
    autoreset_mode: str = "same_step"  # the self-play game env resets in next_step mode only

    def wraps_features(self) -> bool:
        return self.features or self.aim_scale != 1.0 or self.action_mode != "direct"

    def build(self, n_envs: int, seed: int | None):
        """The SB3 adapter over ``n_envs`` native tables (``seed + i`` for
        table ``i``), with ``ShotFeatures`` when the config asks for them."""
        from ..interface.features import ShotFeatures
        from .vec_env import make_sb3_vec_env

        env = make_sb3_vec_env(self.env_id, n_envs, seed=seed, autoreset_mode=self.autoreset_mode, **self.env_kwargs)
        if self.wraps_features():
            env = ShotFeatures(env, env.unwrapped, self.features, self.aim_scale, self.action_mode)
        return env


def find_workers(env) -> "WorkerVecEnv | None":
    """The ``WorkerVecEnv`` under SB3 wrappers, or None when the tables are in this process."""
    from billiards_env.contract.unwrap import env_chain

    return next((e for e in env_chain(env) if isinstance(e, WorkerVecEnv)), None)


def cpu_seconds(env) -> tuple[float, float]:
    """CPU time of this process plus that of ``env``'s workers (if any), and
    of this process plus its busiest worker: the workers step at once while
    this process waits, so on idle cores the latter is about the wall time."""
    w = find_workers(env)
    own, workers = time.process_time(), (w.worker_cpu_seconds() if w is not None else [0.0])
    return own + sum(workers), own + max(workers)


def _process_seconds(env) -> float:
    return time.process_time()


class _Profiler:
    """The worker's cProfile while ``profile_start`` .. ``profile_stop`` (scripts/profile_training.py)."""
    prof = None


def profile_start(env, wall: bool = False) -> None:
    import cProfile
    _Profiler.prof = cProfile.Profile(time.perf_counter if wall else time.process_time)
    _Profiler.prof.enable()


def profile_stop(env, directory: str) -> str:
    """Stop the worker's profile and write it to ``directory``; returns the file's path."""
    import os
    _Profiler.prof.disable()
    path = os.path.join(directory, f"env_worker_{os.getpid()}.prof")
    _Profiler.prof.dump_stats(path)
    _Profiler.prof = None
    return path


def _serve(env, cmd: str, arg):
    """One command of the parent, on the worker's ``env``."""
    if cmd == "step":
        env.step_async(arg)
        return env.step_wait()
    if cmd == "reset":
        seeds, options = arg
        native = native_vec_env(env)
        native._seeds, native._options = list(seeds), list(options)
        return env.reset()
    if cmd == "get_attr":
        return env.get_attr(arg)[0]
    if cmd == "set_attr":
        return env.set_attr(*arg)
    if cmd == "env_method":
        name, args, kwargs = arg
        return env.env_method(name, *args, **kwargs)
    if cmd == "apply":
        fn, args = arg
        return fn(env, *args)
    raise ValueError(f"unknown worker command {cmd!r}")


def _worker(conn, spec: TableEnvSpec, n_envs: int) -> None:
    """A worker's loop: build the env, then serve commands until ``close``
    or until the parent's end of the pipe is gone."""
    try:
        import numba
        numba.set_num_threads(min(spec.numba_threads, numba.config.NUMBA_NUM_THREADS))
        env = spec.build(n_envs, None)
        conn.send(("ok", (env.observation_space, env.action_space)))
    except Exception:  # noqa: BLE001 (reported to the parent, which raises)
        conn.send(("error", traceback.format_exc()))
        return
    while True:
        try:
            cmd, arg = conn.recv()
        except (EOFError, OSError):  # the parent died
            break
        if cmd == "close":
            env.close()
            conn.send(("ok", None))
            break
        try:
            conn.send(("ok", _serve(env, cmd, arg)))
        except Exception:  # noqa: BLE001
            conn.send(("error", traceback.format_exc()))
    conn.close()


class WorkerVecEnv(VecEnv):
    """``n_envs`` tables of ``spec`` over ``workers`` processes (module docstring)."""

    def __init__(self, spec: TableEnvSpec, n_envs: int, workers: int):
        if workers < 1 or n_envs % workers:
            raise ValueError(f"n_envs={n_envs} tables do not split evenly over {workers} env workers")
        self.per = n_envs // workers
        ctx = mp.get_context("spawn")
        self._conns, self._procs = [], []
        for _ in range(workers):
            parent, child = ctx.Pipe()
            proc = ctx.Process(target=_worker, args=(child, spec, self.per), daemon=True)
            proc.start()
            child.close()
            self._conns.append(parent)
            self._procs.append(proc)
        self._closed = False
        try:
            spaces = self._gather(timeout=START_TIMEOUT_S)
        except BaseException:
            for proc in self._procs:  # the others may still be starting
                proc.kill()
                proc.join()
            raise
        super().__init__(n_envs, *spaces[0])

    # -- talking to the workers ------------------------------------------
    def _recv(self, j: int, timeout: float | None = None):
        conn = self._conns[j]
        if timeout is not None and not conn.poll(timeout):
            raise TimeoutError(f"env worker {j} did not answer within {timeout:.0f} s")
        try:
            status, out = conn.recv()
        except EOFError:
            raise RuntimeError(f"env worker {j} exited (exit code {self._procs[j].exitcode})") from None
        if status == "error":
            raise RuntimeError(f"env worker {j} failed:\n{out}")
        return out

    def _gather(self, timeout: float | None = None) -> list:
        return [self._recv(j, timeout) for j in range(len(self._conns))]

    def _send_all(self, cmd: str, arg=None) -> list:
        for conn in self._conns:
            conn.send((cmd, arg))
        return self._gather()

    def apply(self, fn, *args) -> list:
        """``fn(env, *args)`` in every worker (``fn`` module-level, picklable); the results in worker order."""
        return self._send_all("apply", (fn, args))

    def _rows(self, a, j: int):
        """Worker ``j``'s tables' rows of ``a`` (an array or a list in table order)."""
        return a[j * self.per:(j + 1) * self.per]

    def apply_slices(self, fn, *arrays) -> list:
        """``fn(env, *slices)`` in every worker, each given its own tables' rows of ``arrays``."""
        for j, conn in enumerate(self._conns):
            conn.send(("apply", (fn, tuple(self._rows(a, j) for a in arrays))))
        return self._gather()

    def worker_cpu_seconds(self) -> list[float]:
        """Each worker's CPU time so far (its ``time.process_time``)."""
        return [float(x) for x in self.apply(_process_seconds)]

    # -- core API --------------------------------------------------------
    def reset(self) -> np.ndarray:
        for j, conn in enumerate(self._conns):
            conn.send(("reset", (self._rows(self._seeds, j), self._rows(self._options, j))))
        obs = np.concatenate(self._gather())
        self._reset_seeds()
        self._reset_options()
        return obs

    def step_async(self, actions: np.ndarray) -> None:
        actions = np.asarray(actions)
        for j, conn in enumerate(self._conns):
            conn.send(("step", self._rows(actions, j)))

    def step_wait(self):
        parts = self._gather()
        obs = np.concatenate([o for o, _, _, _ in parts])
        rewards = np.concatenate([r for _, r, _, _ in parts])
        dones = np.concatenate([d for _, _, d, _ in parts])
        infos = VecInfos.concat([i for _, _, _, i in parts])
        return obs, rewards, dones, infos

    def _indices(self, indices: VecEnvIndices) -> list[int]:
        return env_indices(self.num_envs, indices)

    def get_attr(self, attr_name: str, indices: VecEnvIndices = None) -> list[Any]:
        # the attributes of a batch are shared (NativeVecEnv.get_attr): worker 0's
        self._conns[0].send(("get_attr", attr_name))
        value = self._recv(0)
        return [value for _ in self._indices(indices)]

    def set_attr(self, attr_name: str, value: Any, indices: VecEnvIndices = None) -> None:
        self._send_all("set_attr", (attr_name, value, None))

    def env_method(self, method_name: str, *method_args, indices: VecEnvIndices = None, **method_kwargs) -> list:
        out = [r for part in self._send_all("env_method", (method_name, method_args, method_kwargs)) for r in part]
        return [out[i] for i in self._indices(indices)]

    def env_is_wrapped(self, wrapper_class, indices: VecEnvIndices = None) -> list[bool]:
        return [False for _ in self._indices(indices)]

    def close(self) -> None:
        if self._closed:
            return
        self._closed = True
        for j, conn in enumerate(self._conns):
            try:
                conn.send(("close", None))
                self._recv(j, timeout=START_TIMEOUT_S)
            except (OSError, RuntimeError, TimeoutError):
                pass  # already gone
            conn.close()
        for proc in self._procs:
            proc.join(timeout=START_TIMEOUT_S)

    def get_images(self) -> Sequence[np.ndarray | None]:
        return [None for _ in range(self.num_envs)]
