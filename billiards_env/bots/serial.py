"""A decision on a few tables runs on one thread (``serial``): the same plans at about half the CPU time.

The simulator's kernels spread a batch of tables over numba's threads (``physics.simulate``) and numpy's matrix
products spread over OpenBLAS's. After each parallel region the pools' workers spin, waiting for the next one
(libgomp's and OpenBLAS's busy wait), so a decision on one table, tens of small batched calls a few hundred
microseconds apart, keeps the second core spinning from its first call to its last: measured on the 2-core machine
(``scripts/lookahead_cost.py --single``), champion's one-table decision took 39 ms of CPU in 19 ms of wall time,
exit-fast's 5.4 ms in 2.3. On one thread they take 25 and 2.4 ms of CPU, at a somewhat longer wall time (25 ms for
champion). Many tables at once (matches, training) keep both threads: there the second core does work.

The plans do not depend on the thread count: each table is simulated by one thread start to end, and a matrix
product's entries are summed in the same order whichever thread computes them (``tests/bots/test_serial.py``
checks the players' plans both ways).
"""
from __future__ import annotations

import contextlib
import ctypes
import functools
import glob
import os

import numba
import numpy as np

SERIAL_TABLES = 4    # decisions on at most this many tables run on one thread

_BLAS: list = []     # [(set, get)] of numpy's bundled OpenBLAS, or [None]: found on first use


def blas_threads():
    """(set, get) of the thread count of the OpenBLAS numpy bundles (``scipy_openblas``), or None if this
    numpy has none (another BLAS: its threads are left alone)."""
    if not _BLAS:
        found = None
        for path in sorted(glob.glob(os.path.join(os.path.dirname(np.__file__), os.pardir, "numpy.libs",
                                                  "*openblas*"))):
            try:
                lib = ctypes.CDLL(path)
            except OSError:
                continue
            for stem in ("scipy_openblas_", "openblas_"):
                for tail in ("num_threads64_", "num_threads"):
                    s, g = getattr(lib, f"{stem}set_{tail}", None), getattr(lib, f"{stem}get_{tail}", None)
                    if s is not None and g is not None and found is None:
                        s.argtypes, s.restype, g.restype = [ctypes.c_int], None, ctypes.c_int
                        found = (s, g)
        _BLAS.append(found)
    return _BLAS[0]


@contextlib.contextmanager
def serial(n_tables: int):
    """Within: numba's and OpenBLAS's thread counts 1 if ``n_tables`` <= ``SERIAL_TABLES`` (restored after)."""
    if n_tables > SERIAL_TABLES:
        yield
        return
    threads = numba.get_num_threads()
    blas = blas_threads()
    nb = blas[1]() if blas is not None else 1
    numba.set_num_threads(1)
    if nb > 1:
        blas[0](1)
    try:
        yield
    finally:
        numba.set_num_threads(threads)
        if nb > 1:
            blas[0](nb)


def serial_act(act):
    """A bot's ``act(view)`` run within ``serial(view.n)``."""
    @functools.wraps(act)
    def wrapped(self, view):
        with serial(view.n):
            return act(self, view)
    return wrapped
