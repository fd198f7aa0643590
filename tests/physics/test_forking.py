"""The simulator in a process forked from one that ran it (physics/forking.py):
the child runs the serial kernels, with the parallel kernels' results bit
for bit; a kernel compiled rather than loaded says so once, and a warm
cache is silent (physics/_jit.py)."""
import multiprocessing as mp
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numba
import numpy as np
import pytest

from billiards_env.physics import forking, kernels, rack, set_num_threads, simulate, strike_velocity

ROOT = Path(__file__).resolve().parents[2]
TABLES = 24  # a batch the parent runs on two threads
CHILD_TIMEOUT_S = 600  # the child may compile the serial kernels (20-160 s each on a cold cache)


def _break(pool, params):
    s = rack(pool, params, "nine", TABLES, seed=3)
    rng = np.random.default_rng(4)
    return strike_velocity(s, np.pi / 2 + rng.normal(0, 0.02, TABLES), rng.uniform(3, 9, TABLES),
                           rng.uniform(-0.3, 0.3, TABLES), rng.uniform(-0.3, 0.3, TABLES), params)


def _in_child(conn, s, pool, params):
    results = [simulate(s, pool, params, solver=solver, dt=dt) for solver, dt in (("event", None), ("step", 1e-3))]
    conn.send((forking.threads_usable(), [(r.state.pos, r.state.vel, r.state.pocket, r.time, r.n_events)
                                          for r in results]))
    conn.close()


@pytest.mark.skipif(not hasattr(os, "fork"), reason="needs fork(2)")
def test_forked_child_runs_serial_kernels_with_the_same_results(pool, params):
    s = _break(pool, params)
    set_num_threads(min(2, numba.config.NUMBA_NUM_THREADS))
    parent = [simulate(s, pool, params, solver=solver, dt=dt) for solver, dt in (("event", None), ("step", 1e-3))]
    assert forking.threads_usable()
    ctx = mp.get_context("fork")
    here, there = ctx.Pipe()
    child = ctx.Process(target=_in_child, args=(there, s, pool, params))
    child.start()
    there.close()
    assert here.poll(CHILD_TIMEOUT_S), "the forked child sent nothing"
    usable, got = here.recv()
    child.join(CHILD_TIMEOUT_S)
    assert child.exitcode == 0
    if numba.threading_layer() in forking.FORK_UNSAFE_LAYERS:
        assert not usable  # the child ran the serial variants
    for r, (pos, vel, pocket, time, n_events) in zip(parent, got):
        assert np.array_equal(r.state.pos, pos) and np.array_equal(r.state.vel, vel)
        assert np.array_equal(r.state.pocket, pocket)
        assert np.array_equal(r.time, time) and np.array_equal(r.n_events, n_events)


def test_serial_kernels_are_named_in_their_compile_message():
    key = ("event", True, True, False, "coulomb/constant", "han2005", True, "contacts", "serial")
    assert kernels._label(key) == ("the event solver (spin, sliding; ball-ball coulomb/constant, cushion han2005; "
                                   "diagnostics; contacts; serial)")


KERNEL_MODULE = '''
import numba
from billiards_env.physics._jit import cached_kernel

def run(a):
    for i in numba.prange(a.shape[0]):
        a[i] += 1.0

kernel = cached_kernel(run, "tests/compile-message", "a test kernel", parallel=False)
'''


def test_a_compile_says_so_once_and_a_warm_cache_is_silent(tmp_path):
    (tmp_path / "tiny_kernel.py").write_text(textwrap.dedent(KERNEL_MODULE))
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "cache"),
               PYTHONPATH=os.pathsep.join([str(tmp_path), str(ROOT), os.environ.get("PYTHONPATH", "")]))
    code = "import numpy as np, tiny_kernel; a = np.zeros(3); tiny_kernel.kernel(a); tiny_kernel.kernel(a); print(a)"
    runs = [subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=300)
            for _ in range(2)]
    assert all(r.returncode == 0 and "[2. 2. 2.]" in r.stdout for r in runs), [r.stderr for r in runs]
    cold, warm = (r.stderr for r in runs)
    assert cold.count("compiling the simulator's kernel for a test kernel (first use only") == 1, cold
    assert "compiling" not in warm, warm
