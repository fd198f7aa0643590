"""What champion's jump and massé strokes out of a hook are worth where balls fly (issue 46): champion against
itself without them (``Parts(escapes=False)``), 9-ball at ``tournament`` noise with ``effects={"airborne": True}``,
paired racks; the win rate and how many of each side's decisions elevated the cue.

    python scripts/escapes_worth.py --racks 500 --seed 9 --out results/champion/airborne/escapes_worth.json
    python scripts/escapes_worth.py --quick
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

from billiards_env.bots.planner.bot import Champion, Parts
from billiards_env.studies.matches import play_pairing


class _Counting(Champion):
    """champion counting its decisions and those that elevate the cue (``ShotPlan.theta`` > 0)."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self.decisions = self.elevated = 0

    def act(self, view):
        plan = super().act(view)
        self.decisions += len(plan.phi)
        if plan.theta is not None:
            self.elevated += int((np.asarray(plan.theta) > 0).sum())
        return plan


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--racks", type=int, default=500, help="racks, each played twice (each side breaking once)")
    ap.add_argument("--seed", type=int, default=9)
    ap.add_argument("--quick", action="store_true", help="2 racks, games cut at 20 shots")
    ap.add_argument("--out", type=Path, default=None, help="write the JSON here too")
    args = ap.parse_args(argv)
    racks, max_shots = (2, 20) if args.quick else (args.racks, 200)
    bots = {}

    def factory(spec, seed):
        bots[spec] = _Counting(seed=seed, parts=Parts(escapes=spec == "champion"))
        bots[spec].name = spec
        return bots[spec]

    result = play_pairing("champion", "champion-no-escapes", "nine_ball", racks, args.seed, "tournament",
                          max_shots=max_shots, bot_factory=factory, rack="realistic", effects={"airborne": True})
    doc = dict(command=" ".join(["python", "scripts/escapes_worth.py"] + (argv if argv is not None else sys.argv[1:])),
               summary=result.summary(),
               decisions={k: b.decisions for k, b in bots.items()}, elevated={k: b.elevated for k, b in bots.items()})
    text = json.dumps(doc, indent=1, default=float) + "\n"
    if args.out is not None:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text(text)
    print(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
