"""The games' racks: ``realistic`` (seeded gaps and offsets, the default)
and ``perfect`` (every ball frozen), and the 9-on-the-break option."""
import numpy as np
import pytest

from billiards_env.envs.games import GameConfig, GameCore
from billiards_env.envs.games.setup import RACK_GAP, RACK_JITTER, loosen

GAMES = ("nine_ball", "eight_ball", "ten_ball")


def racked(game, rack, n=64, seed=3):
    core = GameCore(GameConfig(game=game, rack=rack), n)
    core.streams.seed(np.arange(n), np.arange(n) + seed)
    core.reset_tables(np.arange(n))
    return core


def neighbour_gaps(pos, R):
    """Per table: the gap to the nearest other object ball of every object ball."""
    d = np.linalg.norm(pos[:, 1:, None] - pos[:, None, 1:], axis=-1)
    d[:, np.arange(d.shape[1]), np.arange(d.shape[1])] = np.inf
    return d.min(axis=2) - 2 * R


@pytest.mark.parametrize("game", GAMES)
def test_realistic_racks_have_small_seeded_gaps_and_never_overlap(game):
    perfect, real = racked(game, "perfect"), racked(game, "realistic")
    R = real.params.R
    gp, gr = neighbour_gaps(perfect.state.pos, R), neighbour_gaps(real.state.pos, R)
    assert np.allclose(gp, 0.0, atol=1e-12)                           # frozen: every ball touches a neighbour
    assert gr.min() >= -1e-12 and gr.max() <= RACK_GAP + 2 * RACK_JITTER + 1e-12
    assert np.median(gr) > 0.2 * RACK_GAP                              # open, not frozen
    moved = np.linalg.norm(real.state.pos[:, 1:] - perfect.state.pos[:, 1:], axis=-1)
    assert moved.max() < 5 * (RACK_GAP + RACK_JITTER)                  # the same order, a sub-millimetre change
    # the breaker and the noise factor come from the same draws with either rack
    assert (real.game.shooter == perfect.game.shooter).all()
    again = racked(game, "realistic")
    assert np.array_equal(again.state.pos, real.state.pos)             # seeded


def test_loosen_keeps_the_apex_and_rejects_overlapping_sizes():
    core = racked("nine_ball", "perfect", n=2)
    pos = core.state.pos.copy()
    apex = pos[:, 1].copy()
    loosen(pos, core.table, core.params.R, np.full((2, 18), 0.0))      # zero offsets: only the stretch
    assert np.allclose(pos[:, 1], apex)
    with pytest.raises(ValueError, match="twice the jitter"):
        loosen(pos, core.table, core.params.R, np.zeros((2, 18)), gap=1e-4, jitter=1e-4)


def test_bad_rack_options_are_named():
    with pytest.raises(ValueError, match="rack must be one of"):
        GameConfig(rack="tight")
    with pytest.raises(ValueError, match="break_nine"):
        GameConfig(game="eight_ball", break_nine="spotted")
    assert GameCore(GameConfig(break_nine="spotted"), 1).rules.spot_break_nine
