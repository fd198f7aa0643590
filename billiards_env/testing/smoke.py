"""An installed package's smoke test: ``python -m billiards_env.testing.smoke [folder]``.

Run from any folder after ``pip install billiards_env`` (the wheel, not a
checkout): every registered env id makes, resets and steps (the one-player
tasks also render an RGB frame, singly and as a vector env), on each game
with learned agents in the package its strongest shipped rung loads and
plays a match against ``ghost-safety`` to the end, and an exact replay page
is written. Exits non-zero, naming the failure, if any step fails. It also
checks that the wheel installed no top-level ``agents`` module.
"""
from __future__ import annotations

import importlib.util
import sys
import tempfile
from pathlib import Path

import numpy as np


def main(argv=None) -> int:
    import gymnasium as gym

    import billiards_env  # noqa: F401 (registers the ids)
    from billiards_env.envs.registration import ENV_IDS, GAME_IDS
    from billiards_env.rendering import RecordReplay
    from billiards_env.bots.learned.ladder import ladder_names
    from billiards_env.bots.registry import default_bot
    from billiards_env.rendering.game_words import game_words
    from billiards_env.rules import GAMES
    from billiards_env.studies.matches import play_pairing

    argv = sys.argv[1:] if argv is None else argv
    out = Path(argv[0]) if argv else Path(tempfile.mkdtemp(prefix="billiards_smoke_"))
    out.mkdir(parents=True, exist_ok=True)
    if importlib.util.find_spec("agents") is not None and "site-packages" in str(importlib.util.find_spec("agents").origin):
        print("FAIL: the install put a top-level 'agents' module into site-packages", file=sys.stderr)
        return 1
    for env_id in ENV_IDS:
        env = gym.make(env_id, render_mode="rgb_array")
        env.reset(seed=0)
        env.step(env.action_space.sample())
        frame = env.render()
        assert frame.ndim == 3 and frame.shape[2] == 3 and frame.dtype == np.uint8, (env_id, frame.shape)
        venv = gym.make_vec(env_id, num_envs=4, vectorization_mode="vector_entry_point")
        venv.reset(seed=0)
        venv.step(venv.action_space.sample())
        print(f"ok  {env_id}: made, stepped, rendered {frame.shape[1]}x{frame.shape[0]}; vector env stepped")
    for env_id in GAME_IDS:
        env = gym.make(env_id)
        game = env.unwrapped.core.config.game
        # the pool games against ghost and search16; the others against their own bot (no pockets to pot in)
        single, vector = ("ghost", "search16") if default_bot(game) == "ghost" else (default_bot(game),) * 2
        env = gym.make(env_id, opponent=single)
        env.reset(seed=0)
        env.step(env.action_space.sample())
        venv = gym.make_vec(env_id, num_envs=4, vectorization_mode="vector_entry_point", opponent=vector)
        venv.reset(seed=0)
        venv.step(venv.action_space.sample())
        print(f"ok  {env_id}: made and stepped against {single}; versus vector env against {vector}")
    shipped = [g for g in GAMES if ladder_names(g)]  # the games with learned agents in the package
    assert shipped, "the package ships no ladder weights (bots/learned/ladder/<game>/)"
    for game in shipped:
        rung = ladder_names(game)[-1]
        r = play_pairing(rung, "ghost-safety", game, n_racks=1, seed=0, max_shots=60)
        assert r.n == 2, r
        print(f"ok  match: {rung} vs ghost-safety, {r.n} games of {game_words(game)}, {r.shots.sum()} shots "
              f"(the package's ladder weights)")
    env = RecordReplay(gym.make("Billiards-PotOne-v1", render_mode="rgb_array"), out, name_prefix="smoke")
    env.reset(seed=0)
    done = False
    while not done:
        _, _, term, trunc, _ = env.step(env.action_space.sample())
        done = term or trunc
    env.close()
    pages = sorted(out.glob("smoke-*.html"))
    assert pages and pages[0].stat().st_size > 1000, pages
    print(f"ok  replay page: {pages[0]}")
    print("smoke test passed")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
