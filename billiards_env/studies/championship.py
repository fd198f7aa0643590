"""The championship protocol: 8-ball matches under the conditions of the
2011 computer pool championship (its noise levels: the tournament noise,
five times it, and a variable level), every entrant's compute per shot
beside the results.

At each level (``LEVELS``: ``tournament`` 1x, ``high`` 5x, ``variable``,
a factor uniform in [0, 5] drawn per game) every pairing of the entrants
plays the same seeded racks twice, each side breaking once
(``studies.matches.tournament``: alternating breaks on the same racks), with
Bradley-Terry ratings. Each bot is wrapped in ``TimedBot``, which counts the
tables it decides and the wall-clock seconds its ``act`` takes (the
preview simulations it runs included), so compute per shot is measured in
the same run as the results, on the same machine."""
from __future__ import annotations

import time

from ..bots import make_bot
from .matches import tournament

GAME = "eight_ball"
LEVELS = ("tournament", "high", "variable")


class TimedBot:
    """A bot whose ``act`` calls are timed into ``clock[name]`` = [shots, seconds]."""

    def __init__(self, bot, name: str, clock: dict):
        self.bot, self.name, self.clock = bot, name, clock
        clock.setdefault(name, [0, 0.0])

    def act(self, view):
        t0 = time.perf_counter()
        plan = self.bot.act(view)
        c = self.clock[self.name]
        c[0] += view.n
        c[1] += time.perf_counter() - t0
        return plan

    def __getattr__(self, attr):  # everything else is the bot's own
        return getattr(self.bot, attr)


def championship(names: list, n_racks: int, seed: int = 0, levels=LEVELS, bot_factory=make_bot,
                 progress=None, **kw) -> list[dict]:
    """Every level of ``levels``: a dict (noise, results, ratings, compute:
    {entrant: {shots, seconds, ms_per_shot}}, seconds). ``progress(level)``
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
        compute = {k: dict(shots=int(v[0]), seconds=float(v[1]), ms_per_shot=1e3 * v[1] / max(v[0], 1))
                   for k, v in clock.items()}
        out.append(dict(noise=noise, results=results, ratings=table, compute=compute,
                        seconds=time.perf_counter() - t0))
    return out


def compute_table(levels: list[dict]) -> str:
    """Markdown: each entrant's shots and milliseconds per shot at every level."""
    names = sorted({k for lv in levels for k in lv["compute"]})
    head = "| entrant | " + " | ".join(f"{lv['noise']}: shots, ms/shot" for lv in levels) + " |"
    lines = [head, "|" + "---|" * (1 + len(levels))]
    for n in names:
        cells = []
        for lv in levels:
            c = lv["compute"].get(n)
            cells.append(f"{c['shots']}, {c['ms_per_shot']:.2f}" if c else "-")
        lines.append(f"| {n} | " + " | ".join(cells) + " |")
    return "\n".join(lines)
