"""``champion-fast``: the strongest player without search of each game, at most 2 ms of CPU a shot.

Which bot that is, is a measurement, not a design: the game's registry entry names it
(``rules.games.GameSpec.champion_fast``), and docs/ladder.md#champion-fast gives the matches that chose it. The bot
of a game is made on its first view and kept (seeded with this bot's seed); a game without one (snooker and
three-cushion, whose own bots search) is refused, naming the games it plays.
"""
from __future__ import annotations

from ..rules import GAMES, get_game
from .serial import serial_act


class ChampionFast:
    """See the module docstring."""

    name = "champion-fast"

    def __init__(self, make, seed: int = 0):
        self.make, self.seed = make, seed  # make(name, seed=...): the bot of a name (bots.registry.make_bot)
        self.players: dict = {}  # game -> its bot, made on first use

    def player(self, game: str):
        """The bot that plays ``game`` (made on first use)."""
        if game not in self.players:
            name = get_game(game).champion_fast
            if name is None:
                games = ", ".join(g for g, spec in GAMES.items() if spec.champion_fast)
                raise ValueError(f"champion-fast plays {games}; no player without search is measured for {game!r}")
            self.players[game] = self.make(name, seed=self.seed)
        return self.players[game]

    @serial_act
    def act(self, view):
        return self.player(view.game).act(view)
