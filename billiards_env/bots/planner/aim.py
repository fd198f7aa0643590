"""Throw-corrected aim: the cue's aim refined so the object ball leaves in the wanted direction.

The ghost-ball aim sends the object ball along the line of centres; friction between the balls at contact
(collision-induced throw, and the throw of the cue ball's side spin) turns it off that line by up to a few
degrees on a cut, most at low speed, enough to miss a pocket from a metre away. For each candidate a scene of only
the cue ball and the object ball is struck as planned and simulated with the table's physics; the object ball's
velocity just after the first ball-ball event gives its departure direction, and a
secant step on the aim closes the gap. All candidates are refined in the same batched simulations.
"""
from __future__ import annotations

import numpy as np

from ...physics import BallState, simulate, strike_velocity
from ...physics.simulate import SimOptions

PROBE = 2e-4    # rad: the aim step whose effect on the departure direction gives the secant's slope
STEPS = 2       # secant steps after the probe (a third measured no closer: the map is nearly linear)
MAX_EVENTS = 4  # events the cue ball may have before the contact (slide to roll, spin stop, ...)
MAX_FIX = 0.05  # rad: the largest correction accepted (a larger one means the probe hit something else)


def departure(view, cue, obj, phi, speed, a, b):
    """[k] the object ball's direction (rad) after the cue ball at ``cue`` [k, 2] struck (phi, speed, a, b) [k]
    hits it at ``obj`` [k, 2], alone on the table (NaN where the cue ball misses it). The simulation stops after
    ``m`` events (m = 1, 2, ...): where the first ball-ball contact was among them, the object ball's velocity
    then is its departure (the event log with ``record=True`` says the same, at many times the cost)."""
    k = len(phi)
    pos = np.stack([cue, obj], axis=1)
    state = BallState(pos, np.zeros((k, 2, 2)), np.zeros((k, 2, 3)), np.full((k, 2), -1, np.int64))
    struck = strike_velocity(state, phi, speed, a, b, view.params)
    out = np.full(k, np.nan)
    todo = np.arange(k)
    for m in range(1, MAX_EVENTS + 1):
        if not len(todo):
            break
        res = simulate(struck.take(todo), view.table, view.params, solver=view.solver, dt=view.dt,
                       effects=view.effects, models=view.models, options=SimOptions(validate=False, max_events=m))
        hit = res.first_contact == 1
        vel = res.state.vel[hit, 1]
        out[todo[hit]] = np.arctan2(vel[:, 1], vel[:, 0])
        todo = todo[~hit & res.truncated]
    return out


def wrap(x):
    return (x + np.pi) % (2 * np.pi) - np.pi


def corrected(view, cue, obj, want, phi0, speed, a, b):
    """The aims [k] (rad) that send the object balls at ``obj`` [k, 2] off in directions ``want`` [k], starting
    from ``phi0`` [k] (the ghost-ball aims), the cue balls at ``cue`` [k, 2] struck at ``speed``, ``a``, ``b``;
    a candidate whose correction fails (a miss, or more than ``MAX_FIX``) keeps ``phi0``."""
    k = len(phi0)
    if k == 0:
        return phi0
    two = lambda x: np.concatenate([x, x])             # the aim and the probe in one batch
    d0, d1 = np.split(departure(view, two(cue), two(obj), np.concatenate([phi0, phi0 + PROBE]), two(speed), two(a),
                                two(b)), 2)
    slope = wrap(d1 - d0) / PROBE
    good = np.isfinite(slope) & (np.abs(slope) > 1e-3)
    slope = np.where(good, slope, 1.0)
    phi = phi0 + np.where(good, wrap(want - d0) / slope, 0.0)
    for _ in range(STEPS - 1):
        d = departure(view, cue, obj, phi, speed, a, b)
        ok = np.isfinite(d)
        phi = np.where(ok & good, phi + np.where(ok, wrap(want - d), 0.0) / slope, phi)
    bad = ~good | (np.abs(wrap(phi - phi0)) > MAX_FIX)
    return np.where(bad, phi0, phi)
