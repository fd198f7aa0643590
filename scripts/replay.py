#!/usr/bin/env python
"""Turn a saved replay, a seeded episode of a policy, or a demo shot into an
HTML viewer page, a GIF or MP4 animation, or replay JSON.

    python scripts/replay.py --replay episode-0000.json --out episode.html
    python scripts/replay.py --env Billiards-NineBall-v1 --policy search64 --seed 3 \
        --out nine.html --out nine.json --out nine.gif
    python scripts/replay.py --env Billiards-NineBall2P-v1 --policy search64 --opponent ghost --seed 3 \
        --out game.html
    python scripts/replay.py --scene break --out break.html

The output kind follows each ``--out`` suffix: ``.html`` (self-contained
viewer), ``.json`` (replay), ``.gif`` / ``.mp4`` (raster renderer; MP4 needs
imageio-ffmpeg). ``--policy``: ``ghost``, ``random``, ``search<K>`` (e.g.
``search64``) or a saved model (agents.evaluation.policies.make_policy); the episode
is the first one of a one-table vector env reset with ``--seed``. For a
two-player game id (any registered id whose env is a game env: 9-ball,
8-ball, ...) it is one whole game, every shot of both players from the break:
``--policy`` plays player 1 (the env's agent) and ``--opponent`` player 2
(each a bot name, ``module:factory`` or a saved model).
``--scene``: ``cut-draw`` (a cut shot with draw) or ``break`` (a 9-ball
break at 8 m/s).
"""
from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

SUFFIXES = (".html", ".json", ".gif", ".mp4")


def scene(name: str):
    """A demo shot as a one-shot Replay."""
    import numpy as np

    from billiards_env.physics import BallState, PhysicsParams, Table, simulate, strike_velocity
    from billiards_env.physics.state import diamond_slots
    from billiards_env.rendering import Replay

    table, params = Table.pool(9), PhysicsParams.standard()
    if name == "cut-draw":
        # object ball 30 cm from the top-right corner pocket, cut about 30 degrees, drawn back
        corner = np.array([table.width, table.length])
        obj = corner - 0.3 * np.array([1.0, 1.0]) / math.sqrt(2.0)
        ghost = obj - 2 * params.R * (corner - obj) / np.linalg.norm(corner - obj)
        cue = ghost + 0.9 * np.array([math.cos(math.radians(200.0)), math.sin(math.radians(200.0))])
        pos = np.array([cue, obj])
        d = ghost - cue
        phi, speed, a, b, title = math.atan2(d[1], d[0]), 3.0, 0.0, -0.4, "Cut shot with draw"
    elif name == "break":
        slots = diamond_slots(table, params.R)
        pos = np.zeros((10, 2))
        pos[1], pos[9] = slots[0], slots[4]
        pos[[2, 3, 4, 5, 6, 7, 8]] = slots[[1, 2, 3, 5, 6, 7, 8]]
        pos[0] = (table.width / 2 + 0.12, 0.25 * table.length)
        d = pos[1] - pos[0]
        phi, speed, a, b, title = math.atan2(d[1], d[0]), 8.0, 0.0, -0.1, "9-ball break"
    else:
        raise SystemExit(f"unknown scene {name!r}: choose cut-draw or break")
    start = strike_velocity(BallState.from_positions(pos), phi, speed, a, b, params)
    res = simulate(start, table, params, record=True)
    return Replay.from_sim(res, start, table, params, meta={"title": title, "scene": name})


def game_of(env_id: str) -> str | None:
    """The game (``nine_ball``, ...) of a registered two-player id, found by
    its entry point (a ``GameEnv``), else None."""
    import gymnasium as gym

    import billiards_env  # noqa: F401  (registers the ids)
    from billiards_env.envs.games.single import GameEnv

    try:
        entry = gym.spec(env_id).entry_point
    except gym.error.Error:
        return None
    if isinstance(entry, str):
        from gymnasium.envs.registration import load_env_creator
        entry = load_env_creator(entry)
    return entry.game if isinstance(entry, type) and issubclass(entry, GameEnv) else None


def game(env_id: str, policy: str, opponent: str, seed: int, noise: str | None = None,
         max_shots: int | None = None):
    """One whole game of ``env_id`` (a two-player id) seeded with ``seed``:
    ``policy`` (player 1, the env's agent) against ``opponent``, as a Replay."""
    import gymnasium as gym

    from agents.evaluation.entrants import bot_factory
    from billiards_env.rendering import GameRecorder

    kw = {"noise": noise} if noise else {}
    if max_shots:
        kw["max_shots"] = max_shots
    env = gym.make(env_id, render_mode="rgb_array", opponent=bot_factory(opponent, seed + 1), **kw)
    core = env.unwrapped.core
    players = (policy, opponent)
    rec = GameRecorder(core, [0], players=players,
                       meta={"env": env_id, "policy": policy, "opponent": opponent, "seed": seed,
                             "noise": noise or "none"})
    bot = bot_factory(policy, seed)
    env.reset(seed=seed)
    done = False
    while not done:
        _, _, term, trunc, _ = env.step(core.actions_of(bot.act(core.view([0])), [0])[0])
        done = term or trunc
    env.close()
    return rec.games(0)[-1]  # a game the opponent ended before the agent's first shot is not the one played


def episode(env_id: str, policy: str, seed: int, noise: str | None = None, max_shots: int | None = None):
    """The first episode of ``policy`` on a one-table vector env reset with ``seed``, as a Replay."""
    import gymnasium as gym
    import numpy as np

    import billiards_env  # noqa: F401  (registers the ids)
    from agents.evaluation.policies import make_policy
    from billiards_env.rendering import record_env_shot, replay_for_env

    kw = {"noise": noise} if noise else {}
    venv = gym.make_vec(env_id, num_envs=1, vectorization_mode="vector_entry_point", render_mode="rgb_array",
                        autoreset_mode="disabled", **kw)
    pol = make_policy(policy, venv, seed=seed)
    obs, _ = venv.reset(seed=seed)
    rep = replay_for_env(venv, meta={"title": f"{env_id} \u00b7 {getattr(pol, 'name', policy)} \u00b7 seed {seed}",
                                     "env": env_id, "policy": getattr(pol, "name", policy), "seed": seed,
                                     "noise": noise or "none"})
    while True:
        act = pol.act(obs)
        obs, rew, term, trunc, info = venv.step(act)
        record_env_shot(rep, venv, info, rew, act, index=0)
        if term[0] or trunc[0] or (max_shots and len(rep) >= max_shots):
            break
    venv.close()
    return rep


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    src = ap.add_mutually_exclusive_group(required=True)
    src.add_argument("--replay", help="a saved replay (.json)")
    src.add_argument("--env", help="env id, e.g. Billiards-NineBall-v1 (with --policy and --seed)")
    src.add_argument("--scene", choices=["cut-draw", "break"], help="a demo shot")
    ap.add_argument("--policy", default="ghost", help="ghost | random | search<K> | model path (default ghost)")
    ap.add_argument("--opponent", default="ghost", help="two-player games: player 2's bot (default ghost)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--noise", default=None, help="shot noise of the env: none (default) | tournament")
    ap.add_argument("--max-shots", type=int, default=None, help="stop the episode after this many shots")
    ap.add_argument("--out", action="append", required=True, help="output file: .html, .json, .gif or .mp4 (repeatable)")
    ap.add_argument("--title", default=None, help="page title (HTML)")
    ap.add_argument("--fps", type=int, default=30, help="GIF/MP4 frames per second")
    ap.add_argument("--ppm", type=float, default=300, help="GIF/MP4 pixels per metre")
    ap.add_argument("--speedup", type=float, default=1.0, help="GIF/MP4 playback speed")
    a = ap.parse_args(argv)

    outs = [Path(o) for o in a.out]
    for o in outs:
        if o.suffix.lower() not in SUFFIXES:
            ap.error(f"--out {o}: the suffix must be one of {', '.join(SUFFIXES)}")
    if any(o.suffix.lower() == ".mp4" for o in outs):
        import importlib.util
        if importlib.util.find_spec("imageio_ffmpeg") is None and importlib.util.find_spec("av") is None:
            ap.error("MP4 output needs imageio-ffmpeg: pip install imageio-ffmpeg (or write a .gif)")

    from billiards_env.rendering import Replay, save_replay_animation, save_replay_html

    if a.replay:
        rep = Replay.load(a.replay)
    elif a.scene:
        rep = scene(a.scene)
    elif game_of(a.env):
        rep = game(a.env, a.policy, a.opponent, a.seed, a.noise, a.max_shots)
    else:
        rep = episode(a.env, a.policy, a.seed, a.noise, a.max_shots)
    for o in outs:
        o.parent.mkdir(parents=True, exist_ok=True)
        kind = o.suffix.lower()
        if kind == ".html":
            save_replay_html(rep, o, title=a.title)
        elif kind == ".json":
            rep.save(o)
        else:
            save_replay_animation(o, rep, fps=a.fps, ppm=a.ppm, speedup=a.speedup)
        print(f"wrote {o} ({o.stat().st_size:,} bytes; {len(rep)} shot{'s' if len(rep) != 1 else ''})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
