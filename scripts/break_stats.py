#!/usr/bin/env python
"""The break's outcomes with perfect and realistic racks, with and without noise.

    python scripts/break_stats.py --game nine_ball --racks 1000
    python scripts/break_stats.py --game nine_ball --racks 1000 --break-nine spotted
    python scripts/break_stats.py --quick          # a few racks, for the tests

One seeded break per rack (the ghost bot's standard break, which every
built-in bot plays) on the racks of scripts/match.py's seeds. Prints a
Markdown table (rates with 95% intervals) and writes it with the JSON to
``<out>/<game>.md`` and ``.json``.
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from billiards_env.envs.games import GAMES  # noqa: E402
from billiards_env.rules import DEFAULT_GAME  # noqa: E402
from billiards_env.envs.games.core import BREAK_NINE  # noqa: E402
from billiards_env.envs.games.setup import RACKS  # noqa: E402
from billiards_env.studies.breaks import break_outcomes  # noqa: E402

COLUMNS = ("pockets a ball", "game ball down", "breaker wins", "legal", "scratch", "breaker shoots on")


def table(rows: list) -> str:
    head = "| rack | noise | balls pocketed | " + " | ".join(COLUMNS) + " |"
    lines = [head, "|" + "---|" * (3 + len(COLUMNS))]
    for r in rows:
        cells = [f"{r[c]['rate']:.3f} [{r[c]['ci95'][0]:.3f}, {r[c]['ci95'][1]:.3f}]" for c in COLUMNS]
        lines.append(f"| {r['config']['rack']} | {r['noise']} | {r['mean_pocketed']:.2f} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def markdown(doc: dict) -> str:
    """``<game>.md`` from its JSON (``command`` and ``rows``): what scripts/regenerate.py renders."""
    r = doc["rows"][0]
    return f"# Breaks: {r['game']}, {r['racks']} racks\n\n`{doc['command']}`\n\n{table(doc['rows'])}\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    pool = [g for g, spec in GAMES.items() if spec.rules.game_ball]  # the games with a game ball to break on
    ap.add_argument("--game", choices=pool, default=DEFAULT_GAME,
                    help="a game with a game ball (the pool games; three-cushion and snooker have none)")
    ap.add_argument("--racks", type=int, default=1000)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--noise", nargs="+", default=["none", "tournament"])
    ap.add_argument("--break-nine", choices=BREAK_NINE, default="wins", help="9-ball: the 9 on the break wins or is spotted")
    ap.add_argument("--out", type=Path, default=ROOT / "results" / "breaks")
    ap.add_argument("--quick", action="store_true", help="8 racks, nothing written unless --out is given")
    args = ap.parse_args(argv)
    if args.quick:
        args.racks = 8
    if args.racks < 1:
        ap.error(f"--racks must be positive, got {args.racks}")
    t0, rows = time.perf_counter(), []
    extra = {"break_nine": args.break_nine} if args.break_nine != "wins" else {}
    for noise in args.noise:
        for rack in RACKS[::-1]:  # perfect first: the old racks, then the new default
            rows.append(break_outcomes(args.game, args.racks, args.seed, noise, rack=rack, **extra))
            print(f"{rack} racks, {noise} noise: done ({time.perf_counter() - t0:.0f} s)", file=sys.stderr)
    cmd = " ".join(["python", "scripts/break_stats.py"] + (argv if argv is not None else sys.argv[1:]))
    md = markdown(dict(command=cmd, rows=rows))
    print(md)
    if not args.quick or "--out" in (argv if argv is not None else sys.argv[1:]):
        args.out.mkdir(parents=True, exist_ok=True)
        stem = args.out / (args.game + ("_spotted" if extra else ""))
        stem.with_suffix(".md").write_text(md)
        stem.with_suffix(".json").write_text(json.dumps(dict(command=cmd, rows=rows), indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
