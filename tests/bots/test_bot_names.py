"""One grammar for bot names (``bots.registry.parse_bot_name``): what the envs' ``opponent=``, ``make_bot``, the
evaluation harness's policies and the play server read."""
import pytest

from billiards_env.bots.registry import BOT_NAMES, BotName, is_bot_name, make_bot, parse_bot_name


@pytest.mark.parametrize("name,parsed", [
    ("ghost", BotName("ghost")), ("search", BotName("search")), ("search64", BotName("search", 64)),
    ("carom8", BotName("carom", 8)), ("ladder-3", BotName("ladder", 3)), ("champion", BotName("champion")),
    ("lookahead-2026.12", BotName("lookahead-2026.12")),
    ("my_bots:planner", BotName("module", target="my_bots:planner")),
    ("search0", None), ("search²", None), ("ladder-", None), ("nope", None), (42, None), ("search-1", None),
])
def test_the_grammar(name, parsed):
    assert parse_bot_name(name) == parsed and is_bot_name(name) == (parsed is not None)


def test_every_listed_name_parses_and_a_bad_one_is_named():
    for n in BOT_NAMES:
        example = n.replace("<K>", "16").replace("<k>", "1").replace("<module>:<factory>", "my_bots:planner")
        assert is_bot_name(example), n
    with pytest.raises(ValueError, match="unknown bot 'search0'"):
        make_bot("search0")
    assert make_bot("search16").k == 16


def test_champion_fast_plays_each_game_with_its_measured_player():
    """``champion-fast`` hands each game to the bot its registry entry names (``GameSpec.champion_fast``): the
    same shots as that bot with the same seed; as an env's opponent and in the AEC env by name; a game without
    one is refused naming the games it plays."""
    import gymnasium as gym
    import numpy as np

    from billiards_env.envs.games import GameConfig, GameCore
    from billiards_env.rules import GAMES
    bot = make_bot("champion-fast", seed=3)
    played = [g for g, spec in GAMES.items() if spec.champion_fast]
    assert {"nine_ball", "eight_ball", "ten_ball"} <= set(played)
    for game in played:
        core = GameCore(GameConfig(game=game), 4)
        core.streams.seed(np.arange(4), np.arange(4) + 11)
        core.reset_tables(np.arange(4))
        core.step(np.zeros((4, core.action_dim)), np.arange(4))  # past the break
        view = core.view(np.arange(4))
        mine, theirs = bot.act(view), make_bot(GAMES[game].champion_fast, seed=3).act(view)
        assert bot.player(game).name == make_bot(GAMES[game].champion_fast).name
        mine, theirs = (core.actions_of(p, np.arange(4)) if hasattr(p, "phi") else p for p in (mine, theirs))
        assert np.array_equal(mine, theirs), game
        env = gym.make(GAMES[game].env_id, opponent="champion-fast")
        env.reset(seed=1)
        for _ in range(3):
            *_, term, trunc, _ = env.step(env.action_space.sample())
            if term or trunc:
                env.reset()
    with pytest.raises(ValueError, match="champion-fast plays nine_ball, eight_ball, ten_ball; .*'snooker'"):
        bot.player("snooker")
