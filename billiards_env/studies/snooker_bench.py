"""Snooker's figures: the 22-ball opening per thread against the pool break,
and complete frames per second between the snooker bots.

    python scripts/benchmark.py --only snooker            # writes snooker.md
    python scripts/benchmark.py --only snooker --quick

``break_rows``: the frozen snooker opening (15 reds, six colours, the cue
ball in the D struck at the apex red at N(8, 0.2) m/s, the speed of the
pool scenes' breaks) and the 15-ball pool break of the solver section, on
one thread, timed in alternation (``repeats`` rounds, medians): breaks per
second, events per break, and the cost of one event, with the snooker
cost's ratio to the pool break's measured in the same run.

``frame_row``: ``games_bench.games_per_second`` for snooker (its default bot,
``snooker``, against itself at tournament noise): frames per second over ``tables``
tables, shots per frame, and the time in the simulator, the rules and the
bots.
"""
from __future__ import annotations

import statistics
import time

import numba
import numpy as np

from ..physics import PhysicsParams, Table, rack, set_num_threads, simulate, strike_velocity
from . import games_bench
from .scenes import straight_break

GAME = "snooker"           # the game whose frames this study times (the registry's name)
BREAK_SPEED = (8.0, 0.2)   # m/s: as the pool scenes' breaks
BREAK_CUE = (0.1, -0.03)   # m from the D's centre: the cue ball's spot for the opening (right of the brown)


def snooker_break(n: int, seed: int = 0):
    """The struck snooker opening on ``n`` tables: (state, table, params)."""
    T, P = Table.snooker(), PhysicsParams.snooker()
    rng = np.random.default_rng(seed)
    s = rack(T, P, "snooker", n)
    s.pos[:, 0] = np.array(T.marks.d_centre) + BREAK_CUE
    d = s.pos[0, 1] - s.pos[0, 0]
    phi = np.arctan2(d[1], d[0]) + rng.normal(0, 0.01, n)
    return strike_velocity(s, phi, rng.normal(*BREAK_SPEED, n), 0.0, rng.uniform(-0.1, 0.1, n), P), T, P


def break_rows(batch: int, repeats: int) -> list[dict]:
    """Snooker opening and pool 15-ball break on one thread, interleaved."""
    snk = snooker_break(batch)
    Tp, Pp = Table.pool(9), PhysicsParams.standard()
    pool = (straight_break(Tp, Pp, batch, 0, layout="eight"), Tp, Pp)
    cases = {"snooker opening (22 balls, 8 m/s)": snk, "pool 15-ball break (8 m/s)": pool}
    set_num_threads(1)
    try:
        events = {k: float(np.sum(simulate(*v).n_events)) for k, v in cases.items()}  # warm-up, event counts
        times = {k: [] for k in cases}
        for _ in range(repeats):
            for k, v in cases.items():
                t0 = time.perf_counter()
                simulate(*v)
                times[k].append(time.perf_counter() - t0)
    finally:
        set_num_threads(numba.config.NUMBA_NUM_THREADS)
    rows = []
    for k in cases:
        t = statistics.median(times[k])
        rows.append(dict(scene=k, batch=batch, breaks_per_s_1t=batch / t, events_per_break=events[k] / batch,
                         us_per_event=1e6 * t / events[k]))
    ref = rows[1]["us_per_event"]
    for r in rows:
        r["cost_vs_pool"] = r["us_per_event"] / ref
    return rows


def frame_row(tables: int, frames: int) -> dict:
    games_bench.games_per_second(GAME, 4, 2)  # compile / load the kernels
    return games_bench.games_per_second(GAME, tables, frames)


def markdown(breaks: list[dict], frames: dict) -> str:
    lines = ["| scene | batch | breaks/s (1 thread) | events per break | µs per event | per-event cost vs pool |",
             "|---|---|---|---|---|---|"]
    for r in breaks:
        lines.append(f"| {r['scene']} | {r['batch']} | **{r['breaks_per_s_1t']:,.0f}** | {r['events_per_break']:.1f} | "
                     f"{r['us_per_event']:.2f} | {r['cost_vs_pool']:.2f} |")
    s = frames["split"]
    lines += ["", "| frames, snooker vs snooker (tournament noise) | tables | frames/s | shots per frame | "
              "simulator s | rules s | bots s (+ their simulator) | other s | wall s |",
              "|---|---|---|---|---|---|---|---|---|",
              f"| {frames['games']} frames | {frames['tables']} | **{frames['games_per_second']:,.1f}** | "
              f"{frames['shots_per_game']:.1f} | {s['simulate']:.2f} | {s['rules']:.2f} | {s['policies']:.2f} "
              f"(+{s['policy_simulate']:.2f}) | {s['other']:.2f} | {frames['seconds']:.2f} |"]
    return "\n".join(lines) + "\n"


def snooker_markdown(batch: int, repeats: int) -> str:
    """The section's table: breaks of ``batch`` tables, ``batch`` frames on ``batch`` tables."""
    return markdown(break_rows(batch, repeats), frame_row(batch, batch))
