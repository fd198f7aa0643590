"""The play server's games in memory: at most ``limit`` of them, and a game
someone is playing is never dropped to make room.

A new game takes a free place, or the place of the game left longest
(untouched for ``idle_s``, or finished and untouched for ``finished_idle_s``);
when every game is in play the new one is refused (503, with how long until a
place may free up). A dropped game's id is remembered, so a request for it
says it was dropped (410) rather than that it never was (404).
"""
from __future__ import annotations

import collections
import math
import threading
import time

from .session import PlayError

MAX_GAMES = 32            # games kept at once (each holds a simulator, its bots and its record: a few MB)
GAME_IDLE_S = 15 * 60     # s: a game with no request this long may be dropped (a person in a game asks every shot)
FINISHED_IDLE_S = 2 * 60  # s: a finished game with no request this long may be dropped (time to save it)
GONE_REMEMBERED = 4096    # dropped games' ids kept, to say "dropped" rather than "never here" (16 bytes each)


def span(seconds: float) -> str:
    """A time in words: "40 s", "15 min"."""
    return f"{seconds:.0f} s" if seconds < 120 else f"{seconds / 60:.0f} min"


class Store:
    """At most ``limit`` games by id; ``clock``: seconds (``time.monotonic``; a test passes its own)."""

    def __init__(self, limit: int = MAX_GAMES, idle_s: float = GAME_IDLE_S, finished_idle_s: float = FINISHED_IDLE_S,
                 clock=time.monotonic):
        if int(limit) < 1:
            raise ValueError(f"the store must hold at least one game, got limit={limit}")
        self.limit, self.idle_s, self.finished_idle_s = int(limit), float(idle_s), float(finished_idle_s)
        self.clock, self.lock = clock, threading.Lock()
        self.games: collections.OrderedDict = collections.OrderedDict()  # id -> session, least recently used first
        self.used: dict[str, float] = {}                                  # id -> the clock at its last request
        self.gone: collections.OrderedDict = collections.OrderedDict()   # id -> why it was dropped

    def __len__(self) -> int:
        return len(self.games)

    # --- what may go --------------------------------------------------------------------
    def _left_for(self, gid: str, now: float) -> float:
        """Seconds until game ``gid`` may be dropped (<= 0: it may now)."""
        finished = getattr(self.games[gid], "finished", lambda: False)()
        wait = min(self.idle_s, self.finished_idle_s) if finished else self.idle_s
        return self.used[gid] + wait - now

    def _victim(self, now: float) -> str | None:
        """The game left longest among those that may go (None: every game is in play)."""
        return next((gid for gid in self.games if self._left_for(gid, now) <= 0), None)

    def drop(self, gid: str, why: str) -> None:
        """Forget game ``gid``, remembering ``why`` for whoever asks for it later."""
        with self.lock:
            self._drop(gid, why)

    def _drop(self, gid: str, why: str) -> None:
        self.games.pop(gid, None)
        self.used.pop(gid, None)
        self.gone[gid] = why
        while len(self.gone) > GONE_REMEMBERED:
            self.gone.popitem(last=False)

    # --- the store's own work -------------------------------------------------------------
    def full_problem(self) -> PlayError | None:
        """The 503 a new game gets now (None: there is a free place, or one that may be freed)."""
        with self.lock:
            return self._full_problem(self.clock())

    def _full_problem(self, now: float) -> PlayError | None:
        if len(self.games) < self.limit or self._victim(now) is not None:
            return None
        wait = max(1, math.ceil(min(self._left_for(g, now) for g in self.games)))
        return PlayError(503, f"the server is holding {self.limit} games, all of them in play (a game is dropped "
                              f"only after {span(self.idle_s)} without a request, or {span(self.finished_idle_s)} "
                              f"once finished); try again in {wait} s",
                         headers={"Retry-After": str(wait)})

    def add(self, session) -> None:
        """Keep ``session``, dropping the game left longest if the store is full; PlayError(503) if none may go."""
        with self.lock:
            now = self.clock()
            problem = self._full_problem(now)
            if problem:
                raise problem
            if len(self.games) >= self.limit:
                victim = self._victim(now)
                idle = span(now - self.used[victim])
                self._drop(victim, f"it was dropped after {idle} without a request, to make room for a new game")
            self.games[session.id] = session
            self.used[session.id] = now

    def get(self, gid: str):
        """Game ``gid`` (its last use now); PlayError 410 if it was dropped, 404 if it was never here."""
        with self.lock:
            s = self.games.get(gid)
            if s is None:
                shown = repr(gid[:40]) + ("..." if len(gid) > 40 else "")
                if gid in self.gone:
                    raise PlayError(410, f"game {shown} is no longer on this server: {self.gone[gid]}. "
                                         "Start a new game at /")
                raise PlayError(404, f"no game {shown} on this server (it was never started here, or the server "
                                     "has restarted since). Start a new game at /")
            self.games.move_to_end(gid)
            self.used[gid] = self.clock()
            return s
