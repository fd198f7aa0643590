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
