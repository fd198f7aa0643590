"""``env_chain``: the one walk through wrappers down to a native env."""
from __future__ import annotations

MAX_WRAPPERS = 10  # wrapper layers looked through (SB3 VecEnv wrappers, Gymnasium wrappers, adapters)


def env_chain(env, depth: int = MAX_WRAPPERS):
    """``env`` and the envs under it, outermost first, through SB3 adapters
    and wrappers (``venv``) and Gymnasium wrappers (``unwrapped``, ``env``)."""
    for _ in range(depth):
        yield env
        for attr in ("venv", "unwrapped", "env"):
            inner = getattr(env, attr, None)
            if inner is not None and inner is not env:
                env = inner
                break
        else:
            return
