"""The game envs' action convention (``contract.codec.ActionCodec``): what a
view's codec encodes is what the env's step decodes, placements and aims
included, on tables in every phase of a game."""
import math

import numpy as np
import pytest

from billiards_env.bots import ShotPlan, make_bot
from billiards_env.envs.games import GameConfig, GameCore
from billiards_env.envs.games.play import play_round
from billiards_env.physics.strike import Shots, draw_to_speed

N = 64


def _played_core(game: str, rounds: int) -> GameCore:
    core = GameCore(GameConfig(game=game, noise="none", max_shots=60), N)
    every = np.arange(N)
    core.streams.seed(every, 11 + every)
    core.reset_tables(every)
    bots = [make_bot("random", 1), make_bot("random", 2)]
    for _ in range(rounds):
        out = play_round(core, bots, every)
        done = np.nonzero(out["terminated"] | out["truncated"])[0]
        if len(done):
            core.reset_tables(done)
    return core


@pytest.mark.parametrize("game", ["nine_ball", "eight_ball", "ten_ball"])
@pytest.mark.parametrize("rounds", [0, 3])
def test_encoded_plans_decode_to_the_same_shots(game, rounds):
    core = _played_core(game, rounds)
    idx = np.arange(N)
    view = core.view(idx)
    rng = np.random.default_rng(5)
    p = core.params
    lo = draw_to_speed(core.config.min_draw, p)
    shots = Shots(rng.uniform(-math.pi, math.pi, N), rng.uniform(lo, p.max_speed, N),
                  rng.uniform(-0.3, 0.3, N), rng.uniform(-0.3, 0.3, N))
    want = np.column_stack([rng.uniform(0, core.table.width, N), rng.uniform(0, core.table.length, N)])
    plan = ShotPlan.of(shots, placement=want)
    a = view.codec.encode(plan.shots, plan.placement)
    assert a.shape == (N, core.action_dim) and np.all(np.abs(a) <= 1.0)
    # the same actions through the env's decoding
    hand = view.in_hand
    spots_plan, _ = view.legal_placement(want[hand], np.nonzero(hand)[0])
    spots_env, _ = core.legal_placement(core.codec(idx).placement_of(a[hand]), idx[hand])
    assert np.allclose(spots_env, spots_plan, atol=1e-9)
    if hand.any():
        core.state.pos[idx[hand], 0] = spots_env
        core.state.pocket[idx[hand], 0] = -1
        core._changed()
    decoded = core.actions_to_shots(np.ascontiguousarray(a[:, :4]), idx)
    dphi = (decoded.phi - shots.phi + math.pi) % (2 * math.pi) - math.pi
    assert np.max(np.abs(dphi)) < 1e-9
    assert np.allclose(decoded.speed, shots.speed, rtol=1e-9)
    assert np.allclose(decoded.a, shots.a) and np.allclose(decoded.b, shots.b)


def test_a_taken_views_codec_is_the_codec_of_its_rows():
    core = _played_core("nine_ball", 2)
    view = core.view(np.arange(N))
    rows = np.array([3, 0, 17, 40])
    sub, direct = view.take(rows).codec, core.codec(rows)
    assert np.array_equal(sub.origin, direct.origin) and np.array_equal(sub.aim_point, direct.aim_point)
    shots = Shots(np.full(4, 0.3), np.full(4, 2.0), np.zeros(4), np.zeros(4))
    place = np.tile([0.5, 0.6], (4, 1))
    assert np.array_equal(sub.encode(shots, place), direct.encode(shots, place))
