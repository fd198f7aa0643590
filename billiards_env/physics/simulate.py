"""Public entry point: simulate a batch of tables until every ball rests."""
from __future__ import annotations

import dataclasses
import numbers
import threading
from typing import NamedTuple

import numba
import numpy as np

from . import constants as C
from .effects import Effects
from .params import PhysicsParams
from .kernels import call, make_kernel
from .layout import Balls, EventScratch, Geometry, LogBuffers, OrderedOutputs, Outputs
from .models import Models
from .state import BallState
from .table import Table
from .validation import check_air, check_arrays, check_finite, check_placement

SOLVERS = ("event", "step")
RECORD_CAPACITY = 4096  # events kept per table when record=True
LOG_COLUMNS = 10  # a ball's state in the event log (EventLog.states)
# Bytes of per-table scratch a call holds at once: larger batches run in chunks of tables (results do
# not depend on the batch size), so 120,000 8-ball tables take ~64 MB of pair times, not ~245 MB.
MAX_SCRATCH_BYTES = 64 * 2 ** 20
# The event solver's scratch of calls up to this size is kept between calls (one set per thread: simulate
# may run in several threads at once) and reused, so the bots' many small previews do not allocate,
# clear and page in fresh buffers on every call; larger calls allocate their own.
KEEP_SCRATCH_BYTES = 8 * 2 ** 20
_kept = threading.local()
# ``Balls.air`` of the planar kernels, which never index it (one shared
# array: no allocation per call).
NO_AIR = np.zeros((0, 0, 2))


class SimOptions(NamedTuple):
    """The less common options of a ``simulate`` call (``simulate(...,
    options=SimOptions(max_events=100))``); until this structure they were
    ``simulate``'s keywords ``max_events`` and ``validate``.

    ``max_events``: events (step solver: contacts) a table may have; a table
    that reaches it stops there, with ``SimResult.truncated`` set.
    ``validate``: check the input state (array shapes, finite values, no
    ball overlapping another or off the table); ``False`` skips the checks
    for a caller whose states are already known to be valid.
    ``contacts``: keep the cue ball's first ``contacts`` contacts, balls and
    cushions, in the order they happen (``SimResult.contacts``; the carom
    rules read it); 0 (the default) keeps none, and the kernel then has none
    of that code (a separate compiled variant).
    ``inplace``: the kernel works in the input state's own arrays (when they
    are contiguous float64 / int64) instead of a copy, so ``SimResult.state``
    shares them; for a caller that hands over a state it has just made and
    does not read again (the envs' and the bots' struck states). Results are
    the same either way.

    A named tuple, not a frozen dataclass: callers that simulate one table
    at a time build one per call, and a tuple is built 5x faster (0.5 us
    against 2.5 us, ``python -m timeit``). ``simulate`` checks its fields."""

    max_events: int = C.MAX_EVENTS
    validate: bool = True
    contacts: int = 0
    inplace: bool = False


def _check_options(options) -> None:
    if not isinstance(options, SimOptions):
        raise TypeError(f"options must be a SimOptions, got {type(options).__name__}")
    m = options.max_events
    if isinstance(m, (bool, np.bool_)) or not isinstance(m, numbers.Integral) or m < 0:
        raise ValueError(f"SimOptions.max_events must be a non-negative integer, got {m!r}")
    if not isinstance(options.validate, (bool, np.bool_)):
        raise TypeError(f"SimOptions.validate must be True or False, got {options.validate!r}")
    k = options.contacts
    if isinstance(k, (bool, np.bool_)) or not isinstance(k, numbers.Integral) or k < 0:
        raise ValueError(f"SimOptions.contacts must be a non-negative integer (contacts kept), got {k!r}")
    if not isinstance(options.inplace, (bool, np.bool_)):
        raise TypeError(f"SimOptions.inplace must be True or False, got {options.inplace!r}")


DEFAULT_OPTIONS = SimOptions()


@dataclasses.dataclass(frozen=True, eq=False)
class EventLog:
    """Events of one table: ``time [N]``, ``kind [N]`` (constants.EV_*),
    ``balls [N, 2]`` (second id -1, or the cushion/tip/pocket index for
    boundary events) and ``states [N, 2, 10]``: for each involved ball after the
    event, (x, y, vx, vy, wx, wy, wz, motion state, h, vz): the last two, the
    height of its lowest point above the slate and its vertical velocity,
    are 0 but with ``Effects(airborne=True)``."""

    time: np.ndarray
    kind: np.ndarray
    balls: np.ndarray
    states: np.ndarray

    def __len__(self):
        return len(self.time)

    def kinds(self):
        return [C.EVENT_NAMES[k] for k in self.kind]


@dataclasses.dataclass(frozen=True, eq=False)
class SimResult:
    state: BallState
    time: np.ndarray           # [E] simulated time until every ball rests (s)
    n_events: np.ndarray       # [E]
    first_contact: np.ndarray  # [E] first ball the cue ball touched, -1 if none
    cushion_hits: np.ndarray   # [E, B]
    truncated: np.ndarray      # [E] True if the event or step cap was hit
    cushion_hits_after_contact: np.ndarray  # [E, B] cushion hits once the cue ball has touched a ball (the rules' "rail after contact")
    events: list | None = None  # [E] EventLog with record=True
    diagnostics: np.ndarray | None = None  # [E, 4]: max energy gain (J) of any impact or of the total from one event (step) to the next, max momentum error of a ball-ball impact (kg m/s), min gap (m), max off-table (m)
    contacts: np.ndarray | None = None  # [E, K, 2] with SimOptions(contacts=K): the cue ball's contacts in order, (constants.EV_BALL_BALL, other ball) or (EV_CUSHION / EV_JAW_TIP, segment / tip index); rows past n_contacts are -1
    n_contacts: np.ndarray | None = None  # [E] the cue ball's contacts in all (more than K: the rest were not kept)

    @property
    def pocketed(self) -> np.ndarray:
        return self.state.pocket >= 0


def kernel_geometry(table: Table, pockets: bool) -> Geometry:
    """The kernels' ``Geometry`` of ``table`` with or without its pockets,
    built once per table (cached on it, as ``Table.groups`` is), its arrays
    in the one dtype of the kernels' signature (``kernels.call``)."""
    cache = table.__dict__.setdefault("_kernel_geometry", {})
    if pockets not in cache:
        f64 = lambda a: np.ascontiguousarray(a, dtype=np.float64)  # noqa: E731
        i64 = lambda a: np.ascontiguousarray(a, dtype=np.int64)  # noqa: E731
        segs, norms, tips, pk = table.geometry(pockets)
        g = table.groups(pockets)
        cache[pockets] = Geometry(f64(segs), f64(norms), f64(tips), f64(pk), float(table.width), float(table.length),
                                  i64(g.rails), i64(g.free_tips), f64(g.near), i64(g.gsegs), i64(g.gtips))
    return cache[pockets]


def simulate(state: BallState, table: Table, params: PhysicsParams | None = None, solver: str = "event",
             dt: float | None = None, record: bool = False, effects: Effects | None = None, *,
             diagnostics: bool = False, models: Models | dict | None = None,
             options: SimOptions | None = None) -> SimResult:
    """Simulate every table of the batch until all balls rest.

    ``solver="event"`` (exact, event-driven) or ``"step"`` (fixed step ``dt``).
    ``effects`` selects the physics (default: all), ``models`` the model of
    each interaction (a ``Models`` or its dict; default: ``Models()``, see
    docs/models.md). ``record=True`` keeps
    each table's event log. ``diagnostics=True`` compiles a checking variant
    that reports per table the largest energy gain and momentum error of any
    impact, the smallest gap between balls and the largest excursion off the
    table. ``options`` (a ``SimOptions``) holds the less common options: the
    event cap and whether to validate the input. The input state is not
    modified (unless ``options.inplace``).

    Changed: the keywords ``max_events=n`` and ``validate=False`` are now
    ``options=SimOptions(max_events=n, validate=False)`` (same meaning and
    defaults), and ``diagnostics``, ``models`` and ``options`` are keywords
    only (no caller passed them by position); every other argument is as
    before.
    """
    if options is None:
        options = DEFAULT_OPTIONS
    elif options is not DEFAULT_OPTIONS:
        _check_options(options)
    max_events = options.max_events
    params = params or PhysicsParams.standard()
    effects = effects or Effects()
    models = Models.from_dict(models) if isinstance(models, dict) else (models or Models())
    if not isinstance(models, Models):
        raise TypeError(f"models must be a Models or a dict, got {type(models).__name__}")
    if solver not in SOLVERS:
        raise ValueError(f"unknown solver {solver!r}; choose one of {SOLVERS}")
    if solver == "step":
        if dt is None:
            raise ValueError("the step solver needs a time step: pass dt (s), e.g. dt=1e-4")
        if not (isinstance(dt, (int, float)) and np.isfinite(dt) and dt > 0):
            raise ValueError(f"dt must be a positive finite number of seconds, got {dt!r}")
    if not isinstance(state, BallState):
        raise TypeError(f"state must be a BallState, got {type(state).__name__}")
    if not isinstance(table, Table):
        raise TypeError(f"table must be a Table, got {type(table).__name__}")
    if not isinstance(params, PhysicsParams):
        raise TypeError(f"params must be a PhysicsParams, got {type(params).__name__}")
    if options.validate:
        check_arrays(state)
        check_finite(state)
        check_air(state, effects.airborne)
        check_placement(state, table, params, effects.pockets)

    s = state if options.inplace else state.copy()
    air = None
    if effects.airborne:  # a ball's height and vertical velocity: only the airborne kernels read them
        air = np.ascontiguousarray(s.vertical(), dtype=np.float64)
    s = BallState(np.ascontiguousarray(s.pos, dtype=np.float64), np.ascontiguousarray(s.vel, dtype=np.float64),
                  np.ascontiguousarray(s.omega, dtype=np.float64), np.ascontiguousarray(s.pocket, dtype=np.int64),
                  air)
    if (s.pos.ndim, s.vel.ndim, s.omega.ndim, s.pocket.ndim) != (3, 3, 3, 2):  # the kernels' one signature
        raise ValueError("state arrays must be pos and vel [E, B, 2], omega [E, B, 3] and pocket [E, B], got "
                         f"{s.pos.shape}, {s.vel.shape}, {s.omega.shape} and {s.pocket.shape}")
    E, B = s.pos.shape[:2]
    n_contacts = int(options.contacts)
    geo, p = kernel_geometry(table, effects.pockets), params.as_array()
    kernel = make_kernel(solver, effects, models, diagnostics, n_contacts > 0)
    flags = (int(max_events), bool(diagnostics), n_contacts)
    if not record and E * B * (B + 12) * 8 <= MAX_SCRATCH_BYTES:  # the common case: one call (chunk_rows' count)
        return _simulate_chunk(s, geo, p, kernel, solver, dt, False, flags)
    run = (geo, p, kernel, solver, dt, bool(record), flags)
    rows = chunk_rows(B, record)
    parts = [_simulate_chunk(s.take(slice(e0, min(E, e0 + rows))), *run) for e0 in range(0, E, rows)]
    return _concatenate(parts)


def chunk_rows(n_balls: int, record: bool) -> int:
    """Tables per kernel call: the scratch of a chunk stays under ``MAX_SCRATCH_BYTES``."""
    per_table = 8 * (n_balls * n_balls + 12 * n_balls) + (RECORD_CAPACITY * 8 * (4 + 2 * LOG_COLUMNS) if record else 0)
    return max(1, MAX_SCRATCH_BYTES // per_table)


def _concatenate(parts: list) -> SimResult:
    cat = np.concatenate
    st = BallState.stack([r.state for r in parts])
    events = None if parts[0].events is None else [e for r in parts for e in r.events]
    diag = None if parts[0].diagnostics is None else cat([r.diagnostics for r in parts])
    order = None if parts[0].contacts is None else cat([r.contacts for r in parts])
    norder = None if parts[0].n_contacts is None else cat([r.n_contacts for r in parts])
    return SimResult(st, cat([r.time for r in parts]), cat([r.n_events for r in parts]),
                     cat([r.first_contact for r in parts]), cat([r.cushion_hits for r in parts]),
                     cat([r.truncated for r in parts]), cat([r.cushion_hits_after_contact for r in parts]), events, diag,
                     order, norder)


def _simulate_chunk(s: BallState, geo: Geometry, p: np.ndarray, kernel, solver: str, dt, record: bool,
                    flags: tuple) -> SimResult:
    """One kernel call over the tables of ``s`` (contiguous float64 / int64 arrays, modified in place);
    ``flags``: (max_events, diagnostics, contacts kept)."""
    max_events, diagnostics, n_contacts = flags
    E, B = s.pos.shape[:2]
    balls = Balls(s.pos, s.vel, s.omega, np.zeros((E, B), dtype=np.int64), s.pocket,
                  NO_AIR if s.air is None else s.air)
    out = dict(time=np.zeros(E), nev=np.zeros(E, dtype=np.int64), first=np.full(E, -1, dtype=np.int64),
               cush=np.zeros((E, B), dtype=np.int64), cush_after=np.zeros((E, B), dtype=np.int64),
               trunc=np.zeros(E, dtype=np.bool_), diag=np.zeros((E, 4)))
    out = (OrderedOutputs(**out, order=np.full((E, n_contacts, 2), -1, dtype=np.int64),
                          norder=np.zeros(E, dtype=np.int64))
           if n_contacts else Outputs(**out))
    cap = RECORD_CAPACITY if record else 1
    rows = E if record else 1
    log = LogBuffers(on=bool(record), n=np.zeros(E, dtype=np.int64), t=np.zeros((rows, cap)),
                     kind=np.zeros((rows, cap), dtype=np.int64), ij=np.zeros((rows, cap, 2), dtype=np.int64),
                     state=np.zeros((rows, cap, 2, LOG_COLUMNS)))
    # Waking worker threads costs more than a small batch takes: use no more
    # threads than tables (results do not depend on the thread count).
    threads = numba.get_num_threads()
    if threads > E:
        numba.set_num_threads(E)
    try:
        if solver == "event":
            call(kernel, balls, geo, p, _event_scratch(E, B), out, log, int(max_events))
        else:
            call(kernel, balls, geo, p, out, log, int(max_events), float(dt), int(C.MAX_STEPS))
    finally:
        if threads > E:
            numba.set_num_threads(threads)

    events = None
    if record:
        if np.any(log.n > cap):
            raise RuntimeError(f"event log overflow: a table had {log.n.max()} events, more than the "
                               f"record capacity {cap}")
        events = [EventLog(log.t[e, :log.n[e]].copy(), log.kind[e, :log.n[e]].copy(),
                           log.ij[e, :log.n[e]].copy(), log.state[e, :log.n[e]].copy()) for e in range(E)]
    return SimResult(s, out.time, out.nev, out.first, out.cush, out.trunc, out.cush_after, events,
                     out.diag if diagnostics else None, out.order if n_contacts else None,
                     out.norder if n_contacts else None)


def _event_scratch(E: int, B: int) -> EventScratch:
    """The event solver's scratch for E tables of B balls: tt, tb and paths
    zeroed (the first refresh pass reads them as zeros before every ball has
    been refreshed); the rest is written for every ball by that pass before
    anything reads it, so it is not cleared (tpair is the big one: E x B x B).
    Rows of the thread's kept buffers (``KEEP_SCRATCH_BYTES``) when it fits;
    the rows of the last size asked for are kept too."""
    kept = getattr(_kept, "event", None)
    if kept is None or kept.tt.shape[1] != B or kept.tt.shape[0] < E:
        n = E if kept is None or kept.tt.shape[1] != B else max(E, kept.tt.shape[0])
        kept = EventScratch(tt=np.empty((n, B)), tb=np.empty((n, B)), bkind=np.empty((n, B), dtype=np.int64),
                            bidx=np.empty((n, B), dtype=np.int64), tpair=np.empty((n, B, B)),
                            paths=np.empty((n, B, 6)), tlast=np.empty((n, B)))
        if n * B * (B + 11) * 8 > KEEP_SCRATCH_BYTES:
            return _cleared(kept)  # too big to keep: this call's own
        _kept.event = _kept.rows = kept
    if _kept.rows.tt.shape[0] != E:
        _kept.rows = EventScratch(*(a[:E] for a in kept))
    return _cleared(_kept.rows)


def _cleared(scr: EventScratch) -> EventScratch:
    scr.tt.fill(0.0)
    scr.tb.fill(0.0)
    scr.paths.fill(0.0)
    return scr


def set_num_threads(n: int) -> None:
    """Threads numba uses for the batch loop (results do not depend on it)."""
    numba.set_num_threads(int(n))
