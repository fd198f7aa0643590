"""JIT settings in one place: every kernel is compiled with these flags.

Only the top-level solver kernels are cached on disk (KERNEL_JIT), keyed by
the source hash they capture (solvers.SOURCE_TAG). Helpers are NOT cached:
numba checks only a cached function's own file, so a helper cached in an
unchanged file (e.g. detection.pair_time) would keep the old code of a callee
edited in another file (e.g. roots.first_entry) and link it into every kernel
compiled afterwards. A cached kernel holds its callees' code, so helpers need
no cache of their own.
"""
import numba

JIT = dict(cache=False, nogil=True, fastmath=False, error_model="numpy")
KERNEL_JIT = dict(JIT, cache=True)
njit = numba.njit(**JIT)
