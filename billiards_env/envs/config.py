"""Typed, frozen task configuration loaded from YAML (``billiards_env/envs/tasks/defaults/<task>.yaml``, package data).

A ``TaskConfig`` holds everything a task needs: table, physics preset,
solver, ball count, shot limit, action mapping, reward weights
(``RewardConfig``), shot noise (``NoiseConfig``), physics effects
(``Effects``) and the model of each interaction (``Models``). Unknown keys anywhere raise a ``ValueError`` naming them.
The YAML files are the only source of defaults; checks that depend on the
task (e.g. pot_one has one object ball) are the task's own ``validate``.
"""
from __future__ import annotations

import dataclasses
from pathlib import Path

import yaml

from ..physics import Effects, Models, PhysicsParams, Table
from ..physics.noise import NoiseConfig  # noqa: F401 (NoiseConfig re-exported)
from ..physics.validation import check_keys, finite_number as _number  # noqa: F401 (check_keys re-exported)
from .tasks.base import CONFIG_DIR
from .tasks.registry import get_task

CONFIG_VERSION = 1
AIMS = ("relative", "absolute", "impact")        # meaning of action a0 (billiards._COMMON_DOC)
SPEED_SCALES = ("linear", "log")                  # meaning of action a1 (billiards._COMMON_DOC)
OBSERVATIONS = ("table", "target_frame")          # observation layouts (billiards._COMMON_DOC)
__all__ = ["TaskConfig", "RewardConfig", "NoiseConfig", "CONFIG_DIR", "CONFIG_VERSION", "check_keys"]


@dataclasses.dataclass(frozen=True)
class RewardConfig:
    """Reward weights. Each term is reported separately in ``info["reward_terms"]``.

    - ``pocket``: per legal ball pocketed on a shot without foul or scratch;
    - ``scratch``: added when the cue ball is pocketed (a penalty: negative);
    - ``foul``: added on a wrong first contact (no ball hit, or not the legal one);
    - ``contact``: added when the cue ball first hits the legal target ball;
    - ``success``: added when the shot completes the task (pot / run out / 9 legally);
    - ``shaping``: weight of the potential-based term gamma*Phi(s') - Phi(s),
      Phi = -(distance of the legal target ball to its nearest pocket) / table
      diagonal, Phi = 0 in terminal states (so the optimal policy is unchanged).
    """

    pocket: float = 1.0
    scratch: float = -1.0
    foul: float = -1.0
    contact: float = 0.1
    success: float = 0.0
    shaping: float = 0.0
    gamma: float = 0.99

    def __post_init__(self):
        for f in dataclasses.fields(self):
            object.__setattr__(self, f.name, _number(getattr(self, f.name), f"reward.{f.name}"))
        if not 0.0 <= self.gamma <= 1.0:
            raise ValueError(f"reward.gamma must lie in [0, 1], got {self.gamma}")

    @classmethod
    def from_dict(cls, d: dict | None) -> "RewardConfig":
        d = dict(d or {})
        check_keys(cls, d, "reward config")
        return cls(**d)

    def to_dict(self) -> dict:
        return dataclasses.asdict(self)


@dataclasses.dataclass(frozen=True)
class TaskConfig:
    """Everything that defines a task instance.

    - ``task``: a registered task name (``pot_one``, ``run_out``, ``nine_ball``, ...);
    - ``table``: ``pool`` (with ``table_size_ft`` 7, 8 or 9), ``pocketless`` or
      ``carom`` (the carom match table, ``Table.carom()``);
    - ``physics``: a ``PhysicsParams`` preset name (``standard``, ``seed``, ``carom``);
    - ``solver``: ``event`` (exact) or ``step`` (fixed step ``dt`` seconds);
    - ``n_balls``: object balls (pot_one: 1, nine_ball: 9);
    - ``max_shots``: shots per episode before truncation;
    - ``aim``: ``relative`` (a0 turns the aim away from the line cue -> legal
      target ball), ``absolute`` (a0 * pi from +x) or ``impact`` (a0 sets the
      fullness of the hit on the legal target: the cue ball's path passes
      its centre at 2R * a0, ``envs/impact.py``);
    - ``speed_scale``: ``linear`` (a1 -> cue draw linearly from ``min_draw``
      to ``max_draw``) or ``log`` (geometrically: equal steps of a1 are
      equal speed ratios, so slow shots get as much of the range as fast ones);
    - ``observation``: ``table`` (ball positions in table coordinates) or
      ``target_frame`` (positions and pockets relative to the legal target
      and the line cue -> target, ``envs/target_frame.py``);
    - ``min_draw``: cue draw (m) at a1 = -1 (small and positive so the cue ball moves);
    - ``margin``: clearance (m) between randomly placed balls and from the cushions;
    - ``break_speed``: nine_ball break-shot speed (m/s);
    - ``effects``, ``models``, ``reward``, ``noise``: nested configs (``NESTED``);
      ``models`` names the model of each interaction (docs/models.md), e.g.
      ``models: {cushion: mathavan2010}``; unnamed interactions keep ``Models()``.
    """

    task: str
    version: int = CONFIG_VERSION
    table: str = "pool"
    table_size_ft: int = 9
    physics: str = "standard"
    solver: str = "event"
    dt: float | None = None
    n_balls: int = 1
    max_shots: int = 1
    aim: str = "relative"
    speed_scale: str = "linear"
    observation: str = "table"
    min_draw: float = 0.01
    margin: float = 0.01
    break_speed: float = 8.0
    effects: Effects = dataclasses.field(default_factory=Effects)
    models: Models = dataclasses.field(default_factory=Models)
    reward: RewardConfig = dataclasses.field(default_factory=RewardConfig)
    noise: NoiseConfig = dataclasses.field(default_factory=NoiseConfig)

    def __post_init__(self):
        if self.version != CONFIG_VERSION:
            raise ValueError(f"config version {self.version!r} is not supported (expected {CONFIG_VERSION})")
        task = get_task(self.task)  # ValueError naming the registered tasks
        if self.table not in ("pool", "pocketless", "carom"):
            raise ValueError(f"table must be 'pool', 'pocketless' or 'carom', got {self.table!r}")
        if self.solver not in ("event", "step"):
            raise ValueError(f"solver must be 'event' or 'step', got {self.solver!r}")
        if self.solver == "step":
            if self.dt is None or _number(self.dt, "dt") <= 0:
                raise ValueError("the step solver needs a positive time step dt (s), e.g. dt: 1.0e-4")
        if self.aim not in AIMS:
            raise ValueError(f"aim must be one of {AIMS}, got {self.aim!r}")
        if self.speed_scale not in SPEED_SCALES:
            raise ValueError(f"speed_scale must be one of {SPEED_SCALES}, got {self.speed_scale!r}")
        if self.observation not in OBSERVATIONS:
            raise ValueError(f"observation must be one of {OBSERVATIONS}, got {self.observation!r}")
        for name in ("n_balls", "max_shots", "table_size_ft", "version"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int) or v < 1:
                raise ValueError(f"{name} must be a positive integer, got {v!r}")
        if self.n_balls > 15:
            raise ValueError(f"n_balls must be at most 15, got {self.n_balls}")
        object.__setattr__(self, "min_draw", _number(self.min_draw, "min_draw"))
        object.__setattr__(self, "margin", _number(self.margin, "margin", 0.0))
        object.__setattr__(self, "break_speed", _number(self.break_speed, "break_speed"))
        if not 0 < self.min_draw < self.params().max_draw:
            raise ValueError(f"min_draw must lie in (0, max_draw = {self.params().max_draw}), got {self.min_draw}")
        if not 0 < self.break_speed <= 2 * self.params().max_speed:
            raise ValueError(f"break_speed must be positive and plausible, got {self.break_speed}")
        for name, (cls, _) in NESTED.items():
            if not isinstance(getattr(self, name), cls):
                raise ValueError(f"{name} must be a {cls.__name__} (use TaskConfig.from_dict for mappings)")
        task.validate(self)

    # --- construction -----------------------------------------------------
    @classmethod
    def from_dict(cls, d: dict, **overrides) -> "TaskConfig":
        d = {**dict(d), **overrides}
        check_keys(cls, d, "task config")
        if "task" not in d:
            raise ValueError("task config needs a 'task' key")
        for name, (sub, build) in NESTED.items():
            if name in d and not isinstance(d[name], sub):
                d[name] = build(d[name])
        return cls(**d)

    @classmethod
    def from_yaml(cls, path, **overrides) -> "TaskConfig":
        path = Path(path)
        with open(path) as f:
            d = yaml.safe_load(f) or {}
        try:
            return cls.from_dict(d, **overrides)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"{path}: {exc}") from exc

    @classmethod
    def default(cls, task: str, **overrides) -> "TaskConfig":
        """The task's shipped configuration (``billiards_env/envs/tasks/defaults/<task>.yaml``, package data, or
        the task's own ``config_path``), the single source of its defaults."""
        path = get_task(task).default_config_path
        if not path.exists():
            raise FileNotFoundError(
                f"no default configuration for task {task!r}: {path} does not exist. A built-in task's YAML "
                f"is package data in billiards_env/envs/tasks/defaults/; a task of your own names its file "
                f"with config_path, or pass config=<path to a YAML file or a TaskConfig>")
        return cls.from_yaml(path, **overrides)

    def to_dict(self) -> dict:
        d = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}
        for name in NESTED:
            d[name] = d[name].to_dict()
        return d

    def to_yaml(self, path) -> None:
        with open(path, "w") as f:
            yaml.safe_dump(self.to_dict(), f, sort_keys=False)

    # --- derived objects --------------------------------------------------
    def params(self) -> PhysicsParams:
        return PhysicsParams.preset(self.physics)

    def make_table(self) -> Table:
        if self.table == "carom":
            return Table.carom()
        return Table.pool(self.table_size_ft) if self.table == "pool" else Table.pocketless()



# Nested configs of TaskConfig: field -> (class, builder from YAML data). A new
# nested config is one TaskConfig field plus one line here.
NESTED = {
    "effects": (Effects, Effects.from_dict),
    "models": (Models, Models.from_dict),
    "reward": (RewardConfig, RewardConfig.from_dict),
    "noise": (NoiseConfig, NoiseConfig.from_any),
}
