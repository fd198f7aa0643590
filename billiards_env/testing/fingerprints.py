"""Behaviour fingerprints of every registered env id, and the command that records them.

    python -m billiards_env.testing.fingerprints            # compare with the committed file
    python -m billiards_env.testing.fingerprints --write    # regenerate it (after a version bump)
    python -m billiards_env.testing.fingerprints --id Billiards-PotOne-v1   # one id

A fingerprint plays each id a few seeded steps of seeded uniform random
actions through both of its entry points: ``gym.make(id)`` (the games
against their default opponent, so each step is the agent's shot and the
opponent's whole turns after it) and ``gym.make_vec(id, num_envs=VEC_ENVS,
vectorization_mode="vector_entry_point")`` (the games: self-play, both
players' turns). It hashes what a user sees, every observation, reward,
termination, truncation and numeric info entry (episode outcomes:
``success``, ``winner``, fouls, pocketed balls ...), each float rounded to
``PRECISION``. ``tests/envs/test_fingerprints.py`` compares the hashes with
``FINGERPRINTS`` (``tests/envs/env_fingerprints.json``); a mismatch
means the id's behaviour changed: bump its version (Gymnasium's convention,
docs/versions.md) and regenerate.
"""
from __future__ import annotations

import argparse
import hashlib
import json
import sys
from pathlib import Path

import numpy as np

# Floats are hashed as round(x / PRECISION): 1e-6 is far coarser than the ulp-level differences between CPUs and
# compilers (fused multiply-adds, vectorised libm; ~1e-12 relative after a shot's ~10^3 floating operations),
# so the hash is the same on every machine, yet far finer than any change of behaviour: a changed rule, rack,
# noise draw or bot moves positions by millimetres (1e-3 in table units), rewards by 1e-2 and flips flags.
# (A value within an ulp of a rounding boundary could still flip; at ~1e-10 odds per value it has not happened.)
PRECISION = 1e-6
SEED = 2026            # the reset seed of both entry points and of the actions' generator
SINGLE_STEPS = 24      # steps of gym.make(id): a game's step is a shot plus the opponent's turns after it
VEC_ENVS = 3           # tables of gym.make_vec(id)
VEC_STEPS = 12         # steps of the vector env (its tables autoreset as the env's mode does)
ROOT = Path(__file__).resolve().parents[2]
FINGERPRINTS = ROOT / "tests" / "envs" / "env_fingerprints.json"  # beside its test (tests/regressions holds fuzz-found cases)
CHANGED = ("behaviour changed: bump the id's version (-v{n} -> -v{n+1}: register the new id, keep the old "
           "one raising), record what changed in docs/versions.md, and regenerate the fingerprints with "
           "python -m billiards_env.testing.fingerprints --write")


def registered_ids() -> list[str]:
    """Every id the package registers: the one-player tasks' and the two-player games'."""
    import billiards_env  # noqa: F401 (registers the ids)
    from billiards_env.envs.registration import ENV_IDS, GAME_IDS
    return sorted(ENV_IDS) + sorted(GAME_IDS)


class _Hasher:
    """sha256 over rounded numbers, labelled so that the same values in another place hash differently."""

    def __init__(self):
        self.h = hashlib.sha256()

    def add(self, label: str, value) -> None:
        self.h.update(label.encode() + b"\0")
        a = np.asarray(value)
        if a.dtype == object:
            return
        if a.dtype.kind == "f":
            a = a.astype(np.float64)
            finite = np.isfinite(a)
            q = np.where(finite, np.round(np.where(finite, a, 0.0) / PRECISION), 0.0).astype(np.int64)
            self.h.update(np.ascontiguousarray(q).tobytes() + np.ascontiguousarray(~finite).tobytes())
        elif a.dtype.kind in "biu":
            self.h.update(np.ascontiguousarray(a.astype(np.int64)).tobytes())
        else:
            self.h.update(str(a.tolist()).encode())
        self.h.update(str(a.shape).encode())

    def add_tree(self, label: str, value) -> None:
        if isinstance(value, dict):
            for k in sorted(value, key=str):
                self.add_tree(f"{label}.{k}", value[k])
        elif isinstance(value, (tuple, list)) and value and isinstance(value[0], (dict, tuple, list, np.ndarray)):
            for i, v in enumerate(value):
                self.add_tree(f"{label}[{i}]", v)
        else:
            a = np.asarray(value) if not isinstance(value, str) else np.asarray(value, dtype=object)
            if a.dtype != object:
                self.add(label, a)

    def hexdigest(self) -> str:
        return self.h.hexdigest()


def _actions(space, rng: np.random.Generator, n: int | None = None):
    """Uniform random actions of a Box space from ``rng`` (not space.sample(), whose generator is Gymnasium's)."""
    from gymnasium import spaces
    if not isinstance(space, spaces.Box):
        raise TypeError(f"fingerprints draw Box actions; got {space}")
    shape = space.shape if n is None else (n,) + space.shape
    return rng.uniform(np.broadcast_to(space.low, shape), np.broadcast_to(space.high, shape)).astype(space.dtype)


def fingerprint_single(env_id: str) -> str:
    """The hash of ``gym.make(env_id)`` over ``SINGLE_STEPS`` seeded random steps (a finished episode is reset
    with the next seed)."""
    import gymnasium as gym
    env = gym.make(env_id)
    rng = np.random.default_rng(SEED)
    h = _Hasher()
    obs, info = env.reset(seed=SEED)
    h.add_tree("reset", (obs, info))
    episodes = 0
    for t in range(SINGLE_STEPS):
        obs, reward, term, trunc, info = env.step(_actions(env.action_space, rng))
        h.add_tree(f"step{t}", dict(obs=obs, reward=reward, term=term, trunc=trunc, info=info))
        if term or trunc:
            episodes += 1
            obs, info = env.reset(seed=SEED + episodes)
            h.add_tree(f"reset{t}", (obs, info))
    env.close()
    return h.hexdigest()


def fingerprint_vector(env_id: str) -> str:
    """The hash of ``gym.make_vec(env_id, VEC_ENVS)`` (the native vector entry point) over ``VEC_STEPS`` seeded
    random steps."""
    import gymnasium as gym
    env = gym.make_vec(env_id, num_envs=VEC_ENVS, vectorization_mode="vector_entry_point")
    rng = np.random.default_rng(SEED + 1)
    h = _Hasher()
    obs, info = env.reset(seed=SEED)
    h.add_tree("reset", (obs, info))
    for t in range(VEC_STEPS):
        obs, reward, term, trunc, info = env.step(_actions(env.single_action_space, rng, VEC_ENVS))
        h.add_tree(f"step{t}", dict(obs=obs, reward=reward, term=term, trunc=trunc, info=info))
    env.close()
    return h.hexdigest()


def fingerprints(ids=None) -> dict[str, dict[str, str]]:
    """``{id: {"single": hash, "vector": hash}}`` of ``ids`` (default: every registered id)."""
    return {env_id: {"single": fingerprint_single(env_id), "vector": fingerprint_vector(env_id)}
            for env_id in (ids or registered_ids())}


def document(hashes: dict) -> dict:
    """The file's contents: the hashes and what they were taken with."""
    return {"about": "Behaviour fingerprints of every registered env id (billiards_env/testing/fingerprints.py); "
                     "regenerate with: python -m billiards_env.testing.fingerprints --write",
            "precision": PRECISION, "seed": SEED, "single_steps": SINGLE_STEPS, "vec_envs": VEC_ENVS,
            "vec_steps": VEC_STEPS, "ids": hashes}


def load(path=FINGERPRINTS) -> dict:
    return json.loads(Path(path).read_text())


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--write", action="store_true", help=f"write the hashes to {FINGERPRINTS.relative_to(ROOT)}")
    ap.add_argument("--id", action="append", default=None, help="only this id (repeatable; not with --write)")
    ap.add_argument("--file", default=str(FINGERPRINTS), help="the fingerprints file (default: the committed one)")
    a = ap.parse_args(argv)
    if a.write and a.id:
        ap.error("--write records every id; --id checks some")
    got = fingerprints(a.id)
    if a.write:
        Path(a.file).parent.mkdir(parents=True, exist_ok=True)
        Path(a.file).write_text(json.dumps(document(got), indent=2) + "\n")
        print(f"wrote {len(got)} ids to {a.file}")
        return 0
    want = load(a.file)["ids"] if Path(a.file).exists() else {}
    bad = 0
    for env_id, h in got.items():
        for kind, value in h.items():
            same = want.get(env_id, {}).get(kind) == value
            bad += not same
            print(f"{'ok  ' if same else 'DIFF'} {env_id} {kind} {value[:16]}")
    if bad:
        print(CHANGED)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
