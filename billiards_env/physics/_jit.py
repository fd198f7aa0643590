"""JIT settings in one place: every kernel is compiled with these flags."""
import numba

JIT = dict(cache=True, nogil=True, fastmath=False, error_model="numpy")
njit = numba.njit(**JIT)
