"""The two solvers, compiled per effect set (numba closures over constants).

``make_solver(kind, effects_key, diagnostics)`` returns one compiled kernel
that simulates a batch of tables to rest, in parallel over tables (prange).
The effect flags are free variables of the closure, which numba freezes as
compile-time constants: the kernel's branches on them are pruned when it
compiles, and helpers receive them as constant arguments (folded where LLVM
inlines the helper), so a disabled effect's code never runs. Each variant is cached on disk (numba keys the cache on the closure's
values) and memoised in-process.

Event solver: exact event-driven simulation (Leckie & Greenspan 2006; the
scheme of pooltool): jump to the earliest of all ball-ball, ball-cushion,
ball-pocket and motion-transition times; after an event only the times of the
balls it changed are recomputed.

Step solver: the write-up's algorithm: fixed time step dt; within a step balls
move in straight lines, the earliest collision in the step is found from the
quadratic, balls are advanced to it and it is resolved, until the step is
used up; then felt friction updates the velocities for the step (clamped so
it never reverses a velocity).

Simultaneous ball-ball impacts (within SIMULTANEOUS_TIME) are resolved in both
orders and the two results averaged: the outcome is symmetric under swapping
the two impacts, conserves momentum exactly, and since kinetic energy is
convex in the velocities it cannot exceed the energy of either order.
"""
import hashlib
import math
import pathlib

import numba
import numpy as np

from . import constants as C
from ._jit import JIT, KERNEL_JIT
from .ball_ball import resolve_ball_ball, rest_contact
from .ball_cushion import resolve_cushion
from .detection import boundary_time, pair_time, pair_time_linear, sweep_path
from .vec import norm
from .motion import acceleration, apply_transition, classify, end_slide, energy, evolve, friction_step, transition_time

# Ball-ball events closer in time than this are one simultaneous impact:
# 1e-12 s is a femtometre of travel at 1 m/s.
SIMULTANEOUS_TIME = 1e-12
# Diagnostics: a ball counts as off the table if it is outside the rails by
# more than this and not within POCKET_REGION of a pocket centre.
OFF_TABLE_TOL = 1e-9
POCKET_REGION = 0.15

_cache = {}


def _source_tag() -> int:
    """Hash of the physics sources. Captured by every kernel closure, so it is
    part of numba's on-disk cache key: numba checks only the timestamp of a
    kernel's own file, and an edit to a helper module would otherwise leave a
    stale compiled kernel in the cache."""
    h = hashlib.sha256()
    for f in sorted(pathlib.Path(__file__).parent.glob("*.py")):
        h.update(f.read_bytes())
    return int.from_bytes(h.digest()[:7], "little")


SOURCE_TAG = _source_tag()


def make_solver(kind: str, effects_key: tuple, diagnostics: bool = False):
    key = (kind, effects_key, diagnostics)
    if key not in _cache:
        maker = _make_event if kind == "event" else _make_step
        _cache[key] = maker(*effects_key, diagnostics)
    return _cache[key]


# ----------------------------------------------------------------- shared --
@numba.njit(**JIT)
def _prepare(pos, vel, om, st, pocket, e, p, spin_on, slide_on, zspin_on):
    R = p[C.P_R]
    for i in range(pos.shape[1]):
        if pocket[e, i] >= 0:
            st[e, i] = C.POCKETED
            vel[e, i, 0] = 0.0; vel[e, i, 1] = 0.0
            om[e, i, 0] = 0.0; om[e, i, 1] = 0.0; om[e, i, 2] = 0.0
            continue
        if not zspin_on:
            om[e, i, 2] = 0.0
        classify(vel, om, st, e, i, R, spin_on)
        if not slide_on and st[e, i] == C.SLIDING:
            end_slide(vel, om, e, i, R)
            classify(vel, om, st, e, i, R, spin_on)


@numba.njit(**JIT)
def _after_impact(vel, om, st, e, i, p, spin_on, slide_on, zspin_on):
    R = p[C.P_R]
    if not zspin_on:
        om[e, i, 2] = 0.0
    classify(vel, om, st, e, i, R, spin_on)
    if not slide_on and st[e, i] == C.SLIDING:
        end_slide(vel, om, e, i, R)
        classify(vel, om, st, e, i, R, spin_on)


@numba.njit(**JIT)
def _pocket_ball(vel, om, st, pocket, e, i, k):
    pocket[e, i] = k
    st[e, i] = C.POCKETED
    vel[e, i, 0] = 0.0; vel[e, i, 1] = 0.0
    om[e, i, 0] = 0.0; om[e, i, 1] = 0.0; om[e, i, 2] = 0.0


@numba.njit(**JIT)
def _record(rec_n, rec_t, rec_kind, rec_ij, rec_state, pos, vel, om, st, e, t, kind, i, j):
    n = rec_n[e]
    if n >= rec_t.shape[1]:
        rec_n[e] = n + 1  # counts overflow; the wrapper reports it
        return
    rec_t[e, n] = t
    rec_kind[e, n] = kind
    rec_ij[e, n, 0] = i
    rec_ij[e, n, 1] = j
    for s in range(2):
        b = i if s == 0 else j
        # only ball-ball events name a second ball (else j is a cushion,
        # tip or pocket index, not a ball)
        if b < 0 or (s == 1 and kind != C.EV_BALL_BALL):
            continue
        rec_state[e, n, s, 0] = pos[e, b, 0]; rec_state[e, n, s, 1] = pos[e, b, 1]
        rec_state[e, n, s, 2] = vel[e, b, 0]; rec_state[e, n, s, 3] = vel[e, b, 1]
        rec_state[e, n, s, 4] = om[e, b, 0]; rec_state[e, n, s, 5] = om[e, b, 1]
        rec_state[e, n, s, 6] = om[e, b, 2]; rec_state[e, n, s, 7] = st[e, b]
    rec_n[e] = n + 1


@numba.njit(**JIT)
def _check_geometry(pos, st, e, p, width, length, pockets, diag):
    """Diagnostics: smallest pair gap (diag[e, 2]) and worst excursion off the
    table (diag[e, 3])."""
    R = p[C.P_R]
    B = pos.shape[1]
    for i in range(B):
        if st[e, i] == C.POCKETED:
            continue
        for j in range(i + 1, B):
            if st[e, j] == C.POCKETED:
                continue
            gap = math.hypot(pos[e, i, 0] - pos[e, j, 0], pos[e, i, 1] - pos[e, j, 1]) - 2.0 * R
            if gap < diag[e, 2]:
                diag[e, 2] = gap
        x, y = pos[e, i, 0], pos[e, i, 1]
        out = max(R - x, x - (width - R), R - y, y - (length - R), 0.0)
        if out > OFF_TABLE_TOL:
            near = False
            for k in range(pockets.shape[0]):
                if math.hypot(x - pockets[k, 0], y - pockets[k, 1]) < POCKET_REGION:
                    near = True
            if not near and out > diag[e, 3]:
                diag[e, 3] = out


@numba.njit(**JIT)
def _total_energy(vel, om, st, e, p):
    en = 0.0
    for i in range(vel.shape[1]):
        en += energy(vel, om, st, e, i, p)
    return en


@numba.njit(**JIT)
def _save(pos, vel, om, st, e, i, buf, k):
    buf[k, 0] = vel[e, i, 0]; buf[k, 1] = vel[e, i, 1]
    buf[k, 2] = om[e, i, 0]; buf[k, 3] = om[e, i, 1]; buf[k, 4] = om[e, i, 2]
    buf[k, 5] = st[e, i]


@numba.njit(**JIT)
def _load(vel, om, st, e, i, buf, k):
    vel[e, i, 0] = buf[k, 0]; vel[e, i, 1] = buf[k, 1]
    om[e, i, 0] = buf[k, 2]; om[e, i, 1] = buf[k, 3]; om[e, i, 2] = buf[k, 4]
    st[e, i] = np.int64(buf[k, 5])


@numba.njit(**JIT)
def _resolve_boundary(pos, vel, om, st, pocket, e, kind, a, b, p, norms, tips,
                      friction_on, spin_on, slide_on, zspin_on, diag_on, diag, out_cush):
    """Ball a meets boundary b (both solvers): drops into pocket b, or
    rebounds from cushion segment b or jaw tip b."""
    if kind == C.EV_POCKET:
        _pocket_ball(vel, om, st, pocket, e, a, b)
        return
    if kind == C.EV_CUSHION:
        nx, ny = norms[b, 0], norms[b, 1]
    else:  # the detector's own normal: ball centre minus jaw tip
        nx = pos[e, a, 0] - tips[b, 0]; ny = pos[e, a, 1] - tips[b, 1]
    e0 = energy(vel, om, st, e, a, p) if diag_on else 0.0
    resolve_cushion(vel, om, st, e, a, nx, ny, p, friction_on, spin_on)
    _after_impact(vel, om, st, e, a, p, spin_on, slide_on, zspin_on)
    if diag_on:
        diag[e, 0] = max(diag[e, 0], energy(vel, om, st, e, a, p) - e0)
    out_cush[e, a] += 1


MAX_SIMULTANEOUS = 4  # ball-ball impacts resolved as one simultaneous set


@numba.njit(**JIT)
def _refresh(pos, vel, om, st, tt, tb, bkind, bidx, tpair, paths, e, i, t, p, segs, norms, tips, pockets):
    """Recompute every event time that involves ball i (absolute times),
    and ball i's entry in ``paths``: its acceleration and the box its path
    sweeps until its next transition or boundary event. Both hold until
    that event refreshes the ball again, so pair checks read them instead
    of recomputing them for the other ball of every pair."""
    B = pos.shape[1]
    if st[e, i] == C.POCKETED:
        tt[e, i] = math.inf; tb[e, i] = math.inf
        for j in range(B):
            tpair[e, i, j] = math.inf; tpair[e, j, i] = math.inf
        return
    tt[e, i] = t + transition_time(vel, om, st, e, i, p)
    h = tt[e, i] - t
    ax, ay = acceleration(vel, om, st, e, i, p)
    tb_rel, k, idx = boundary_time(pos, vel, st, e, i, ax, ay, h, p, segs, norms, tips, pockets, False)
    tb[e, i] = t + tb_rel; bkind[e, i] = k; bidx[e, i] = idx
    # A pair needs looking at only until the first known event of either
    # ball (transition or boundary): that event refreshes the ball and so
    # recomputes the pair. Short horizons keep the broad phase tight.
    next_i = min(tt[e, i], tb[e, i])
    sweep_path(pos, vel, st, e, i, ax, ay, next_i - t, paths)
    for j in range(B):
        if j == i:
            continue
        hj = min(next_i, tt[e, j], tb[e, j]) - t
        tij = t + pair_time(pos, vel, st, paths, e, i, j, hj, p)
        tpair[e, i, j] = tij; tpair[e, j, i] = tij


@numba.njit(**JIT)
def _break_collapse(pos, vel, om, st, tt, tb, bkind, bidx, tpair, paths, e, t, p, segs, norms, tips, pockets,
                    stuck, rounds, spin_on):
    """Stop the translation and rolling of the slow balls of an inelastic
    collapse (constants.ZENO_EVENTS; the speed limit doubles with each
    earlier round at this instant) and recompute their events."""
    R = p[C.P_R]
    limit = C.ZENO_FREEZE_SPEED * 2.0 ** rounds
    for i in range(pos.shape[1]):
        if not stuck[i] or st[e, i] == C.POCKETED:
            continue
        contact = norm(vel[e, i, 0], vel[e, i, 1]) + R * norm(om[e, i, 0], om[e, i, 1])
        if contact < limit:
            vel[e, i, 0] = 0.0; vel[e, i, 1] = 0.0
            om[e, i, 0] = 0.0; om[e, i, 1] = 0.0
            classify(vel, om, st, e, i, R, spin_on)  # SPINNING or STATIONARY
    for i in range(pos.shape[1]):
        if stuck[i]:
            _refresh(pos, vel, om, st, tt, tb, bkind, bidx, tpair, paths, e, i, t, p, segs, norms, tips, pockets)


@numba.njit(**JIT)
def _impact_buffers():
    """Per-table scratch of a simultaneous impact set: pair ids, approach
    speeds, ball ids and two state copies (for the two resolution orders)."""
    return (np.empty(MAX_SIMULTANEOUS, dtype=np.int64), np.empty(MAX_SIMULTANEOUS, dtype=np.int64),
            np.empty(MAX_SIMULTANEOUS), np.empty(2 * MAX_SIMULTANEOUS, dtype=np.int64),
            np.empty((2 * MAX_SIMULTANEOUS, 6)), np.empty((2 * MAX_SIMULTANEOUS, 6)))


@numba.njit(**JIT)
def _balls_of(sim_i, sim_j, ns, balls):
    """Distinct balls of the impact set, into ``balls``; returns how many."""
    nb = 0
    for s in range(ns):
        for bb in (sim_i[s], sim_j[s]):
            seen = False
            for q in range(nb):
                if balls[q] == bb:
                    seen = True
            if not seen:
                balls[nb] = bb; nb += 1
    return nb


@numba.njit(**JIT)
def _impact_set(pos, vel, om, st, e, sim_i, sim_j, sim_w, ns, balls, nb, buf, buf2, p, friction_on, spin_on):
    """Impulses of a set of simultaneous ball-ball impacts (both solvers).
    One impact: resolved directly. Several: resolved in index order and in
    reverse order from the same state, and the two results averaged (see the
    module docstring). sim_w receives each impact's approach speed."""
    if ns == 1:
        sim_w[0] = resolve_ball_ball(pos, vel, om, st, e, sim_i[0], sim_j[0], p, friction_on, spin_on)
        return
    for q in range(nb):
        _save(pos, vel, om, st, e, balls[q], buf, q)
    for s in range(ns):
        sim_w[s] = resolve_ball_ball(pos, vel, om, st, e, sim_i[s], sim_j[s], p, friction_on, spin_on)
    for q in range(nb):
        _save(pos, vel, om, st, e, balls[q], buf2, q)
        _load(vel, om, st, e, balls[q], buf, q)
    for s in range(ns - 1, -1, -1):
        w2 = resolve_ball_ball(pos, vel, om, st, e, sim_i[s], sim_j[s], p, friction_on, spin_on)
        sim_w[s] = min(sim_w[s], w2)
    for q in range(nb):
        bq = balls[q]
        vel[e, bq, 0] = 0.5 * (vel[e, bq, 0] + buf2[q, 0])
        vel[e, bq, 1] = 0.5 * (vel[e, bq, 1] + buf2[q, 1])
        om[e, bq, 0] = 0.5 * (om[e, bq, 0] + buf2[q, 2])
        om[e, bq, 1] = 0.5 * (om[e, bq, 1] + buf2[q, 3])
        om[e, bq, 2] = 0.5 * (om[e, bq, 2] + buf2[q, 4])


@numba.njit(**JIT)
def _after_impact_set(pos, vel, om, st, e, sim_i, sim_j, sim_w, ns, balls, nb, p, spin_on, slide_on, zspin_on):
    """Resting contacts for impacts slower than ZENO_SPEED, then the new
    motion states of every ball of the set."""
    for s in range(ns):
        if sim_w[s] < C.ZENO_SPEED:
            rest_contact(pos, vel, om, st, e, sim_i[s], sim_j[s], p, spin_on)
    for q in range(nb):
        _after_impact(vel, om, st, e, balls[q], p, spin_on, slide_on, zspin_on)


@numba.njit(**JIT)
def _resolve_impact_set(pos, vel, om, st, e, t, sim_i, sim_j, sim_w, ns, balls, buf, buf2, p,
                        friction_on, spin_on, slide_on, zspin_on, diag_on, diag, out_first,
                        rec_on, rec_n, rec_t, rec_kind, rec_ij, rec_state):
    """Everything a set of simultaneous ball-ball impacts does, for both
    solvers: impulses, diagnostics of that impulse set (energy, momentum),
    resting contacts and new motion states, first contact, event log.
    Returns the number of balls involved (listed in ``balls``)."""
    nb = _balls_of(sim_i, sim_j, ns, balls)
    e0 = 0.0; px0 = 0.0; py0 = 0.0
    if diag_on:
        for q in range(nb):
            e0 += energy(vel, om, st, e, balls[q], p)
            px0 += vel[e, balls[q], 0]; py0 += vel[e, balls[q], 1]
    _impact_set(pos, vel, om, st, e, sim_i, sim_j, sim_w, ns, balls, nb, buf, buf2, p, friction_on, spin_on)
    if diag_on:
        e1 = 0.0; px1 = 0.0; py1 = 0.0
        for q in range(nb):
            e1 += energy(vel, om, st, e, balls[q], p)
            px1 += vel[e, balls[q], 0]; py1 += vel[e, balls[q], 1]
        diag[e, 0] = max(diag[e, 0], e1 - e0)
        diag[e, 1] = max(diag[e, 1], math.hypot(px1 - px0, py1 - py0) * p[C.P_M])
    _after_impact_set(pos, vel, om, st, e, sim_i, sim_j, sim_w, ns, balls, nb, p, spin_on, slide_on, zspin_on)
    for s in range(ns):
        i, j = sim_i[s], sim_j[s]
        if out_first[e] == -1 and (i == 0 or j == 0):
            out_first[e] = j if i == 0 else i
        if rec_on:
            _record(rec_n, rec_t, rec_kind, rec_ij, rec_state, pos, vel, om, st, e, t, C.EV_BALL_BALL, i, j)
    return nb


# ---------------------------------------------------------- event solver --
def _make_event(SPIN, SLIDE, ZSPIN, BALL_FRICTION, CUSHION_FRICTION, POCKETS, DIAG):
    TAG = SOURCE_TAG
    @numba.njit(**KERNEL_JIT, parallel=True)
    def run(pos, vel, om, pocket, p, segs, norms, tips, pockets, width, length,
            max_events, st, tt, tb, bkind, bidx, tpair, paths,
            out_time, out_nev, out_first, out_cush, out_trunc,
            rec_on, rec_n, rec_t, rec_kind, rec_ij, rec_state, diag):
        E, B = pos.shape[0], pos.shape[1]
        pk = pockets if POCKETS else pockets[:0]
        out_time[:] = 0.0 * TAG  # TAG keys the disk cache on the sources
        for e in numba.prange(E):
            _prepare(pos, vel, om, st, pocket, e, p, SPIN, SLIDE, ZSPIN)
            t = 0.0
            if rec_on:
                for i in range(B):
                    _record(rec_n, rec_t, rec_kind, rec_ij, rec_state, pos, vel, om, st, e, 0.0, C.EV_START, i, -1)
            for i in range(B):
                tpair[e, i, i] = math.inf
                _refresh(pos, vel, om, st, tt, tb, bkind, bidx, tpair, paths, e, i, 0.0, p, segs, norms, tips, pk)
            en_prev = 0.0
            if DIAG:
                diag[e, 0] = 0.0; diag[e, 1] = 0.0; diag[e, 2] = math.inf; diag[e, 3] = 0.0
                _check_geometry(pos, st, e, p, width, length, pockets, diag)
                en_prev = _total_energy(vel, om, st, e, p)
            out_first[e] = -1
            nev = 0
            sim_i, sim_j, sim_w, balls, buf, buf2 = _impact_buffers()
            stuck = np.zeros(B, dtype=np.bool_)  # balls of the events at the current instant
            n_stuck = 0  # events since time last advanced
            rounds = 0  # collapse rounds at the current instant
            while True:
                # earliest event; ties go to the first found (pairs, then
                # boundaries, then transitions), a fixed deterministic order
                tmin = math.inf; kind = -1; a = -1; b = -1
                for i in range(B):
                    for j in range(i + 1, B):
                        if tpair[e, i, j] < tmin:
                            tmin = tpair[e, i, j]; kind = C.EV_BALL_BALL; a = i; b = j
                for i in range(B):
                    if tb[e, i] < tmin:
                        tmin = tb[e, i]; kind = bkind[e, i]; a = i; b = bidx[e, i]
                for i in range(B):
                    if tt[e, i] < tmin:
                        tmin = tt[e, i]; kind = -2; a = i; b = -1
                if tmin == math.inf:
                    break
                if nev >= max_events:
                    out_trunc[e] = True
                    break
                if tmin < t:
                    tmin = t
                dt = tmin - t
                if dt > SIMULTANEOUS_TIME:
                    n_stuck = 0
                    rounds = 0
                    stuck[:] = False
                n_stuck += 1
                for i in range(B):
                    evolve(pos, vel, om, st, e, i, dt, p, ZSPIN, SPIN)
                t = tmin
                nev += 1
                if kind == C.EV_BALL_BALL:
                    # gather simultaneous impacts
                    ns = 0
                    for i in range(B):
                        for j in range(i + 1, B):
                            if tpair[e, i, j] <= tmin + SIMULTANEOUS_TIME and ns < MAX_SIMULTANEOUS:
                                sim_i[ns] = i; sim_j[ns] = j; ns += 1
                    nb = _resolve_impact_set(pos, vel, om, st, e, t, sim_i, sim_j, sim_w, ns, balls, buf, buf2, p,
                                             BALL_FRICTION, SPIN, SLIDE, ZSPIN, DIAG, diag, out_first,
                                             rec_on, rec_n, rec_t, rec_kind, rec_ij, rec_state)
                    for q in range(nb):
                        stuck[balls[q]] = True
                        _refresh(pos, vel, om, st, tt, tb, bkind, bidx, tpair, paths, e, balls[q], t, p, segs, norms, tips, pk)
                else:
                    if kind == -2:
                        kind = apply_transition(vel, om, st, e, a, p)
                        b = -1
                    else:
                        _resolve_boundary(pos, vel, om, st, pocket, e, kind, a, b, p, norms, tips,
                                          CUSHION_FRICTION, SPIN, SLIDE, ZSPIN, DIAG, diag, out_cush)
                    if rec_on:
                        _record(rec_n, rec_t, rec_kind, rec_ij, rec_state, pos, vel, om, st, e, t, kind, a, b)
                    stuck[a] = True
                    _refresh(pos, vel, om, st, tt, tb, bkind, bidx, tpair, paths, e, a, t, p, segs, norms, tips, pk)
                if n_stuck > C.ZENO_EVENTS:
                    _break_collapse(pos, vel, om, st, tt, tb, bkind, bidx, tpair, paths, e, t, p, segs, norms, tips,
                                    pk, stuck, rounds, SPIN)
                    n_stuck = 0
                    rounds += 1
                if DIAG:
                    _check_geometry(pos, st, e, p, width, length, pockets, diag)
                    # total energy may never rise from one event to the next
                    en = _total_energy(vel, om, st, e, p)
                    diag[e, 0] = max(diag[e, 0], en - en_prev)
                    en_prev = en
            out_time[e] = t
            out_nev[e] = nev

    return run


# ----------------------------------------------------------- step solver --
def _make_step(SPIN, SLIDE, ZSPIN, BALL_FRICTION, CUSHION_FRICTION, POCKETS, DIAG):
    TAG = SOURCE_TAG
    @numba.njit(**KERNEL_JIT, parallel=True)
    def run(pos, vel, om, pocket, p, segs, norms, tips, pockets, width, length,
            max_events, st, dt, max_steps,
            out_time, out_nev, out_first, out_cush, out_trunc,
            rec_on, rec_n, rec_t, rec_kind, rec_ij, rec_state, diag):
        E, B = pos.shape[0], pos.shape[1]
        pk = pockets if POCKETS else pockets[:0]
        out_time[:] = 0.0 * TAG  # TAG keys the disk cache on the sources
        for e in numba.prange(E):
            _prepare(pos, vel, om, st, pocket, e, p, SPIN, SLIDE, ZSPIN)
            if rec_on:
                for i in range(B):
                    _record(rec_n, rec_t, rec_kind, rec_ij, rec_state, pos, vel, om, st, e, 0.0, C.EV_START, i, -1)
            en_prev = 0.0
            if DIAG:
                diag[e, 0] = 0.0; diag[e, 1] = 0.0; diag[e, 2] = math.inf; diag[e, 3] = 0.0
                _check_geometry(pos, st, e, p, width, length, pk, diag)
                en_prev = _total_energy(vel, om, st, e, p)
            out_first[e] = -1
            t = 0.0
            nev = 0
            steps = 0
            sim_i, sim_j, sim_w, balls, buf, buf2 = _impact_buffers()
            while True:
                moving = False
                for i in range(B):
                    if st[e, i] != C.STATIONARY and st[e, i] != C.POCKETED:
                        moving = True
                if not moving:
                    break
                if steps >= max_steps or nev >= max_events:
                    out_trunc[e] = True
                    break
                steps += 1
                rem = dt
                while rem > 0.0 and nev < max_events:
                    tmin = math.inf; kind = -1; a = -1; b = -1
                    for i in range(B):
                        for j in range(i + 1, B):
                            tij = pair_time_linear(pos, vel, st, e, i, j, min(rem, tmin), p)
                            if tij < tmin:
                                tmin = tij; kind = C.EV_BALL_BALL; a = i; b = j
                    for i in range(B):
                        tbi, k, idx = boundary_time(pos, vel, st, e, i, 0.0, 0.0, min(rem, tmin), p,
                                                    segs, norms, tips, pk, True)
                        if tbi < tmin:
                            tmin = tbi; kind = k; a = i; b = idx
                    adv = min(tmin, rem)
                    for i in range(B):
                        if st[e, i] == C.SLIDING or st[e, i] == C.ROLLING:
                            pos[e, i, 0] += vel[e, i, 0] * adv
                            pos[e, i, 1] += vel[e, i, 1] * adv
                    rem -= adv
                    if kind < 0:
                        break
                    nev += 1
                    tev = t + (dt - rem)
                    if kind == C.EV_BALL_BALL:
                        # every pair touching and closing now is one simultaneous set,
                        # resolved by the event solver's policy
                        ns = 0
                        for i in range(B):
                            for j in range(i + 1, B):
                                if ns < MAX_SIMULTANEOUS and pair_time_linear(pos, vel, st, e, i, j, SIMULTANEOUS_TIME, p) <= SIMULTANEOUS_TIME:
                                    sim_i[ns] = i; sim_j[ns] = j; ns += 1
                        if ns == 0:  # rounding moved the pair off contact: resolve it alone
                            sim_i[0] = a; sim_j[0] = b; ns = 1
                        _resolve_impact_set(pos, vel, om, st, e, tev, sim_i, sim_j, sim_w, ns, balls, buf, buf2, p,
                                            BALL_FRICTION, SPIN, SLIDE, ZSPIN, DIAG, diag, out_first,
                                            rec_on, rec_n, rec_t, rec_kind, rec_ij, rec_state)
                    else:
                        _resolve_boundary(pos, vel, om, st, pocket, e, kind, a, b, p, norms, tips,
                                          CUSHION_FRICTION, SPIN, SLIDE, ZSPIN, DIAG, diag, out_cush)
                    if DIAG:
                        en = _total_energy(vel, om, st, e, p)
                        diag[e, 0] = max(diag[e, 0], en - en_prev)
                        en_prev = en
                    if rec_on and kind != C.EV_BALL_BALL:
                        _record(rec_n, rec_t, rec_kind, rec_ij, rec_state, pos, vel, om, st, e, tev, kind, a, b)
                for i in range(B):
                    if st[e, i] != C.STATIONARY and st[e, i] != C.POCKETED:
                        friction_step(vel, om, st, e, i, dt, p, ZSPIN, SPIN)
                t += dt
                if DIAG:
                    _check_geometry(pos, st, e, p, width, length, pk, diag)
                    en = _total_energy(vel, om, st, e, p)
                    diag[e, 0] = max(diag[e, 0], en - en_prev)
                    en_prev = en
            out_time[e] = t
            out_nev[e] = nev

    return run
