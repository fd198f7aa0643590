"""The helpers' JIT settings (billiards_env.physics._jit)."""
import numba
import pytest
from numba.core import types

from billiards_env.physics._jit import njit

pytestmark = pytest.mark.skipif(numba.config.DISABLE_JIT, reason="checks compiled signatures")


def _caller_of(helper):
    @njit
    def caller(x):
        k = -1  # typed as the literal -1 until the loop widens it to int64
        for i in range(3):
            if x > i:
                k = i
        return helper(x, k, True) + helper(x, 0, True)
    return caller


def _with_flag(x, k, flag):
    return 2 * x + k if flag else 0


def test_helper_compiled_once_for_integer_constants():
    helper = njit(_with_flag)
    assert _caller_of(helper)(5) == (10 + 2) + (10 + 0)
    # one signature: k as int64 (not also the literals -1 and 0), the flag
    # still a boolean literal (branches on it are pruned)
    assert [sig for sig in helper.signatures] == [(types.int64, types.int64, types.BooleanLiteral(True))]


def test_plain_numba_compiles_literal_variants():
    """The case the helpers' dispatcher exists for: numba's own compiles
    the callee again for each integer constant (if this ever fails, numba
    changed and ``_HelperDispatcher`` may have become unnecessary)."""
    helper = numba.njit(_with_flag)
    assert _caller_of(helper)(5) == 22
    assert len(helper.signatures) > 1


_TWO_BALL = """
import json, numpy as np
from billiards_env.physics import BallState, PhysicsParams, Table, simulate, strike_velocity
from billiards_env.testing.invariants import run_checked
P, T = PhysicsParams.standard(), Table.pool(9)
s = strike_velocity(BallState.from_positions(np.array([[[0.5, 0.5], [0.6, 1.2]]])), 1.2, 2.0, 0.2, 0.3, params=P)
r = simulate(s, T, P)
run_checked(s, T, P, "event")
print(json.dumps([int(r.n_events[0]), r.state.pos.ravel().tolist()]))
"""


def test_simulate_runs_without_jit():
    """With NUMBA_DISABLE_JIT=1 (for debugging the kernels in Python) the
    simulator and the invariant checks run and agree with the compiled kernels."""
    import json
    import os
    import subprocess
    import sys

    def run(disable):
        env = {**os.environ, "NUMBA_DISABLE_JIT": "1" if disable else "0"}
        out = subprocess.run([sys.executable, "-c", _TWO_BALL], capture_output=True, text=True, env=env, timeout=600)
        assert out.returncode == 0, out.stderr[-2000:]
        return json.loads(out.stdout.strip().splitlines()[-1])

    (n_py, pos_py), (n_jit, pos_jit) = run(True), run(False)
    assert n_py == n_jit
    assert max(abs(a - b) for a, b in zip(pos_py, pos_jit)) < 1e-9
