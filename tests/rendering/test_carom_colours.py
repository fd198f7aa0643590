"""Three-cushion's raster images draw each ball in its owner's colour: slot 0
holds the ball of the player to move, and white is the starter's ball."""
import numpy as np

from billiards_env.envs.games import GameConfig, GameCore
from billiards_env.rendering.draw import BORDER, PPM, STYLE_BALL_COLORS, world_to_pixel
from billiards_env.rendering.game import render_game


def _colour_at(core, img, slot):
    x, y = world_to_pixel(core.table, core.state.pos[0, slot], PPM, BORDER)
    return tuple(int(v) for v in img[int(round(y)), int(round(x))])


def test_second_players_innings_draws_slot_zero_yellow():
    core = GameCore(GameConfig(game="three_cushion"), 1)
    core.streams.seed(np.array([0]), np.array([3]))
    core.reset_tables(np.array([0]))
    white, yellow = STYLE_BALL_COLORS["carom"][0], STYLE_BALL_COLORS["carom"][1]
    starter = int(core.game.breaker[0])
    assert int(core.game.shooter[0]) == starter
    img = render_game(core, 0)
    assert _colour_at(core, img, 0) == white and _colour_at(core, img, 1) == yellow
    core.game.shooter[0] = 1 - starter  # the other player's innings: their (yellow) ball is in slot 0
    img = render_game(core, 0)
    assert _colour_at(core, img, 0) == yellow and _colour_at(core, img, 1) == white
