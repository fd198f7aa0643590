#!/usr/bin/env python
"""Ladder matches in this process against the same matches on Ray: games per second, same results.

    python scripts/match_throughput.py                      # 9-ball ladder + ghost, ghost-safety, search64
    python scripts/match_throughput.py --racks 16 --chunk-racks 4 --repeats 3 --num-cpus 2
    python scripts/match_throughput.py --quick              # smoke test: ladder-1 v ghost, 2 racks

Every pairing of ``--entrants`` (default: the game's ladder agents and
``ghost``, ``ghost-safety``, ``search64``) plays ``--racks`` paired racks at
``--noise``, in chunks of ``--chunk-racks`` racks, through
``agents.evaluation.distributed.play_jobs`` three ways: in this process
with numba's default threads (``here``), in this process with one numba
thread (``here-1-thread``), and as Ray tasks (one numba thread each) on a
local Ray instance of ``--num-cpus`` CPUs (``ray``; started once, before
the timing; one warm-up pass of each path loads the workers' kernels). The
paths take turns ``--repeats`` times (the order rotating); each pass's
games must equal the first pass's, else the script fails. Prints and writes
to ``--out`` (``match_throughput.json``) the median games per second of
each path and the ratios to ``here``.
"""
from __future__ import annotations

import argparse
import itertools
import json
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from agents.evaluation.distributed import MatchJob, chunks, play_jobs  # noqa: E402
from billiards_env.bots.learned import ladder as L  # noqa: E402
from billiards_env.studies import match_report  # noqa: E402


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    from billiards_env.rules import DEFAULT_GAME, GAMES
    laddered = [g for g in GAMES if L.ladder_names(g)]  # the games with shipped ladder agents
    ap.add_argument("--game", choices=laddered, default=DEFAULT_GAME,
                    help="a game with shipped ladder agents (bots/learned/ladder/<game>/)")
    ap.add_argument("--entrants", nargs="+", default=None, help="default: the game's ladder, ghost, ghost-safety, search64")
    ap.add_argument("--racks", type=int, default=8, help="racks per pairing (each played twice)")
    ap.add_argument("--chunk-racks", type=int, default=4)
    ap.add_argument("--noise", choices=match_report.NOISES, default="tournament")
    ap.add_argument("--seed", type=int, default=2026, help="match seed (the ladder table's)")
    ap.add_argument("--max-shots", type=int, default=200)
    ap.add_argument("--repeats", type=int, default=3, help="timed passes of each path")
    ap.add_argument("--num-cpus", type=int, default=None, help="CPUs of the local Ray instance (default: all cores)")
    ap.add_argument("--out", type=Path, default=ROOT / "results" / "distributed")
    ap.add_argument("--quick", action="store_true", help="ladder-1 v ghost, 2 racks of 1 chunk each, 20 shots, 1 pass")
    args = ap.parse_args(argv)
    if args.quick:
        args.entrants, args.racks, args.chunk_racks, args.max_shots, args.repeats = ["ladder-1", "ghost"], 2, 1, 20, 1
    if args.racks < 1 or args.chunk_racks < 1 or args.repeats < 1:
        ap.error("--racks, --chunk-racks and --repeats must be positive")
    entrants = args.entrants or L.ladder_names(args.game) + ["ghost", "ghost-safety", "search64"]
    jobs = [MatchJob(a, b, args.game, args.racks, args.seed, args.noise, args.max_shots, args.chunk_racks)
            for a, b in itertools.combinations(entrants, 2)]
    n_chunks, n_games = sum(len(chunks(j)) for j in jobs), 2 * args.racks * len(jobs)
    print(f"{len(jobs)} pairings, {n_games} games in {n_chunks} chunks", flush=True)
    import ray

    import numba

    threads = numba.get_num_threads()
    paths = {"here": (None, threads), "here-1-thread": (None, 1), "ray": ("local", threads)}  # (address, numba here)
    reference = play_jobs(jobs)  # the warm-up pass here, and the results every pass must give
    if play_jobs(jobs, "local", num_cpus=args.num_cpus) != reference:  # Ray starts here and stays up
        raise SystemExit("the Ray path's games differ from this process's")
    cpus = int(ray.cluster_resources().get("CPU", 0))
    rates = {k: [] for k in paths}
    names = list(paths)
    for r in range(args.repeats):
        for name in names[r % 3:] + names[:r % 3]:
            address, n_threads = paths[name]
            numba.set_num_threads(n_threads)
            t0 = time.perf_counter()
            games = play_jobs(jobs, address)
            rates[name].append(n_games / (time.perf_counter() - t0))
            numba.set_num_threads(threads)
            if games != reference:
                raise SystemExit(f"pass {r} {name}: the games differ from the first pass's")
            print(f"pass {r + 1} {name}: {rates[name][-1]:.2f} games/s", flush=True)
    med = {k: statistics.median(v) for k, v in rates.items()}
    doc = dict(command=" ".join(["python", "scripts/match_throughput.py"] + (argv if argv is not None else sys.argv[1:])),
               game=args.game, noise=args.noise, entrants=entrants, racks=args.racks, chunk_racks=args.chunk_racks,
               games=n_games, chunks=n_chunks, ray_cpus=cpus, numba_threads_here=threads, games_per_s=rates,
               median_games_per_s=med, over_here={k: v / med["here"] for k, v in med.items()}, same_results=True)
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "match_throughput.json").write_text(json.dumps(doc, indent=2) + "\n")
    print(f"median games/s: here ({threads} numba threads) {med['here']:.2f}, here (1 thread) "
          f"{med['here-1-thread']:.2f}, Ray ({cpus} CPUs) {med['ray']:.2f}; Ray / here {doc['over_here']['ray']:.2f}, "
          f"Ray / here with 1 thread {med['ray'] / med['here-1-thread']:.2f}; the same games on every path")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
