"""Event solver: exact event-driven simulation (Leckie & Greenspan 2006; the
scheme of pooltool): jump to the earliest of all ball-ball, ball-cushion,
ball-pocket and motion-transition times; after an event only the times of the
balls it changed are recomputed.

Evolution is lazy: a ball's state in ``Balls`` refers to the time of its last
event (``EventScratch.tlast``); an event first brings the balls it involves
to the event time, pair checks shift the other ball's quadratic path to now
(``detection.pair_time``), and every ball is brought to the final time at the
end. An event costs work in proportion to the balls it touches, not to all
balls. (With diagnostics on, every ball is brought to every event's time:
they check the whole table.)

``make_run`` returns the kernel's Python function for one effect set and
impact functions (``impacts.make_impacts``); ``kernels`` compiles it,
parallel over tables (prange).
"""
import math

import numba
import numpy as np

from . import airborne
from . import constants as C
from . import diagnostics, event_log
from ._jit import njit, njit_inline, variant_njit
from .ball_ball import flight
from .cushion import rail
from .detection import boundary_time, pair_time, paths_apart, sweep_path
from .layout import ChunkScratch, impact_scratch
from .motion import acceleration, apply_transition, classify, evolve, transition_time
from .vec import norm


# Most tables a worker thread simulates with one scratch (prange over
# chunks): enough to amortise the scratch's allocation, few enough to keep
# the threads balanced (``run`` uses smaller chunks for small batches).
TABLES_PER_CHUNK = 8
# Smaller chunks for small batches: at least this many, 4 per thread on a
# 4-core machine, so a batch of a few dozen tables still spreads over them.
MIN_CHUNKS = 16


@njit_inline
def refresh(balls, scr, geo, e, i, t, p, air_on):
    """Recompute every event time that involves ball i (absolute times),
    and ball i's entry in ``scr.paths``: its acceleration and the box its
    path sweeps until its next transition or boundary event. Both hold until
    that event refreshes the ball again, so pair checks read them instead
    of recomputing them for the other ball of every pair. With ``air_on``
    (a compile-time constant) a ball in flight has its landing as its
    transition, ``cushion.rail``'s boundaries, and its pairs are checked in
    3D (``ball_ball.flight``).

    Inlined at its one call site, the event loop: a call passes the named
    structures (~200 machine words), more than a pair check costs; an
    inlined copy is type-inferred and optimised again, so one call site
    only (docs/performance.md, cold start)."""
    pos, vel, om, st = balls.pos, balls.vel, balls.om, balls.st
    tt, tb, tpair, paths, tlast = scr.tt, scr.tb, scr.tpair, scr.paths, scr.tlast
    B = pos.shape[1]
    if st[e, i] == C.POCKETED:
        tt[e, i] = math.inf; tb[e, i] = math.inf
        for j in range(B):
            tpair[e, i, j] = math.inf; tpair[e, j, i] = math.inf
        return
    if air_on and st[e, i] == C.AIRBORNE:
        tt[e, i] = t + airborne.drop_time(balls.air[e, i, 0], balls.air[e, i, 1], p[C.P_G])
        h = tt[e, i] - t
        ax, ay = 0.0, 0.0
        tb_rel, k, idx = rail.boundary_time(balls, e, i, h, p, geo)
    else:
        tt[e, i] = t + transition_time(vel, om, st, e, i, p)
        h = tt[e, i] - t
        ax, ay = acceleration(vel, om, st, e, i, p)
        tb_rel, k, idx = boundary_time(balls, e, i, ax, ay, h, p, geo, False)
    tb[e, i] = t + tb_rel; scr.bkind[e, i] = k; scr.bidx[e, i] = idx
    # A pair needs looking at only until the first known event of either
    # ball (transition or boundary): that event refreshes the ball and so
    # recomputes the pair. Short horizons keep the broad phase tight.
    next_i = min(tt[e, i], tb[e, i])
    sweep_path(pos, vel, st, e, i, ax, ay, next_i - t, paths)
    for j in range(B):
        if j == i:
            continue
        hj = min(next_i, tt[e, j], tb[e, j]) - t
        if air_on and (st[e, i] == C.AIRBORNE or st[e, j] == C.AIRBORNE):
            # a ball meeting the slate now (its landing: the earliest event
            # of this instant's) has its pairs checked once it has bounced
            if (st[e, j] == C.POCKETED or airborne.landing_now(balls, e, i, tt[e, i], t)
                    or airborne.landing_now(balls, e, j, tt[e, j], t)
                    or paths_apart(paths, e, i, j, 2.0 * p[C.P_R])):
                tij = math.inf
            else:
                acc = (paths[e, i, 0], paths[e, i, 1], paths[e, j, 0], paths[e, j, 1])
                tij = t + flight.contact_time(balls, e, i, j, acc, hj, p, t - tlast[e, j])
        else:
            tij = t + pair_time(pos, vel, st, paths, e, i, j, hj, p, t - tlast[e, j])
        tpair[e, i, j] = tij; tpair[e, j, i] = tij


@njit
def break_collapse(balls, e, p, stuck, rounds, spin_on):
    """Stop the translation and rolling of the slow balls of an inelastic
    collapse (constants.ZENO_EVENTS; the speed limit doubles with each
    earlier round at this instant). The stuck balls' states are at the
    current time (``catch_up``); the caller recomputes their events."""
    vel, om, st = balls.vel, balls.om, balls.st
    R = p[C.P_R]
    limit = C.ZENO_FREEZE_SPEED * 2.0 ** rounds
    for i in range(vel.shape[1]):
        if not stuck[i] or st[e, i] == C.POCKETED or st[e, i] == C.AIRBORNE:
            continue
        contact = norm(vel[e, i, 0], vel[e, i, 1]) + R * norm(om[e, i, 0], om[e, i, 1])
        if contact < limit:
            vel[e, i, 0] = 0.0; vel[e, i, 1] = 0.0
            om[e, i, 0] = 0.0; om[e, i, 1] = 0.0
            classify(vel, om, st, e, i, R, spin_on)  # SPINNING or STATIONARY


@njit_inline
def catch_up(balls, tlast, e, i, t, p, zspin_on, spin_on, air_on):
    """Bring ball i's state from its last event to time t."""
    if air_on and balls.st[e, i] == C.AIRBORNE:
        airborne.fly(balls, e, i, t - tlast[e, i], p[C.P_G])
    else:
        evolve(balls.pos, balls.vel, balls.om, balls.st, e, i, t - tlast[e, i], p, zspin_on, spin_on)
    tlast[e, i] = t


@njit_inline
def next_event(scr, e, B):
    """Earliest event of table e: (time, kind, a, b); kind -2 is a motion
    transition of ball a. Ties go to the first found (pairs, then
    boundaries, then transitions), a fixed deterministic order."""
    tpair, tb, tt = scr.tpair, scr.tb, scr.tt
    tmin = math.inf; kind = -1; a = -1; b = -1
    for i in range(B):
        for j in range(i + 1, B):
            if tpair[e, i, j] < tmin:
                tmin = tpair[e, i, j]; kind = C.EV_BALL_BALL; a = i; b = j
    for i in range(B):
        if tb[e, i] < tmin:
            tmin = tb[e, i]; kind = scr.bkind[e, i]; a = i; b = scr.bidx[e, i]
    for i in range(B):
        if tt[e, i] < tmin:
            tmin = tt[e, i]; kind = -2; a = i; b = -1
    return tmin, kind, a, b


def make_run(spin_on, zspin_on, diag_on, impacts):
    """The event kernel's Python function:
    ``run(balls, geo, p, scr, out, log, max_events)``; with
    ``impacts.air_on`` balls fly (``airborne``)."""
    prepare, resolve_boundary = impacts.prepare, impacts.resolve_boundary
    resolve_impact_set, resolve_flight_impact = impacts.resolve_impact_set, impacts.resolve_flight_impact
    settle, air_on = impacts.settle, impacts.air_on

    @variant_njit(__name__, spin_on, zspin_on, diag_on, *impacts.choices)
    def table(balls, geo, p, scr, out, log, max_events, e, work):
        """Simulate table e to rest (work: its worker's
        layout.ChunkScratch)."""
        pos, vel, om, st, tpair, tlast = balls.pos, balls.vel, balls.om, balls.st, scr.tpair, scr.tlast
        imp, stuck, todo = work
        B = pos.shape[1]
        prepare(balls, e, p)
        t = 0.0
        event_log.record_start(log, balls, e)
        for i in range(B):
            tlast[e, i] = 0.0
            tpair[e, i, i] = math.inf
            todo[i] = i
        n_todo = B  # balls whose events to recompute: at first every ball
        en_prev = 0.0
        out.first[e] = -1
        nev = 0
        sim_i, sim_j = imp.i, imp.j
        stuck[:] = False  # balls of the events at the current instant
        n_stuck = 0  # events since time last advanced
        rounds = 0  # collapse rounds at the current instant
        while True:
            if n_stuck > C.ZENO_EVENTS:
                # An inelastic collapse: the stuck balls (every ball of the
                # events since time last advanced) are slowed, and all their
                # events recomputed, in the order of their index. The last
                # event's balls are among them: their own recomputation is
                # this one (any earlier one would be overwritten).
                n_todo = 0
                for i in range(B):
                    if stuck[i]:
                        catch_up(balls, tlast, e, i, t, p, zspin_on, spin_on, air_on)
                        todo[n_todo] = i; n_todo += 1
                break_collapse(balls, e, p, stuck, rounds, spin_on)
                n_stuck = 0
                rounds += 1
            # the balls the last event changed (the one call site of
            # ``refresh``: inlined)
            for q in range(n_todo):
                refresh(balls, scr, geo, e, todo[q], t, p, air_on)
            n_todo = 0
            if nev == 0:
                if diag_on:
                    en_prev = diagnostics.start(balls, geo, e, p, out.diag)
            else:
                if diag_on:
                    diagnostics.check_geometry(balls, geo, e, p, out.diag)
                    en_prev = diagnostics.energy_step(balls, e, p, out.diag, en_prev)
            tmin, kind, a, b = next_event(scr, e, B)
            if tmin == math.inf:
                break
            if nev >= max_events:
                out.trunc[e] = True
                break
            if tmin < t:
                tmin = t
            dt = tmin - t
            if dt > C.SIMULTANEOUS_TIME:
                n_stuck = 0
                rounds = 0
                stuck[:] = False
            n_stuck += 1
            t = tmin
            if diag_on:
                for i in range(B):
                    catch_up(balls, tlast, e, i, t, p, zspin_on, spin_on, air_on)
            nev += 1
            if air_on and kind == C.EV_BALL_BALL and (st[e, a] == C.AIRBORNE or st[e, b] == C.AIRBORNE):
                # a ball in flight: this pair alone, in 3D (a simultaneous
                # contact follows at the same time)
                catch_up(balls, tlast, e, a, t, p, zspin_on, spin_on, air_on)
                catch_up(balls, tlast, e, b, t, p, zspin_on, spin_on, air_on)
                resolve_flight_impact(balls, e, t, a, b, p, out, log)
                stuck[a] = True; stuck[b] = True
                todo[0] = a; todo[1] = b
                n_todo = 2
            elif kind == C.EV_BALL_BALL:
                # gather simultaneous impacts
                ns = 0
                for i in range(B):
                    for j in range(i + 1, B):
                        if air_on and (st[e, i] == C.AIRBORNE or st[e, j] == C.AIRBORNE):
                            continue  # in flight: resolved alone, in 3D (a pair of its own)
                        if tpair[e, i, j] <= tmin + C.SIMULTANEOUS_TIME and ns < C.MAX_SIMULTANEOUS:
                            sim_i[ns] = i; sim_j[ns] = j; ns += 1
                for s in range(ns):
                    catch_up(balls, tlast, e, sim_i[s], t, p, zspin_on, spin_on, air_on)
                    catch_up(balls, tlast, e, sim_j[s], t, p, zspin_on, spin_on, air_on)
                nb = resolve_impact_set(balls, e, t, imp, ns, p, out, log)
                involved = imp.balls
                for q in range(nb):
                    stuck[involved[q]] = True
                    todo[q] = involved[q]
                n_todo = nb
            else:
                catch_up(balls, tlast, e, a, t, p, zspin_on, spin_on, air_on)
                if air_on and kind == -2 and st[e, a] == C.AIRBORNE:
                    if not airborne.land(balls, e, a, p):
                        settle(balls, e, a, p)  # the bounces have ended: on the felt
                    kind = C.EV_SLATE
                    b = -1
                elif kind == -2:
                    kind = apply_transition(vel, om, st, e, a, p)
                    b = -1
                else:
                    resolve_boundary(balls, geo, e, kind, a, b, p, out)
                if log.on:
                    event_log.record(log, balls, e, t, kind, a, b)
                stuck[a] = True
                todo[0] = a
                n_todo = 1
        for i in range(B):
            catch_up(balls, tlast, e, i, t, p, zspin_on, spin_on, air_on)
        out.time[e] = t
        out.nev[e] = nev

    def run(balls, geo, p, scr, out, log, max_events):
        # Tables in chunks of up to TABLES_PER_CHUNK (and at least
        # MIN_CHUNKS chunks), each chunk with one scratch: an allocation per
        # table cost a two-ball shot ~5% of its time. (The thread count is
        # not read here: a kernel that reads it cannot be cached on disk.)
        E = balls.pos.shape[0]
        per = max(1, min(TABLES_PER_CHUNK, E // MIN_CHUNKS))
        for c in numba.prange((E + per - 1) // per):
            work = ChunkScratch(impact_scratch(), np.zeros(balls.pos.shape[1], dtype=np.bool_),
                                np.empty(balls.pos.shape[1], dtype=np.int64))
            for e in range(c * per, min(E, (c + 1) * per)):
                table(balls, geo, p, scr, out, log, max_events, e, work)

    return run
