"""The equipment section of a configuration, written once for the one-player
tasks and the two-player games: what every shot is played on and with.

``EquipmentConfig`` holds the table (``table``, ``table_size_ft``), the
physics preset, the solver (``solver``, ``dt``), the cue's shortest draw
(``min_draw``), the physics ``effects``, the ``models`` of the interactions
and the execution ``noise``. A task's YAML (``TaskConfig``,
``envs/tasks/defaults/<task>.yaml``) and a game's (``GameConfig``,
``envs/games/defaults/<game>.yaml``) both hold it as ``equipment:``, the same
schema (docs/configuration.md).

``Equipped`` is what the two configs share about the section: its keys read
flat (``cfg.noise`` is ``cfg.equipment.noise``), flat keyword overrides
(``gym.make(id, noise="high")``) go into it (``with_overrides``), a
version-1 mapping (the section's keys at the top level) is converted
(``upgrade``), and the YAML in and out.
"""
from __future__ import annotations

import dataclasses
from pathlib import Path

import yaml

from ..physics import Effects, Models, PhysicsParams, Table
from ..physics.noise import NOISE_LEVELS, NoiseLevel
from ..physics.validation import check_keys, finite_number
from ..rules.games import GAMES

CONFIG_VERSION = 2  # 2: the equipment section (version 1: its keys at the top level; converted on load)
SECTION = "equipment"  # the section's key in a configuration
# The tables a configuration may name: the pool table (``Table.pool(table_size_ft)``), the closed box
# (``Table.pocketless()``) and the registered games' own (their rules' ``table_style``, each made by the ``Table``
# constructor of that name: ``Table.carom()``, ``Table.snooker()``), read from the games' registry when checked, so
# a game registered later brings its table.
OWN_TABLES = ("pool", "pocketless")


def tables() -> tuple[str, ...]:
    """The table names a configuration may give (``OWN_TABLES`` and every registered game's ``table_style``)."""
    return tuple(dict.fromkeys(OWN_TABLES + tuple(spec.rules.table_style for spec in GAMES.values())))
SOLVERS = ("event", "step")  # the simulator's solvers: exact events, or a fixed time step of dt seconds


@dataclasses.dataclass(frozen=True)
class EquipmentConfig:
    """What every shot is played on and with, the same for a task and a game.

    - ``table``: ``pool`` (six pockets, ``table_size_ft`` 7, 8 or 9),
      ``pocketless``, ``carom`` (the carom match table) or ``snooker`` (the
      12 ft snooker table); a game's table is its rules' (``Rules.table_style``);
    - ``physics``: a ``PhysicsParams`` preset (``standard``, ``seed``,
      ``carom``: carom balls and cloth, ``snooker``: snooker balls);
    - ``solver``: ``event`` (exact) or ``step`` (fixed step ``dt`` seconds);
    - ``min_draw``: the cue draw (m) at a1 = -1, the shortest stroke (small
      and positive so the cue ball moves; the longest, ``max_draw``, is the
      physics preset's);
    - ``effects``: the physics effects (``Effects``; docs/effects.md);
    - ``models``: the model of each interaction (``Models``; docs/models.md),
      e.g. ``{cushion: mathavan2010}``; unnamed interactions keep ``Models()``;
    - ``noise``: the execution noise, a level's name (``none``,
      ``tournament``, ``high`` = 5x tournament; a game also takes
      ``variable``, a factor drawn per game) or the deviations as a mapping
      ``{preset, aim_deg, speed, side_mm, height_mm}`` (``physics.noise``).

    A key a file leaves out takes the default here (the pool table's standard
    equipment). Mappings and names are converted and everything is checked
    here, once; an unknown key is a ``ValueError`` naming it."""

    table: str = "pool"
    table_size_ft: int = 9
    physics: str = "standard"
    solver: str = "event"
    dt: float | None = None
    min_draw: float = 0.01
    effects: Effects = dataclasses.field(default_factory=Effects)
    models: Models = dataclasses.field(default_factory=Models)
    noise: NoiseLevel = NOISE_LEVELS["none"]

    def __post_init__(self):
        if self.table not in tables():
            raise ValueError(f"table must be one of {tables()}, got {self.table!r}")
        v = self.table_size_ft
        if isinstance(v, bool) or not isinstance(v, int) or v < 1:
            raise ValueError(f"table_size_ft must be a positive integer, got {v!r}")
        if self.table == "pool":
            try:
                self.make_table()  # Table.pool's own check of the size
            except ValueError as exc:
                raise ValueError(f"table_size_ft: {exc}") from None
        params = self.params()  # ValueError naming the presets
        if self.solver not in SOLVERS:
            raise ValueError(f"solver must be one of {SOLVERS}, got {self.solver!r}")
        if self.dt is not None:
            object.__setattr__(self, "dt", finite_number(self.dt, "dt"))
        if self.solver == "step" and (self.dt is None or self.dt <= 0):
            raise ValueError("the step solver needs a positive time step dt (s), e.g. dt: 1.0e-4")
        object.__setattr__(self, "min_draw", finite_number(self.min_draw, "min_draw"))
        if not 0 < self.min_draw < params.max_draw:
            raise ValueError(f"min_draw must lie in (0, max_draw = {params.max_draw}), got {self.min_draw}")
        for name, cls in (("effects", Effects), ("models", Models)):
            if not isinstance(getattr(self, name), cls):
                object.__setattr__(self, name, cls.from_dict(getattr(self, name)))
        object.__setattr__(self, "noise", NoiseLevel.of(self.noise))

    @classmethod
    def from_dict(cls, d: dict | None) -> "EquipmentConfig":
        """From a mapping such as a YAML ``equipment:`` section (None: the defaults)."""
        d = {} if d is None else d
        check_keys(cls, d, "equipment section")
        return cls(**d)

    def to_dict(self) -> dict:
        """The YAML form: mappings for ``effects`` and ``models``; ``noise`` a
        level's name, or its deviations as a mapping."""
        d = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}
        d["effects"], d["models"] = self.effects.to_dict(), self.models.to_dict()
        d["noise"] = _noise_data(self.noise)
        return d

    def params(self) -> PhysicsParams:
        return PhysicsParams.preset(self.physics)

    def make_table(self) -> Table:
        if self.table == "pool":
            return Table.pool(self.table_size_ft)
        return getattr(Table, self.table)()  # the constructor named as the style (``tables``)


KEYS = tuple(f.name for f in dataclasses.fields(EquipmentConfig))  # the section's keys


def _noise_data(level: NoiseLevel):
    if NOISE_LEVELS.get(level.name) == level:
        return level.name
    if level.variable:
        raise ValueError(f"noise level {level.name!r} draws a factor per game in {level.spread}; only the named "
                         f"levels {list(NOISE_LEVELS)} write such a level to a configuration")
    return level.config.to_dict()


def upgrade(d: dict, where: str) -> dict:
    """A configuration mapping in the current layout (a copy). Version 1 (the
    equipment's keys at the top level) is converted, because saved version-1
    files must keep loading; in the current version those keys at the top level
    are an error naming where they belong. No ``version``: the current one."""
    if not isinstance(d, dict):
        raise ValueError(f"{where} must be a mapping, got {type(d).__name__}")
    d = dict(d)
    version = d.get("version", CONFIG_VERSION)
    if isinstance(version, bool) or version not in (1, CONFIG_VERSION):
        raise ValueError(f"config version {version!r} is not supported (expected {CONFIG_VERSION}; "
                         f"a version-1 configuration is converted)")
    flat = [k for k in KEYS if k in d]
    if version == 1:
        if SECTION in d:
            raise ValueError(f"{where} of version 1 has no '{SECTION}' section: its keys {list(KEYS)} stand at "
                             f"the top level (or write version: {CONFIG_VERSION})")
        d[SECTION] = {k: d.pop(k) for k in flat}
        d["version"] = CONFIG_VERSION
    elif flat:
        raise ValueError(f"key(s) {flat} of {where} belong in its '{SECTION}' section since version "
                         f"{CONFIG_VERSION} (write them under '{SECTION}:'; version: 1 marks the old flat layout)")
    return d


def with_overrides(d: dict, overrides: dict) -> dict:
    """``d`` (the current layout) with ``overrides`` over it (a new mapping):
    a configuration's own keys, the equipment's keys flat (``noise="high"``)
    or ``equipment=`` (a mapping: over the section key by key; an
    ``EquipmentConfig``: the whole section). A key given both flat and in an
    ``equipment`` mapping is an error."""
    d, over = dict(d), dict(overrides)
    flat = {k: over.pop(k) for k in KEYS if k in over}
    section = d.get(SECTION)
    if SECTION in over:
        given = over.pop(SECTION)
        if isinstance(given, dict):
            both = sorted(set(flat) & set(given))
            if both:
                raise ValueError(f"{both} given both as keyword(s) and in {SECTION}=: give each once")
            base = section.to_dict() if isinstance(section, EquipmentConfig) else dict(section or {})
            section = {**base, **given}
        elif isinstance(given, EquipmentConfig):
            section = given
        else:
            raise ValueError(f"{SECTION} must be a mapping or an EquipmentConfig, got {type(given).__name__}")
    if flat:
        section = (dataclasses.replace(section, **flat) if isinstance(section, EquipmentConfig)
                   else {**(section or {}), **flat})
    d.update(over)
    if section is not None:
        d[SECTION] = section
    return d


def check_config_keys(cls, d: dict, where: str) -> None:
    """``check_keys`` for a configuration with the section: an unknown key's
    error also names the section's keys (they override flat)."""
    try:
        check_keys(cls, d, where)
    except ValueError as exc:
        raise ValueError(f"{exc} (the {SECTION}'s keys, under '{SECTION}:' or flat as keyword overrides: "
                         f"{sorted(KEYS)})") from None


def read_yaml(path) -> dict:
    with open(path) as f:
        return yaml.safe_load(f) or {}


class Equipped:
    """Base of ``TaskConfig`` and ``GameConfig`` (frozen dataclasses with an
    ``equipment`` field): the section's keys read flat (``cfg.noise``,
    ``cfg.table``, ...: properties, set below), the table and the physics it
    builds, YAML in and out. ``from_dict(d, **overrides)`` is each config's own."""

    equipment: EquipmentConfig

    @classmethod
    def from_yaml(cls, path, **overrides):
        path = Path(path)
        d = read_yaml(path)
        try:
            return cls.from_dict(d, **overrides)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"{path}: {exc}") from exc

    def to_dict(self) -> dict:
        """The YAML form, the layout of the current version (the sections as mappings)."""
        d = {}
        for f in dataclasses.fields(self):
            v = getattr(self, f.name)
            d[f.name] = v.to_dict() if hasattr(v, "to_dict") else dict(v) if isinstance(v, dict) else v
        return d

    def to_yaml(self, path) -> None:
        with open(path, "w") as f:
            yaml.safe_dump(self.to_dict(), f, sort_keys=False)

    def params(self) -> PhysicsParams:
        return self.equipment.params()

    def make_table(self) -> Table:
        return self.equipment.make_table()


def _flat(name: str) -> property:
    return property(lambda self: getattr(self.equipment, name), doc=f"``equipment.{name}``, read flat")


for _name in KEYS:
    setattr(Equipped, _name, _flat(_name))
