"""Placement and respotting are written once (physics.state) and every
caller keeps its own random stream: the shared sampler reproduces, draw for
draw, the generator-driven placement and the scene respotting they replaced
(references below: the former implementations, verbatim in logic)."""
from __future__ import annotations

import numpy as np
import pytest

from billiards_env.physics import BallState, PhysicsParams, Table, random_placement
from billiards_env.studies.scenes import respot_cue

P = PhysicsParams.standard()


def reference_random_placement(table, params, n_balls, n_envs=1, *, seed=None, margin=0.0, max_tries=10_000):
    rng = seed if isinstance(seed, np.random.Generator) else np.random.default_rng(seed)
    R = params.R
    lo = np.array([R + margin, R + margin])
    hi = np.array([table.width - R - margin, table.length - R - margin])
    pos = np.empty((n_envs, n_balls, 2))
    for e in range(n_envs):
        placed = tries = 0
        while placed < n_balls:
            tries += 1
            if tries > max_tries:
                raise ValueError("could not place")
            p = rng.uniform(lo, hi)
            if placed and np.min(np.hypot(*(pos[e, :placed] - p).T)) < 2 * R + margin:
                continue
            if not table.contains(p[None], R + margin, 0.0)[0]:
                continue
            pos[e, placed] = p
            placed += 1
    return pos


def reference_respot_cue(state, table, params):
    out = state.copy()
    R, w, l = params.R, table.width, table.length
    cands = [(w / 2, l / 4)]
    for k in range(1, 200):
        for sgn in (1, -1):
            cands.append((w / 2 + sgn * k * 0.01, l / 4))
    for k in range(1, 200):
        cands.append((w / 2, l / 4 - k * 0.005))
    for e in np.nonzero(out.pocket[:, 0] >= 0)[0]:
        on = out.pocket[e] < 0
        on[0] = False
        others = out.pos[e, on]
        for c in cands:
            c = np.array(c)
            if not table.contains(c[None], R + 1e-6, 0.0)[0]:
                continue
            if len(others) == 0 or np.min(np.hypot(*(others - c).T)) > 2 * R + 1e-6:
                out.pos[e, 0] = c
                out.pocket[e, 0] = -1
                break
    return out.pos, out.pocket


@pytest.mark.parametrize("table", [Table.pool(9), Table.pool(7), Table.pocketless(1.0, 2.0)], ids=lambda t: t.name)
def test_random_placement_reproduces_the_generator_stream(table):
    for seed in range(40):
        for n_balls, margin in ((2, 0.01), (6, 0.0), (16, 0.005)):
            rng_a, rng_b = np.random.default_rng(seed), np.random.default_rng(seed)
            new = random_placement(table, P, n_balls, 3, seed=rng_a, margin=margin).pos
            ref = reference_random_placement(table, P, n_balls, 3, seed=rng_b, margin=margin)
            np.testing.assert_array_equal(new, ref)
            assert rng_a.random() == rng_b.random()  # the generator advanced by exactly as much


def test_random_placement_gives_up_after_max_tries():
    with pytest.raises(ValueError, match="could not place 30 balls"):
        random_placement(Table.pocketless(0.3, 0.3), P, 30, seed=0, max_tries=500)


def test_respot_cue_matches_the_former_search():
    table = Table.pool(9)
    R, w, l = P.R, table.width, table.length
    rng = np.random.default_rng(0)
    for trial in range(60):
        s = random_placement(table, P, 8, 4, seed=rng, margin=0.0)
        pos, pocket = s.pos.copy(), s.pocket.copy()
        pocket[:, 0] = 2
        # crowd the head spot and the head string so the search has to walk
        k = rng.integers(0, 6, size=4)
        for e in range(4):
            for j in range(1, 1 + k[e]):
                pos[e, j] = (w / 2 + (j - 3) * 2.05 * R * rng.choice([0.5, 1.0]), l / 4 + rng.normal(0, 0.01))
        s = BallState.from_positions(pos, pocket)
        new = respot_cue(s, table, P)
        ref_pos, ref_pocket = reference_respot_cue(s, table, P)
        np.testing.assert_array_equal(new.pos, ref_pos)
        np.testing.assert_array_equal(new.pocket, ref_pocket)
