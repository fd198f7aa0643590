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
