"""Simulator and environment throughput, and how it compares across commits.

Compiles before timing, reports medians over repeats and ratios measured in
the same run, prints Markdown tables (one file per section, joined in
benchmark.md), appends rows with the git revision to benchmark.csv and plots
the history of the headline figures (history.png), all in ``--out``: by
default a new run folder, ``runs/benchmark/<timestamp>/`` (git-ignored). The
committed tables and history of ``results/benchmark`` are rewritten only
when ``--out results/benchmark`` names them.

    python scripts/benchmark.py                 # full run (a few minutes), into runs/benchmark/<timestamp>/
    python scripts/benchmark.py --out results/benchmark   # the same, rewriting the committed tables
    python scripts/benchmark.py --quick         # smaller batches, fewer repeats
    python scripts/benchmark.py --only solver --against HEAD~1 --quick
    python scripts/benchmark.py --only models   # each non-default model (models.md)
    python scripts/benchmark.py --only airborne --out results/benchmark   # what flight costs (airborne.md, physics.md)
    python scripts/benchmark.py --only rllib    # RLlib vs SB3 vs bare env (docs/distributed.md; needs [ray])
    python scripts/benchmark.py --history --out results/benchmark   # only redraw history.png there
    python scripts/benchmark.py --only games    # two-player games/s and vector-env steps/s (games.md)
    python scripts/benchmark.py --only snooker  # snooker openings/s against the pool break, frames/s (snooker.md)

``--against REV`` checks REV out in a temporary git worktree, warms both
trees' numba caches, then runs each section in both trees in turn, a fresh
process per run with PYTHONPATH set to the tree and the same seeds, ``--rounds``
times (the order alternating), and writes the medians of both and their
ratio (this tree / REV) to against.md.
"""
from __future__ import annotations

import argparse
import datetime
import json
from pathlib import Path

from ..run_folder import run_folder
from .options import DEFAULT_SECTIONS, ROOT, SECTION_NAMES, RunOptions


def parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="benchmark.py", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--batch", type=int, default=None, help="tables per simulator call (default 1024, quick 64)")
    ap.add_argument("--repeats", type=int, default=None, help="timed repeats per figure (default 5, quick 2)")
    ap.add_argument("--quick", action="store_true", help="batch 64, 2 repeats, 4 env steps")
    ap.add_argument("--only", nargs="*", default=list(DEFAULT_SECTIONS),
                    choices=list(SECTION_NAMES) + ["games", "snooker"],
                    help="sections (default: all but models and airborne; models: every effect with each "
                         "non-default model, written to models.md; airborne: the planar against the airborne "
                         "kernel, written to airborne.md)")
    ap.add_argument("--scene", action="append", default=None,
                    help="keep only scenes (or env ids) containing this text (repeatable)")
    ap.add_argument("--out", type=Path, default=None,
                    help="folder of the tables and CSV (default: a new runs/benchmark/<timestamp>/; results/benchmark "
                         "only when named)")
    ap.add_argument("--against", metavar="REV", default=None,
                    help="time this tree and git revision REV (temporary worktree) in turn; writes against.md")
    ap.add_argument("--rounds", type=int, default=3, help="interleaved rounds per tree with --against")
    ap.add_argument("--history", action="store_true", help="only redraw <out>/history.png from the CSVs there (needs --out)")
    ap.add_argument("--worker", type=Path, default=None, help=argparse.SUPPRESS)  # rows as JSON to this file
    return ap


def _games(opts: RunOptions, out: Path) -> None:
    """The two-player games' table, games.md (billiards_env/studies/games_bench.py)."""
    from .sections import games_markdown
    md = games_markdown(opts)
    print(md)
    (out / "games.md").write_text(md)


def _snooker(opts: RunOptions, out: Path) -> None:
    """Snooker's table, snooker.md (billiards_env/studies/snooker_bench.py)."""
    from ..snooker_bench import snooker_markdown
    md = snooker_markdown(opts.batch, opts.repeats)
    print(md)
    (out / "snooker.md").write_text(md)


def _against(args, opts: RunOptions, common: dict) -> None:
    from .against import Comparison, against
    from .report import against_markdown, append_csv
    rows = against(Comparison(args.against, tuple(args.only), args.rounds, opts))
    md = against_markdown(rows, args.against)
    print()
    print(md)
    (args.out / "against.md").write_text(md)
    append_csv(args.out / "benchmark.csv", [{**r, **common} for r in rows])
    print(f"\nwrote {args.out / 'against.md'} and appended to {args.out / 'benchmark.csv'}")


def _history(out: Path) -> Path | None:
    """Redraw history.png; None (and a note) without matplotlib (the plot extra)."""
    from .report import plot_history
    try:
        return plot_history(out)
    except ImportError as e:
        print(f"history.png not drawn ({e}; install the plot extra)")
        return None


def _run(args, opts: RunOptions, common: dict) -> None:
    from .report import append_csv, markdown, write_tables
    from .sections import run_sections
    from .trees import revision
    rows = run_sections(opts, args.only)
    print()
    print(markdown(rows))
    bench_md = write_tables(args.out, rows, args.only)
    append_csv(args.out / "benchmark.csv", [{**r, **common, "revision": revision(ROOT)} for r in rows])
    history = _history(args.out)
    print(f"\nwrote {bench_md}{' and ' + str(history) if history else ''}, appended to "
          f"{args.out / 'benchmark.csv'}")


def main(argv=None) -> None:
    ap = parser()
    args = ap.parse_args(argv)
    opts = RunOptions.make(args.batch, args.repeats, args.quick, args.scene)
    if args.history:
        if args.out is None:
            ap.error("--history redraws history.png from a folder's benchmark CSVs: name it, e.g. --out results/benchmark")
        from .report import plot_history
        path = plot_history(args.out)
        print(f"wrote {path}" if path else f"no full-size rows in {args.out}/benchmark*.csv: nothing to plot")
        return
    if args.worker is not None:  # one section for --against (in this tree's process): rows as JSON
        from .sections import run_sections
        args.worker.write_text(json.dumps(run_sections(opts, args.only)))
        return
    if args.out is None:
        args.out = run_folder(ROOT, "benchmark")
        print(f"writing to {args.out} (--out names another folder)", flush=True)
    args.out.mkdir(parents=True, exist_ok=True)
    if "games" in args.only:
        _games(opts, args.out)
        args.only = [s for s in args.only if s != "games"]
        if not args.only:
            return
    if "snooker" in args.only:
        _snooker(opts, args.out)
        args.only = [s for s in args.only if s != "snooker"]
        if not args.only:
            return
    common = dict(timestamp=datetime.datetime.now().isoformat(timespec="seconds"), quick=args.quick)
    if args.against:
        _against(args, opts, common)
    else:
        _run(args, opts, common)
