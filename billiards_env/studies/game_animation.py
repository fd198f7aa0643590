"""One seeded game between two bots, written as an animation: every shot with its ball paths, then the
resting table with the ruling (``rendering.game`` draws the frames; this module plays the game)."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..bots import make_bot
from ..envs.games import GameConfig, GameCore
from ..envs.games.play import bot_actions
from ..rendering.draw import Animation, write_animation
from ..rendering.game import GAME_ANIMATION, render_game, shot_frames
from ..rules import DEFAULT_GAME


def save_game_animation(path, game: str = DEFAULT_GAME, policies=("ghost", "ghost"), seed: int = 0,
                        anim: Animation = GAME_ANIMATION, max_shots: int = 60, noise: str = "tournament") -> Path:
    """Play one seeded game between two bots (names for ``bots.make_bot``,
    or bots) and write it as a GIF (or MP4): every shot animated at
    ``anim.speedup`` x real time, then ``anim.hold`` frames of the resting
    table with the ruling. Returns the path."""
    ppm, hold = anim.ppm, anim.hold
    core = GameCore(GameConfig(game=game, noise=noise, max_shots=max_shots), 1, record=True)
    core.streams.seed([0], [seed])
    core.reset_tables([0], [0])
    bots = [make_bot(policies[0], seed), make_bot(policies[1], seed + 1)]
    frames = [render_game(core, 0, None, ppm=ppm)] * hold
    info = None
    while True:
        who = int(core.constraints().shooter[0])
        start_pos, start_on = core.state.pos[0].copy(), core.state.pocket[0] < 0
        out = core.step(bot_actions(core, bots[who], [0]), [0])
        log = core.last_events[0]
        start_pos[0], start_on[0] = out["info"]["placement"][0], True
        if not out["info"]["passed"][0] and log is not None:
            frames += shot_frames(core, start_pos, start_on, log, info, anim)
        info = out["info"]
        frames += [render_game(core, 0, info, ppm=ppm)] * hold
        if out["terminated"][0] or out["truncated"][0]:
            break
    return write_animation(path, np.stack(frames), anim.fps)
