"""Impacts of both solvers: ball-ball impact sets, boundary events (pocket,
cushion, jaw tip) and the motion states after them.

``make_impacts`` builds the jitted functions for one effect set and one
choice of models; the models are jitted functions it closes over
(``ball_ball`` and ``cushion`` packages), the effect flags are compile-time
constants of the closures.

Simultaneous ball-ball impacts (within SIMULTANEOUS_TIME) are resolved in both
orders and the two results averaged: the outcome is symmetric under swapping
the two impacts, conserves momentum exactly, and since kinetic energy is
convex in the velocities it cannot exceed the energy of either order.
"""
import math
import types

import numpy as np

from . import airborne
from . import constants as C
from . import event_log
from ._jit import name_of, njit, variant_njit
from .ball_ball import flight
from .ball_ball.contact import rest_contact
from .cushion import rail
from .cushion.contact import make_resolve as make_cushion
from .motion import classify, end_slide, energy


@njit
def pocket_ball(balls, e, i, k):
    """Ball i drops into pocket k (or leaves the table: k an off-table
    code, constants.OFF_TABLE)."""
    balls.pocket[e, i] = k
    balls.st[e, i] = C.POCKETED
    balls.vel[e, i, 0] = 0.0; balls.vel[e, i, 1] = 0.0
    balls.om[e, i, 0] = 0.0; balls.om[e, i, 1] = 0.0; balls.om[e, i, 2] = 0.0


@njit
def ground(balls, e, i):
    """Ball i is out of play: no height, no vertical velocity."""
    balls.air[e, i, 0] = 0.0; balls.air[e, i, 1] = 0.0


@njit
def _save(vel, om, st, e, i, buf, k):
    buf[k, 0] = vel[e, i, 0]; buf[k, 1] = vel[e, i, 1]
    buf[k, 2] = om[e, i, 0]; buf[k, 3] = om[e, i, 1]; buf[k, 4] = om[e, i, 2]
    buf[k, 5] = st[e, i]


@njit
def _load(vel, om, st, e, i, buf, k):
    vel[e, i, 0] = buf[k, 0]; vel[e, i, 1] = buf[k, 1]
    om[e, i, 0] = buf[k, 2]; om[e, i, 1] = buf[k, 3]; om[e, i, 2] = buf[k, 4]
    st[e, i] = np.int64(buf[k, 5])


@njit
def _balls_of(imp, ns):
    """Distinct balls of the impact set, into ``imp.balls``; returns how many."""
    sim_i, sim_j, balls = imp.i, imp.j, imp.balls
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


@njit
def _impact_sums(balls, e, imp, nb, p):
    """Energy and momentum / m of the balls of an impact set."""
    en = 0.0; px = 0.0; py = 0.0
    for q in range(nb):
        en += energy(balls.vel, balls.om, balls.st, e, imp.balls[q], p)  # planar impacts: no ball in flight
        px += balls.vel[e, imp.balls[q], 0]; py += balls.vel[e, imp.balls[q], 1]
    return en, px, py


@njit
def note_contact(out, e, kind, index):
    """Append a cue-ball contact (event kind, ball or boundary index) to
    table e's contact order; past its capacity only the count grows."""
    n = out.norder[e]
    if n < out.order.shape[1]:
        out.order[e, n, 0] = kind
        out.order[e, n, 1] = index
    out.norder[e] = n + 1


def make_impacts(spin_on, slide_on, zspin_on, diag_on, ball_ball, cushion, order_on=False, air_on=False):
    """The impact functions for one effect set, with ball-ball model
    ``ball_ball`` and cushion model ``cushion`` (see their packages);
    ``order_on``: the cue ball's contacts are noted in order (``note_contact``;
    a compile-time constant, so a kernel without it has none of that code);
    ``air_on``: balls fly (``Effects.airborne``: the contacts of a ball in
    flight, ``ball_ball.flight`` and ``cushion.rail``)."""
    choices = (spin_on, slide_on, zspin_on, diag_on, name_of(ball_ball), name_of(cushion))
    if order_on:  # the default kernels keep their variant names
        choices = choices + ("order",)
    if air_on:
        choices = choices + ("airborne",)
    variant = variant_njit("impacts", *choices)
    resolve_cushion = make_cushion(cushion, spin_on)

    @variant
    def settle(balls, e, i, p):
        """New motion state of ball i after its velocities changed, under
        the effects: no vertical spin, or no sliding (a slide ends at once)."""
        vel, om, st = balls.vel, balls.om, balls.st
        R = p[C.P_R]
        if not zspin_on:
            om[e, i, 2] = 0.0
        classify(vel, om, st, e, i, R, spin_on)
        if not slide_on and st[e, i] == C.SLIDING:
            end_slide(vel, om, e, i, R)
            classify(vel, om, st, e, i, R, spin_on)

    @variant
    def ball_energy(balls, e, i, p):
        """Ball i's energy (J): with balls in flight, its height's and
        vertical motion's too."""
        en = energy(balls.vel, balls.om, balls.st, e, i, p)
        if air_on:
            en += airborne.flight_energy(balls, e, i, p)
        return en

    @variant
    def prepare(balls, e, p):
        """Initial motion states of table e (pocketed balls stay out; with
        ``air_on`` a ball above the slate or moving vertically flies)."""
        vel, om, st, pocket = balls.vel, balls.om, balls.st, balls.pocket
        for i in range(vel.shape[1]):
            if pocket[e, i] >= 0:
                st[e, i] = C.POCKETED
                vel[e, i, 0] = 0.0; vel[e, i, 1] = 0.0
                om[e, i, 0] = 0.0; om[e, i, 1] = 0.0; om[e, i, 2] = 0.0
                if air_on:
                    ground(balls, e, i)
                continue
            if air_on and airborne.leaves_slate(balls, e, i):
                st[e, i] = C.AIRBORNE
                continue
            settle(balls, e, i, p)

    @variant
    def resolve_boundary(balls, geo, e, kind, a, b, p, out):
        """Ball a meets boundary b: drops into pocket b, or rebounds from
        cushion segment b or jaw tip b."""
        if kind == C.EV_POCKET:
            pocket_ball(balls, e, a, b)
            if air_on:
                ground(balls, e, a)
            return
        if air_on and kind == C.EV_OFF_TABLE:  # over the rail: where it comes down
            pocket_ball(balls, e, a, rail.landing_code(balls, geo, e, a, b, p))
            ground(balls, e, a)
            return
        if kind == C.EV_CUSHION:
            nx, ny = geo.norms[b, 0], geo.norms[b, 1]
        else:  # the detector's own normal: ball centre minus jaw tip
            nx = balls.pos[e, a, 0] - geo.tips[b, 0]; ny = balls.pos[e, a, 1] - geo.tips[b, 1]
        e0 = ball_energy(balls, e, a, p) if diag_on else 0.0
        resolve_cushion(balls.vel, balls.om, e, a, nx, ny, p)
        if not (air_on and balls.st[e, a] == C.AIRBORNE):  # in flight it flies on, its vertical velocity kept
            settle(balls, e, a, p)
        if diag_on:
            out.diag[e, 0] = max(out.diag[e, 0], ball_energy(balls, e, a, p) - e0)
        out.cush[e, a] += 1
        if out.first[e] >= 0:
            out.cush_after[e, a] += 1
        if order_on:  # a compile-time constant: without it the branch, and out.order, are not compiled
            if a == 0:
                note_contact(out, e, kind, b)

    @variant
    def impulses(balls, e, imp, ns, nb, p):
        """Impulses of a set of simultaneous ball-ball impacts. One impact:
        resolved directly. Several: resolved in index order and in reverse
        order from the same state, and the two results averaged (module
        docstring). imp.w receives each impact's approach speed."""
        pos, vel, om, st = balls.pos, balls.vel, balls.om, balls.st
        sim_i, sim_j, sim_w, bs = imp.i, imp.j, imp.w, imp.balls
        if ns == 1:
            sim_w[0] = ball_ball(pos, vel, om, e, sim_i[0], sim_j[0], p)
            return
        buf, buf2 = imp.saved, imp.swapped
        for q in range(nb):
            _save(vel, om, st, e, bs[q], buf, q)
        for s in range(ns):
            sim_w[s] = ball_ball(pos, vel, om, e, sim_i[s], sim_j[s], p)
        for q in range(nb):
            _save(vel, om, st, e, bs[q], buf2, q)
            _load(vel, om, st, e, bs[q], buf, q)
        for s in range(ns - 1, -1, -1):
            w2 = ball_ball(pos, vel, om, e, sim_i[s], sim_j[s], p)
            sim_w[s] = min(sim_w[s], w2)
        for q in range(nb):
            bq = bs[q]
            vel[e, bq, 0] = 0.5 * (vel[e, bq, 0] + buf2[q, 0])
            vel[e, bq, 1] = 0.5 * (vel[e, bq, 1] + buf2[q, 1])
            om[e, bq, 0] = 0.5 * (om[e, bq, 0] + buf2[q, 2])
            om[e, bq, 1] = 0.5 * (om[e, bq, 1] + buf2[q, 3])
            om[e, bq, 2] = 0.5 * (om[e, bq, 2] + buf2[q, 4])

    @variant
    def note_impact(balls, e, t, i, j, out, log):
        """What an impact of balls i and j at time t leaves on record: the
        cue ball's first contact, its contact order (``order_on``) and the
        event log."""
        if out.first[e] == -1 and (i == 0 or j == 0):
            out.first[e] = j if i == 0 else i
        if order_on:
            if i == 0 or j == 0:
                note_contact(out, e, C.EV_BALL_BALL, j if i == 0 else i)
        if log.on:
            event_log.record(log, balls, e, t, C.EV_BALL_BALL, i, j)

    @variant
    def resolve_impact_set(balls, e, t, imp, ns, p, out, log):
        """Everything a set of ns simultaneous ball-ball impacts (pairs
        imp.i, imp.j) does: impulses, diagnostics of that impulse set
        (energy, momentum), resting contacts for impacts slower than
        ZENO_SPEED and new motion states, first contact, event log. Returns
        the number of balls involved (listed in ``imp.balls``)."""
        nb = _balls_of(imp, ns)
        e0 = 0.0; px0 = 0.0; py0 = 0.0
        if diag_on:
            e0, px0, py0 = _impact_sums(balls, e, imp, nb, p)
        impulses(balls, e, imp, ns, nb, p)
        if diag_on:
            e1, px1, py1 = _impact_sums(balls, e, imp, nb, p)
            out.diag[e, 0] = max(out.diag[e, 0], e1 - e0)
            out.diag[e, 1] = max(out.diag[e, 1], math.hypot(px1 - px0, py1 - py0) * p[C.P_M])
        sim_i, sim_j, sim_w = imp.i, imp.j, imp.w
        for s in range(ns):
            if sim_w[s] < C.ZENO_SPEED:
                rest_contact(balls.pos, balls.vel, balls.om, e, sim_i[s], sim_j[s], p, spin_on)
        for q in range(nb):
            settle(balls, e, imp.balls[q], p)
        for s in range(ns):
            note_impact(balls, e, t, sim_i[s], sim_j[s], out, log)
        return nb

    @variant
    def resolve_flight_impact(balls, e, t, i, j, p, out, log):
        """The impact of balls i and j, one of them in flight
        (``ball_ball.flight``): the impulse, the ball on the slate's new
        motion state (in flight if the impact knocked it off the slate), its diagnostics (energy), first contact, contact
        order and event log, as ``resolve_impact_set`` for a planar set."""
        e0 = 0.0
        if diag_on:
            e0 = ball_energy(balls, e, i, p) + ball_energy(balls, e, j, p)
        flight.resolve(balls, e, i, j, p)
        for q in (i, j):
            if balls.st[e, q] == C.AIRBORNE:
                continue
            if airborne.leaves_slate(balls, e, q):
                balls.st[e, q] = C.AIRBORNE  # knocked off the slate
            else:
                settle(balls, e, q, p)
        if diag_on:
            out.diag[e, 0] = max(out.diag[e, 0], ball_energy(balls, e, i, p) + ball_energy(balls, e, j, p) - e0)
        note_impact(balls, e, t, i, j, out, log)

    return types.SimpleNamespace(settle=settle, prepare=prepare, resolve_boundary=resolve_boundary,
                                 resolve_impact_set=resolve_impact_set, resolve_flight_impact=resolve_flight_impact,
                                 choices=choices, air_on=air_on)
