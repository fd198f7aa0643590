#!/usr/bin/env python
"""Learning curves (training success rate and reward vs env steps) from
runs/<name>/progress.csv.

    python scripts/plot_learning_curve.py runs/<a> [runs/<b> ...] --out curve.png
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
    a = ap.parse_args(argv)

    from agents.plotting import plot_runs
    plot_runs(a.runs, a.out, a.labels)
    print(f"wrote {a.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
