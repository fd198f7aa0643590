"""A Gymnasium wrapper that records every episode of a billiards env, or
every game of a two-player game env, as a replay (JSON) and its viewer page
(HTML)."""
from __future__ import annotations

from pathlib import Path

import gymnasium as gym
import numpy as np

from .game_replay import GameRecorder
from .html import save_replay_html
from .replay import Replay, record_env_shot, replay_for_env


class RecordReplay(gym.Wrapper):
    """Write each episode of a single-table billiards env to
    ``folder/<name_prefix>-NNNN.json`` (``Replay``) and ``.html`` (viewer),
    when it terminates or is truncated, or on ``close()`` / the next
    ``reset()`` if it was left unfinished.

    The env must keep each shot's event log, which it does when created
    with a render mode: ``gymnasium.make("Billiards-PotOne-v1",
    render_mode="rgb_array")``. An episode's first shot starts from the
    table ``reset()`` set up; for NineBall that is the table after the break
    (the env simulates the break inside ``reset()`` and keeps no log of it).

    A two-player game env (``Billiards-NineBall2P-v1``, ...) is recorded a
    game at a time, every shot of both players from the break, the
    opponent's too (``GameRecorder``): ``folder/<name_prefix>-NNNN`` is the
    NNNN-th game the env played, a game the opponent ended before the
    agent's first shot included.
    """

    def __init__(self, env: gym.Env, folder, name_prefix: str = "episode", html: bool = True,
                 meta: dict | None = None):
        super().__init__(env)
        u = env.unwrapped
        self.games: GameRecorder | None = None
        if hasattr(getattr(u, "core", None), "listeners"):  # a two-player game env
            if getattr(u, "render_mode", None) is None:
                raise ValueError("RecordReplay needs the env to keep event logs: create it with a render mode, e.g. "
                                 "gymnasium.make(env_id, render_mode='rgb_array')")
            spec = getattr(u, "_opponent_spec", None)
            opponent = spec if isinstance(spec, str) else getattr(spec, "name", type(spec).__name__)
            self.games = GameRecorder(u.core, [0], players=("agent", opponent), meta=meta)
        elif not hasattr(u, "last_events") or isinstance(getattr(u, "last_events", None), list):
            raise TypeError("RecordReplay wraps a single-table billiards env (one of billiards_env's *Env classes)")
        if getattr(u, "render_mode", None) is None:
            raise ValueError("RecordReplay needs the env to keep event logs: create it with a render mode, e.g. "
                             "gymnasium.make(env_id, render_mode='rgb_array')")
        self.folder = Path(folder)
        self.folder.mkdir(parents=True, exist_ok=True)
        self.name_prefix, self.html, self.meta = name_prefix, html, dict(meta or {})
        self.episode = 0
        self.replay: Replay | None = None
        self.saved: list[Path] = []

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        self._finish()
        if self.games is not None:
            self.games.meta["seed"] = seed
            obs, info = self.env.reset(seed=seed, options=options)
            self._save_games(self.games.take_finished(0))
            return obs, info
        obs, info = self.env.reset(seed=seed, options=options)
        spec = getattr(self.env, "spec", None) or getattr(self.env.unwrapped, "spec", None)
        env_id = spec.id if spec is not None else type(self.env.unwrapped).__name__
        meta = {"title": f"{env_id} episode {self.episode}", "env": env_id, "seed": seed, "episode": self.episode,
                **self.meta}
        self.replay = replay_for_env(self.env, meta=meta)
        return obs, info

    def step(self, action):
        if self.games is not None:
            out = self.env.step(action)
            self._save_games(self.games.take_finished(0))
            return out
        if self.replay is None:
            raise RuntimeError("call reset() before step()")
        act = np.asarray(action, dtype=np.float64).copy()
        obs, reward, terminated, truncated, info = self.env.step(action)
        record_env_shot(self.replay, self.env, info, reward, act)
        if terminated or truncated:
            self._finish()
        return obs, reward, terminated, truncated, info

    def _save_games(self, games) -> None:
        for rep in games:
            if len(rep):
                self.replay = rep
                self._finish()

    def _finish(self) -> None:
        if self.replay is None or len(self.replay) == 0:
            self.replay = None
            return
        stem = self.folder / f"{self.name_prefix}-{self.episode:04d}"
        self.saved.append(self.replay.save(stem.with_suffix(".json")))
        if self.html:
            self.saved.append(save_replay_html(self.replay, stem.with_suffix(".html")))
        self.episode += 1
        self.replay = None

    def close(self):
        if self.games is not None:
            self._save_games(self.games.take_finished(0, unfinished=True))
            self.games.detach()
        self._finish()
        super().close()
