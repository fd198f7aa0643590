"""The three-cushion bot (bots.carom, name carom<K>) through the bot API and the match harness."""
import numpy as np
import pytest

from billiards_env.bots import make_bot
from billiards_env.bots.carom import CaromBot
from billiards_env.bots.registry import is_bot_name
from billiards_env.envs.games import GameConfig, GameCore


def test_registered_by_name():
    assert is_bot_name("carom") and is_bot_name("carom16") and not is_bot_name("carom-x")
    bot = make_bot("carom16", seed=3)
    assert isinstance(bot, CaromBot) and bot.k == 16 and bot.name == "carom16"
    with pytest.raises(ValueError, match="positive"):
        CaromBot(k=0)


def test_noise_free_estimate_is_the_previewed_outcome():
    """Without noise the bot's estimate of its chosen shot is exactly what the preview of that shot rules."""
    core = GameCore(GameConfig(game="three_cushion"), 6)
    core.streams.seed(np.arange(6), np.arange(6) + 1)
    core.reset_tables(np.arange(6))
    core.step(np.zeros((6, 8)), np.arange(6))  # leave the opening: positions of open play
    view = core.view(np.arange(6))
    bot = CaromBot(seed=0, k=48)
    plan = bot.act(view)
    pre = view.preview(plan)
    assert np.array_equal(pre.record.points > 0, bot.last_estimate == 1.0)
    assert bot.last_estimate.sum() >= 1  # 48 candidates find a point on at least one of six tables


def test_rated_by_the_match_harness_above_random():
    from billiards_env.studies.matches import play_pairing
    r = play_pairing("carom24", "random", "three_cushion", n_racks=3, seed=0, noise="tournament",
                     rule_options={"max_innings": 6})
    s = r.summary()
    assert s["games"] == 6 and s["a_points_per_inning"] > s["b_points_per_inning"]
    assert (r.innings == 6).all() or (r.winner >= 0).any()


def test_balls_in_contact_searched_from_where_they_lie_and_from_the_starting_position():
    """With the cue ball touching a ball the bot also searches the starting position a replace gives, and
    has the balls replaced only where the point found there is the likelier: the three balls frozen in a row
    on the bottom cushion (no point found from there) are replaced, the cue ball frozen to the red in the
    open is played where it lies. Without the touching ball nothing changes (the same random stream)."""
    from billiards_env.testing.positions import game_table
    R_ = 0.03075
    rows = {"row": ({0: (0.7, R_ + 1e-4), 2: (0.7 + 2 * R_, R_ + 1e-4), 1: (0.7 + 4 * R_ + 1e-4, R_ + 1e-4)}, True),
            "open": ({0: (0.6, 0.8), 2: (0.6 + 2 * R_, 0.8), 1: (0.3, 2.0)}, False)}
    for balls, replaces in rows.values():
        core = game_table("three_cushion", balls)
        view = core.view([0])
        assert view.may_replace[0] and core.observe()[0, -1] == 1.0  # the observation says it touches
        bot, lie = CaromBot(seed=0, k=192), CaromBot(seed=0, k=192, replace=False)
        plan, plan_lie = bot.act(view), lie.act(view)
        assert plan.replace[0] == replaces and not plan_lie.replace[0]
        assert bot.last_estimate[0] >= lie.last_estimate[0]
        assert (bot.last_estimate[0] > lie.last_estimate[0]) == replaces
        assert view.preview(plan).record.replaced[0] == replaces
        if not replaces:
            assert np.array_equal(plan.phi, plan_lie.phi) and np.array_equal(plan.speed, plan_lie.speed)
