#!/usr/bin/env python
"""What kind of shots a policy plays on a multi-shot task, and what it leaves.

    python scripts/shot_stats.py --policy runs/<run> --policy ghost --policy search64 \
        --env Billiards-NineBall-v1 --episodes 1000

Plays the first episode of the held tables of scripts/evaluate.py (same
seed, no noise) and classifies every shot by the position before it: the
legal ball has an *open pot* (a ghost-ball shot into some pocket whose paths
are clear and whose approach the pocket accepts, billiards_env.bots.geometry.open_pots)
or not. Reports, per policy: shots per episode; the share of shots with an
open pot; how often a shot with an open pot pots a ball legally; how often
one without pots anyway, or is a legal miss (keeps the table) or a foul /
scratch; and the *leave*: after a legal pot that does not end the episode,
the share of positions whose next legal ball has an open pot (position play
raises it). Writes <out>.json when --out is given.
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def shot_stats(spec: str, env_id: str, episodes: int, seed: int) -> dict:
    import numpy as np

    from billiards_env.bots import geometry as G
    from agents.evaluation.harness import policy_factory
    from agents.sb3.vec_env import make_sb3_vec_env

    policy_fn, name, env_kwargs = policy_factory(spec, seed=0)
    env = make_sb3_vec_env(env_id, episodes, **env_kwargs)
    env.seed(seed)
    obs = env.reset()
    nat = env.unwrapped
    side = G.side_pocket_mask(nat.table)
    policy = policy_fn(env)

    def open_now():
        st = nat.state
        sh = G.ghost_shots(st.pos, st.on_table, np.asarray(nat.legal_target()), nat.table, nat.params, 0.0)
        return G.open_pots(sh, side).any(axis=1)

    live = np.ones(episodes, dtype=bool)
    n = dict(shots=0, open=0, open_pot=0, closed_pot=0, closed_miss=0, closed_fail=0, open_fail=0, pots_on=0,
             leave_open=0)
    for _ in range(10_000):
        if not live.any():
            break
        had_open = open_now()
        obs, _, dones, infos = env.step(policy.act(obs))
        pot = np.array([bool(i.get("n_pocketed", 0)) and not (i.get("foul") or i.get("scratch")) for i in infos])
        fail = np.array([bool(i.get("foul") or i.get("scratch")) for i in infos])
        after = open_now()  # tables that ended were reset: only the live, not done ones count below
        on = live & ~dones
        n["shots"] += int(live.sum())
        n["open"] += int((live & had_open).sum())
        n["open_pot"] += int((live & had_open & pot).sum())
        n["open_fail"] += int((live & had_open & fail).sum())
        n["closed_pot"] += int((live & ~had_open & pot).sum())
        n["closed_fail"] += int((live & ~had_open & fail).sum())
        n["closed_miss"] += int((live & ~had_open & ~pot & ~fail).sum())
        n["pots_on"] += int((on & pot).sum())
        n["leave_open"] += int((on & pot & after).sum())
        live &= ~dones
    env.close()
    closed = max(n["shots"] - n["open"], 1)
    return dict(policy=name, env_id=env_id, episodes=episodes, seed=seed, counts=n,
                shots_per_episode=n["shots"] / episodes,
                open_share=n["open"] / max(n["shots"], 1),
                pot_given_open=n["open_pot"] / max(n["open"], 1),
                fail_given_open=n["open_fail"] / max(n["open"], 1),
                pot_given_closed=n["closed_pot"] / closed,
                legal_miss_given_closed=n["closed_miss"] / closed,
                fail_given_closed=n["closed_fail"] / closed,
                leave_open_after_pot=n["leave_open"] / max(n["pots_on"], 1))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--policy", action="append", required=True, help="baseline name or run directory (repeatable)")
    ap.add_argument("--env", default="Billiards-NineBall-v1")
    ap.add_argument("--episodes", type=int, default=1000)
    ap.add_argument("--seed", type=int, default=12345)
    ap.add_argument("--out", default=None, help="write <out>.json")
    a = ap.parse_args(argv)
    rows = [shot_stats(p, a.env, a.episodes, a.seed) for p in a.policy]
    cols = ["shots_per_episode", "open_share", "pot_given_open", "fail_given_open", "pot_given_closed",
            "legal_miss_given_closed", "fail_given_closed", "leave_open_after_pot"]
    print("| policy | " + " | ".join(c.replace("_", " ") for c in cols) + " |")
    print("|---" * (len(cols) + 1) + "|")
    for r in rows:
        print(f"| {r['policy']} | " + " | ".join(f"{r[c]:.3f}" for c in cols) + " |")
    if a.out:
        Path(a.out).with_suffix(".json").write_text(json.dumps(rows, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
