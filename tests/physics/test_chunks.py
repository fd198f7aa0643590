"""simulate runs large batches in chunks of tables (bounded scratch memory);
the result is the same as one call over the whole batch."""
import importlib

import numpy as np

from billiards_env.physics import PhysicsParams, Table, rack, simulate, strike

S = importlib.import_module("billiards_env.physics.simulate")


def test_chunked_batches_equal_one_call(monkeypatch):
    P, T = PhysicsParams.standard(), Table.pool(9)
    st = strike(rack(T, P, "eight", n_envs=300, seed=1), phi=np.pi / 2, draw=0.25, a=0.0, b=0.2, params=P)
    whole = simulate(st, T, P, record=True, diagnostics=True)
    per_table = 8 * (16 * 16 + 12 * 16) + S.RECORD_CAPACITY * 152  # chunk_rows' own count
    monkeypatch.setattr(S, "MAX_SCRATCH_BYTES", 40 * per_table)
    assert S.chunk_rows(16, True) == 40  # 300 tables in 8 chunks, the last one short
    parts = simulate(st, T, P, record=True, diagnostics=True)
    for f in ("time", "n_events", "first_contact", "cushion_hits", "truncated", "cushion_hits_after_contact",
              "diagnostics"):
        assert np.array_equal(getattr(whole, f), getattr(parts, f)), f
    for f in ("pos", "vel", "omega", "pocket"):
        assert np.array_equal(getattr(whole.state, f), getattr(parts.state, f)), f
    assert len(parts.events) == 300
    assert all(np.array_equal(a.states, b.states) for a, b in zip(whole.events, parts.events))


def test_chunk_size_bounds_the_scratch():
    rows = S.chunk_rows(16, False)
    assert rows * 16 * 16 * 8 <= S.MAX_SCRATCH_BYTES < (rows + 1) * (16 * 16 * 8 + 12 * 16 * 8) + 16 * 16 * 8
