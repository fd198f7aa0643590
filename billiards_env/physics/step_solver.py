"""Step solver: the original fixed-step scheme: fixed time step dt; within a step
balls move in straight lines, the earliest collision in the step is found from
the quadratic, balls are advanced to it and it is resolved, until the step is
used up; then felt friction updates the velocities for the step (clamped so
it never reverses a velocity).

Balls in flight (``Effects(airborne=True)``): a ball in flight moves on its
parabola within the step (straight in x, y; its height exact), its landing
on the slate is an event of the step (``airborne.land``), its contacts are
``ball_ball.flight`` (3D, the other ball straight) and ``cushion.rail``, and
no felt friction acts on it.

``make_run`` returns the kernel's Python function for one effect set and
impact functions (``impacts.make_impacts``); ``kernels`` compiles it,
parallel over tables (prange).
"""
import math

import numba

from . import airborne
from . import constants as C
from . import diagnostics, event_log
from ._jit import njit, njit_inline, variant_njit
from .ball_ball import flight
from .cushion import rail
from .detection import boundary_time, pair_time_linear
from .layout import impact_scratch
from .motion import friction_step


NO_ACC = (0.0, 0.0, 0.0, 0.0)  # straight lines on the felt within a step: no acceleration


@njit_inline
def earliest_contact(balls, geo, e, rem, p, air_on):
    """Earliest contact of table e within rem (s), balls moving in straight
    lines (in flight: on their parabola): (time, kind, a, b), kind -1 if
    none, -2 the landing of ball a in flight (``air_on``)."""
    pos, vel, st = balls.pos, balls.vel, balls.st
    B = pos.shape[1]
    tmin = math.inf; kind = -1; a = -1; b = -1
    for i in range(B):
        for j in range(i + 1, B):
            if air_on and (st[e, i] == C.AIRBORNE or st[e, j] == C.AIRBORNE):
                # as the event solver: a ball meeting the slate now bounces first
                if (st[e, i] == C.POCKETED or st[e, j] == C.POCKETED or airborne.meets_slate(balls, e, i)
                        or airborne.meets_slate(balls, e, j)):
                    continue
                tij = flight.contact_time(balls, e, i, j, NO_ACC, min(rem, tmin), p, 0.0)
            else:
                tij = pair_time_linear(pos, vel, st, e, i, j, min(rem, tmin), p)
            if tij < tmin:
                tmin = tij; kind = C.EV_BALL_BALL; a = i; b = j
    for i in range(B):
        if air_on and st[e, i] == C.AIRBORNE:
            tl = airborne.drop_time(balls.air[e, i, 0], balls.air[e, i, 1], p[C.P_G])
            if tl <= min(rem, tmin) and tl < tmin:
                tmin = tl; kind = -2; a = i; b = -1
            tbi, k, idx = rail.boundary_time(balls, e, i, min(rem, tmin, tl), p, geo)
        else:
            tbi, k, idx = boundary_time(balls, e, i, 0.0, 0.0, min(rem, tmin), p, geo, True)
        if tbi < tmin:
            tmin = tbi; kind = k; a = i; b = idx
    return tmin, kind, a, b


@njit
def touching_set(balls, e, imp, a, b, p):
    """Every pair touching and closing now, into imp (one simultaneous set,
    resolved by the event solver's policy); returns how many."""
    pos, vel, st = balls.pos, balls.vel, balls.st
    sim_i, sim_j = imp.i, imp.j
    B = pos.shape[1]
    ns = 0
    for i in range(B):
        for j in range(i + 1, B):
            if st[e, i] == C.AIRBORNE or st[e, j] == C.AIRBORNE:  # in flight: resolved alone, in 3D
                continue
            if ns < C.MAX_SIMULTANEOUS and pair_time_linear(pos, vel, st, e, i, j, C.SIMULTANEOUS_TIME, p) <= C.SIMULTANEOUS_TIME:
                sim_i[ns] = i; sim_j[ns] = j; ns += 1
    if ns == 0:  # rounding moved the pair off contact: resolve it alone
        sim_i[0] = a; sim_j[0] = b; ns = 1
    return ns


@njit
def moving(st, e):
    """True if a ball of table e still moves or spins."""
    for i in range(st.shape[1]):
        if st[e, i] != C.STATIONARY and st[e, i] != C.POCKETED:
            return True
    return False


def make_run(spin_on, zspin_on, diag_on, impacts):
    """The step kernel's Python function:
    ``run(balls, geo, p, out, log, max_events, dt, max_steps)``."""
    prepare, resolve_boundary = impacts.prepare, impacts.resolve_boundary
    resolve_impact_set, resolve_flight_impact = impacts.resolve_impact_set, impacts.resolve_flight_impact
    settle, air_on = impacts.settle, impacts.air_on

    @variant_njit(__name__, spin_on, zspin_on, diag_on, *impacts.choices)
    def table(balls, geo, p, out, log, max_events, dt, max_steps, e, imp):
        """Simulate table e to rest (imp: its impact scratch)."""
        pos, vel, om, st = balls.pos, balls.vel, balls.om, balls.st  # once, not per step
        B = pos.shape[1]
        prepare(balls, e, p)
        event_log.record_start(log, balls, e)
        en_prev = 0.0
        if diag_on:
            en_prev = diagnostics.start(balls, geo, e, p, out.diag)
        out.first[e] = -1
        t = 0.0
        nev = 0
        steps = 0
        while True:
            if not moving(st, e):
                break
            if steps >= max_steps or nev >= max_events:
                out.trunc[e] = True
                break
            steps += 1
            rem = dt
            while rem > 0.0 and nev < max_events:
                tmin, kind, a, b = earliest_contact(balls, geo, e, rem, p, air_on)
                adv = min(tmin, rem)
                for i in range(B):
                    if st[e, i] == C.SLIDING or st[e, i] == C.ROLLING:
                        pos[e, i, 0] += vel[e, i, 0] * adv
                        pos[e, i, 1] += vel[e, i, 1] * adv
                    elif air_on and st[e, i] == C.AIRBORNE:
                        airborne.fly(balls, e, i, adv, p[C.P_G])
                rem -= adv
                if kind == -1:  # nothing within the step
                    break
                nev += 1
                tev = t + (dt - rem)
                if air_on and kind == C.EV_BALL_BALL and (st[e, a] == C.AIRBORNE or st[e, b] == C.AIRBORNE):
                    resolve_flight_impact(balls, e, tev, a, b, p, out, log)
                elif kind == C.EV_BALL_BALL:
                    ns = touching_set(balls, e, imp, a, b, p)
                    resolve_impact_set(balls, e, tev, imp, ns, p, out, log)
                elif air_on and kind == -2:  # a ball in flight meets the slate
                    if not airborne.land(balls, e, a, p):
                        settle(balls, e, a, p)
                    kind = C.EV_SLATE
                else:
                    resolve_boundary(balls, geo, e, kind, a, b, p, out)
                if diag_on:
                    en_prev = diagnostics.energy_step(balls, e, p, out.diag, en_prev)
                if log.on and kind != C.EV_BALL_BALL:
                    event_log.record(log, balls, e, tev, kind, a, b)
            for i in range(B):
                if st[e, i] != C.STATIONARY and st[e, i] != C.POCKETED and not (air_on and st[e, i] == C.AIRBORNE):
                    friction_step(vel, om, st, e, i, dt, p, zspin_on, spin_on)
            t += dt
            if diag_on:
                diagnostics.check_geometry(balls, geo, e, p, out.diag)
                en_prev = diagnostics.energy_step(balls, e, p, out.diag, en_prev)
        out.time[e] = t
        out.nev[e] = nev

    def run(balls, geo, p, out, log, max_events, dt, max_steps):
        for e in numba.prange(balls.pos.shape[0]):
            table(balls, geo, p, out, log, max_events, dt, max_steps, e, impact_scratch())

    return run
