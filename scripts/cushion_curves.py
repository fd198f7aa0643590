"""Rebound angle and speed against the incoming angle, every cushion model,
for a rolling, a stun and a side-spin ball (docs/models.md):

    python scripts/cushion_curves.py                  # results/accuracy/cushion_models.png and .csv
    python scripts/cushion_curves.py --quick --out /tmp/c.png   # 5 angles (the test's run)
"""
from __future__ import annotations

import argparse
import pathlib

from billiards_env.studies import cushion_curves

ROOT = pathlib.Path(__file__).resolve().parents[1]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="5 incoming angles instead of 81")
    ap.add_argument("--out", type=pathlib.Path, default=ROOT / "results" / "accuracy" / "cushion_models.png")
    args = ap.parse_args(argv)
    rows = cushion_curves.curves(cushion_curves.default_angles(args.quick))
    for path in cushion_curves.write(rows, args.out):
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
