#!/usr/bin/env python
"""Train the proposal network by Expert Iteration and ship ``exit-search`` and ``exit-fast`` (``agents.exit``,
docs/expert_iteration.md).

    python scripts/expert_iteration.py --config configs/exit_nine_ball.yaml --run runs/exit_nine_ball --address local
    python scripts/expert_iteration.py --run runs/exit_nine_ball --resume          # continue a stopped run
    python scripts/expert_iteration.py --run runs/exit_nine_ball --ship            # into the package
    python scripts/expert_iteration.py --quick --run /tmp/exit_quick               # a smoke run of the whole pipeline

Each round prints one line per self-play job and one per epoch of the fit; the state (``<run>/exit.json``), the
records (``<run>/data``), the fits' checkpoints and the snapshots are written as they are done. ``--address``:
play the games on Ray (``local`` starts it on this machine, ``auto`` or HOST:PORT joins a cluster); without it
they are played in this process.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from agents.exit import QUICK, ExItConfig  # noqa: E402
from billiards_env.bots.learned.proposal_bot import games  # noqa: E402
from billiards_env.rules import DEFAULT_GAME  # noqa: E402


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--config", type=Path, default=None, help="default configs/exit_<game>.yaml")
    ap.add_argument("--game", choices=games(), default=None, help="the config's game if not given")
    ap.add_argument("--run", type=Path, required=True, help="the run directory (state, records, snapshots)")
    ap.add_argument("--resume", action="store_true", help="continue the run in --run from its exit.json")
    ap.add_argument("--rounds", type=int, default=None, help="stop when this many rounds are done (default: all)")
    ap.add_argument("--ship", action="store_true", help="only copy the finished run's networks into the package")
    ap.add_argument("--play", default=None, metavar="YAML",
                    help="with --ship: changes to the config's play budget, e.g. '{k: 48, first: 16}'")
    ap.add_argument("--quick", action="store_true", help="a smoke run: 2 tiny rounds and the distillation")
    ap.add_argument("--address", default=None, help="play the games on Ray: local, auto or HOST:PORT")
    ap.add_argument("--workers", type=int, default=None,
                    help="CPUs of a local Ray instance (--address local; default all cores)")
    args = ap.parse_args(argv)
    from agents.exit.loop import run_exit, ship
    if args.ship:
        play = yaml.safe_load(args.play) if args.play else None
        for stem in ship(args.run, log=lambda s: print(s, flush=True), play=play):
            print(f"shipped {stem}.npz / .json")
        return 0
    cfg = None
    if not args.resume:
        path = args.config or ROOT / "configs" / f"exit_{args.game or DEFAULT_GAME}.yaml"
        cfg = ExItConfig.load(path, game=args.game)
        if args.quick:
            cfg = cfg.replace(**QUICK)
    state = run_exit(args.run, cfg, resume=args.resume, rounds=args.rounds, address=args.address,
                     log=lambda s: print(s, flush=True), workers=args.workers)
    print(f"{state['round']} rounds, {state['decisions']} decisions, {state['seconds']:.0f} s; snapshots: "
          + ", ".join(f"{s['stem']} ({s['sha256'][:12]})" for s in state["snapshots"])
          + (f"; fast ({state['fast']['sha256'][:12]})" if state.get("fast") else ""))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
