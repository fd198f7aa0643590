#!/usr/bin/env python
"""The game bots' compute: cost per decision on many tables and on one table at a time, and the lookahead's
strength against compute.

    python scripts/lookahead_cost.py --game nine_ball --tables 1024            # cost per decision at 1,024 tables
    python scripts/lookahead_cost.py --game eight_ball --budgets fast medium default --racks 60
    python scripts/lookahead_cost.py --single 24 --players champion champion-fast lookahead-2026.12
    python scripts/lookahead_cost.py --quick                                    # a few tables and racks (the test)

``--tables``: N seeded tables are played ``--rounds`` shots into their games by ``ghost``; then the lookahead
decides on all tables where a game is live, at once, ``--repeats`` times (after one warm-up call on a few tables,
which compiles the kernels): the median wall time and the process's CPU time per decision, and the previews per
decision.

``--single``: the play page's case, one table decided at a time. N seeded tables at each of ``--noises`` are played
``--rounds`` shots into their games by ``ghost``; after every round each ``--players`` bot decides each live table
alone (every bot the same positions, after a warm-up call on two tables): the median of the process's CPU time
(``time.process_time``, every thread's) and of the wall time per decision, and each bot's median CPU over
``lookahead-2026.12``'s in the same run. Prints a JSON line per (noise, bot) and a markdown table with the load
average.

``--budgets``: for each budget (``bots.game_lookahead.BUDGETS`` or ``default``; ``value`` or ``value-<budget>``:
value-lookahead with it), ``--racks`` paired racks against
``--opponent`` (``studies.matches.play_pairing``, each rack twice, each side breaking once) at ``--noise``: the win
rate with its Wilson 95% interval and the lookahead's wall and CPU time per shot over the match (``TimedBot``). Writes
``<out>/budgets_<game>_<noise>.json`` and ``.md``.
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
FROZEN = "lookahead-2026.12"   # --single's yardstick


def bot_of(budget: str, seed: int):
    """The lookahead with a budget: ``default``, a name of ``BUDGETS``, or ``value`` / ``value-<name>``:
    value-lookahead (its blind leaves valued by the shipped learned value) with the default or that budget."""
    from billiards_env.bots.game_lookahead import BUDGETS, GameLookahead
    learned = budget == "value" or budget.startswith("value-")
    search = budget[len("value-"):] if budget.startswith("value-") else ("default" if learned else budget)
    if search != "default" and search not in BUDGETS:
        names = ["default", *sorted(BUDGETS)]
        raise SystemExit(f"unknown budget {budget!r}; choose one of {names}, value or value-<one of them>")
    changes = {} if search == "default" else BUDGETS[search]
    if learned:
        from billiards_env.bots.learned.value import value_lookahead
        bot = value_lookahead(seed=seed, **changes)
        if search != "default":
            bot.name = budget
        return bot
    bot = GameLookahead(seed=seed, **changes)
    bot.name = "lookahead" if budget == "default" else f"lookahead-{budget}"
    return bot


def cost(game: str, n: int, rounds: int, repeats: int, seed: int, budget: str) -> dict:
    import numpy as np

    from billiards_env.bots import make_bot
    from billiards_env.envs.games import GameConfig, GameCore
    from billiards_env.envs.games.play import play_round

    core = GameCore(GameConfig(game=game, noise="tournament"), n)
    core.streams.seed(np.arange(n), seed * 1_000_003 + np.arange(n))
    core.reset_tables(np.arange(n), np.zeros(n, dtype=np.int64))
    ghosts = [make_bot("ghost", seed), make_bot("ghost", seed + 1)]
    live = np.arange(n)
    for _ in range(rounds):
        out = play_round(core, ghosts, live)
        live = live[~(out["terminated"] | out["truncated"])]
    bot = bot_of(budget, seed)
    bot.act(core.view(live[:4]))  # warm-up: compiles the kernels
    times, cpu, sims = [], [], []
    for _ in range(repeats):
        s0 = bot.sims
        t0, c0 = time.perf_counter(), time.process_time()
        bot.act(core.view(live))
        times.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
        sims.append(bot.sims - s0)
    t = float(np.median(times))
    return dict(game=game, budget=budget, tables=int(len(live)), seconds=t, ms_per_decision=1e3 * t / len(live),
                cpu_ms_per_decision=1e3 * float(np.median(cpu)) / len(live),
                previews_per_decision=float(np.median(sims)) / len(live))


def single(game: str, n: int, rounds: int, players: list, noises: list, seed: int) -> list:
    """One table at a time (``--single``): rows of (noise, player, decisions, CPU and wall ms per decision as
    medians, the CPU median over lookahead-2026.12's)."""
    import numpy as np

    from billiards_env.bots import make_bot
    from billiards_env.envs.games import GameConfig, GameCore
    from billiards_env.envs.games.play import play_round
    rows = []
    for noise in noises:
        core = GameCore(GameConfig(game=game, noise=noise), n)
        core.streams.seed(np.arange(n), seed * 1_000_003 + np.arange(n))
        core.reset_tables(np.arange(n), np.zeros(n, dtype=np.int64))
        ghosts = [make_bot("ghost", seed), make_bot("ghost", seed + 1)]
        bots = {name: make_bot(name, seed=seed) for name in players}
        cpu: dict = {name: [] for name in players}
        wall: dict = {name: [] for name in players}
        live = np.arange(n)
        for r in range(rounds):
            out = play_round(core, ghosts, live)
            live = live[~(out["terminated"] | out["truncated"])]
            for name, bot in bots.items():
                if r == 0:
                    bot.act(core.view(live[:2]))  # warm-up: compiles the kernels, measures the pocket windows
                for i in live:
                    view = core.view(np.array([i]))
                    t0, c0 = time.perf_counter(), time.process_time()
                    bot.act(view)
                    cpu[name].append(time.process_time() - c0)
                    wall[name].append(time.perf_counter() - t0)
        ref = float(np.median(cpu[FROZEN])) if FROZEN in cpu else None
        for name in players:
            c = float(np.median(cpu[name]))
            rows.append(dict(game=game, noise=noise, player=name, decisions=len(cpu[name]),
                             cpu_ms_per_decision=1e3 * c, wall_ms_per_decision=1e3 * float(np.median(wall[name])),
                             cpu_over_lookahead=c / ref if ref else None))
    return rows


def single_markdown(rows: list, command: str) -> str:
    load = " / ".join(f"{x:.1f}" for x in os.getloadavg())
    head = f"`{command}` (load average {load}, numba threads {numba_threads()})\n\n" \
           "| noise | player | decisions | CPU ms per decision (median) | wall ms | CPU over lookahead-2026.12 |\n" \
           "|---|---|---|---|---|---|\n"
    return head + "".join(f"| {r['noise']} | {r['player']} | {r['decisions']} | {r['cpu_ms_per_decision']:.1f} | "
                          f"{r['wall_ms_per_decision']:.1f} | "
                          + ("" if r["cpu_over_lookahead"] is None else f"{r['cpu_over_lookahead']:.2f}") + " |\n"
                          for r in rows)


def numba_threads() -> int:
    import numba
    return numba.get_num_threads()


def budgets(game: str, names: list, racks: int, opponent: str, noise: str, seed: int) -> list:
    import numpy as np

    from billiards_env.studies.championship import TimedBot, per_shot
    from billiards_env.studies.matches import play_pairing
    rows = []
    for name in names:
        clock: dict = {}
        bot = TimedBot(bot_of(name, seed), name, clock)
        t0 = time.perf_counter()
        r = play_pairing(bot, opponent, game, n_racks=racks, seed=seed, noise=noise)
        s = r.summary()
        played = np.isin(np.arange(r.n), sorted(bot.tables))
        t = per_shot(clock[name])
        rows.append(dict(budget=name, opponent=opponent, games=s["games"], win_rate=s["a_win_rate"], ci95=s["ci95"],
                         lost_without_a_shot=int(((r.winner == 1) & ~played).sum()),
                         ms_per_shot=t["ms_per_shot"], cpu_ms_per_shot=t["cpu_ms_per_shot"], shots=t["shots"],
                         previews_per_shot=bot.bot.sims / max(t["shots"], 1), match_seconds=time.perf_counter() - t0))
    return rows


def budgets_markdown(game: str, noise: str, seed: int, rows: list) -> str:
    """``budgets_<game>_<noise>.md`` from its JSON rows (the budgets, the opponent and the racks are in them; the
    seed is not): what scripts/regenerate.py renders."""
    names = " ".join(r["budget"] for r in rows)
    racks, opponent = rows[0]["games"] // 2, rows[0]["opponent"]
    head = f"# lookahead budgets, {game}, {noise} noise, against {opponent}\n\n" \
           f"`python scripts/lookahead_cost.py --game {game} --budgets {names} --racks {racks}" \
           f" --opponent {opponent} --noise {noise} --seed {seed}` ({racks} racks, each played twice)\n\n" \
           "| budget | games | win rate | 95% interval | lost without a shot | ms per shot | CPU ms per shot |" \
           " previews per shot |\n|---|---|---|---|---|---|---|---|\n"
    md = head + "".join(f"| {r['budget']} | {r['games']} | {r['win_rate']:.3f} | {r['ci95'][0]:.3f}-{r['ci95'][1]:.3f}"
                        f" | {r['lost_without_a_shot']} | {r['ms_per_shot']:.1f} | {r['cpu_ms_per_shot']:.1f}"
                        f" | {r['previews_per_shot']:.0f} |\n"
                        for r in rows)
    return md + "\n'lost without a shot': games the lookahead lost without playing a shot other than its break.\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    from billiards_env.rules import DEFAULT_GAME, GAMES
    pool = [g for g, spec in GAMES.items() if not spec.own_bots]  # the games the pool bots (lookahead) play
    ap.add_argument("--game", default=DEFAULT_GAME, choices=pool,
                    help="a game the lookahead plays (the pool games; three-cushion and snooker have bots of their own)")
    ap.add_argument("--tables", type=int, default=0, help="time one decision on this many tables")
    ap.add_argument("--rounds", type=int, default=3, help="shots played into the games before timing")
    ap.add_argument("--single", type=int, default=0,
                    help="decide one table at a time on this many seeded tables after each of --rounds ghost rounds")
    ap.add_argument("--players", nargs="*", default=["champion", "champion-fast", FROZEN], help="bots --single times")
    ap.add_argument("--noises", nargs="*", default=["tournament", "none"], help="noise levels --single times at")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--budget", default="default", help="the budget timed with --tables (value: value-lookahead)")
    ap.add_argument("--budgets", nargs="*", default=[], help="budgets played against --opponent")
    ap.add_argument("--racks", type=int, default=60)
    ap.add_argument("--opponent", default="search64")
    ap.add_argument("--noise", default="tournament")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--out", default=str(ROOT / "results" / "matches" / "lookahead"))
    ap.add_argument("--quick", action="store_true",
                    help="8 tables, 1 repeat; the fast budget on 2 racks; --single on 3 tables")
    a = ap.parse_args(argv)
    if a.quick:
        a.tables, a.repeats, a.budgets, a.racks, a.single = 8, 1, ["fast"], 2, 3
    if a.single:
        rows = single(a.game, a.single, a.rounds, a.players, a.noises, a.seed)
        for r in rows:
            print(json.dumps(r))
        print(single_markdown(rows, "python scripts/lookahead_cost.py " + " ".join(argv if argv is not None
                                                                                       else sys.argv[1:])))
    if a.tables:
        print(json.dumps(cost(a.game, a.tables, a.rounds, a.repeats, a.seed, a.budget)))
    if a.budgets:
        rows = budgets(a.game, a.budgets, a.racks, a.opponent, a.noise, a.seed)
        md = budgets_markdown(a.game, a.noise, a.seed, rows)
        print(md)
        if not a.quick:
            out = Path(a.out)
            out.mkdir(parents=True, exist_ok=True)
            stem = out / f"budgets_{a.game}_{a.noise}"
            stem.with_suffix(".json").write_text(json.dumps(rows, indent=1))
            stem.with_suffix(".md").write_text(md)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
