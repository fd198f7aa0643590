"""Rules of two-player pool, apart from the physics: pure numpy, batched over tables.

A ruleset (``NineBallRules``, ``EightBallRules``, ``TenBallRules``, ``ThreeCushionRules``, ``SnookerRules``) turns a table before and
after a shot (``ShotInput``) into a ruling (``ShotRecord``) and the next
game state (``GameState``), and tells the next shooter what they may do
(``Constraints``). Every rule and simplification: docs/rules.md.
"""
from .common import BREAK_RAIL_BALLS, Rules, lowest_on_table
from .eight_ball import EightBallRules
from .games import DEFAULT_GAME, GAMES, GameSpec, GameWords, StudyPresets, bot_games, get_game, register_game
from .nine_ball import NineBallRules
from .placement import FOOT_SPOT, HEAD_STRING, KITCHEN_GAP
from .records import (CALL_NONE, CALL_SAFETY, END_NAMES, FOUL_NAMES, GROUP_OPEN, GROUP_SOLIDS, GROUP_STRIPES,
                      IN_HAND_ANYWHERE, IN_HAND_KITCHEN, IN_HAND_NONE, PHASE_AFTER_BREAK, PHASE_BREAK, PHASE_OPTION,
                      PHASE_PLAY, PHASE_PUSHED, Constraints, GameState, ShotInput, ShotRecord)
from .snooker import SnookerRules
from .ten_ball import TenBallRules
from .three_cushion import ThreeCushionRules

_DEFAULT: dict = {}  # each game's ruleset with its default settings, made once


def get_rules(name: str, **options) -> Rules:
    """The ruleset of a registered game by name (``nine_ball``, ``eight_ball``,
    ``ten_ball``, ``three_cushion``, ``snooker``, or one added with
    ``register_game``); ``options`` build a ruleset of the game's own settings
    (9-ball: ``spot_break_nine=True``; three-cushion: ``target``,
    ``max_innings``, ``equal_innings``)."""
    spec = get_game(name)
    if options:
        return spec.rules(**options)
    rules = _DEFAULT.get(name)
    if rules is None or type(rules) is not spec.rules:
        rules = _DEFAULT[name] = spec.rules()
    return rules


__all__ = ["BREAK_RAIL_BALLS", "Rules", "lowest_on_table", "EightBallRules", "NineBallRules", "TenBallRules", "ThreeCushionRules",
           "SnookerRules",
           "CALL_NONE", "CALL_SAFETY", "PHASE_OPTION", "END_NAMES",
           "FOUL_NAMES", "IN_HAND_ANYWHERE", "IN_HAND_KITCHEN", "IN_HAND_NONE", "Constraints", "GameState",
           "ShotInput", "ShotRecord", "DEFAULT_GAME", "GAMES", "GameSpec", "GameWords", "StudyPresets", "get_game",
           "register_game", "bot_games", "get_rules", "GROUP_OPEN", "GROUP_SOLIDS", "GROUP_STRIPES",
           "PHASE_AFTER_BREAK", "PHASE_BREAK", "PHASE_PLAY", "PHASE_PUSHED", "FOOT_SPOT", "HEAD_STRING", "KITCHEN_GAP"]
