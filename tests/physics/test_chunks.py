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
    per_table = 8 * (16 * 16 + 12 * 16) + S.RECORD_CAPACITY * 8 * (4 + 2 * S.LOG_COLUMNS)  # chunk_rows' own count
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


def _same(a, b):
    return all(np.array_equal(getattr(a, f), getattr(b, f)) for f in ("time", "n_events", "first_contact",
                                                                      "cushion_hits")) and \
        all(np.array_equal(getattr(a.state, f), getattr(b.state, f)) for f in ("pos", "vel", "omega", "pocket"))


def test_kept_scratch_gives_the_fresh_result(monkeypatch):
    """The kept event scratch (rows of a larger earlier call, full of its
    values) gives the result of freshly allocated scratch."""
    P, T = PhysicsParams.standard(), Table.pool(9)
    big = strike(rack(T, P, "nine", n_envs=200, seed=3), phi=np.pi / 2, draw=0.3, a=0.1, b=-0.2, params=P)
    small = strike(rack(T, P, "nine", n_envs=37, seed=4), phi=1.4, draw=0.2, a=-0.2, b=0.3, params=P)
    monkeypatch.setattr(S, "KEEP_SCRATCH_BYTES", 0)  # nothing kept: every call allocates its own
    monkeypatch.setattr(S, "_kept", type(S._kept)())
    fresh = simulate(small, T, P)
    monkeypatch.undo()
    simulate(big, T, P)  # leaves its values in the kept buffers
    kept = S._kept.event
    assert kept.tt.shape[0] >= 200
    again = simulate(small, T, P)
    assert S._kept.event is kept  # rows of the same buffers
    assert _same(fresh, again)


def test_kept_scratch_is_per_thread():
    """Simulating in two threads at once (each its own kept scratch) gives
    each the result it gets alone."""
    import threading
    P, T = PhysicsParams.standard(), Table.pool(9)
    shots = [strike(rack(T, P, "nine", n_envs=60, seed=s), phi=1.5 + 0.1 * s, draw=0.3, a=0.0, b=0.1, params=P)
             for s in range(2)]
    alone = [simulate(s, T, P) for s in shots]
    got = [None, None]

    def work(k):
        for _ in range(5):
            got[k] = simulate(shots[k], T, P)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert all(_same(a, g) for a, g in zip(alone, got))
