"""Measure the play page's latency (click to the shot's first frame, the bot's
reply) and frame rate in headless Chromium (billiards_env.play.latency; docs/play.md).

    python scripts/play_latency.py                       # ghost, search64, lookahead, ladder-3, champion; 50 shots each
    python scripts/play_latency.py --quick               # a few shots against ghost (the test's mode)
"""
import argparse
from pathlib import Path

from billiards_env.play.latency import run

ROOT = Path(__file__).resolve().parents[1]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--bots", nargs="+", default=["ghost", "search64", "lookahead", "ladder-3", "champion"])
    ap.add_argument("--shots", type=int, default=50, help="person shots and bot replies timed per bot (default 50)")
    ap.add_argument("--out", type=Path, default=ROOT / "results" / "play", help="where latency.{csv,json,md} go")
    ap.add_argument("--docs", action="store_true", help="also write the table into docs/play.md")
    ap.add_argument("--quick", action="store_true", help="3 shots against ghost, a short frame count, nothing written")
    args = ap.parse_args(argv)
    if args.shots < 1:
        ap.error("--shots must be at least 1")
    if args.quick:
        res = run(["ghost"], 3, None, fps=True)
    else:
        res = run(args.bots, args.shots, args.out, ROOT / "docs" / "play.md" if args.docs else None)
    from billiards_env.play.latency import table_md
    print(table_md(res["rows"], res["fps"], res["load"]))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
