"""Whether the kernels may run their loop over tables on threads in this
process, or must run it on one thread because the process was forked.

numba runs the kernels' ``prange`` loop on its threading layer, on Linux
GNU OpenMP (``omp``) when no TBB is installed. GNU OpenMP does not survive
a fork, and numba stops a child forked from a process that has started it
at the child's first parallel loop ("Terminating: fork() called from a
process already using GNU OpenMP, this is unsafe."). Python's
``multiprocessing`` forks by default on Linux before Python 3.14, and so
does ``gym.make_vec(id, vectorization_mode="async")``.

A child forked from a process whose threading layer is GNU OpenMP therefore
runs the serial variant of each kernel (the same code compiled without
``parallel=True``, cached on disk as any variant). Its results are the same
bit for bit: no table's result depends on the threads that run the batch
(tests/physics/test_physics.py, tests/envs/test_gym_api.py). Every other
process keeps the parallel kernels, so the simulator is as fast as before
where it was usable at all.

The other way out, numba's ``workqueue`` layer (fork-safe, and in every
numba build), was not taken: it aborts the process when two threads run a
parallel loop at once, and ``simulate`` may run in several threads at once
(tests/physics/test_chunks.py, the play server).
"""
from __future__ import annotations

import os
import sys

import numba

# Threading layers that a forked child must not use (numba's docs, "The Threading Layers":
# GNU OpenMP, which is what "omp" is on Linux, is not fork-safe; tbb and workqueue are).
FORK_UNSAFE_LAYERS = ("omp",) if sys.platform.startswith("linux") else ()

_forked_from_openmp = False


def _after_fork_in_child() -> None:
    global _forked_from_openmp
    try:
        layer = numba.threading_layer()
    except ValueError:  # the parent never started a threading layer: this child starts its own
        return
    if layer in FORK_UNSAFE_LAYERS:
        _forked_from_openmp = True


os.register_at_fork(after_in_child=_after_fork_in_child)


def threads_usable() -> bool:
    """False in a process forked (at any depth) from one that had started
    numba's GNU OpenMP threading layer: its kernels must run serially."""
    return not _forked_from_openmp
