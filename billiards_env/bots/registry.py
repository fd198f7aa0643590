"""Bots by name: what the envs' ``opponent=``, ``scripts/match.py`` and the
games benchmark accept.

- ``random``, ``ghost``, ``ghost-safety``, ``search<K>`` (K candidates per
  pot, default 64), ``lookahead`` (``bots.game_lookahead``: shots chosen by
  their leave under sampled noise): the built-in bots of the games (the
  one-player tasks' ``lookahead`` is ``bots.lookahead.LookaheadPolicy``,
  named by the tasks' own policy registry);
- ``lookahead-2026.12``: ``lookahead`` frozen as it was on 2026-12-07 (``GameLookahead()`` with that day's
  default ``Budget``, every field spelled out in ``FROZEN_LOOKAHEAD``), the fixed yardstick later changes are
  measured against;
- ``champion`` (``bots.planner.Champion``): Monte-Carlo over throw-corrected pots aimed into pocket windows
  measured in the simulator, safeties and kicks, candidates judged by successive halving under noise
  (docs/games.md#champion);
- ``snooker`` (``bots.snooker.SnookerBot``): pots on the ball on with its
  nomination, safeties and a break-off chosen in the preview (snooker only);
- ``carom<K>`` (K candidate strikes per table, default 96): the
  three-cushion bot (``bots.carom``: paths searched in the simulator, scored
  by the point's probability under noise);
- ``ladder-<k>`` (``bots.learned.ladder``): the k-th shipped learned agent
  of the game it is handed, weakest first (numpy only; no torch);
- ``value-lookahead`` (``bots.learned.value``): ``lookahead`` ranking its leaves by the shipped learned
  value of the game it is handed (trained by ``agents.league``, docs/league.md);
- ``exit-search`` and ``exit-fast`` (``bots.learned.proposal_bot``): the search over the shipped Expert Iteration
  network's shot proposals, and its distilled network alone (trained by ``agents.exit``, docs/expert_iteration.md;
  9-ball only so far);
- ``champion-fast`` (``bots.champion_fast``): the strongest player without search of the game it is handed,
  by measurement (the game's registry entry names it, ``GameSpec.champion_fast``; docs/ladder.md#champion-fast);
- ``module:factory`` (for example ``my_bots:planner``): a bot of your own;
  ``factory(seed=...)`` must return an object with ``name`` and
  ``act(view: GameView) -> ShotPlan`` (docs/bots.md);
- a bot object (anything with ``act``) is used as it is.
"""
from __future__ import annotations

import dataclasses
import importlib
import re

from ..rules import get_game

BOT_NAMES = ("random", "ghost", "ghost-safety", "search<K>", "lookahead", "lookahead-2026.12", "champion", "carom<K>",
             "snooker", "ladder-<k>", "value-lookahead", "exit-search", "exit-fast", "champion-fast", "<module>:<factory>")
DEFAULT_SEARCH_K = 64
# ``lookahead-2026.12``: the Budget of ``lookahead`` on 2026-12-07, spelled out so later changes to the defaults
# do not move the yardstick (bots.game_lookahead.Budget's fields; REPLY_BUDGET as it was that day)
FROZEN_LOOKAHEAD = dict(
    n_pots=6, hand_pots=3, n_safe=16, n_kick=8, n_bank=16, n_push=24, n_eval=32, n_eval_safe=8, n_samples=12,
    throws=(0.0, 0.03490658503988659), speeds=(1.1, 1.5, 2.2, 3.2), heights=(-0.35, 0.0, 0.35),
    sigma_model=0.012, v_none=0.5, v_full=0.9, q_run=0.0, combos=False, w_next=0.0, break_search=128,
    break_racks=16, break_samples=2, reply_eval=6, reply_safe=4, reply_samples=8, reply_keep=False,
    # the opponent's reply search: that day's REPLY_BUDGET, every field given as a change so it stays put
    reply=(("n_pots", 3), ("hand_pots", 2), ("n_safe", 6), ("n_kick", 2), ("n_bank", 4), ("n_push", 0),
           ("n_eval", 8), ("n_eval_safe", 2), ("n_samples", 8), ("throws", (0.0,)), ("speeds", (1.15, 1.8, 2.8)),
           ("break_search", 0), ("reply_eval", 0)))
# fields of the frozen Budget that were off that day; a later Budget without them plays the same
FROZEN_OFF = dict(q_run=0.0, combos=False, w_next=0.0)


def frozen_budget():
    """``lookahead-2026.12``'s ``Budget``: ``FROZEN_LOOKAHEAD``, less the ``FROZEN_OFF`` fields (off that day) a
    later ``Budget`` no longer has."""
    import dataclasses

    from .game_lookahead import Budget
    known = {f.name for f in dataclasses.fields(Budget)}
    gone = set(FROZEN_LOOKAHEAD) - known
    if gone - set(FROZEN_OFF) or any(FROZEN_LOOKAHEAD[k] != FROZEN_OFF[k] for k in gone):
        raise RuntimeError(f"lookahead-2026.12: Budget lost the fields {sorted(gone)} it was played with")
    return Budget(**{k: v for k, v in FROZEN_LOOKAHEAD.items() if k in known})


def default_bot(game: str) -> str:
    """The name of the bot that plays ``game`` by default: its registry entry's ``default_bot``."""
    return get_game(game).default_bot


FIXED_NAMES = ("random", "ghost", "ghost-safety", "lookahead", "lookahead-2026.12", "champion", "snooker",
               "value-lookahead", "exit-search", "exit-fast", "champion-fast")
COUNTED = ("search", "carom")  # name<K>: K candidates per table (no K: the bot's default)
_NAME = re.compile(r"(?P<counted>search|carom)(?P<k>[0-9]*)|ladder-(?P<rung>[0-9]+)|(?P<module>[\w.]+):(?P<attr>\w+)")


@dataclasses.dataclass(frozen=True)
class BotName:
    """A bot name read by the one grammar every name-taking place uses (``parse_bot_name``): ``family`` (a fixed
    name, ``search``, ``carom``, ``ladder`` or ``module``), ``k`` (``search<K>``'s and ``carom<K>``'s K, None for
    the default; ``ladder-<k>``'s rung) and ``target`` (``module:factory``)."""

    family: str
    k: int | None = None
    target: str | None = None


def parse_bot_name(name) -> BotName | None:
    """The ``BotName`` of ``name``, or None if it names no bot: a fixed name (``FIXED_NAMES``), ``search<K>`` or
    ``carom<K>`` (K in ASCII digits, at least 1), ``ladder-<k>`` or ``module:factory``."""
    if not isinstance(name, str):
        return None
    if name in FIXED_NAMES:
        return BotName(name)
    m = _NAME.fullmatch(name)
    if m is None:
        return None
    if m["counted"]:
        k = int(m["k"]) if m["k"] else None
        return None if k == 0 else BotName(m["counted"], k)
    if m["rung"]:
        return BotName("ladder", int(m["rung"]))
    return BotName("module", target=name)


def is_bot_name(name) -> bool:
    """Whether ``name`` names a built-in bot or a ``module:factory`` (``parse_bot_name``)."""
    return parse_bot_name(name) is not None


def make_bot(spec, seed: int = 0):
    """The bot of ``spec`` (see the module docstring), seeded with ``seed``."""
    if hasattr(spec, "act"):
        return spec
    if not isinstance(spec, str):
        raise TypeError(f"a bot is a name, a 'module:factory' string or an object with act(view); got {spec!r}")
    name = parse_bot_name(spec)
    if name is None:
        raise ValueError(f"unknown bot {spec!r}; choose one of {BOT_NAMES}")
    family = name.family
    if family == "random":
        from .random_bot import RandomBot
        return RandomBot(seed=seed)
    if family in ("ghost", "ghost-safety"):
        from .ghost import GhostBot
        return GhostBot(seed=seed, safety=family == "ghost-safety")
    if family == "snooker":
        from .snooker import SnookerBot
        return SnookerBot(seed=seed)
    if family == "lookahead":
        from .game_lookahead import GameLookahead
        return GameLookahead(seed=seed)
    if family == "lookahead-2026.12":
        from .game_lookahead import GameLookahead
        bot = GameLookahead(seed=seed, budget=frozen_budget())
        bot.name = "lookahead-2026.12"
        return bot
    if family == "champion":
        from .planner import Champion
        return Champion(seed=seed)
    if family == "value-lookahead":
        from .learned.value import value_lookahead
        return value_lookahead(seed=seed)
    if family in ("exit-search", "exit-fast"):
        from .learned.proposal_bot import exit_fast, exit_search
        return (exit_search if family == "exit-search" else exit_fast)(seed=seed)
    if family == "champion-fast":
        from .champion_fast import ChampionFast
        return ChampionFast(make_bot, seed=seed)
    if family == "search":
        from .search import SearchBot
        return SearchBot(seed=seed, k=name.k or DEFAULT_SEARCH_K)
    if family == "carom":
        from .carom import DEFAULT_K, CaromBot
        return CaromBot(seed=seed, k=name.k or DEFAULT_K)
    if family == "ladder":
        from .learned.ladder import LadderBot
        return LadderBot(spec, seed=seed)
    return _user_bot(spec, seed)


def _user_bot(spec: str, seed: int):
    mod_name, _, attr = spec.partition(":")
    try:
        mod = importlib.import_module(mod_name)
    except ImportError as exc:
        raise ValueError(f"bot {spec!r}: cannot import module {mod_name!r} ({exc}); is it on PYTHONPATH?") from exc
    factory = getattr(mod, attr, None)
    if factory is None:
        raise ValueError(f"bot {spec!r}: module {mod_name!r} has no attribute {attr!r}")
    bot = factory(seed=seed)
    if not hasattr(bot, "act"):
        raise TypeError(f"bot {spec!r}: {attr}(seed=...) returned {type(bot).__name__}, which has no act(view)")
    if not getattr(bot, "name", None):
        bot.name = spec
    return bot
