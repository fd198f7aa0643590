#!/usr/bin/env python
"""Learning curves (training success rate and reward vs env steps) from
runs/<name>/progress.csv, or with ``--held-out`` the held-out evaluations
(runs/<name>/evaluations.csv, ``train.eval_every``) against training seconds.

    python scripts/plot_learning_curve.py runs/<a> [runs/<b> ...] --out curve.png
    python scripts/plot_learning_curve.py runs/<a> runs/<b> --held-out --out held_out.png
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--labels", nargs="*", default=None)
    ap.add_argument("--out", default="learning_curve.png")
    ap.add_argument("--held-out", action="store_true",
                    help="held-out success against training seconds (equal wall time) instead")
    a = ap.parse_args(argv)
    if a.labels and len(a.labels) != len(a.runs):
        ap.error(f"--labels: {len(a.labels)} labels for {len(a.runs)} runs")

    from agents.plotting import plot_held_out, plot_runs
    (plot_held_out if a.held_out else plot_runs)(a.runs, a.out, a.labels)
    print(f"wrote {a.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
