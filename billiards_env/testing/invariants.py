"""Invariants every simulated shot must satisfy, shared by the
hard-case tests, the hypothesis fuzzing and scripts/fuzz.py.

``check_invariants`` returns a list of violation messages per table;
``assert_invariants`` fails a test with all of them.
"""
from __future__ import annotations

import time

import numpy as np

from billiards_env.physics import Effects, Models, simulate
from billiards_env.physics import constants as C
from billiards_env.physics.kernels import make_kernel
from billiards_env.physics.motion import kinetic_energy

# Balls may overlap by at most C.OVERLAP_TOL and leave the table (except
# into a pocket) by at most C.OFF_TABLE_TOL (m): the kernels' own tolerances.
ENERGY_TOL_ABS = 1e-12   # J: rounding of a sum of energies of order 10 J is ~1e-15 J
ENERGY_TOL_REL = 1e-12   # relative to the initial energy
MOMENTUM_TOL = 1e-12     # kg m/s per impact (momenta are of order 1)
MAX_WALL_S = 20.0        # s of wall time per simulate call (after compilation)


def initial_energy(state, params) -> np.ndarray:
    """Total energy per table of the balls on the table (J), by the kernels'
    own formula (motion.kinetic_energy, on numpy arrays), with the height's
    and the vertical motion's (airborne.flight_energy) where the state has
    them."""
    v, w = state.vel, state.omega
    energy = getattr(kinetic_energy, "py_func", kinetic_energy)  # the plain function under NUMBA_DISABLE_JIT=1
    e = energy(v[..., 0], v[..., 1], w[..., 0], w[..., 1], w[..., 2], params.as_array())
    if state.air is not None:
        e = e + params.m * (params.g * state.air[..., 0] + 0.5 * state.air[..., 1] ** 2)
    return (e * (state.pocket < 0)).sum(-1)


def check_invariants(result, initial, table, params, *, max_events=None, pockets=True):
    """Violations per table: list (length E) of lists of strings."""
    E = result.state.n_envs
    out = [[] for _ in range(E)]
    s = result.state
    diag = result.diagnostics
    e0 = initial_energy(initial, params)
    R = params.R
    for e in range(E):
        bad = out[e]
        for name in ("pos", "vel", "omega"):
            if not np.all(np.isfinite(getattr(s, name)[e])):
                bad.append(f"non-finite final {name}")
        if not np.isfinite(result.time[e]):
            bad.append("non-finite simulated time")
        if result.truncated[e]:
            bad.append(f"truncated after {result.n_events[e]} events (cap hit)")
        if max_events is not None and result.n_events[e] > max_events:
            bad.append(f"{result.n_events[e]} events > bound {max_events}")
        on = s.pocket[e] < 0
        if np.any(s.vel[e][on] != 0.0) or np.any(s.omega[e][on] != 0.0):
            bad.append("a ball on the table is not at rest at the end")
        if s.air is not None and np.any(s.air[e][on] != 0.0):
            bad.append("a ball on the table is not on the slate at the end")
        if diag is not None:
            d = diag[e]
            if not np.all(np.isfinite(d[[0, 1, 3]])) or np.isnan(d[2]):
                bad.append(f"non-finite diagnostics {d}")
            tol = ENERGY_TOL_ABS + ENERGY_TOL_REL * e0[e]
            if d[0] > tol:
                bad.append(f"energy increased by {d[0]:.3e} J (> {tol:.1e})")
            if d[1] > MOMENTUM_TOL:
                bad.append(f"ball-ball impact momentum error {d[1]:.3e} kg m/s")
            if d[2] < -C.OVERLAP_TOL:
                bad.append(f"balls overlapped by {-d[2]:.3e} m")
            if d[3] > C.OFF_TABLE_TOL:
                bad.append(f"a ball left the table by {d[3]:.3e} m")
        # final state, independently of the kernel's diagnostics
        pos = s.pos[e][on]
        if len(pos):
            if np.all(np.isfinite(pos)):
                ok = table.contains(pos, R, C.OFF_TABLE_TOL, pockets)
                if not ok.all():
                    bad.append(f"final ball position(s) off the table: {pos[~ok].tolist()}")
            dd = np.hypot(*(pos[:, None, :] - pos[None, :, :]).transpose(2, 0, 1))
            dd[np.diag_indices(len(pos))] = np.inf
            if dd.min() < 2 * R - C.OVERLAP_TOL:
                bad.append(f"final overlap {2 * R - dd.min():.3e} m")
    return out


def assert_invariants(result, initial, table, params, *, wall=None, max_events=None, pockets=True):
    """Assert every invariant of ``check_invariants`` for each table of ``result``, the
    simulation of ``initial`` (needs ``diagnostics=True``)."""
    assert result.diagnostics is not None, "run with diagnostics=True"
    viol = check_invariants(result, initial, table, params, max_events=max_events, pockets=pockets)
    msgs = [f"table {e}: {m}" for e, v in enumerate(viol) for m in v]
    if wall is not None and wall > MAX_WALL_S:
        msgs.append(f"wall time {wall:.1f} s > {MAX_WALL_S} s")
    assert not msgs, "\n".join(msgs)


def run_checked(state, table, params, solver, *, dt=1e-3, effects=None, max_events=None,
                record=False, models=None):
    """Simulate with diagnostics, assert the invariants, return the result."""
    kw = {} if solver == "event" else {"dt": dt}
    effects = effects or Effects.all()
    models = models or Models()
    # the wall-time bound is for the simulation, not for compiling (or
    # loading from cache) a kernel variant on its first call in this process
    compiled = bool(getattr(make_kernel(solver, effects, models, True), "signatures", True))  # no JIT: nothing to compile
    t0 = time.perf_counter()
    res = simulate(state, table, params, solver=solver, effects=effects, diagnostics=True,
                   record=record, models=models, **kw)
    wall = time.perf_counter() - t0 if compiled else None
    assert_invariants(res, state, table, params, wall=wall, max_events=max_events, pockets=effects.pockets)
    return res
