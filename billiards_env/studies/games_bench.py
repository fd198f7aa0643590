"""Throughput of the two-player games: complete games per second between two
policies on a batch of tables, and steps per second of the self-play vector
env, with the time split between the simulator, the rules and the policies.

    python -m billiards_env.studies.games_bench --tables 1024 --n-games 3072 --games nine_ball ten_ball
    (or ``python scripts/benchmark.py --only games``)

``games_per_second``: every table plays game after game (a finished table
is re-racked at once, from its own stream), each step shoots every table
with one simulator call, and the clock runs until ``games`` games have
finished. The split: ``simulate`` is the simulator time of the env's shots,
``rules`` the rulings (``rules.judge``), ``policies`` the time in the
bots' ``act`` (which includes the simulator calls of their previews,
reported as ``policy_simulate``); ``other`` is the rest of the env step
(placement, respots, bookkeeping, re-racks). Each game is played by its
own default bot (its spec's ``default_bot``: the ghost bot, three-cushion's ``carom``, snooker's ``snooker``);
the games a run times and their rule settings are their specs' ``presets`` (``rules.games.StudyPresets``).

``carom_shots``: three-cushion shots per second per thread (random strikes
from random three-ball positions on the carom table with carom equipment,
the contact order kept as the game keeps it, one numba thread), and the
cost per simulated event beside the pool scenes' (the 9-ball break and
two-ball cuts, measured in the same run, interleaved).
"""
from __future__ import annotations

import argparse
import importlib
import json
import time

import numpy as np

from ..bots import make_bot
from ..envs.games import GAMES, GameConfig, GameCore
from ..rules import DEFAULT_GAME, get_game
from ..envs.games.play import play_round
from ..envs.games.vector import GameVectorEnv


def _timed_simulate(calls: dict):
    """Wrap ``physics.simulate`` as seen by ``contract.turn`` (every game shot: the env's and the bots'
    previews) so its time is counted."""
    pv = importlib.import_module("billiards_env.contract.turn")
    inner = pv.simulate

    def timed(*a, **kw):
        t0 = time.perf_counter()
        try:
            return inner(*a, **kw)
        finally:
            calls["t"] += time.perf_counter() - t0
    pv.simulate = timed
    return lambda: setattr(pv, "simulate", inner)


def games_per_second(game: str = DEFAULT_GAME, n_tables: int = 1024, n_games: int = 3072, policies=None,
                     noise: str = "tournament", seed: int = 0, max_shots: int = 200,
                     rule_options: dict | None = None) -> dict:
    """Complete games per second (see the module docstring) and the time split;
    ``rule_options``: the ruleset's settings (a quick run's short three-cushion games)."""
    policies = policies or (get_game(game).default_bot,) * 2
    core = GameCore(GameConfig(game=game, noise=noise, max_shots=max_shots, rule_options=rule_options or {}),
                    n_tables)
    all_ = np.arange(n_tables)
    core.streams.seed(all_, seed * 1_000_003 + all_)
    core.reset_tables(all_)
    bots = [make_bot(policies[0], seed), make_bot(policies[1], seed + 1)]
    clock = {"bots": 0.0}
    psim = {"t": 0.0}
    restore = _timed_simulate(psim)
    t_reset = 0.0
    shots, games, steps = [], 0, 0
    try:
        t0 = time.perf_counter()
        while games < n_games:
            out = play_round(core, bots, all_, clock)
            steps += 1
            done = np.nonzero(out["terminated"] | out["truncated"])[0]
            if len(done):
                shots.extend(core.game.shots[done].tolist())
                games += len(done)
                tr = time.perf_counter()
                core.reset_tables(done)
                t_reset += time.perf_counter() - tr
        wall = time.perf_counter() - t0
    finally:
        restore()
    t_pol = clock["bots"]
    sim, rules = core.timers["simulate"], core.timers["rules"]
    return dict(game=game, tables=n_tables, policies=list(policies), noise=noise, rule_options=dict(rule_options or {}),
                games=games, steps=steps, seconds=wall, games_per_second=games / wall, shots_per_game=float(np.mean(shots)),
                split=dict(simulate=sim, rules=rules, policies=t_pol - (psim["t"] - sim), policy_simulate=psim["t"] - sim,
                           other=wall - sim - rules - t_pol))


def vector_steps_per_second(game: str = DEFAULT_GAME, n_tables: int = 1024, n_steps: int = 30, seed: int = 0,
                            noise: str = "tournament") -> dict:
    """Steps per second (tables x steps / s) of the self-play vector env under uniform random actions."""
    env = GameVectorEnv(n_tables, game=game, noise=noise)
    env.reset(seed=seed)
    rng = np.random.default_rng(seed)
    acts = rng.uniform(-1, 1, (n_steps, n_tables, env.core.action_dim)).astype(np.float32)
    t0 = time.perf_counter()
    for k in range(n_steps):
        env.step(acts[k])
    wall = time.perf_counter() - t0
    c = env.core.timers
    return dict(game=game, tables=n_tables, steps=n_steps, seconds=wall, env_steps_per_second=n_tables * n_steps / wall,
                split=dict(simulate=c["simulate"], rules=c["rules"], other=wall - c["simulate"] - c["rules"]))


def carom_shots(n: int = 1024, repeats: int = 5, seed: int = 0) -> list[dict]:
    """Shots/s on one thread and the cost per event (us) of three-cushion
    shots beside two pool scenes, timed in turn ``repeats`` times (medians);
    see the module docstring."""
    import numba

    from ..physics import PhysicsParams, SimOptions, Table, simulate
    from ..physics.state import random_placement
    from ..physics.strike import strike_velocity
    from .bench.scenes import SCENES
    rng = np.random.default_rng(seed)
    cp, ct = PhysicsParams.carom(), Table.carom()
    carom = strike_velocity(random_placement(ct, cp, 3, n, seed=rng), rng.uniform(0, 2 * np.pi, n),
                            rng.uniform(1.5, 7.0, n), rng.uniform(-0.4, 0.4, n), rng.uniform(-0.3, 0.3, n), cp)
    P, T = PhysicsParams.standard(), Table.pool(9)
    cases = {"three-cushion shot (carom table, contacts kept)": (carom, ct, cp, SimOptions(contacts=64)),
             "three-cushion shot (carom table, contacts off)": (carom, ct, cp, SimOptions())}
    for name in ("9-ball break (8 m/s)", "two-ball cut (2 m/s, top+side)"):
        cases[name] = (SCENES[name](n, P, T, np.random.default_rng(seed)), T, P, SimOptions())
    threads = numba.get_num_threads()
    numba.set_num_threads(1)
    times = {k: [] for k in cases}
    events = {}
    try:
        for k, (s, t, p, o) in cases.items():  # compile, count events
            events[k] = float(simulate(s, t, p, options=o).n_events.mean())
        for _ in range(repeats):
            for k, (s, t, p, o) in cases.items():
                t0 = time.perf_counter()
                simulate(s, t, p, options=o)
                times[k].append(time.perf_counter() - t0)
    finally:
        numba.set_num_threads(threads)
    out = []
    for k in cases:
        sec = float(np.median(times[k]))
        out.append(dict(scene=k, shots=n, shots_per_s_1t=n / sec, events_per_shot=events[k],
                        us_per_event=1e6 * sec / (n * events[k])))
    return out


def carom_markdown(rows_: list[dict]) -> str:
    base = rows_[-1]["us_per_event"]
    lines = ["| scene (1 thread) | shots | shots/s | events per shot | us per event | per event / two-ball cut |",
             "|---|---|---|---|---|---|"]
    for r in rows_:
        lines.append(f"| {r['scene']} | {r['shots']} | **{r['shots_per_s_1t']:,.0f}** | {r['events_per_shot']:.1f} | "
                     f"{r['us_per_event']:.2f} | {r['us_per_event'] / base:.2f} |")
    return "\n".join(lines) + "\n"


def warm(game: str) -> None:
    """Compile (or load) every kernel the measurements use."""
    games_per_second(game, 8, 4, rule_options=get_game(game).presets.rule_options(quick=True))
    vector_steps_per_second(game, 8, 2)


def benchmarked_games() -> tuple[str, ...]:
    """The games the benchmark's games section times: those whose spec's ``presets.benchmarked`` is set."""
    return tuple(name for name, spec in GAMES.items() if spec.presets.benchmarked)


def rows(games=(DEFAULT_GAME,), n_tables: int = 1024, n_games: int = 3072, n_steps: int = 30,
         quick: bool = False) -> list[dict]:
    """Each game's ``games_per_second`` and ``vector_steps_per_second``; its spec's ``presets`` set its rules
    (a quick or a full run's) and how many games each table plays (0: ``n_games`` over all the tables)."""
    out = []
    for g in games:
        warm(g)
        p = get_game(g).presets
        played = n_tables * p.games_per_table if p.games_per_table else n_games
        out.append(games_per_second(g, n_tables, played, rule_options=p.rule_options(quick)))
        out.append(vector_steps_per_second(g, n_tables, n_steps))
    return out


def markdown(results: list[dict]) -> str:
    lines = ["| measure | game | tables | figure | shots per game | simulator s | rules s | policies s "
             "(+ their simulator) | other s | wall s |", "|---|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        s = r["split"]
        if "games_per_second" in r:
            opts = ", ".join(f"{k}={v}" for k, v in r.get("rule_options", {}).items())
            lines.append(f"| games/s, {' vs '.join(r['policies'])} | {r['game']}{f' ({opts})' if opts else ''} | {r['tables']} | "
                         f"**{r['games_per_second']:,.0f}** ({r['games']} games) | {r['shots_per_game']:.1f} | "
                         f"{s['simulate']:.2f} | {s['rules']:.2f} | "
                         f"{s['policies']:.2f} (+{s['policy_simulate']:.2f}) | "
                         f"{s['other']:.2f} | {r['seconds']:.2f} |")
        else:
            lines.append(f"| vector env steps/s, random actions | {r['game']} | {r['tables']} | "
                         f"**{r['env_steps_per_second']:,.0f}** ({r['steps']} steps) | | {s['simulate']:.2f} | "
                         f"{s['rules']:.2f} | | {s['other']:.2f} | {r['seconds']:.2f} |")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--games", nargs="+", default=[DEFAULT_GAME], choices=list(GAMES))
    ap.add_argument("--tables", type=int, default=1024)
    ap.add_argument("--n-games", type=int, default=3072)
    ap.add_argument("--steps", type=int, default=30)
    ap.add_argument("--json", default=None, help="also write the rows to this JSON file")
    ap.add_argument("--carom-shots", type=int, default=0, help="also time this many three-cushion shots "
                    "per thread beside the pool scenes (carom_shots)")
    args = ap.parse_args(argv)
    res = rows(args.games, args.tables, args.n_games, args.steps)
    print(markdown(res))
    if args.carom_shots:
        print(carom_markdown(carom_shots(args.carom_shots)))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(res, f, indent=2)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
