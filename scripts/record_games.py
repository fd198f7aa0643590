#!/usr/bin/env python
"""Record seeded rollouts of every two-player game id into one .npz, or compare two such files:
the games' fingerprint.

    python scripts/record_games.py record out.npz [--steps 60] [--tables 16] [--quick]
    python scripts/record_games.py compare a.npz b.npz

For each game id: self-play with uniform random actions, and the agent
(random actions) against each of the game's reference opponents (the bots
that act through ``GameView.preview``: ``ghost`` and ``lookahead`` in the
pool games, ``carom`` in three-cushion, ``snooker`` in snooker), a vector
env of ``--tables`` tables reset with a fixed seed and stepped ``--steps``
times; every observation, reward, flag and info array is stored. Only the
public Gymnasium API is used, so the same file runs against an older tree
(``PYTHONPATH=<tree>``) and ``compare`` shows whether two trees play the
games bit-identically (``record_rollouts.py`` does the same for the
one-player tasks).
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))  # the sibling script record_rollouts

import numpy as np

from record_rollouts import compare  # noqa: E402  (the same comparison of two recordings)

SEED = 4321
OPPONENTS = {"NineBall2P": (None, "ghost", "lookahead"), "EightBall": (None, "ghost", "lookahead"),
             "TenBall": (None, "ghost", "lookahead"), "ThreeCushion": (None, "carom"),
             "Snooker": (None, "snooker")}


def _ids():
    from billiards_env.envs.registration import GAME_IDS
    return sorted(GAME_IDS)


def _opponents(env_id: str) -> tuple:
    name = env_id.split("-")[1]
    return OPPONENTS.get(name, (None,))


def _flat(prefix: str, info: dict, out: dict) -> None:
    for k, v in info.items():
        if isinstance(v, dict):
            _flat(f"{prefix}{k}.", v, out)
        elif isinstance(v, np.ndarray) and v.dtype != object:
            out[prefix + k] = v


def record(path: str, steps: int, tables: int, quick: bool = False) -> None:
    import gymnasium as gym

    import billiards_env  # noqa: F401  (registers the ids)

    arrays = {}
    for env_id in _ids():
        for opp in _opponents(env_id)[:2 if quick else None]:
            kw = {} if opp is None else {"opponent": opp}
            env = gym.make_vec(env_id, num_envs=tables, vectorization_mode="vector_entry_point", **kw)
            obs, info = env.reset(seed=SEED)
            rng = np.random.default_rng(7)
            cols = {"obs": [obs]}
            for _ in range(steps):
                act = rng.uniform(-1, 1, size=env.action_space.shape).astype(np.float32)
                obs, r, te, tr, info = env.step(act)
                flat = {}
                _flat("info.", info, flat)
                for k, v in (("obs", obs), ("reward", r), ("terminated", te), ("truncated", tr), *flat.items()):
                    cols.setdefault(k, []).append(np.asarray(v))
            env.close()
            tag = f"{env_id}|{opp or 'self-play'}|"
            for k, v in cols.items():
                if len(v) == len(cols["reward"]) + (k == "obs") and len({x.shape for x in v}) == 1:
                    arrays[tag + k] = np.stack(v)
            print(f"recorded {tag} {steps} steps", flush=True)
    np.savez_compressed(path, **arrays)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("record")
    r.add_argument("out")
    r.add_argument("--steps", type=int, default=60)
    r.add_argument("--tables", type=int, default=16)
    r.add_argument("--quick", action="store_true", help="self-play and the first opponent only")
    c = sub.add_parser("compare")
    c.add_argument("a")
    c.add_argument("b")
    args = ap.parse_args(argv)
    if args.cmd == "record":
        record(args.out, args.steps, args.tables, args.quick)
        return 0
    return compare(args.a, args.b)


if __name__ == "__main__":
    sys.exit(main())
