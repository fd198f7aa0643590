"""JIT settings in one place: every kernel is compiled with these flags.

Only the top-level solver kernels are cached on disk (``cached_kernel``),
under a tag that names the physics sources' hash and the variant (effects,
models, diagnostics). Helpers are NOT cached: numba checks only a cached
function's own file, so a helper cached in an unchanged file (e.g.
detection.pair_time) would keep the old code of a callee edited in another
file (e.g. roots.first_entry) and link it into every kernel compiled
afterwards. A cached kernel holds its callees' code, so helpers need no
cache of their own.

A kernel compiled rather than loaded from the disk cache says so once, on
the logger ``billiards_env.physics.compile`` at WARNING level (so it shows
without any logging set up): a compile takes 20-160 s and would otherwise
look like a hang. A warm cache is silent.
"""
import hashlib
import logging
import re

import numba
from numba.core import types
from numba.core.caching import FunctionCache
from numba.core.registry import CPUDispatcher

JIT = dict(cache=False, nogil=True, fastmath=False, error_model="numpy")


def _unliteral_int(ty):
    return types.unliteral(ty) if isinstance(ty, types.IntegerLiteral) else ty


class _HelperDispatcher(CPUDispatcher):
    """numba's dispatcher, compiling a helper for plain integers where a
    caller passes an integer constant. Type inference resolves a call as
    soon as its arguments have a type, and a variable first assigned a
    constant (``b = -1``, ``rounds = 0``) is at first typed as that literal:
    the callee was compiled once for the literal and once more for int64
    when the caller's type inference widened the variable, and so were the
    callees it passes it on to (16 helpers of the event kernel, 17 extra
    compilations: docs/performance.md, cold start). Boolean literals (the
    effect flags) stay: branches on them are pruned."""

    def get_call_template(self, args, kws):
        return super().get_call_template(tuple(map(_unliteral_int, args)),
                                         {k: _unliteral_int(v) for k, v in kws.items()})


def _helper_jit(options):
    """``numba.njit(**options)`` compiling with ``_HelperDispatcher``
    (never cached: see above)."""
    targetoptions = {k: v for k, v in options.items() if k != "cache"}
    targetoptions["nopython"] = True

    def decorate(function):
        if numba.config.DISABLE_JIT:
            return function
        return _HelperDispatcher(py_func=function, locals={}, targetoptions=dict(targetoptions))
    return decorate


# Helpers are compiled without numba's runtime (NRT): they allocate nothing,
# and with it every array they read out of a structure or receive is
# reference-counted by an atomic call at entry and exit, which cost a small
# scene up to a third of its time. The few functions that allocate (the
# kernels' prange loop, layout.impact_scratch) keep it: ``njit_alloc``.
HELPER_JIT = dict(JIT, _nrt=False)
njit = _helper_jit(HELPER_JIT)
njit_alloc = numba.njit(**JIT)
# Inlined into the caller at numba's level: for a helper of the step loop,
# which runs every few nanoseconds, a call that passes the named structures
# (a few dozen machine words each) costs as much as the work.
njit_inline = numba.njit(**HELPER_JIT, inline="always")


def name_of(function) -> str:
    """Module-qualified name of a jitted (or plain) function."""
    f = getattr(function, "py_func", function)
    return f"{f.__module__}.{f.__qualname__}"


def variant_njit(*choices):
    """``njit`` for a function a factory builds per variant (effect flags,
    models): its name gets a tag of ``choices``. numba names a compiled
    function by its qualified name and a per-process counter, and links the
    functions of a kernel loaded from the disk cache as one-definition
    symbols: two cached variants of one closure can get the same name in
    different processes, and once both are loaded, one kernel would run the
    other's code. The tag keeps the names apart."""
    tag = hashlib.sha256(repr(choices).encode()).hexdigest()[:12]

    def decorate(function):
        function.__qualname__ = f"{re.sub(r'[^0-9A-Za-z_]', '_', function.__qualname__)}_{tag}"
        return njit(function)
    return decorate


COMPILE_LOG = logging.getLogger("billiards_env.physics.compile")


class _TaggedCache(FunctionCache):
    """numba's on-disk function cache, keyed on a tag instead of the
    closure's variables. numba keys a closure's cache entry on a pickle of
    its captured values; a captured jitted function pickles with a random
    per-process id, so a kernel that closes over its model functions would
    never find its cache entry again. The tag names everything the kernel's
    code depends on (the sources' hash and the variant).

    numba asks the cache first (``load_overload``) and compiles when it
    finds nothing: that miss is announced, once per kernel, as ``label``."""

    def __init__(self, py_func, tag: str, label: str):
        super().__init__(py_func)
        self._tag = tag
        self._label = label
        self._announced = False

    def load_overload(self, sig, target_context):
        found = super().load_overload(sig, target_context)
        if found is None and not self._announced:
            self._announced = True
            COMPILE_LOG.warning("billiards_env: compiling the simulator's kernel for %s (first use only, "
                                "20-160 s; cached on disk afterwards) ...", self._label)
        return found

    def _index_key(self, sig, codegen):
        digest = lambda b: hashlib.sha256(b).hexdigest()
        return (sig, codegen.magic_tuple(),
                (digest(self._py_func.__code__.co_code), digest(self._tag.encode())))


def cached_kernel(py_func, tag: str, label: str, **options):
    """Compile ``py_func`` with the JIT flags and ``options`` (e.g.
    parallel=True), cached on disk under ``tag`` (its name tagged as in
    ``variant_njit``); ``label`` names it in the message of a compile."""
    py_func.__qualname__ = f"{re.sub(r'[^0-9A-Za-z_]', '_', py_func.__qualname__)}_{hashlib.sha256(tag.encode()).hexdigest()[:12]}"
    kernel = numba.njit(**JIT, **options)(py_func)
    kernel._cache = _TaggedCache(py_func, tag, label)  # what njit(cache=True) sets, with our key
    return kernel
