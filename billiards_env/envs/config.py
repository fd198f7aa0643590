"""Typed, frozen task configuration loaded from YAML (``billiards_env/envs/tasks/defaults/<task>.yaml``, package data).

A ``TaskConfig`` holds everything a task needs: its ``equipment`` section
(``EquipmentConfig``: table, physics preset, solver, cue draw, effects,
models, noise; the same schema as the games', ``envs/equipment.py``,
docs/configuration.md), ball count, shot limit, action mapping and reward
weights (``RewardConfig``). Unknown keys anywhere raise a ``ValueError``
naming them; a version-1 file (the equipment's keys at the top level) is
converted on load. The YAML files are the only source of defaults; checks
that depend on the task (e.g. pot_one has one object ball) are the task's
own ``validate``.
"""
from __future__ import annotations

import dataclasses

from ..physics.noise import NoiseConfig
from ..physics.validation import check_keys, finite_number as _number  # noqa: F401 (check_keys re-exported)
from .equipment import CONFIG_VERSION, EquipmentConfig, Equipped, check_config_keys, upgrade, with_overrides
from .tasks.base import CONFIG_DIR
from .tasks.registry import get_task

AIMS = ("relative", "absolute", "impact")        # meaning of action a0 (billiards._COMMON_DOC)
SPEED_SCALES = ("linear", "log")                  # meaning of action a1 (billiards._COMMON_DOC)
OBSERVATIONS = ("table", "target_frame")          # observation layouts (billiards._COMMON_DOC)
__all__ = ["TaskConfig", "RewardConfig", "NoiseConfig", "EquipmentConfig", "CONFIG_DIR", "CONFIG_VERSION", "check_keys"]


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
class TaskConfig(Equipped):
    """Everything that defines a task instance.

    - ``task``: a registered task name (``pot_one``, ``run_out``, ``nine_ball``, ...);
    - ``version``: of the layout (``CONFIG_VERSION``; version 1, the
      equipment's keys at the top level, is converted by ``from_dict``);
    - ``equipment``: table, physics, solver, ``min_draw``, effects, models
      and noise (``EquipmentConfig``, docs/configuration.md); its keys also
      read flat (``cfg.table``, ``cfg.noise``) and override flat
      (``TaskConfig.default(task, noise="high")``). A task's noise is
      fixed deviations: ``cfg.noise`` is the level's ``NoiseConfig``, and
      ``variable`` (a factor drawn per game) is a game's level only;
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
    - ``margin``: clearance (m) between randomly placed balls and from the cushions;
    - ``break_speed``: nine_ball break-shot speed (m/s);
    - ``reward``: the reward weights (``RewardConfig``).
    """

    task: str
    version: int = CONFIG_VERSION
    equipment: EquipmentConfig = dataclasses.field(default_factory=EquipmentConfig)
    n_balls: int = 1
    max_shots: int = 1
    aim: str = "relative"
    speed_scale: str = "linear"
    observation: str = "table"
    margin: float = 0.01
    break_speed: float = 8.0
    reward: RewardConfig = dataclasses.field(default_factory=RewardConfig)

    def __post_init__(self):
        if self.version != CONFIG_VERSION:
            raise ValueError(f"config version {self.version!r} is not supported (expected {CONFIG_VERSION}; "
                             f"TaskConfig.from_dict converts a version-1 mapping)")
        task = get_task(self.task)  # ValueError naming the registered tasks
        for name, (cls, _) in NESTED.items():
            if not isinstance(getattr(self, name), cls):
                raise ValueError(f"{name} must be a {cls.__name__} (use TaskConfig.from_dict for mappings)")
        if self.aim not in AIMS:
            raise ValueError(f"aim must be one of {AIMS}, got {self.aim!r}")
        if self.speed_scale not in SPEED_SCALES:
            raise ValueError(f"speed_scale must be one of {SPEED_SCALES}, got {self.speed_scale!r}")
        if self.observation not in OBSERVATIONS:
            raise ValueError(f"observation must be one of {OBSERVATIONS}, got {self.observation!r}")
        for name in ("n_balls", "max_shots"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int) or v < 1:
                raise ValueError(f"{name} must be a positive integer, got {v!r}")
        if self.n_balls > 15:
            raise ValueError(f"n_balls must be at most 15, got {self.n_balls}")
        if self.equipment.noise.variable:
            raise ValueError(f"noise {self.equipment.noise.name!r} draws a factor per game, a game's level: a "
                             f"task's noise is fixed deviations (none, tournament, high or a mapping)")
        object.__setattr__(self, "margin", _number(self.margin, "margin", 0.0))
        object.__setattr__(self, "break_speed", _number(self.break_speed, "break_speed"))
        if not 0 < self.break_speed <= 2 * self.params().max_speed:
            raise ValueError(f"break_speed must be positive and plausible, got {self.break_speed}")
        task.validate(self)

    @property
    def noise(self) -> NoiseConfig:
        """The deviations of the equipment's noise level (a task draws no factor per game)."""
        return self.equipment.noise.config

    # --- construction -----------------------------------------------------
    @classmethod
    def from_dict(cls, d: dict, **overrides) -> "TaskConfig":
        """From a mapping such as a YAML file's (a version-1 one converted),
        with ``overrides`` over it: any key, the equipment's keys flat
        (``noise="high"``) or in ``equipment={...}``."""
        d = with_overrides(upgrade(d, "task config"), overrides)
        check_config_keys(cls, d, "task config")
        if "task" not in d:
            raise ValueError("task config needs a 'task' key")
        for name, (sub, build) in NESTED.items():
            if name in d and not isinstance(d[name], sub):
                d[name] = build(d[name])
        return cls(**d)

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


# Nested configs of TaskConfig: field -> (class, builder from YAML data). A new
# nested config is one TaskConfig field plus one line here.
NESTED = {
    "equipment": (EquipmentConfig, EquipmentConfig.from_dict),
    "reward": (RewardConfig, RewardConfig.from_dict),
}
