"""The event solver's cheap paths: lazy evolution (a ball is evolved only
when an event involves it) and the pocket neighbourhoods of the boundary
broad phase must give the results of evolving every ball at every event and
of testing every boundary element."""
import math

import numpy as np

from billiards_env.physics import BallState, PhysicsParams, Table, simulate, strike_velocity
from billiards_env.physics.table import POCKET_GROUP_RADIUS, pocket_groups


def test_pool_pocket_groups_hold_every_jaw_and_tip_once():
    T = Table.pool(9)
    g = T.groups(True)
    # the six rails are always tested; the twelve jaws and tips belong to pockets
    assert sorted(g.rails) == [0, 3, 6, 9, 12, 15]
    assert len(g.free_tips) == 0
    segs = sorted(s for s in g.gsegs.ravel() if s >= 0)
    tips = sorted(v for v in g.gtips.ravel() if v >= 0)
    assert segs == sorted(set(range(18)) - set(g.rails))
    assert tips == list(range(12))
    for k, (cx, cy, r) in enumerate(T.pockets):
        x0, x1, y0, y1 = g.near[k]
        assert x0 <= cx - r and cx + r <= x1 and y0 <= cy - r and cy + r <= y1
        for s in g.gsegs[k][g.gsegs[k] >= 0]:
            for x, y in (T.segments[s, :2], T.segments[s, 2:]):
                assert x0 <= x <= x1 and y0 <= y <= y1
                assert math.hypot(x - cx, y - cy) < POCKET_GROUP_RADIUS
        for v in g.gtips[k][g.gtips[k] >= 0]:
            assert x0 <= T.tips[v, 0] <= x1 and y0 <= T.tips[v, 1] <= y1


def test_segments_far_from_pockets_are_rails():
    # a lone short segment in mid-table is near no pocket: always tested
    segs = np.array([[0.5, 1.0, 0.6, 1.0]])
    tips = np.array([[0.5, 1.0], [0.0, 0.05]])
    pockets = np.array([[0.0, 0.0, 0.05]])
    g = pocket_groups(segs, tips, pockets)
    assert list(g.rails) == [0]
    assert list(g.free_tips) == [0]
    assert list(g.gtips[0][g.gtips[0] >= 0]) == [1]


def _shots(n, P, rng):
    """Two-ball shots with spin, aimed anywhere around a full hit, at speeds
    that reach the cushions and the pockets."""
    cue = np.column_stack([rng.uniform(0.2, 1.07, n), rng.uniform(0.3, 1.0, n)])
    obj = cue + np.column_stack([rng.uniform(-0.2, 0.2, n), rng.uniform(0.3, 0.8, n)])
    d = obj - cue
    phi = np.arctan2(d[:, 1], d[:, 0]) + rng.uniform(-1, 1, n) * np.arcsin(P.R / np.linalg.norm(d, axis=1))
    s = BallState.from_positions(np.stack([cue, obj], axis=1))
    return strike_velocity(s, phi, rng.uniform(1.0, 5.0, n), rng.uniform(-0.4, 0.4, n), rng.uniform(-0.4, 0.4, n), P)


def test_lazy_evolution_matches_evolving_every_ball_at_every_event():
    # With diagnostics on, the solver brings every ball to every event's
    # time (the diagnostics check the whole table); without, only the balls
    # an event involves. Both must end in the same state up to rounding.
    P, T = PhysicsParams.standard(), Table.pool(9)
    s = _shots(64, P, np.random.default_rng(7))
    lazy = simulate(s, T, P)
    eager = simulate(s, T, P, diagnostics=True)
    assert np.mean(lazy.n_events) > 5  # the shots do something
    assert np.array_equal(lazy.n_events, eager.n_events)
    assert np.array_equal(lazy.state.pocket, eager.state.pocket)
    assert (lazy.state.pocket >= 0).any()  # some shots reach the pockets
    on = lazy.state.pocket < 0
    assert np.abs(lazy.state.pos - eager.state.pos)[on].max() < 1e-9
    assert np.allclose(lazy.time, eager.time, rtol=0, atol=1e-9)
