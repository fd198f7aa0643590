#!/usr/bin/env python
"""Seeded matches between bots (and trained models), with win rates and ratings.

    python scripts/match.py --game nine_ball --policies random ghost ghost-safety --racks 100
    python scripts/match.py --policies my_bots:planner ghost search64 --racks 50   # a bot of your own
    python scripts/match.py --game eight_ball --noise high --racks 50 --out results/matches
    python scripts/match.py --game ten_ball --policies ghost ghost-safety search64 --racks 100
    python scripts/match.py --summary    # every game and noise level of results/matches in one table
    python scripts/match.py --policies ghost search64 --racks 20 --save-replays 4   # + 4 whole games per pairing

Every pairing plays ``--racks`` racks twice (each side breaks once on each
rack). Writes ``<out>/<game>_<noise>.json``, ``.md`` and ``.png`` (ratings
with 95% intervals); with ``--save-replays N``, the first N games of every
pairing (rack 1 with each side breaking, rack 2, ...) as replay pages and
JSON in ``<out>/replays/<game>_<noise>/``. An entrant is a built-in bot (``random``, ``ghost``,
``ghost-safety``, ``search<K>``), ``module:factory`` (a bot of your own,
docs/bots.md; the module is looked up on PYTHONPATH and in the current
directory) or the path of a saved model. Noise levels: ``tournament``, ``high`` (5x), ``variable``
(a factor uniform in [0, 5] per game), ``none``.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(1, str(Path.cwd()))  # module:factory bots in the current directory

from agents.evaluation.entrants import bot_factory  # noqa: E402
from billiards_env.envs.games import GAMES  # noqa: E402
from billiards_env.rendering import save_replay_html  # noqa: E402
from billiards_env.studies import match_report  # noqa: E402
from billiards_env.studies.matches import tournament  # noqa: E402


def write_replays(folder: Path, results) -> None:
    """Each pairing's recorded games as ``<a>_v_<b>-NN.html`` and ``.json``."""
    for r in results:
        for n, rep in enumerate(r.replays):
            folder.mkdir(parents=True, exist_ok=True)
            stem = folder / f"{_safe(r.a)}_v_{_safe(r.b)}-{n:02d}"
            rep.save(stem.with_suffix(".json"))
            save_replay_html(rep, stem.with_suffix(".html"))
            print(f"wrote {stem.with_suffix('.html')} ({len(rep)} shots)")


def _safe(name: str) -> str:
    return "".join(c if c.isalnum() or c in "-." else "-" for c in Path(name).name)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--game", choices=list(GAMES), default="nine_ball")
    ap.add_argument("--policies", nargs="+", default=["random", "ghost"],
                    help="entrants: random, ghost, ghost-safety, search<K>, module:factory, or paths of saved models")
    ap.add_argument("--racks", type=int, default=100, help="racks per pairing (each played twice)")
    ap.add_argument("--noise", choices=match_report.NOISES, default="tournament")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--max-shots", type=int, default=200)
    ap.add_argument("--out", type=Path, default=ROOT / "results" / "matches")
    ap.add_argument("--save-replays", type=int, default=0, metavar="N",
                    help="write the first N games of every pairing as replays (HTML and JSON)")
    ap.add_argument("--summary", action="store_true", help="only write <out>/summary.md from the JSON files there")
    args = ap.parse_args(argv)
    if args.summary:
        md = match_report.summary(args.out)
        (args.out / "summary.md").write_text(md)
        print(md)
        return 0
    if len(set(args.policies)) < 2:
        ap.error("need at least two different policies")
    if not 0 <= args.save_replays <= 2 * args.racks:
        ap.error(f"--save-replays must be between 0 and 2 x --racks ({2 * args.racks}), got {args.save_replays}")
    t0 = time.perf_counter()
    for spec in args.policies:  # a bad entrant fails before any game is played
        bot_factory(spec, args.seed)
    results, table = tournament(args.policies, args.game, args.racks, args.seed, args.noise, max_shots=args.max_shots,
                                bot_factory=bot_factory, save_replays=args.save_replays)
    seconds = time.perf_counter() - t0
    write_replays(args.out / "replays" / f"{args.game}_{args.noise}", results)
    doc = dict(command=" ".join(["python", "scripts/match.py"] + (argv if argv is not None else sys.argv[1:])),
               game=args.game, noise=args.noise, racks=args.racks, seed=args.seed, seconds=seconds,
               pairings=[r.summary() for r in results], ratings=table)
    md = match_report.write(args.out / f"{args.game}_{args.noise}", doc, results, table)
    print(md)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
