"""SB3's per-env info list, read off Gymnasium's vector info when asked.

A Gymnasium vector env reports one dict of arrays per step (each key with an
optional ``_key`` mask, possibly nested); stable-baselines3 wants a list of
``n`` per-env dicts. Building the ``n`` dicts at once (31 keys at 1,024
tables on the games) cost as much as the simulator: ``ndarray.tolist`` of
every key, then pickling the dicts from the env workers to the trainer
(docs/agents_benchmark.md, "Where the default's time goes"), while training
reads a handful of keys, most of them only on the tables whose episode ended.

``VecInfos`` is that list as a view: ``infos[i]`` is a mapping over row ``i``
of the arrays, converted to Python values (``.tolist()``) only when a key is
read, with the same keys and values the per-env dicts had (a masked key is
absent where its mask is False; a value that is not an array of ``n`` rows is
every env's). Writing to a row (``terminal_observation``,
``TimeLimit.truncated``) keeps the value in that row's own overlay: the other
keys stay unconverted.
``column(key)`` gives a key's values for every env as one array, for readers
that want them all. Pickled, it carries the arrays, not ``n`` dicts; the env
workers' lists join with ``VecInfos.concat``.
"""
from __future__ import annotations

from bisect import bisect_right
from collections.abc import Iterator, MutableMapping, Sequence

import numpy as np

_ABSENT = object()


def _row_value(info: dict, key: str, n: int, j: int):
    """Row ``j``'s value of ``info[key]`` (``n`` rows), or ``_ABSENT`` where it has none."""
    value = info.get(key, _ABSENT)
    if value is _ABSENT or key.startswith("_"):
        return _ABSENT
    mask = info.get("_" + key)
    if mask is not None and not mask[j]:
        return _ABSENT
    if isinstance(value, dict):
        return EnvInfo(value, n, j)
    if isinstance(value, np.ndarray) and value.ndim >= 1 and len(value) == n:
        return value[j].tolist()
    return value


class EnvInfo(MutableMapping):
    """Row ``j`` of a vector info of ``n`` rows, as SB3's per-env dict (module docstring).
    Writes and deletions go to the row's own overlay (the arrays are never
    written to), and a nested info read from the row is kept there, so that
    writes into it stay too; the first one registers the row with ``owner``,
    whose ``infos[i]`` then returns this same mapping."""

    __slots__ = ("_info", "_n", "_j", "_owner", "_i", "_over", "_gone")

    def __init__(self, info: dict, n: int, j: int, owner: "VecInfos | None" = None, i: int = 0):
        self._info, self._n, self._j, self._owner, self._i = info, n, j, owner, i
        self._over: dict | None = None   # keys written (and nested infos read) in this row
        self._gone: set | None = None    # keys deleted from this row

    def _keep(self) -> dict:
        if self._over is None:
            self._over, self._gone = {}, set()
            if self._owner is not None:
                self._owner._rows[self._i] = self
        return self._over

    def _value(self, key):
        if self._over is not None:
            if key in self._over:
                return self._over[key]
            if key in self._gone:
                return _ABSENT
        v = _row_value(self._info, key, self._n, self._j)
        if isinstance(v, EnvInfo):
            self._keep()[key] = v
        return v

    def __getitem__(self, key):
        v = self._value(key)
        if v is _ABSENT:
            raise KeyError(key)
        return v

    def get(self, key, default=None):
        if self._over is None and key not in self._info:  # the common read: a key no env has this step
            return default
        v = self._value(key)
        return default if v is _ABSENT else v

    def __contains__(self, key) -> bool:
        return self._value(key) is not _ABSENT

    def __iter__(self) -> Iterator[str]:
        over, gone = self._over or {}, self._gone or ()
        for k in self._info:
            if k not in over and k not in gone and _row_value(self._info, k, self._n, self._j) is not _ABSENT:
                yield k
        yield from list(over)

    def __len__(self) -> int:
        return sum(1 for _ in self)

    def __setitem__(self, key, value) -> None:
        self._keep()[key] = value
        self._gone.discard(key)

    def __delitem__(self, key) -> None:
        if self._value(key) is _ABSENT:
            raise KeyError(key)
        self._keep().pop(key, None)
        self._gone.add(key)

    def __repr__(self) -> str:
        return repr(dict(self.items()))


class VecInfos(Sequence):
    """The per-env infos of one step of ``n`` envs, over Gymnasium's vector info (module docstring)."""

    __slots__ = ("_blocks", "_starts", "_n", "_rows")

    def __init__(self, info: dict, n: int):
        self._blocks: list[tuple[dict, int]] = [(info, n)]
        self._starts = [0]
        self._n = n
        self._rows: dict[int, MutableMapping] = {}  # rows written to or replaced

    @classmethod
    def concat(cls, parts: Sequence["VecInfos"]) -> "VecInfos":
        """The lists of consecutive env ranges (the env workers' slices) as one list."""
        out = cls.__new__(cls)
        out._blocks, out._starts, out._rows, off = [], [], {}, 0
        for p in parts:
            out._blocks += p._blocks
            out._starts += [off + s for s in p._starts]
            out._rows.update({off + i: d for i, d in p._rows.items()})
            off += p._n
        out._n = off
        return out

    def __len__(self) -> int:
        return self._n

    def _locate(self, i: int) -> tuple[dict, int, int]:
        k = bisect_right(self._starts, i) - 1
        info, m = self._blocks[k]
        return info, m, i - self._starts[k]

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[k] for k in range(*i.indices(self._n))]
        i = int(i)
        if i < 0:
            i += self._n
        if not 0 <= i < self._n:
            raise IndexError(f"env {i} of {self._n}")
        row = self._rows.get(i)
        if row is not None:
            return row
        info, m, j = self._locate(i)
        return EnvInfo(info, m, j, self, i)

    def __iter__(self):
        rows = self._rows
        for (info, m), s in zip(self._blocks, self._starts):
            for j in range(m):
                row = rows.get(s + j)
                yield row if row is not None else EnvInfo(info, m, j, self, s + j)

    def __setitem__(self, i: int, row: dict) -> None:
        """Replace env ``i``'s info by ``row`` (a mapping, copied)."""
        i = int(i) + (self._n if int(i) < 0 else 0)
        if not 0 <= i < self._n:
            raise IndexError(f"env {i} of {self._n}")
        self._rows[i] = dict(row)

    def column(self, key: str) -> np.ndarray:
        """``key``'s values for every env, in env order (rows written to read from
        their dicts); KeyError when some env has no such key."""
        parts = []
        for info, m in self._blocks:
            value, mask = info.get(key, _ABSENT), info.get("_" + key)
            if (not isinstance(value, np.ndarray) or value.ndim < 1 or len(value) != m
                    or (mask is not None and not np.all(mask))):
                return np.asarray([self[i][key] for i in range(self._n)])
            parts.append(value)
        col = np.concatenate(parts) if len(parts) > 1 else np.array(parts[0], copy=True)
        for i, row in self._rows.items():
            col[i] = row[key]
        return col

    def __repr__(self) -> str:
        return f"VecInfos(n={self._n}, keys={sorted({k for b, _ in self._blocks for k in b if not k.startswith('_')})})"

