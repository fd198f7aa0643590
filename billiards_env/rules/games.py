"""The games' registry: one ``GameSpec`` per two-player game, the one place a
game is named.

A spec holds the game's ruleset (its class: ``rules.common.Rules``), its
rack, the bot that plays it when none is named, its Gymnasium id stem and
class names, and its vocabulary (``GameWords``: the balls' names, what a call
is, whether it is played to points). Everything else reads the registry:
``rules.get_rules``; the env classes, vector entry points and PettingZoo
classes of ``envs.games``, which are generated from it, and the Gymnasium
ids; the words on the play page, in replays and in the renderer. Adding a
game is one rules module and one ``register_game`` call
(docs/adding_a_game.md; ``tests/envs/test_toy_game.py`` proves it with a toy
game defined in the test suite).
"""
from __future__ import annotations

import dataclasses
from typing import Callable

from .eight_ball import EightBallRules
from .nine_ball import NineBallRules
from .racks import eight_ball_rack, nine_ball_rack, snooker_opening, ten_ball_rack
from .respot import three_cushion_spots
from .snooker import SnookerRules
from .ten_ball import TenBallRules
from .three_cushion import ThreeCushionRules


@dataclasses.dataclass(frozen=True)
class GameWords:
    """How a game reads to a person.

    ``balls``: each ball's name by number (ball 0 first); empty: numbered
    pool balls ("the cue ball", "the 7"). ``colours``: where balls are named
    by colour (snooker, carom), so "the red", not "the 1". ``call``: what the
    shooter must do when the game asks for a call ("" none). ``nominates``:
    a call names a ball (snooker's nomination), not a pocket. ``points``: the
    game is played to points (snooker's frame, three-cushion), so a score
    reads in points and a result as a frame or a game won on points.
    ``pockets``: balls are pocketed (a carom game has no pockets: its shots
    read as points made or not; only its own bots and ``random`` play it)."""

    balls: tuple = ()
    colours: bool = False
    call: str = ""
    nominates: bool = False
    points: bool = False
    pockets: bool = True

    def ball(self, b: int) -> str:
        """'the cue ball', 'the 7', 'the red', 'the black'."""
        b = int(b)
        if self.balls and 0 <= b < len(self.balls):
            return f"the {self.balls[b]}"
        return "the cue ball" if b == 0 else f"the {b}"


@dataclasses.dataclass(frozen=True)
class StudyPresets:
    """How the studies play a game when told no more (``studies.games_bench``
    and the benchmark's games section, ``studies.bench``).

    ``benchmarked``: the games section times it (games per second between
    its default bots, the vector env's steps per second). ``quick_rules`` /
    ``full_rules``: the ruleset's settings (``rules(**options)``) of a quick /
    a full run's games, as (name, value) pairs. ``games_per_table``: games
    each table plays in a run (0: the run's own count)."""

    benchmarked: bool = False
    quick_rules: tuple = ()
    full_rules: tuple = ()
    games_per_table: int = 0

    def rule_options(self, quick: bool = False) -> dict:
        """The ruleset's settings of a quick (``quick``) or a full run's games."""
        return dict(self.quick_rules if quick else self.full_rules)


@dataclasses.dataclass(frozen=True)
class GameSpec:
    """One two-player game: ``name`` (``nine_ball``), ``title`` ("9-ball"),
    ``rules`` (the ruleset class; ``rules(**options)`` a ruleset with the
    game's own settings), ``rack(table, R, u) -> pos [n, B, 2]`` from
    uniforms ``u`` [n, ``rack_draws``] (the cue ball's row is the caller's to
    set in the pool games), ``default_bot`` (the bot name that plays it when
    none is named), ``own_bots`` (the bots written for it, by their
    ``bots.registry`` family: ``carom`` for ``carom<K>``; such a bot plays
    only the games that list it, and a game with bots of its own is offered
    them and ``random``, not the pool bots), ``presets`` (``StudyPresets``:
    how the studies play it), ``id_stem`` (the Gymnasium id ``Billiards-<id_stem>-v<version>``
    and the single-agent class ``<id_stem>Env``), ``class_prefix`` (the
    PettingZoo class ``<class_prefix>AECEnv``), ``summary`` (one sentence: the
    env classes' docstrings open with it), ``words`` (``GameWords``),
    ``version`` (of the id: bumped whenever a change can change a result),
    ``config_path`` (the game's default configuration, a YAML file that
    ``envs.games.GameConfig`` reads; None: ``billiards_env/envs/games/defaults/<name>.yaml``,
    package data) and ``champion_fast`` (the bot name ``champion-fast`` plays
    the game with: its strongest player without search, as measured)."""

    name: str
    title: str
    rules: Callable
    rack: Callable
    rack_draws: int
    default_bot: str
    id_stem: str
    class_prefix: str
    summary: str
    words: GameWords = GameWords()
    own_bots: tuple = ()  # bots.registry families written for this game: they play only the games that list them
    presets: StudyPresets = StudyPresets()
    version: int = 1  # the Gymnasium id's version: bumped whenever a change can change a result (docs/versions.md)
    config_path: str | None = None  # the default configuration's YAML (None: the package's envs/games/defaults/)
    champion_fast: str | None = None  # the bot ``champion-fast`` plays it with: the strongest without search, by
    #                                   measurement (docs/ladder.md#champion-fast); None: no such player yet

    @property
    def env_id(self) -> str:
        """The Gymnasium id, ``Billiards-<id_stem>-v<version>``."""
        return f"Billiards-{self.id_stem}-v{self.version}"

    def __post_init__(self):
        if not self.name.isidentifier():
            raise ValueError(f"a game's name must be an identifier (it names modules and ids), got {self.name!r}")
        if not 0 <= self.rack_draws <= MAX_RACK_DRAWS:
            raise ValueError(f"rack_draws must be between 0 and {MAX_RACK_DRAWS} (the uniforms a table's stream "
                             f"gives a rack), got {self.rack_draws}")


MAX_RACK_DRAWS = 14  # uniforms a rack may draw: GameCore.reset_tables draws 16 per new game (14 rack, breaker, noise)
GAMES: dict[str, GameSpec] = {}
DEFAULT_GAME = "nine_ball"  # the game played when none is named (the envs', the studies' and the play server's)

SNOOKER_BALLS = ("cue ball",) + ("red",) * 15 + ("yellow", "green", "brown", "blue", "pink", "black")
CAROM_BALLS = ("white", "yellow", "red")  # three-cushion: the starting player's ball, the opponent's, the red
# Three-cushion's games in the benchmark: a quick run's end after three innings; a full run's after 10 innings each
# (an innings limit, as UMB events set one): games to the default target take about 110 shots, and 3 x 1,024 of
# them took half an hour on 2 cores; one game per table.
THREE_CUSHION_PRESETS = StudyPresets(benchmarked=True, quick_rules=(("max_innings", 3),),
                                     full_rules=(("max_innings", 10),), games_per_table=1)


def register_game(spec: GameSpec, replace: bool = False) -> GameSpec:
    """Add ``spec`` to the registry (``replace``: over a game of the same name)."""
    if not isinstance(spec, GameSpec):
        raise TypeError(f"register_game takes a GameSpec, got {type(spec).__name__}")
    if spec.name in GAMES and not replace:
        raise ValueError(f"a game named {spec.name!r} is registered already (replace=True replaces it)")
    GAMES[spec.name] = spec
    return spec


def get_game(name: str) -> GameSpec:
    """The spec of a registered game."""
    try:
        return GAMES[name]
    except KeyError:
        raise ValueError(f"unknown game {name!r}; choose one of {sorted(GAMES)}") from None


def bot_games(family: str) -> tuple[str, ...]:
    """The games that list the bot family ``family`` among their ``own_bots``: the only games it plays (empty: a
    bot written for no game in particular)."""
    return tuple(name for name, spec in GAMES.items() if family in spec.own_bots)


for _spec in (
    GameSpec("nine_ball", "9-ball", NineBallRules, nine_ball_rack, 7, "ghost", "NineBall2P", "NineBall",
             "9-ball", presets=StudyPresets(benchmarked=True), champion_fast="exit-fast"),
    GameSpec("eight_ball", "8-ball", EightBallRules, eight_ball_rack, 14, "ghost", "EightBall", "EightBall",
             "8-ball", GameWords(call="call a pocket for the 8"), champion_fast="ladder-4"),
    GameSpec("ten_ball", "10-ball", TenBallRules, ten_ball_rack, 8, "ghost", "TenBall", "TenBall",
             "10-ball (a 9-component action: a8 the called ball)",
             GameWords(call="call the ball and its pocket"), presets=StudyPresets(benchmarked=True),
             champion_fast="ghost"),
    GameSpec("three_cushion", "three-cushion", ThreeCushionRules, three_cushion_spots, 1, "carom", "ThreeCushion",
             "ThreeCushion", "three-cushion", GameWords(balls=CAROM_BALLS, colours=True, points=True,
                                                         pockets=False),
             own_bots=("carom",), presets=THREE_CUSHION_PRESETS, version=3),
    GameSpec("snooker", "snooker", SnookerRules, snooker_opening, 0, "snooker", "Snooker", "Snooker",
             "a frame of snooker (WPBSA rules, docs/rules.md) on the 12 ft table (a 9-component action: a8 the "
             "nominated ball; the reward is the frame's result: +1 won, -1 lost)",
             GameWords(balls=SNOOKER_BALLS, colours=True, call="nominate the colour", nominates=True,
                       points=True), own_bots=("snooker",), version=2),
):
    register_game(_spec)
