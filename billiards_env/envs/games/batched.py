"""What the batched game envs share: a ``gymnasium.vector.VectorEnv`` over
one ``GameCore`` of ``num_envs`` tables, its spaces, and the next shooter's
constraints reported in the info."""
from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium.vector import VectorEnv
from gymnasium.vector.utils import batch_space

from .core import GameCore
from .spaces import action_space, make_config, observation_space

RENDER_MODES = ("rgb_array",)


class GameTables(VectorEnv):
    """Base of ``GameVectorEnv`` (self-play) and ``GameVersusVectorEnv``
    (the agent against an opponent)."""

    def __init__(self, num_envs: int, game: str, config=None, overrides: dict | None = None):
        overrides = dict(overrides or {})
        render_mode = overrides.pop("render_mode", None)
        if render_mode is not None and render_mode not in RENDER_MODES:
            raise ValueError(f"render_mode must be one of {list(RENDER_MODES)} or None, got {render_mode!r}")
        self.config = make_config(config, {**overrides, "game": game} if config is None else overrides)
        self.num_envs = int(num_envs)
        self.render_mode = render_mode
        self.core = GameCore(self.config, self.num_envs, record=render_mode is not None)
        self.single_observation_space = observation_space(self.core)
        self.single_action_space = action_space(self.core)
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self._seeded = False
        self._autoreset_envs = np.zeros(self.num_envs, dtype=bool)

    # the views the policies read
    state = property(lambda self: self.core.state)
    table = property(lambda self: self.core.table)
    params = property(lambda self: self.core.params)

    def _reset_rows(self, options: dict | None) -> tuple[np.ndarray, np.ndarray | None]:
        """The tables a reset deals new games on (``options["reset_mask"]``,
        default all) and their breakers (``options["breaker"]``: 0, 1 or an
        array [N]; None: drawn from each table's stream)."""
        options = options or {}
        mask = options.get("reset_mask")
        idx = np.arange(self.num_envs) if mask is None else np.nonzero(np.asarray(mask, dtype=bool))[0]
        breaker = options.get("breaker")
        if breaker is not None:
            breaker = np.broadcast_to(np.asarray(breaker, dtype=np.int64), (self.num_envs,))[idx]
        return idx, breaker

    def constraints(self):
        return self.core.constraints()

    def render(self):
        """``render_mode="rgb_array"``: a tuple with one frame per table (the table and the
        game's status panel, ``rendering.game.render_game``), as Gymnasium's vector envs return."""
        if self.render_mode is None:
            import gymnasium as gym
            gym.logger.warn("render() called without a render_mode; pass render_mode='rgb_array' to gymnasium.make_vec")
            return None
        if self.core.state is None:
            raise RuntimeError("call reset() before render()")
        from ...rendering.game import render_game
        return tuple(render_game(self.core, k) for k in range(self.num_envs))

    def _constraint_info(self, info: dict[str, Any] | None = None) -> dict:
        """``info`` with the next shooter's constraints on every table."""
        c = self.core.constraints()
        info = {} if info is None else info
        info.update(to_move=c.shooter.copy(), ball_in_hand=c.ball_in_hand.copy(), targets=c.targets.copy(),
                    push_out_allowed=c.push_out_allowed.copy(), may_pass=c.may_pass.copy(),
                    call_needed=c.call_needed.copy())
        return info
