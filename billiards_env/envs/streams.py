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

The placement and respot kernels of the environments live here too: numba's
disk cache checks only a cached function's own file, so a kernel cached in
another file would keep stale code of the stream functions it calls.
"""
from __future__ import annotations

import math

import numba
import numpy as np

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


# ----------------------------------------------------- placement kernels --
@_jit
def _in_pocket(x, y, pockets):
    """True if (x, y) lies in a pocket capture circle (squared distance <= r**2)."""
    for p in range(pockets.shape[0]):
        dx, dy = x - pockets[p, 0], y - pockets[p, 1]
        if dx * dx + dy * dy <= pockets[p, 2] * pockets[p, 2]:
            return True
    return False


@_jit
def place_balls(keys, counters, idx, B, lo_x, lo_y, hi_x, hi_y, pockets, min_dist, max_tries, out):
    """Rejection-sample ``B`` ball centres per table ``idx[j]`` into ``out[j]``.

    Candidates are uniform in the box [lo, hi] (two draws each, from the
    table's stream); a candidate is rejected inside a pocket capture circle
    (squared distance <= r**2) or closer than ``min_dist`` to a ball already
    placed on that table. Returns a bool per table: all ``B`` placed within
    ``max_tries`` candidates."""
    n = len(idx)
    ok = np.ones(n, dtype=np.bool_)
    d2min = min_dist * min_dist
    for j in range(n):
        k = idx[j]
        key, c = keys[k], counters[k]
        placed = 0
        tries = 0
        while placed < B:
            if tries >= max_tries:
                ok[j] = False
                break
            tries += 1
            x = lo_x + (hi_x - lo_x) * _next_uniform(key, c + _ONE)
            y = lo_y + (hi_y - lo_y) * _next_uniform(key, c + _ONE + _ONE)
            c += _ONE + _ONE
            good = not _in_pocket(x, y, pockets)
            if good:
                for q in range(placed):
                    dx, dy = x - out[j, q, 0], y - out[j, q, 1]
                    if dx * dx + dy * dy < d2min:
                        good = False
                        break
            if good:
                out[j, placed, 0] = x
                out[j, placed, 1] = y
                placed += 1
        counters[k] = c
    return ok


@_jit
def _spot_free(x, y, pos, on, width, length, R, pockets, min_dist):
    edge = R + 1e-4
    if x < edge or x > width - edge or y < edge or y > length - edge:
        return False
    if _in_pocket(x, y, pockets):
        return False
    for q in range(pos.shape[0]):
        if on[q]:
            dx, dy = x - pos[q, 0], y - pos[q, 1]
            if math.sqrt(dx * dx + dy * dy) < min_dist:
                return False
    return True


@_jit
def free_spot(pos, on, px, py, dx, dy, width, length, R, pockets):
    """First free point in the respot search order: the preferred spot
    (px, py); then +-k steps along the unit direction (dx, dy), k = 1..59; then
    sideways offsets j = 1..19 steps (both sides) each walked k = 0..29 steps
    along (dx, dy). Step 2R + 1e-3. Free: inside the rectangle inset by
    R + 1e-4, outside every pocket capture circle, and at least 2R + 1e-6
    from every ball with ``on`` set. Returns (x, y, found)."""
    step = 2 * R + 1e-3
    md = 2 * R + 1e-6
    if _spot_free(px, py, pos, on, width, length, R, pockets, md):
        return px, py, True
    for k in range(1, 60):
        for s in (1.0, -1.0):
            x, y = px + s * k * step * dx, py + s * k * step * dy
            if _spot_free(x, y, pos, on, width, length, R, pockets, md):
                return x, y, True
    qx, qy = -dy, dx
    for j in range(1, 20):
        for k in range(0, 30):
            for s in (1.0, -1.0):
                x = px + s * j * step * qx + k * step * dx
                y = py + s * j * step * qy + k * step * dy
                if _spot_free(x, y, pos, on, width, length, R, pockets, md):
                    return x, y, True
    return px, py, False
