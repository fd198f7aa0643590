#!/usr/bin/env python
"""Train the value network of ``value-lookahead`` by a league of generations (``agents.league``, docs/league.md).

    python scripts/league.py --config configs/league_nine_ball.yaml --run runs/league_nine_ball
    python scripts/league.py --run runs/league_nine_ball --resume --generations 6   # continue a stopped run
    python scripts/league.py --run runs/league_nine_ball --ship    # the newest snapshot becomes the shipped value
    python scripts/league.py --quick --run /tmp/league_quick       # a smoke run: 1 generation of 1 rack per job

Each generation prints one line per job (the learner's score, the samples recorded) and the fit's held-out log
loss; the state (``<run>/league.json``), the samples and the snapshots are written after each generation.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from agents.league import LeagueConfig, run_league, ship  # noqa: E402
from agents.league.league import GAMES  # noqa: E402

QUICK = dict(generations=1, racks=1, opponents=["ghost"], noises=["tournament"], max_shots=12,
             fit=dict(hidden=[8], epochs=2))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--config", type=Path, default=None, help="default configs/league_<game>.yaml")
    ap.add_argument("--game", choices=GAMES, default=None,
                    help="the game (default: the config's); the league trains the lookahead's value, so the pool games")
    ap.add_argument("--run", type=Path, required=True, help="the run directory (state, samples, snapshots)")
    ap.add_argument("--resume", action="store_true", help="continue the run in --run from its league.json")
    ap.add_argument("--generations", type=int, default=None, help="train until this many generations are done")
    ap.add_argument("--ship", action="store_true", help="only copy the run's newest snapshot to the package")
    ap.add_argument("--quick", action="store_true", help="1 generation, 1 rack per job against ghost (a smoke run)")
    ap.add_argument("--address", default=None, help="where to play the games (default: here)")
    args = ap.parse_args(argv)
    if args.ship:
        print(f"shipped {ship(args.run)}.npz / .json")
        return 0
    cfg = None
    if not args.resume:
        path = args.config or ROOT / "configs" / f"league_{args.game or 'nine_ball'}.yaml"
        if not path.exists():  # a game without a config of its own: the 9-ball league's settings for it
            path = ROOT / "configs" / "league_nine_ball.yaml"
        cfg = LeagueConfig.load(path, game=args.game)
        if args.quick:
            d = cfg.to_dict()
            d.update(QUICK)
            cfg = LeagueConfig.from_dict(d)
    state = run_league(args.run, cfg, resume=args.resume, generations=args.generations, address=args.address,
                       log=lambda s: print(s, flush=True))
    print(f"{state['generation']} generations, {state['seconds']:.0f} s; snapshots: "
          + ", ".join(f"{s['stem']} ({s['sha256'][:12]})" for s in state["snapshots"]))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
