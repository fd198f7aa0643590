"""Compiled solver kernels, one per solver kind, effect set, model choice
and diagnostics flag, memoised in-process and cached on disk.

``make_kernel`` picks the model functions (``models.Models``), builds the
impact functions over them (``impacts.make_impacts``: numba calls the jitted
functions a closure captures) and compiles the solver's kernel, parallel over
tables. The effect flags are free variables of the closures, which numba
freezes as compile-time constants: branches on them are pruned when the
kernel compiles, so a disabled effect's code never runs. (Pockets need no
flag: without them the table's geometry has no pockets or jaws.)

In a process forked from one running numba's GNU OpenMP threads the
kernels are compiled serial instead (``forking``: GNU OpenMP does not
survive a fork), with the same results.

Kernels: ``event_solver.make_run`` -> ``run(balls, geo, p, scr, out, log,
max_events)``, ``step_solver.make_run`` -> ``run(balls, geo, p, out, log,
max_events, dt, max_steps)`` (structures of ``layout``).
"""
import hashlib
import pathlib

from . import ball_ball, cushion, event_solver, forking, step_solver
from ._jit import cached_kernel
from .effects import Effects
from .impacts import make_impacts
from .models import Models

KINDS = ("event", "step")
_kernels = {}


def _source_tag() -> str:
    """Hash of every physics source (sub-packages included). Part of each
    kernel's disk-cache key: numba checks only the timestamp of a kernel's
    own file, and an edit to a helper module would otherwise leave a stale
    compiled kernel in the cache."""
    root = pathlib.Path(__file__).parent
    h = hashlib.sha256()
    for f in sorted(root.rglob("*.py")):
        h.update(str(f.relative_to(root)).encode())
        h.update(f.read_bytes())
    return h.hexdigest()[:16]


SOURCE_TAG = _source_tag()


def _code_tag(*functions) -> str:
    """Hash of the code of the chosen model functions and of every jitted
    function they close over (a friction law inside the Coulomb model): a
    model registered from outside this package (e.g. by a test) is not
    covered by SOURCE_TAG."""
    h = hashlib.sha256()
    todo = list(functions)
    while todo:
        f = getattr(todo.pop(), "py_func", None)
        if f is None:
            continue
        codes = [f.__code__]
        while codes:
            code = codes.pop()
            h.update(code.co_code)
            for c in code.co_consts:
                if isinstance(c, type(code)):
                    codes.append(c)
                else:
                    h.update(repr(c).encode())
        todo += [c.cell_contents for c in f.__closure__ or ()]
    return h.hexdigest()[:16]


def make_kernel(kind: str, effects: Effects, models: Models, diagnostics: bool = False, contacts: bool = False):
    """The compiled kernel of solver ``kind`` ("event" or "step");
    ``contacts``: it notes the cue ball's contacts in order
    (``impacts.note_contact``, ``SimOptions.contacts``). Parallel over
    tables, or serial in a forked child that may not start threads
    (``forking.threads_usable``)."""
    if kind not in KINDS:
        raise ValueError(f"unknown solver {kind!r}; choose one of {KINDS}")
    n = effects.normalized()
    bb_name, cu_name = models.resolved(n)
    key = (kind, n.spin, n.sliding, n.vertical_spin, bb_name, cu_name, bool(diagnostics))
    if contacts:  # the default kernels keep their keys
        key = key + ("contacts",)
    if n.airborne:
        key = key + ("airborne",)
    serial = not forking.threads_usable()
    if serial:
        key = key + ("serial",)
    if key not in _kernels:
        bb = ball_ball.resolver(n.ball_friction, models.ball_ball_friction)
        cu = cushion.resolver(n.cushion_friction, models.cushion)
        impacts = make_impacts(n.spin, n.sliding, n.vertical_spin, bool(diagnostics), bb, cu, bool(contacts),
                               n.airborne)
        solver = event_solver if kind == "event" else step_solver
        run = solver.make_run(n.spin, n.vertical_spin, bool(diagnostics), impacts)
        tag = f"{SOURCE_TAG}/{'/'.join(map(str, key))}/{_code_tag(bb, cu)}"
        _kernels[key] = cached_kernel(run, tag, _label(key), parallel=not serial)
    return _kernels[key]


def _label(key: tuple) -> str:
    """A kernel's key in words, for the message of its compile."""
    kind, spin, sliding, vertical_spin, bb_name, cu_name, diagnostics = key[:7]
    effects = [name for name, on in (("spin", spin), ("sliding", sliding), ("vertical spin", vertical_spin)) if on]
    extras = [x for x in ("diagnostics" if diagnostics else "", *key[7:]) if x]
    return (f"the {kind} solver ({', '.join(effects) or 'no spin'}; ball-ball {bb_name}, cushion {cu_name}"
            f"{''.join('; ' + x for x in extras)})")


def call(kernel, *args):
    """Run ``kernel`` on ``args``, skipping numba's dispatch after the first
    call. ``simulate`` passes the kernel arguments of the same types on
    every call (C-contiguous float64 and int64 arrays in the same named
    structures), so each kernel has one compiled signature; the dispatcher
    would still work out the type of every array of every structure on every
    call, which costs a single-table call about a sixth of its time. The
    compiled entry point unboxes the arguments itself."""
    entry = _entries.get(kernel)
    if entry is None and not hasattr(kernel, "overloads"):  # NUMBA_DISABLE_JIT=1: a plain Python function
        kernel(*args)
        return
    if entry is None:
        kernel(*args)  # compiles or loads the kernel, and types the arguments once
        if len(kernel.overloads) != 1:
            raise RuntimeError(f"kernel {kernel.py_func.__qualname__} has {len(kernel.overloads)} signatures; "
                               "simulate must pass arguments of one type")
        _entries[kernel] = next(iter(kernel.overloads.values())).entry_point
        return
    entry(*args)


_entries = {}
