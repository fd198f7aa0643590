"""What the break does: seeded breaks of a bot on fresh racks, and their
outcome statistics (balls pocketed, the game's ball on the break, legal
breaks, scratches), for comparing racks (``GameConfig.rack``), noise levels
and the 9-on-the-break rule (``break_nine``). ``scripts/break_stats.py``
prints and saves the table."""
from __future__ import annotations

import numpy as np

from ..bots import make_bot
from ..envs.games import GameConfig, GameCore
from ..envs.games.play import play_round
from ..rules import DEFAULT_GAME, get_game
from .stats import wilson_interval


def break_outcomes(game: str = DEFAULT_GAME, n_racks: int = 500, seed: int = 0, noise: str = "none",
                   bot: str = "ghost", **config) -> dict:
    """One break by ``bot`` on each of ``n_racks`` seeded racks (the seeds of
    ``studies.matches.play_pairing``, so the racks are the matches' racks);
    ``config``: more ``GameConfig`` fields (``rack``, ``break_nine``).
    Returns the rates with 95% Wilson intervals and the mean balls pocketed. The game must have a game ball
    (its rules' ``game_ball``: the pool games)."""
    game_ball = get_game(game).rules.game_ball
    if not game_ball:
        raise ValueError(f"{game} has no game ball (its rules' game_ball is 0): break_outcomes studies the pool games")
    cfg = GameConfig(game=game, noise=noise, **config)
    core = GameCore(cfg, n_racks)
    idx = np.arange(n_racks)
    core.streams.seed(idx, seed * 1_000_003 + idx)
    core.reset_tables(idx, np.zeros(n_racks, dtype=np.int64))
    b = make_bot(bot, seed)
    info = play_round(core, [b, b], idx)["info"]
    pocketed = info["pocketed"]
    objects = pocketed[:, 1:].sum(axis=1)
    rates = {"pockets a ball": objects > 0, "game ball down": pocketed[:, game_ball],
             "breaker wins": info["game_over"] & (info["winner"] == 0), "legal": info["legal"],
             "scratch": pocketed[:, 0], "breaker shoots on": ~info["turn_over"] & ~info["game_over"]}
    out = dict(game=game, noise=noise, racks=n_racks, seed=seed, bot=bot, config=dict(config),
               mean_pocketed=float(objects.mean()))
    for k, v in rates.items():
        x = int(np.count_nonzero(v))
        out[k] = dict(rate=x / n_racks, ci95=list(wilson_interval(x, n_racks)))
    return out
