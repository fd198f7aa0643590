"""The one loop that lets bots play on a ``GameCore``: the versus env, the
match harness, the games benchmark and the renderer all go through it.

``bot_actions`` asks one bot for its shots on some tables (through the
tables' ``GameView``) and turns its ``ShotPlan`` into the env's actions;
``play_round`` shoots every given table once, each by the bot of its player
to move, in one simulator call; ``play_out`` repeats rounds until every
given table's game is over (or cut at the shot cap).
"""
from __future__ import annotations

import time

import numpy as np


def bot_actions(core, bot, idx) -> np.ndarray:
    """The actions [n, action_dim] of ``bot`` on tables ``idx`` (its player is to move on each)."""
    idx = np.asarray(idx, dtype=np.int64)
    view = core.view(idx)
    return core.actions_of(bot.act(view), idx, view.codec)


def play_round(core, bots, idx, clock: dict | None = None) -> dict:
    """One shot on every table ``idx`` by ``bots[player to move]`` (a list or
    dict by player number; a missing player's tables are an error), all in
    one ``core.step``. ``clock``: adds the seconds spent in the bots under
    ``"bots"``. Returns the step's output."""
    idx = np.asarray(idx, dtype=np.int64)
    to_move = core.constraints().shooter[idx]
    actions = np.zeros((len(idx), core.action_dim))
    t0 = time.perf_counter()
    for p in (0, 1):
        m = np.nonzero(to_move == p)[0]
        if len(m):
            actions[m] = bot_actions(core, bots[p], idx[m])
    if clock is not None:
        clock["bots"] = clock.get("bots", 0.0) + time.perf_counter() - t0
    return core.step(actions, idx)


def play_out(core, bots, idx, on_shot=None) -> None:
    """Rounds of ``play_round`` on tables ``idx`` until every game there has
    ended; ``on_shot(out, tables)`` is called after each round."""
    live = np.asarray(idx, dtype=np.int64)
    while len(live):
        out = play_round(core, bots, live)
        if on_shot is not None:
            on_shot(out, live)
        live = live[~(out["terminated"] | out["truncated"])]
