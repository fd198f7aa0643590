"""The championship protocol: 8-ball matches under the conditions of the
2011 computer pool championship (its noise levels: the tournament noise,
five times it, and a variable level), every entrant's compute per shot
beside the results.

At each level (``LEVELS``: ``tournament`` 1x, ``high`` 5x, ``variable``,
a factor uniform in [0, 5] drawn per game) every pairing of the entrants
plays the same seeded racks twice, each side breaking once
(``studies.matches.tournament``: alternating breaks on the same racks), with
Bradley-Terry ratings. Each bot is wrapped in ``TimedBot``, which counts the
tables it decides and the wall-clock and CPU seconds its ``act`` takes (the
preview simulations it runs included), so compute per shot is measured in
the same run as the results, on the same machine. The CPU time is the
process's (``time.process_time``: every thread's, numba's included), which a
loaded machine does not inflate as it does the wall clock."""
from __future__ import annotations

import time

from ..bots import make_bot
from .matches import tournament

GAME = "eight_ball"
LEVELS = ("tournament", "high", "variable")


class TimedBot:
    """A bot whose ``act`` calls are timed into ``clock[name]`` = [tables decided, wall seconds, CPU seconds];
    ``tables`` holds the env tables where it played a shot other than a break."""

    def __init__(self, bot, name: str, clock: dict):
        self.bot, self.name, self.clock, self.tables = bot, name, clock, set()
        clock.setdefault(name, [0, 0.0, 0.0])

    def act(self, view):
        t0, c0 = time.perf_counter(), time.process_time()
        plan = self.bot.act(view)
        c = self.clock[self.name]
        c[0] += view.n
        c[1] += time.perf_counter() - t0
        c[2] += time.process_time() - c0
        brk = getattr(view, "is_break", None)
        if brk is not None:
            self.tables.update(view.rows[~brk].tolist())
        return plan

    def __getattr__(self, attr):  # everything else is the bot's own
        return getattr(self.bot, attr)


def per_shot(entry) -> dict:
    """A clock entry as shots, seconds and milliseconds per shot (wall and CPU)."""
    shots, wall, cpu = int(entry[0]), float(entry[1]), float(entry[2])
    return dict(shots=shots, seconds=wall, cpu_seconds=cpu, ms_per_shot=1e3 * wall / max(shots, 1),
                cpu_ms_per_shot=1e3 * cpu / max(shots, 1))


def championship(names: list, n_racks: int, seed: int = 0, levels=LEVELS, bot_factory=make_bot,
                 progress=None, **kw) -> list[dict]:
    """Every level of ``levels``: a dict (noise, results, ratings, compute:
    {entrant: ``per_shot``}, seconds). ``progress(level)``
    is called as each level starts; ``kw`` go to ``tournament``."""
    out = []
    for noise in levels:
        if progress is not None:
            progress(noise)
        clock: dict = {}

        def timed(spec, s, clock=clock):
            return TimedBot(bot_factory(spec, s), spec if isinstance(spec, str) else type(spec).__name__, clock)

        t0 = time.perf_counter()
        results, table = tournament(names, GAME, n_racks, seed, noise, bot_factory=timed, **kw)
        compute = {k: per_shot(v) for k, v in clock.items()}
        out.append(dict(noise=noise, results=results, ratings=table, compute=compute,
                        seconds=time.perf_counter() - t0))
    return out


def compute_table(levels: list[dict]) -> str:
    """Markdown: each entrant's shots and milliseconds per shot (wall, CPU) at every level."""
    names = sorted({k for lv in levels for k in lv["compute"]})
    head = "| entrant | " + " | ".join(f"{lv['noise']}: shots, ms/shot (CPU)" for lv in levels) + " |"
    lines = [head, "|" + "---|" * (1 + len(levels))]
    for n in names:
        cells = []
        for lv in levels:
            c = lv["compute"].get(n)
            cells.append(f"{c['shots']}, {c['ms_per_shot']:.2f} ({c['cpu_ms_per_shot']:.2f})" if c else "-")
        lines.append(f"| {n} | " + " | ".join(cells) + " |")
    return "\n".join(lines)
