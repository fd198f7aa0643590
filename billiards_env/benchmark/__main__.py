"""``python -m billiards_env.benchmark``: the protocol, the reference rows, and aggregating results files.

    python -m billiards_env.benchmark protocol                 # the suite, budgets, seeds, references
    python -m billiards_env.benchmark reference                # the reference rows and each task's anchors
    python -m billiards_env.benchmark aggregate FILE... [--out DIR]

Scoring a policy is ``python -m agents.evaluation.benchmark score --policy ... --task ...`` (it plays saved
models, which need agents/, above the library; docs/benchmark.md).
"""
from __future__ import annotations

import argparse
import sys

from . import PROTOCOL, REFERENCE, aggregate_files, table, write_aggregate
from .score import anchors


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m billiards_env.benchmark", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    sub.add_parser("protocol", help="print the protocol")
    sub.add_parser("reference", help="print the reference rows")
    g = sub.add_parser("aggregate", help="aggregate results files with the reference rows")
    g.add_argument("files", nargs="+", help="results.json files of the scoring command")
    g.add_argument("--out", default=None, help="also write aggregate.json, aggregate.md and aggregate.png here")
    sub.add_parser("score", help="lives in agents: python -m agents.evaluation.benchmark score ...")
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] == ["score"]:
        print("scoring plays policies (saved models need agents/, above the library); run:\n"
              "  python -m agents.evaluation.benchmark " + " ".join(argv), file=sys.stderr)
        return 2
    a = ap.parse_args(argv)
    if a.cmd == "protocol":
        print(f"protocol {PROTOCOL.version}: runs {PROTOCOL.runs} (evaluation seeds {PROTOCOL.eval_seeds})\n")
        print("| task | metric | noise | episodes/run | training budget (env steps) | 0 | 1 |")
        print("|---|---|---|---|---|---|---|")
        for t in PROTOCOL.tasks:
            print(f"| {t.env_id} | {t.metric} | {t.noise} | {t.episodes} | {t.budget:,} | {t.baseline} | {t.reference} |")
    elif a.cmd == "reference":
        print("| task | algorithm | budget | scores per run | mean |\n|---|---|---|---|---|")
        for r in REFERENCE:
            print(f"| {r.task} | {r.algorithm} | {r.budget or '-'} | {', '.join(f'{s:.3f}' for s in r.scores)} "
                  f"| {r.mean:.3f} |")
        for t in PROTOCOL.tasks:
            try:
                lo, hi = anchors(t.env_id)
                print(f"{t.env_id}: 0 = {t.baseline} {lo:.3f}, 1 = {t.reference} {hi:.3f}")
            except ValueError as e:
                print(f"{t.env_id}: {e}")
    elif a.cmd == "aggregate":
        agg = aggregate_files(a.files)
        print(table(agg))
        if a.out:
            js, png = write_aggregate(agg, a.out)
            print(f"\nwrote {js}, {png} and aggregate.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
