"""Per-table random streams drawn in batches, and the kernels that use them.

Why: the environments must reproduce table k of a vector env with a single
env seeded ``s + k``, so every table needs its own random stream; but one
``numpy.random.Generator`` per table means a Python call per table for every
reset and noisy shot. Here each table's stream is counter based: its n-th
draw is a hash of (key, n), so a numba kernel can draw for any set of tables
at once, and a table's draws depend only on its own key and counter, never
on which other tables draw in the same call.

The hash is the SplitMix64 output function (Steele, Lea & Flood 2014, "Fast
splittable pseudorandom number generators"): draw n of a table is the
(n + 1)-th output of a SplitMix64 generator whose state starts at the
table's key. Keys are SplitMix64 hashes of the integer seeds (taken modulo
2**64). Uniforms keep the top 53 bits (floats in [0, 1)); normals come from
pairs of uniforms by the Box-Muller transform.

Placement (``place_balls``) feeds the shared rejection sampler of
``physics.state`` with candidates drawn from the tables' streams and then
advances each stream by exactly the candidates used. No kernel here calls a
kernel of another file (numba's disk cache checks only a cached function's
own file, so such a kernel would keep stale code of its callee).
"""
from __future__ import annotations

import math

import numba
import numpy as np

from ..physics.state import place_many

_GAMMA = np.uint64(0x9E3779B97F4A7C15)  # SplitMix64 increment (odd; 2**64 / golden ratio)
_M1 = np.uint64(0xBF58476D1CE4E5B9)
_M2 = np.uint64(0x94D049BB133111EB)
_S30, _S27, _S31, _S11 = np.uint64(30), np.uint64(27), np.uint64(31), np.uint64(11)
_ONE = np.uint64(1)
_TWO_M53 = 1.0 / 9007199254740992.0  # 2**-53
_TWO_PI = 2.0 * math.pi

_jit = numba.njit(cache=True, nogil=True)


@_jit
def _mix(z):
    """SplitMix64 output function: a bijective 64-bit avalanche hash."""
    z = (z ^ (z >> _S30)) * _M1
    z = (z ^ (z >> _S27)) * _M2
    return z ^ (z >> _S31)


@_jit
def _next_uniform(key, c):
    """Draw number ``c`` (1-based) of the stream ``key``, in [0, 1)."""
    return np.float64(_mix(key + c * _GAMMA) >> _S11) * _TWO_M53


@_jit
def _seed_keys(seeds, keys, counters, idx):
    for j in range(len(idx)):
        k = idx[j]
        keys[k] = _mix(seeds[j] + _GAMMA)
        counters[k] = np.uint64(0)


@_jit
def _uniform(keys, counters, idx, out):
    for j in range(len(idx)):
        k = idx[j]
        key, c = keys[k], counters[k]
        for i in range(out.shape[1]):
            c += _ONE
            out[j, i] = _next_uniform(key, c)
        counters[k] = c


@_jit
def _normal(keys, counters, idx, out):
    m = out.shape[1]
    for j in range(len(idx)):
        k = idx[j]
        key, c = keys[k], counters[k]
        for i in range(0, m, 2):  # Box-Muller: two uniforms -> two independent normals
            u1 = _next_uniform(key, c + _ONE)
            u2 = _next_uniform(key, c + _ONE + _ONE)
            c += _ONE + _ONE
            r = math.sqrt(-2.0 * math.log(1.0 - u1))  # 1 - u1 in (0, 1]
            out[j, i] = r * math.cos(_TWO_PI * u2)
            if i + 1 < m:
                out[j, i + 1] = r * math.sin(_TWO_PI * u2)
        counters[k] = c


class TableStreams:
    """``n`` independent, seedable random streams, one per table.

    ``keys`` (uint64 [n]) identify the streams, ``counters`` (uint64 [n]) count
    the uniforms each has used. Every method takes the table indices ``idx``
    it draws for (each index's rows follow its own stream; an index listed
    twice draws twice)."""

    def __init__(self, n: int):
        self.keys = np.zeros(n, dtype=np.uint64)
        self.counters = np.zeros(n, dtype=np.uint64)

    @staticmethod
    def _idx(idx) -> np.ndarray:
        return np.ascontiguousarray(idx, dtype=np.int64).reshape(-1)

    def seed(self, idx, seeds) -> None:
        """Key the streams ``idx`` from integer ``seeds`` (modulo 2**64); counters restart at 0."""
        idx = self._idx(idx)
        s = np.array([int(x) & 0xFFFFFFFFFFFFFFFF for x in np.asarray(seeds, dtype=object).reshape(-1)],
                     dtype=np.uint64)
        if len(s) != len(idx):
            raise ValueError(f"need one seed per stream: {len(idx)} streams, {len(s)} seeds")
        _seed_keys(s, self.keys, self.counters, idx)

    def uniform(self, idx, m: int) -> np.ndarray:
        """Uniform floats in [0, 1), [len(idx), m]; row j from stream idx[j]."""
        idx = self._idx(idx)
        out = np.empty((len(idx), int(m)))
        _uniform(self.keys, self.counters, idx, out)
        return out

    def normal(self, idx, m: int) -> np.ndarray:
        """Standard normal floats, [len(idx), m] (uses 2 * ceil(m / 2) uniforms per row)."""
        idx = self._idx(idx)
        out = np.empty((len(idx), int(m)))
        _normal(self.keys, self.counters, idx, out)
        return out


# ------------------------------------------------------------ placement --
def place_balls(streams: TableStreams, idx, B, box, pockets, min_dist, max_tries, out):
    """Rejection-sample ``B`` ball centres per table ``idx[j]`` into ``out[j]``
    (``physics.state.place_from_candidates``: candidates uniform in the box
    ``box`` = (lo_x, lo_y, hi_x, hi_y), two draws each from the table's stream, rejected inside a
    pocket capture circle or closer than ``min_dist`` to a ball already
    placed on that table). Each stream advances by two draws per candidate
    used, so a table's result does not depend on the other tables. Returns
    a bool per table: all ``B`` placed within ``max_tries`` candidates."""
    idx = np.ascontiguousarray(idx, dtype=np.int64)
    lo_x, lo_y, hi_x, hi_y = box
    n = len(idx)
    start = streams.counters[idx].copy()
    used = np.empty(n, dtype=np.int64)
    k = min(B + 2, max_tries)  # candidates per table in the first round: enough for most tables
    place_many(streams.uniform(idx, 2 * k).reshape(n, k, 2), B, lo_x, lo_y, hi_x, hi_y, pockets, min_dist,
               out, used)
    while not (used >= 0).all() and k < max_tries:  # the rest: again from their first draw, with more
        k = min(4 * k, max_tries)
        todo = np.nonzero(used < 0)[0]
        streams.counters[idx[todo]] = start[todo]
        sub = np.empty((len(todo), B, 2))
        got = np.empty(len(todo), dtype=np.int64)
        place_many(streams.uniform(idx[todo], 2 * k).reshape(len(todo), k, 2), B, lo_x, lo_y, hi_x, hi_y,
                   pockets, min_dist, sub, got)
        out[todo] = sub
        used[todo] = got
    ok = used >= 0
    streams.counters[idx] = start + (2 * np.where(ok, used, max_tries)).astype(np.uint64)
    return ok


# ------------------------------------------------------- vector envs --
def seed_vector_env(env, streams: TableStreams, seed) -> None:
    """What ``reset(seed=...)`` of a vector env over ``streams`` does with
    ``seed``: an int keys table k with ``seed + k`` (so table k reproduces a
    single env seeded ``seed + k``), a list gives one int per table; the
    first seed also seeds ``env.np_random``. ``None`` keys the streams from
    ``env.np_random`` on the first reset and continues them afterwards."""
    from gymnasium.error import Error
    from gymnasium.utils import seeding

    n = len(streams.keys)
    if seed is not None:
        seeds = list(seed) if isinstance(seed, (list, tuple, np.ndarray)) else [int(seed) + k for k in range(n)]
        if len(seeds) != n:
            raise ValueError(f"seed must be an int or a list of {n} ints, got {len(seeds)}")
        seeds = [int(s) for s in seeds]
        for s in seeds:
            if s < 0:
                raise Error(f"Seed must be greater or equal to zero, actual value: {s}")
        env._np_random, env._np_random_seed = seeding.np_random(seeds[0])
        streams.seed(np.arange(n), seeds)
    elif not env._seeded:
        streams.seed(np.arange(n), env.np_random.integers(2 ** 63, size=n))
    env._seeded = True
