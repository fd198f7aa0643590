"""Compare the event kernel of this tree with another source tree on a fixed
set of shots: final positions of two-ball and post-break shots (largest
difference in metres) and the outcome statistics of breaks (chaotic: a
rounding difference changes single breaks, so only the distributions can
agree).

    python scripts/compare_kernels.py --other /path/to/tree --shots 10000

Each tree runs in its own process (PYTHONPATH set to it) on the same saved
initial states; the post-break layouts come from breaks simulated once in
the other tree, so both trees start every post-break shot from the same
positions.
"""
from __future__ import annotations

import argparse
import math
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
# Final positions of non-chaotic shots must agree within this (m): lazy
# evolution reorders floating-point operations, which moves a position by
# rounding (~1e-15 m) amplified by a few collisions, far below 1e-9 m.
POSITION_TOL = 1e-9


def make_shots(n: int, seed: int, out: Path, tree: Path) -> None:
    """Initial states: two-ball cuts, breaks (nine and fifteen) and
    post-break shots (a cue-ball shot from the layout the other tree's
    break left), saved in ``out`` (npz)."""
    from billiards_env.physics import BallState, PhysicsParams, Table, rack, simulate, strike_velocity
    P, T = PhysicsParams.standard(), Table.pool(9)
    rng = np.random.default_rng(seed)
    cue = np.column_stack([rng.uniform(0.3, 0.9, n), rng.uniform(0.5, 0.9, n)])
    obj = cue + np.column_stack([rng.uniform(-0.15, 0.15, n), rng.uniform(0.5, 0.8, n)])
    d = obj - cue
    phi = np.arctan2(d[:, 1], d[:, 0]) + rng.uniform(-1, 1, n) * np.arcsin(P.R / np.linalg.norm(d, axis=1))
    two = strike_velocity(BallState.from_positions(np.stack([cue, obj], axis=1)), phi, rng.uniform(0.5, 4.0, n),
                          rng.uniform(-0.4, 0.4, n), rng.uniform(-0.4, 0.4, n), P)
    breaks = {}
    for name in ("nine", "eight"):
        s = rack(T, P, name, n, seed=rng)
        breaks[name] = strike_velocity(s, math.pi / 2 + rng.normal(0, 0.01, n), rng.normal(8.0, 0.2, n),
                                       0.0, rng.uniform(-0.1, 0.1, n), P)
    # post-break layouts: the nine-ball breaks run in the other tree
    layout = run_in_tree(tree, {"nine": breaks["nine"]}, out.parent)["nine"]
    pos, pocket = layout["pos"].copy(), layout["pocket"].copy()
    pocket[:, 0] = -1  # a scratched cue ball is spotted at the head spot
    scratched = layout["pocket"][:, 0] >= 0
    pos[scratched, 0] = (T.width / 2, T.length / 4)
    keep = np.ones(n, dtype=bool)
    for e in np.flatnonzero(scratched):  # drop layouts where the spot is taken
        others = pos[e, 1:][pocket[e, 1:] < 0]
        keep[e] = np.all(np.hypot(*(others - pos[e, 0]).T) > 2 * P.R + 1e-6)
    post = BallState(pos[keep], np.zeros_like(pos[keep]), np.zeros(pos[keep].shape[:2] + (3,)), pocket[keep])
    post = strike_velocity(post, rng.uniform(0, 2 * np.pi, keep.sum()), rng.uniform(0.5, 5.0, keep.sum()),
                           rng.uniform(-0.4, 0.4, keep.sum()), rng.uniform(-0.4, 0.4, keep.sum()), P)
    arrays = {}
    for name, s in (("two", two), ("nine", breaks["nine"]), ("fifteen", breaks["eight"]), ("post", post)):
        arrays.update({f"{name}_pos": s.pos, f"{name}_vel": s.vel, f"{name}_omega": s.omega,
                       f"{name}_pocket": s.pocket})
    np.savez(out, **arrays)


WORKER = r"""
import sys, numpy as np
from billiards_env.physics import BallState, PhysicsParams, Table, simulate
P, T = PhysicsParams.standard(), Table.pool(9)
z = np.load(sys.argv[1])
res = {}
for name in sys.argv[3].split(","):
    s = BallState(z[name + "_pos"], z[name + "_vel"], z[name + "_omega"], z[name + "_pocket"])
    r = simulate(s, T, P, solver="event")
    res.update({name + "_pos": r.state.pos, name + "_pocket": r.state.pocket, name + "_nev": r.n_events,
                name + "_trunc": r.truncated})
np.savez(sys.argv[2], **res)
"""


def run_in_tree(tree: Path, states: dict, tmp: Path) -> dict:
    """Final states of ``states`` ({name: BallState}) simulated in ``tree``."""
    src, dst = tmp / f"in_{os.getpid()}.npz", tmp / "out.npz"
    arrays = {}
    for name, s in states.items():
        arrays.update({f"{name}_pos": s.pos, f"{name}_vel": s.vel, f"{name}_omega": s.omega,
                       f"{name}_pocket": s.pocket})
    np.savez(src, **arrays)
    return run_saved(tree, src, list(states), tmp)


def run_saved(tree: Path, src: Path, names: list[str], tmp: Path) -> dict:
    dst = tmp / f"out_{abs(hash(str(tree)))}.npz"
    env = dict(os.environ, PYTHONPATH=str(tree))
    subprocess.run([sys.executable, "-c", WORKER, str(src), str(dst), ",".join(names)], env=env, check=True,
                   cwd=str(tree))
    z = np.load(dst)
    return {name: {k: z[f"{name}_{k}"] for k in ("pos", "pocket", "nev", "trunc")} for name in names}


def compare(a: dict, b: dict) -> list[str]:
    """Report lines: position agreement (two, post), statistics (breaks)."""
    lines = []
    for name in ("two", "post"):
        x, y = a[name], b[name]
        same_pocket = np.all(x["pocket"] == y["pocket"], axis=1)
        on = (x["pocket"] < 0) & (y["pocket"] < 0)
        dpos = np.where(on[..., None], np.abs(x["pos"] - y["pos"]), 0.0).max(axis=(1, 2))
        bad = (~same_pocket) | (dpos > POSITION_TOL)
        lines.append(f"{name}: {len(dpos)} shots, max |dpos| {dpos.max():.3g} m, {int(bad.sum())} beyond "
                     f"{POSITION_TOL:g} m or with different pockets; events {x['nev'].mean():.3f} vs "
                     f"{y['nev'].mean():.3f} per shot")
    for name in ("nine", "fifteen"):
        x, y = a[name], b[name]
        stats = []
        for r in (x, y):
            potted = (r["pocket"] >= 0).sum(axis=1)
            stats.append(f"pocketed/break {potted.mean():.4f} (se {potted.std() / math.sqrt(len(potted)):.4f}), "
                         f"events/break {r['nev'].mean():.2f} (se {r['nev'].std() / math.sqrt(len(potted)):.2f}), "
                         f"cue scratched {np.mean(r['pocket'][:, 0] >= 0):.4f}, truncated {int(r['trunc'].sum())}")
        lines.append(f"{name} breaks: this tree {stats[0]}; other {stats[1]}")
    return lines


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--other", type=Path, required=True, help="source tree of the kernel to compare with")
    ap.add_argument("--shots", type=int, default=10_000, help="shots per scene")
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        shots = tmp / "shots.npz"
        make_shots(args.shots, args.seed, shots, args.other.resolve())
        names = ["two", "post", "nine", "fifteen"]
        this = run_saved(ROOT, shots, names, tmp)
        other = run_saved(args.other.resolve(), shots, names, tmp)
    lines = compare(this, other)
    print("\n".join(lines))
    bad = [l for l in lines if " 0 beyond" not in l and not l.split(":")[0].endswith("breaks")]
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
