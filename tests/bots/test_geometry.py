"""The ghost-ball geometry (billiards_env.bots.geometry): the construction's
closed forms, the blocked-path test, and the batched shots and the game
bots' kernels agreeing on the same tables."""
import math

import numpy as np
import pytest

from billiards_env.bots import geometry as G
from billiards_env.bots.geometry import lines
from billiards_env.physics import PhysicsParams, Table

TABLE, PARAMS = Table.pool(9), PhysicsParams()
R = PARAMS.R


@pytest.mark.parametrize("r", [2 * R, 2 * R + 0.005, 0.1, 1.0, 3.0e-3])
def test_sqrt_test_d2_is_the_sqrt_comparison(r):
    """``s < sqrt_test_d2(r)`` == ``sqrt(s) < r`` on the doubles around r^2 and at random."""
    t = lines.sqrt_test_d2(r)
    s = [r * r]
    for _ in range(64):
        s = [math.nextafter(s[0], 0.0)] + s + [math.nextafter(s[-1], math.inf)]
    s += list(np.random.default_rng(0).uniform(0, 4 * r * r, 2000))
    assert all((x < t) == (math.sqrt(x) < r) for x in s)


def test_line_length_rounds_as_numpy_norm():
    v = np.random.default_rng(1).uniform(-3, 3, (20000, 2))
    got = np.array([lines.line_length(x, y) for x, y in v])
    assert np.array_equal(got, np.linalg.norm(v, axis=1))


def test_ghost_ball_closed_form():
    """Object ball at (1, 1), aim point (1, 2): the ghost ball sits 2R below
    the ball; from the cue ball at (0, 1 - 2R) the cut is 90 deg minus nothing
    (a path along +x meets a path along +y at 90 deg), from (1, 0) it is 0."""
    ux, uy, gx, gy = lines.ghost_ball(1.0, 1.0, 1.0, 2.0, R, 1.0)
    assert (ux, uy) == (0.0, 1.0) and gx == 1.0 and gy == pytest.approx(1.0 - 2 * R, abs=1e-15)
    pos = np.array([[[1.0, 0.3], [1.0, 1.0]], [[0.3, 1.0 - 2 * R], [1.0, 1.0]],
                    [[1.0 - math.cos(0.5), 1.0 - 2 * R - math.sin(0.5)], [1.0, 1.0]]])
    aims = np.array([[1.0, 2.0]])
    d_cg = math.hypot(pos[0, 1, 0] - pos[0, 0, 0], pos[0, 1, 1] - 2 * R - pos[0, 0, 1])
    out = dict(cost=np.empty(3), phi=np.zeros(3), d_cg=np.zeros(3), d_op=np.zeros(3), cut=np.zeros(3),
               pocket=np.zeros(3, dtype=np.int64), ball=np.zeros(3, dtype=np.int64))
    G.best_pots(pos, np.ones((3, 2), bool), np.array([[False, True]] * 3), aims, np.array([[0.0, -1.0]]),
                np.array([math.pi]), G.PotLimits(R, 0.0, math.pi, 0.5), out)
    assert out["cut"] == pytest.approx([0.0, math.pi / 2, math.pi / 2 - 0.5], abs=1e-7)
    assert out["d_op"] == pytest.approx([1.0] * 3) and out["d_cg"][0] == pytest.approx(d_cg)
    assert out["phi"] == pytest.approx([math.pi / 2, 0.0, 0.5])


def test_blocked_path():
    """A ball within sqrt(d2) of the segment blocks it; one just beyond, the
    cue ball, the skipped balls and balls off the table do not."""
    pos = np.array([[0.0, 0.0], [1.0, 0.0], [0.5, 2 * R - 1e-9], [0.5, 0.0], [0.5, -0.01]])
    on = np.array([True, True, True, True, False])
    d2 = (2 * R) ** 2
    assert lines.blocked(pos, on, 1, 3, 0.0, 0.0, 1.0, 0.0, d2)
    pos[2, 1] = 2 * R + 1e-9
    assert not lines.blocked(pos, on, 1, 3, 0.0, 0.0, 1.0, 0.0, d2)
    assert lines.blocked(pos, on, 1, -1, 0.0, 0.0, 1.0, 0.0, d2)       # ball 3 on the path
    assert lines.seg_dist2(0.0, 0.0, 1.0, 0.0, 1.5, 0.0) == pytest.approx(0.25)  # past the end: to b
    assert lines.seg_dist2(0.0, 0.0, 0.0, 0.0, 0.3, 0.4) == pytest.approx(0.25)  # a point segment


def test_batched_shots_and_game_kernel_agree():
    """On random 9-ball tables with one legal target, the game kernel's best
    pot (no clearance beyond 2R, cut below 88 deg, the pockets' acceptance
    limits) is ``choose_pocket``'s pocket of the batched shots, with the same
    aim and distances up to rounding."""
    rng = np.random.default_rng(3)
    E, B = 2000, 10
    pos = np.stack([rng.uniform(R, TABLE.width - R, (E, B)), rng.uniform(R, TABLE.length - R, (E, B))], -1)
    on = rng.random((E, B)) > 0.3
    on[:, :2] = True
    tgt = np.ones(E, dtype=np.int64)
    sh = G.ghost_shots(pos, on, tgt, TABLE, PARAMS, 0.0)
    side = G.side_pocket_mask(TABLE)
    k = G.choose_pocket(sh, dist_weight=0.5, side_mask=side)
    has = G.open_pots(sh, side).any(axis=1)
    limits = G.pocket_limits(TABLE, math.radians(60.0), math.radians(50.0))
    out = dict(cost=np.empty(E), phi=np.zeros(E), d_cg=np.zeros(E), d_op=np.zeros(E), cut=np.zeros(E),
               pocket=np.zeros(E, dtype=np.int64), ball=np.zeros(E, dtype=np.int64))
    targets = np.zeros((E, B), bool)
    targets[:, 1] = True
    G.best_pots(pos, on, targets, np.ascontiguousarray(G.pocket_aim_points(TABLE, 0.0)),
                np.ascontiguousarray(G.pocket_axes(TABLE)), limits, G.PotLimits(R, 0.0, math.radians(88.0), 0.5), out)
    assert 0.2 < has.mean() < 0.95
    assert np.array_equal(np.isfinite(out["cost"]), has)
    ar = np.nonzero(has)[0]
    assert np.array_equal(out["pocket"][ar], k[ar])
    for name in ("phi", "d_cg", "d_op", "cut"):
        assert np.allclose(out[name][ar], sh[name][ar, k[ar]], rtol=0, atol=1e-7)
