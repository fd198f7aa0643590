"""Gymnasium environments: one step = one shot.

The cue ball is struck, the table is simulated until every ball rests, and
the observation is the resting table. ``BilliardsEnv`` is a single-table
``gymnasium.Env``; ``BilliardsVectorEnv`` is a native
``gymnasium.vector.VectorEnv`` that shoots all its tables with one batched
simulator call. The task classes (``PotOneEnv``, ``PotOneVectorEnv``, ...)
are generated from the task registry (``envs/tasks/``): one single-table and
one vector class per registered task, named ``<class_prefix>Env`` and
``<class_prefix>VectorEnv``, with the task's spec as their docstring.
"""
from __future__ import annotations

import os
import sys
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium import spaces
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from ..physics.strike import Shots
from .config import TaskConfig
from .core import BilliardsCore, ShotContext
from .streams import seed_vector_env
from .tasks.registry import TASKS, get_task

# The per-table info of a step (BilliardsCore.step) and its dtypes; tables
# that were not shot report -1 (no ball) for _NO_BALL_INFO, else zeros.
_INFO_DTYPES = {"pocketed": bool, "n_pocketed": np.int64, "first_contact": np.int64, "legal_target": np.int64,
                "foul": bool, "scratch": bool, "success": bool, "n_events": np.int64, "sim_time": np.float64,
                "sim_truncated": bool, "action_clipped": bool, "shot": np.int64}
_NO_BALL_INFO = ("first_contact", "legal_target")
_BALL_INFO = ("pocketed", "off_table")  # [N, B] entries
_AIRBORNE_INFO = {"off_table": bool}  # the airborne option's own entries (effects={"airborne": True})


def _info_dtypes(core) -> dict:
    return {**_INFO_DTYPES, **_AIRBORNE_INFO} if core.airborne else _INFO_DTYPES

_COMMON_DOC = """
    **Observation** (``Box(0, 1, (4*B + 1,), float32)``, B = n_balls + 1 balls,
    ball 0 the cue ball, then object balls 1..n_balls; balls are never reordered):

    ==============  ===========================================================
    index           meaning
    ==============  ===========================================================
    3*i             ball i x / table width (0 if pocketed)
    3*i + 1         ball i y / table length (0 if pocketed)
    3*i + 2         1 if ball i is on the table, 0 if pocketed
    3*B + i         1 if ball i is the legal target ball (lowest-numbered
                    object ball on the table), else 0 (slot 0 always 0)
    4*B             shots taken this episode / max_shots
    ==============  ===========================================================

    ``observation="target_frame"``: the table seen from the legal target
    ball instead (``Box(-1, 1, (4*B + 2 + 5*P,), float32)``, P pockets):
    cue -> target distance, every ball's position in the frame with origin
    at the target and x-axis along cue -> target, the target one-hot, the
    shot count, and per pocket (straightest first, those the target cannot
    enter on a straight line last) its unit direction and distance from the
    target and its axis; all lengths / table diagonal. Layout:
    ``billiards_env/envs/target_frame.py``.

    **Action** (``Box(-1, 1, (4,), float32)``):

    ===  ========================================================================
    a0   aim: ``aim="relative"`` (default) phi = angle(cue -> legal target) + pi*a0,
         so a0 = 0 aims straight at the target's centre; ``aim="absolute"``:
         phi = pi*a0 counter-clockwise from +x; ``aim="impact"``: a0 is the
         fullness of the hit on the legal target, the cue ball's path
         passing its centre at 2R*a0 (a0 = 0 full, +-1 the thinnest touch),
         so the object ball leaves at asin(a0) counter-clockwise from the
         cue ball's path (without throw): phi = angle(cue -> target) -
         asin(2R*a0 / d), d the centres' distance (``envs/impact.py``)
    a1   cue draw: min_draw + (a1 + 1)/2 * (max_draw - min_draw) m
         (speed = ``draw_to_speed(draw)`` = k * contact_time * draw / m,
         ~10 m/s at max_draw; 0.33 m/s at min_draw); ``speed_scale="log"``:
         min_draw * (max_draw / min_draw) ** ((a1 + 1)/2), a1 = 0 ~1.8 m/s
    a2   side offset a = miscue_limit * a2 (units of R, + = right english)
    a3   height offset b = miscue_limit * a3 (+ = follow, - = draw); (a, b) is
         scaled radially into the disc of radius miscue_limit
    ===  ========================================================================

    Why ``aim="impact"``: the pot depends on the direction the object ball
    leaves in, and that is fixed by the impact parameter alone (it leaves
    along the line of centres at contact, ``asin(b / 2R)`` from the cue
    ball's path); pool players aim by the same quantity, the ball-hit
    fraction ``1 - |a0|`` (D. Alciatore, billiards.colostate.edu, technical
    proof TP A.16). With the relative aim an aim error turns the object
    ball by about d / 2R times as much (17 times at d = 1 m); with the
    impact aim an error in a0 turns it by the same amount at any distance. Balls in the way get no special
    treatment: the simulator decides what the cue ball hits first.

    Values outside [-1, 1] are clipped (``info["action_clipped"]``); NaN or
    infinite values, or a wrong shape, raise ``ValueError``.
    ``actions_to_shots(actions) -> Shots`` (phi, speed in m/s, a, b) and
    ``shots_to_actions(shots) -> actions`` convert, each the inverse of the
    other on the unclipped range; both are relative to ``shot_context()``
    (legal target, aim origin, potential of every table, computed once per
    state change and shared by the observation, the reward and the policies).

    **Shot noise** (``noise=``: ``"none"`` default, ``"tournament"`` = std
    0.125 deg aim, 0.075 m/s speed, 0.5 mm per offset, or a mapping) is drawn
    from the table's own random stream, so seeding reproduces it.

    **The cue's elevation** (an option, off by default: the ids, spaces,
    observations and infos above are the planar env's): with the equipment's
    ``effects={"airborne": True}`` (``gym.make(id, effects={"airborne":
    True})``) the balls fly (jump and massé strokes, bounces on the slate,
    balls driven off the table: ``physics.Effects``) and the action is
    ``Box(-1, 1, (5,), float32)``: a4 is the cue's elevation theta =
    (a4 + 1) / 2 * 60 degrees (``contract.codec.MAX_ACTION_ELEVATION``),
    a4 = -1 the level cue; ``Shots.theta`` and ``ShotPlan.theta`` carry it.
    ``info["off_table"]`` [B] marks the balls the shot drove off the table
    (onto the rail or the floor): out of play as pocketed balls are, but in
    no pocket; the cue ball off the table is a scratch.

    **Reward**: sum of ``info["reward_terms"]``: ``pocket`` (per legal ball
    pocketed), ``scratch``, ``foul``, ``contact`` (legal target hit first),
    ``success`` and ``shaping`` = w * (gamma * Phi(s') - Phi(s)) with
    Phi = -(distance of the legal target to its nearest pocket) / diagonal
    (Phi = 0 in terminal states). Weights: ``RewardConfig``.

    **Info**: ``pocketed`` (balls pocketed by this shot), ``n_pocketed``,
    ``first_contact`` (-1 none), ``legal_target`` (before the shot), ``foul``
    (bool: the task's ruling, a wrong first contact or none; the two-player
    games' ``info["foul"]`` is a foul code instead, docs/games.md),
    ``scratch``, ``success``, ``n_events``, ``sim_time`` (s), ``sim_truncated``,
    ``action_clipped``, ``shot``, ``reward_terms``.

    **Configuration**: ``billiards_env/envs/tasks/defaults/<task>.yaml`` loaded into ``TaskConfig``;
    ``config=`` (a path or TaskConfig) replaces it, and any TaskConfig key
    given as a keyword argument (``n_balls=``, ``reward={...}``, ...)
    overrides it, the keys of its ``equipment`` section (table, physics,
    solver, ``min_draw``, effects, models, noise: the games' section too,
    docs/configuration.md) flat: ``noise=``, ``solver=``, ``dt=``,
    ``physics=``, ``effects={...}``.
"""


def _make_config(task: str, config, overrides: dict) -> TaskConfig:
    if config is None:
        return TaskConfig.default(task, **overrides)
    if isinstance(config, TaskConfig):
        if config.task != task:
            raise ValueError(f"config is for task {config.task!r}, this env is {task!r}")
        return TaskConfig.from_dict(config.to_dict(), **overrides) if overrides else config
    cfg = TaskConfig.from_yaml(config, **overrides)
    if cfg.task != task:
        raise ValueError(f"{config}: config is for task {cfg.task!r}, this env is {task!r}")
    return cfg


def _has_display() -> bool:
    return sys.platform in ("darwin", "win32") or bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


class _Renderer:
    """rgb_array / human rendering of one table, with the last shot's paths."""

    def __init__(self, render_mode, render_ppm, render_paths):
        self.render_mode, self.render_ppm, self.render_paths = render_mode, render_ppm, render_paths
        self._fig = None
        self._warned = False

    def frame(self, core: BilliardsCore, k: int) -> np.ndarray:
        from ..rendering import ball_paths, render_table
        paths = None
        if self.render_paths and core.last_events[k] is not None:
            paths = ball_paths(core.last_events[k], core.params, core.n_balls)
        s = core.state
        size = {} if self.render_ppm is None else {"ppm": self.render_ppm}  # None: the renderer's default
        return render_table(core.table, core.params, s.pos[k], s.pocket[k], paths=paths, **size)

    def show(self, img: np.ndarray, fps: int) -> None:
        if not _has_display():
            if not self._warned:
                gym.logger.warn("render_mode='human' needs a display; none found, nothing is shown")
                self._warned = True
            return
        import matplotlib.pyplot as plt
        if self._fig is None:
            plt.ion()
            self._fig, ax = plt.subplots()
            ax.axis("off")
            self._im = ax.imshow(img)
        else:
            self._im.set_data(img)
        self._fig.canvas.draw_idle()
        plt.pause(1.0 / fps)

    def close(self):
        if self._fig is not None:
            import matplotlib.pyplot as plt
            plt.close(self._fig)
            self._fig = None


class BilliardsEnv(gym.Env):
    """Single-table pool environment (base class; use a task subclass)."""

    metadata = {"render_modes": ["rgb_array", "human"], "render_fps": 4}
    task: str = ""

    def __init__(self, render_mode: str | None = None, config=None, render_ppm: float | None = None,
                 render_paths: bool = True, **overrides: Any):
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise ValueError(f"render_mode must be one of {self.metadata['render_modes']} or None, got {render_mode!r}")
        self.config = _make_config(self.task, config, overrides)
        self.render_mode = render_mode
        self._core = BilliardsCore(self.config, 1, record=render_mode is not None)
        self._renderer = _Renderer(render_mode, render_ppm, render_paths)
        d = self._core.obs_dim
        self.observation_space = spaces.Box(self._core.obs_low, 1.0, shape=(d,), dtype=np.float32)
        self.action_space = spaces.Box(-1.0, 1.0, shape=(self._core.action_dim,), dtype=np.float32)
        self._done = True
        self._seeded = False

    # public views used by baselines
    table = property(lambda self: self._core.table)
    params = property(lambda self: self._core.params)
    effects = property(lambda self: self._core.effects)
    models = property(lambda self: self._core.models)
    state = property(lambda self: self._core.state)
    last_events = property(lambda self: self._core.last_events[0])
    last_start = property(lambda self: self._core.last_start[0])

    def legal_target(self) -> int:
        """Legal target ball id (-1 if none)."""
        return int(self._core.legal_target()[0])

    def aim_origin(self) -> float:
        """Direction (rad) that action a0 = 0 aims at."""
        return float(self._core.shot_context().aim_origin[0])

    def shot_context(self) -> ShotContext:
        """The table's ``ShotContext`` (arrays of length 1; do not modify)."""
        return self._core.shot_context()

    def actions_to_shots(self, actions) -> Shots:
        """Actions [n, action_dim] (or [action_dim]), each for this table as it is now -> ``Shots`` [n] (after
        clipping)."""
        a = np.asarray(actions, dtype=np.float64)
        d = self._core.action_dim
        a2 = self._core.validate_actions(a.reshape(-1, d) if a.ndim == 1 else a, len(a.reshape(-1, d)))
        return self._core.actions_to_shots(a2, np.zeros(len(a2), dtype=np.int64))

    def shots_to_actions(self, shots: Shots) -> np.ndarray:
        """``Shots`` [n] (or scalars), each for this table as it is now -> actions [n, action_dim] (float64,
        clipped to [-1, 1])."""
        return self._core.shots_to_actions(shots, np.zeros(len(shots), dtype=np.int64))

    def view(self):
        """The read-only ``bots.TaskView`` of the table (one row), for a bot (docs/bots.md)."""
        return self._core.view(np.array([0]))

    def actions_of(self, plan) -> np.ndarray:
        """A bot's one-row ``ShotPlan`` -> actions [1, action_dim] (float32)."""
        return self._core.actions_of(plan, np.array([0]))

    def set_state(self, state) -> np.ndarray:
        """Start a new episode from ``state`` (a one-table ``BallState``, or
        positions [B, 2]), balls at rest; returns the observation."""
        self._core.set_state(state, np.array([0]))
        self._done = False
        return self._core.observe()[0]

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        super().reset(seed=seed)
        if seed is not None:
            self._core.streams.seed([0], [seed])
        elif not self._seeded:  # first, unseeded reset: key the table's stream from np_random
            self._core.streams.seed([0], [int(self.np_random.integers(2 ** 63))])
        self._seeded = True  # later unseeded resets continue the stream
        self._core.reset_tables([0])
        self._done = False
        if self.render_mode == "human":
            self.render()
        return self._core.observe()[0], {"legal_target": self.legal_target()}

    def step(self, action):
        if self._done:
            raise RuntimeError("the episode has ended (or never started): call reset() before step()")
        d = self._core.action_dim
        if np.shape(action) != (d,):
            raise ValueError(f"action must have shape ({d},), got {np.shape(action)}")
        a = self._core.validate_actions(np.asarray(action, dtype=np.float64).reshape(1, d), 1)
        out = self._core.step(a, [0])
        info = {k: (v[0] if k in _BALL_INFO else v[0].item()) for k, v in out["info"].items()}
        info["reward_terms"] = {k: float(v[0]) for k, v in out["terms"].items()}
        terminated, truncated = bool(out["terminated"][0]), bool(out["truncated"][0])
        self._done = terminated or truncated
        if self.render_mode == "human":
            self.render()
        return self._core.observe()[0], float(out["reward"][0]), terminated, truncated, info

    def render(self):
        if self.render_mode is None:
            gym.logger.warn("render() called without a render_mode; pass render_mode='rgb_array' to gymnasium.make")
            return None
        if self._core.state is None:
            raise RuntimeError("call reset() before render()")
        img = self._renderer.frame(self._core, 0)
        if self.render_mode == "human":
            self._renderer.show(img, self.metadata["render_fps"])
            return None
        return img

    def close(self):
        self._renderer.close()


def _autoreset_mode(mode) -> AutoresetMode:
    """An AutoresetMode from itself, its value ("SameStep") or its name in
    any case ("same_step")."""
    if isinstance(mode, AutoresetMode):
        return mode
    for m in AutoresetMode:
        if str(mode) in (m.value, m.name, m.name.lower()):
            return m
    raise ValueError(f"autoreset_mode must be one of {[m.name.lower() for m in AutoresetMode]}, got {mode!r}")


class BilliardsVectorEnv(VectorEnv):
    """Vector of pool tables shot with one batched simulator call per step
    (base class; use a task subclass).

    Seeding: ``reset(seed=s)`` seeds table k like a single env seeded with
    ``s + k`` (or pass a list of N seeds), so table k reproduces that single
    env's transitions. ``reset(options={"reset_mask": mask})`` resets only
    the masked tables.

    Autoreset (``autoreset_mode=``, declared in ``metadata["autoreset_mode"]``):

    - ``"next_step"`` (default, Gymnasium's default): the step after a
      table's episode ends resets that table (its action is ignored) and
      returns its first observation with reward 0, terminated = truncated =
      False and zeroed info entries; ``info["reset"]`` marks those tables.
    - ``"same_step"``: a table whose episode ends is reset within the same
      step; the returned observation is the new episode's first one, the
      final observation is in ``info["final_obs"]`` (rows marked by
      ``info["_final_obs"]``). No step is spent on resets: for one-shot tasks
      such as PotOne this halves the calls per episode.
    - ``"disabled"``: finished tables stay finished until
      ``reset(options={"reset_mask": mask})``; stepping them raises.
    """

    metadata = {"render_modes": ["rgb_array"], "render_fps": 4, "autoreset_mode": AutoresetMode.NEXT_STEP}
    task: str = ""

    def __init__(self, num_envs: int = 1, render_mode: str | None = None, config=None, render_ppm: float | None = None,
                 render_paths: bool = True, autoreset_mode: str | AutoresetMode = AutoresetMode.NEXT_STEP,
                 **overrides: Any):
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise ValueError(f"render_mode must be one of {self.metadata['render_modes']} or None, got {render_mode!r}")
        mode = _autoreset_mode(autoreset_mode)
        self.metadata = {**type(self).metadata, "autoreset_mode": mode}
        self.config = _make_config(self.task, config, overrides)
        self.num_envs = int(num_envs)
        self.render_mode = render_mode
        self._core = BilliardsCore(self.config, self.num_envs, record=render_mode is not None)
        self._renderer = _Renderer(render_mode, render_ppm, render_paths)
        d = self._core.obs_dim
        self.single_observation_space = spaces.Box(self._core.obs_low, 1.0, shape=(d,), dtype=np.float32)
        self.single_action_space = spaces.Box(-1.0, 1.0, shape=(self._core.action_dim,), dtype=np.float32)
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self._seeded = False
        self._autoreset_envs = np.zeros(self.num_envs, dtype=bool)
        self._idle_info: dict | None = None  # step's info of tables not shot (built on first use)

    table = property(lambda self: self._core.table)
    params = property(lambda self: self._core.params)
    effects = property(lambda self: self._core.effects)
    models = property(lambda self: self._core.models)
    state = property(lambda self: self._core.state)
    last_events = property(lambda self: self._core.last_events)

    def legal_target(self) -> np.ndarray:
        """Legal target ball id of every table, int [N] (-1 if none)."""
        return self._core.legal_target().copy()

    def aim_origin(self) -> np.ndarray:
        """Direction (rad) that action a0 = 0 aims at, per table [N]."""
        return self._core.shot_context().aim_origin.copy()

    def shot_context(self) -> ShotContext:
        """The ``ShotContext`` of every table (cached until the state changes; do not modify)."""
        return self._core.shot_context()

    def actions_to_shots(self, actions) -> Shots:
        """Actions [N, action_dim] -> ``Shots`` [N] for the current tables (after clipping)."""
        a = self._core.validate_actions(actions, self.num_envs)
        return self._core.actions_to_shots(a, np.arange(self.num_envs))

    def shots_to_actions(self, shots: Shots) -> np.ndarray:
        """``Shots`` [N] (or scalars) -> actions [N, action_dim] (float64, clipped to [-1, 1]) for the current
        tables."""
        return self._core.shots_to_actions(shots, np.arange(self.num_envs))

    def view(self):
        """The read-only ``bots.TaskView`` of every table, for a bot (docs/bots.md)."""
        return self._core.view(np.arange(self.num_envs))

    def actions_of(self, plan) -> np.ndarray:
        """A bot's ``ShotPlan`` for every table -> actions [N, action_dim] (float32)."""
        return self._core.actions_of(plan, np.arange(self.num_envs))

    def set_state(self, state) -> np.ndarray:
        """Start new episodes on every table from ``state`` (a ``BallState``
        of N tables, or positions [N, B, 2]), balls at rest; clears pending
        autoresets; returns the observations. Call ``reset`` first (seeding)."""
        if not self._seeded:
            raise RuntimeError("call reset() before set_state()")
        self._core.set_state(state, np.arange(self.num_envs))
        self._autoreset_envs = np.zeros(self.num_envs, dtype=bool)
        return self._core.observe()

    def reset(self, *, seed=None, options: dict | None = None):
        N = self.num_envs
        seed_vector_env(self, self._core.streams, seed)
        mask = (options or {}).get("reset_mask")
        if mask is None:
            idx = np.arange(N)
        else:
            mask = np.asarray(mask)
            if mask.shape != (N,) or mask.dtype != np.bool_:
                raise ValueError(f"options['reset_mask'] must be a bool array of shape ({N},), got "
                                 f"{mask.dtype} {mask.shape}")
            idx = np.nonzero(mask)[0]
        self._core.reset_tables(idx)
        self._autoreset_envs[idx] = False
        return self._core.observe(), {"legal_target": self.legal_target()}

    def step(self, actions):
        if not self._seeded:
            raise RuntimeError("call reset() before step()")
        N, B = self.num_envs, self._core.n_balls
        a = self._core.validate_actions(actions, N)
        mode = self.metadata["autoreset_mode"]
        done_prev = self._autoreset_envs
        if mode == AutoresetMode.DISABLED and done_prev.any():
            raise RuntimeError(f"tables {np.nonzero(done_prev)[0].tolist()} have finished their episodes: "
                               "reset them with reset(options={'reset_mask': mask}) (autoreset_mode='disabled')")
        act = np.nonzero(~done_prev)[0]
        rst = np.nonzero(done_prev)[0] if mode == AutoresetMode.NEXT_STEP else np.zeros(0, dtype=np.int64)
        if len(act) == N:  # every table shot: the core's arrays are already complete
            out = self._core.step(a, act)
            reward, terminated, truncated = out["reward"], out["terminated"], out["truncated"]
            dtypes = _info_dtypes(self._core)
            info = {k: np.asarray(v, dtype=dtypes[k]) for k, v in out["info"].items()}
            terms = out["terms"]
        else:  # some or no tables shot: the others report zeros
            reward, terminated, truncated = np.zeros(N), np.zeros(N, dtype=bool), np.zeros(N, dtype=bool)
            if self._idle_info is None:  # built once: copies are cheaper than np.full
                self._idle_info = {k: np.full((N, B) if k in _BALL_INFO else N, -1 if k in _NO_BALL_INFO else 0,
                                              dtype=dt) for k, dt in _info_dtypes(self._core).items()}
            info = {k: v.copy() for k, v in self._idle_info.items()}
            terms = {k: np.zeros(N) for k in self._core.task.reward_names}
            if len(act):
                out = self._core.step(a[act], act)
                reward[act] = out["reward"]
                terminated[act] = out["terminated"]
                truncated[act] = out["truncated"]
                for k, v in out["info"].items():
                    info[k][act] = v
                for k, v in out["terms"].items():
                    terms[k][act] = v
        if len(rst):
            self._core.reset_tables(rst)
        info["reward_terms"] = terms
        info["reset"] = done_prev.copy() if mode == AutoresetMode.NEXT_STEP else np.zeros(N, dtype=bool)
        done = terminated | truncated
        obs = self._core.observe()
        if mode == AutoresetMode.SAME_STEP and done.any():
            fin = np.nonzero(done)[0]
            info["final_obs"] = obs.copy()
            info["_final_obs"] = done.copy()
            self._core.reset_tables(fin)
            obs = self._core.observe()
            done = np.zeros(N, dtype=bool)
        self._autoreset_envs = done
        return obs, reward, terminated, truncated, info

    def render(self):
        if self.render_mode is None:
            gym.logger.warn("render() called without a render_mode; pass render_mode='rgb_array' to gymnasium.make_vec")
            return None
        if self._core.state is None:
            raise RuntimeError("call reset() before render()")
        return [self._renderer.frame(self._core, k) for k in range(self.num_envs)]

    def close_extras(self, **kwargs):
        self._renderer.close()


# ----------------------------------------------------------------- tasks
_CLASSES: dict[str, tuple] = {}  # task name -> (task, single-table class, vector class)


def env_classes(task) -> tuple[type, type]:
    """The (single-table, vector) env classes of a registered task (a name or
    a ``Task``), generated on first use: ``<class_prefix>Env`` and
    ``<class_prefix>VectorEnv``, documented by the task's spec."""
    task = get_task(task) if isinstance(task, str) else task
    cached = _CLASSES.get(task.name)
    if cached is not None and cached[0] is task:
        return cached[1], cached[2]
    spec = task.__doc__ or f"{task.env_id}\n"
    ns = {"task": task.name, "__module__": __name__}
    single = type(f"{task.class_prefix}Env", (BilliardsEnv,), {**ns, "__doc__": spec + _COMMON_DOC})
    vector = type(f"{task.class_prefix}VectorEnv", (BilliardsVectorEnv,),
                  {**ns, "__doc__": spec + BilliardsVectorEnv.__doc__ + _COMMON_DOC})
    _CLASSES[task.name] = (task, single, vector)
    return single, vector


def __getattr__(name: str):
    """The env classes of tasks registered after this module was imported
    (what Gymnasium's ``entry_point`` strings resolve to)."""
    for task in list(TASKS.values()):
        if name in (f"{task.class_prefix}Env", f"{task.class_prefix}VectorEnv"):
            single, vector = env_classes(task)
            return single if name == single.__name__ else vector
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


for _task in list(TASKS.values()):  # the built-in tasks: PotOneEnv, PotOneVectorEnv, ...
    for _cls in env_classes(_task):
        globals()[_cls.__name__] = _cls
del _task, _cls
