#!/usr/bin/env python
"""Turn a trained game model into a ladder agent (weights .npz + JSON card).

    python scripts/export_ladder.py --run runs/ladder_nineball2p --steps 250000 --name ladder-1
    python scripts/export_ladder.py --run runs/ladder_eightball --name ladder-4          # the run's final model.zip
    python scripts/export_ladder.py --run runs/ladder_eightball --steps 500000 --name ladder-2 --check 512

Reads the run's checkpoint ``checkpoints/model_<steps>_steps.zip`` (or its
final ``model.zip``) with stable-baselines3, keeps the actor network and the
observation statistics, and writes
``billiards_env/bots/learned/ladder/<game>/<name>.npz`` and ``.json``
(``billiards_env.bots.learned.ladder``). ``--check N`` plays N seeded
positions of the game and fails unless the exported numpy network chooses
exactly the torch policy's actions on all of them.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from agents.sb3.ladder_export import export  # noqa: E402
from billiards_env.bots.learned import ladder as L  # noqa: E402


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--run", type=Path, required=True, help="a training run directory (scripts/train.py)")
    ap.add_argument("--steps", type=int, default=None, help="the checkpoint's step count (default: the final model)")
    ap.add_argument("--name", required=True, help="the rung: ladder-<k>")
    ap.add_argument("--version", type=int, default=1, help="the agent's version (bump when a rung is replaced)")
    ap.add_argument("--out", type=Path, default=L.LADDER_DIR)
    ap.add_argument("--check", type=int, default=256, metavar="N", help="positions to compare numpy with torch on")
    args = ap.parse_args(argv)
    if not L.is_ladder_name(args.name):
        ap.error(f"--name must look like ladder-<k>, got {args.name!r}")
    try:
        card = export(args.run, args.name, args.steps, args.version, args.out, args.check)
    except (FileNotFoundError, ValueError) as exc:
        ap.error(str(exc))
    path = args.out / card["game"] / f"{args.name}.npz"
    print(f"wrote {path} ({path.stat().st_size / 1024:.0f} KiB) and .json: {card['game']}, "
          f"{card['training_steps']} steps; numpy = torch on {card['checked_positions']} positions")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
