#!/usr/bin/env python
"""Record seeded rollouts of every env id into one .npz, or compare two such files.

    python scripts/record_rollouts.py record out.npz [--steps 1000] [--tables 64]
    python scripts/record_rollouts.py compare a.npz b.npz

For each env id, each autoreset mode (next_step, same_step) and each policy
(uniform random actions, the ghost-ball baseline) a vector env of ``--tables``
tables is reset with a fixed seed and stepped ``--steps`` times; every
observation, reward, termination flag and info array is stored. Only the
public Gymnasium API and the ghost-ball baseline (``billiards_env.bots.one_player``; ``agents.baselines`` in older trees) are used, so the
same file runs against an older tree (``PYTHONPATH=<tree>``) and ``compare``
shows whether two trees behave bit-identically.
"""
from __future__ import annotations

import argparse
import sys

import numpy as np

ENV_IDS = ("Billiards-PotOne-v1", "Billiards-RunOut-v1", "Billiards-NineBall-v1")
MODES = ("next_step", "same_step")
POLICIES = ("random", "ghost")


def _flat(prefix: str, info: dict, out: dict) -> None:
    for k, v in info.items():
        if isinstance(v, dict):
            _flat(f"{prefix}{k}.", v, out)
        else:
            out.setdefault(prefix + k, []).append(np.asarray(v))


def record(path: str, steps: int, tables: int) -> None:
    import gymnasium as gym

    import billiards_env  # noqa: F401  (registers the ids)
    try:
        from billiards_env.bots.one_player import BotPolicy, GhostBallPolicy

        def ghost_policy(env):
            return BotPolicy(GhostBallPolicy(), env)
    except ImportError:  # an older tree (PYTHONPATH=<tree>): the baselines lived in agents/
        from agents.baselines import GhostBallPolicy as ghost_policy

    arrays = {}
    for env_id in ENV_IDS:
        for mode in MODES:
            for pol in POLICIES:
                env = gym.make_vec(env_id, num_envs=tables, vectorization_mode="vector_entry_point",
                                   autoreset_mode=mode)
                obs, info = env.reset(seed=1234)
                rng = np.random.default_rng(99)
                ghost = ghost_policy(env.unwrapped) if pol == "ghost" else None
                cols = {"obs": [obs], "reset.legal_target": [np.asarray(info["legal_target"])]}
                for t in range(steps):
                    if ghost is None:
                        act = rng.uniform(-1, 1, size=(tables, 4)).astype(np.float32)
                    else:
                        act = ghost.act(obs)
                    cols.setdefault("action", []).append(np.asarray(act))
                    obs, r, te, tr, info = env.step(act)
                    for k, v in (("obs", obs), ("reward", r), ("terminated", te), ("truncated", tr)):
                        cols.setdefault(k, []).append(np.asarray(v))
                    flat = {}
                    _flat("info.", info, flat)
                    for k, v in flat.items():
                        key = f"{k}@{t}" if k.startswith("info.final_obs") or k.startswith("info._final_obs") else k
                        cols.setdefault(key, []).extend(v)
                env.close()
                tag = f"{env_id}|{mode}|{pol}|"
                for k, v in cols.items():
                    arrays[tag + k] = np.stack(v) if "@" not in k else v[0]
                print(f"recorded {tag} {steps} steps", flush=True)
    np.savez_compressed(path, **arrays)


def compare(a: str, b: str) -> int:
    A, B = np.load(a), np.load(b)
    ka, kb = set(A.files), set(B.files)
    bad = 0
    for k in sorted(ka ^ kb):
        print(f"only in {'first' if k in ka else 'second'}: {k}")
        bad += 1
    n = 0
    for k in sorted(ka & kb):
        x, y = A[k], B[k]
        n += x.size
        if x.shape != y.shape or x.dtype != y.dtype or not np.array_equal(x, y):
            print(f"DIFFERENT: {k} {x.shape} {x.dtype} vs {y.shape} {y.dtype}")
            bad += 1
    print(f"{len(ka & kb)} arrays, {n} values compared; {bad} differences")
    return 1 if bad else 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("record")
    r.add_argument("out")
    r.add_argument("--steps", type=int, default=1000)
    r.add_argument("--tables", type=int, default=64)
    c = sub.add_parser("compare")
    c.add_argument("a")
    c.add_argument("b")
    args = ap.parse_args(argv)
    if args.cmd == "record":
        record(args.out, args.steps, args.tables)
        return 0
    return compare(args.a, args.b)


if __name__ == "__main__":
    sys.exit(main())
