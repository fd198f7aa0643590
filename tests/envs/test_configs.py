"""The configurations' YAML: the equipment section shared by the tasks
(``TaskConfig``) and the games (``GameConfig``), one default file per task
and per game, round trips, unknown keys named, version-1 files converted and
flat keyword overrides going into the section."""
from __future__ import annotations

import dataclasses
import fnmatch
import tomllib
from pathlib import Path

import gymnasium as gym
import pytest
import yaml

import billiards_env  # noqa: F401  (registers the ids)
from billiards_env.envs.config import CONFIG_DIR, CONFIG_VERSION, NoiseConfig, TaskConfig
from billiards_env.envs.equipment import KEYS, OWN_TABLES, EquipmentConfig, tables
from billiards_env.envs.games import core as game_core
from billiards_env.envs.games.core import GAME_CONFIG_DIR, GameConfig
from billiards_env.envs.tasks import TASKS
from billiards_env.physics import Effects, Models, PhysicsParams, Table
from billiards_env.physics.noise import NOISE_LEVELS, NoiseLevel
from billiards_env.rules import GAMES

ROOT = Path(__file__).resolve().parents[2]
BUILTIN_TASKS = [t for t in TASKS.values() if type(t).__module__.startswith("billiards_env.")]
BUILTIN_GAMES = ("nine_ball", "eight_ball", "ten_ball", "three_cushion", "snooker")

# A task configuration saved before the equipment section (version 1: its keys at the top level), as
# TaskConfig.to_yaml wrote it: run_out with tournament noise, no spin and 3 balls.
V1_RUN_OUT = """\
task: run_out
version: 1
table: pool
table_size_ft: 8
physics: standard
solver: event
dt: null
n_balls: 3
max_shots: 10
aim: relative
speed_scale: linear
observation: table
min_draw: 0.02
margin: 0.01
break_speed: 8.0
effects: {spin: false, sliding: true, vertical_spin: true, ball_friction: true, cushion_friction: true, pockets: true}
models: {ball_ball_friction: constant, cushion: mathavan2010}
reward: {pocket: 2.0, scratch: -1.0, foul: -0.5, contact: 0.1, success: 1.0, shaping: 0.5, gamma: 0.99}
noise: {aim_deg: 0.125, speed: 0.075, side_mm: 0.5, height_mm: 0.5}
"""


def _read(path: Path) -> dict:
    return yaml.safe_load(path.read_text())


# ----------------------------------------------------------------- the files
def test_every_task_and_game_file_has_the_equipment_section_of_one_schema():
    files = [t.default_config_path for t in BUILTIN_TASKS] + [GAME_CONFIG_DIR / f"{g}.yaml" for g in BUILTIN_GAMES]
    for path in files:
        d = _read(path)
        assert d["version"] == CONFIG_VERSION == 2, path
        assert set(d["equipment"]) == set(KEYS), path  # every key given: the file is the defaults' one source
        assert not set(d) & set(KEYS), path  # none of them flat


@pytest.mark.parametrize("task", [t.name for t in BUILTIN_TASKS])
def test_task_yaml_round_trip(task, tmp_path):
    """YAML -> config -> YAML: the shipped file is exactly the config's YAML form, and a written one reads back."""
    path = CONFIG_DIR / f"{task}.yaml"
    cfg = TaskConfig.default(task)
    assert cfg.to_dict() == _read(path)
    cfg.to_yaml(tmp_path / "c.yaml")
    assert TaskConfig.from_yaml(tmp_path / "c.yaml") == cfg and _read(tmp_path / "c.yaml") == _read(path)


@pytest.mark.parametrize("game", BUILTIN_GAMES)
def test_game_yaml_round_trip_and_the_env_uses_it(game, tmp_path):
    """Each game's file loads, writes back unchanged, and is the config the env plays with: its table and
    physics are the ones the section builds."""
    path = GAME_CONFIG_DIR / f"{game}.yaml"
    cfg = GameConfig.from_yaml(path)
    assert cfg == GameConfig(game) == GameConfig.default(game) and cfg.to_dict() == _read(path)
    cfg.to_yaml(tmp_path / "g.yaml")
    assert GameConfig.from_yaml(tmp_path / "g.yaml") == cfg
    env_id = GAMES[game].env_id
    core = gym.make(env_id).unwrapped.core
    vec = gym.make_vec(env_id, num_envs=2, vectorization_mode="vector_entry_point")
    for c in (core, vec.core):
        assert c.config == cfg
        assert c.table.name == cfg.make_table().name and c.params == cfg.params()
        assert c.table.style == core.rules.table_style == cfg.table
        assert c.effects == cfg.effects == Effects() and c.models == cfg.models == Models()


def test_the_files_are_package_data():
    """Every default YAML (tasks and games) is matched by a package-data glob of pyproject.toml, so the wheel
    holds it (``python -m billiards_env.testing.smoke`` plays every id from an installed wheel)."""
    data = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["package-data"]
    files = sorted((ROOT / "billiards_env").rglob("defaults/*.yaml"))
    assert {p.parent.parent.name for p in files} == {"tasks", "games"}
    for p in files:
        pkg = ".".join(p.parent.parent.relative_to(ROOT).parts)
        rel = p.relative_to(p.parent.parent).as_posix()
        assert any(fnmatch.fnmatch(rel, g) for g in data.get(pkg, [])), f"{p} is not package data"


# ----------------------------------------------------------- unknown keys named
def test_unknown_keys_are_named_wherever_they_stand(tmp_path):
    base = _read(CONFIG_DIR / "pot_one.yaml")
    with pytest.raises(ValueError, match=r"unknown key.*'n_bals'.*known keys"):
        TaskConfig.from_dict({**base, "n_bals": 1})
    with pytest.raises(ValueError, match=r"unknown key.*'tabel'.*equipment section"):
        TaskConfig.from_dict({**base, "equipment": {**base["equipment"], "tabel": "pool"}})
    with pytest.raises(ValueError, match=r"unknown key.*'nois'.*'noise'"):  # a typo among the flat overrides
        TaskConfig.default("pot_one", nois="high")
    with pytest.raises(ValueError, match="unknown effects.*'magnus'"):
        TaskConfig.default("pot_one", effects={"magnus": True})
    with pytest.raises(ValueError, match=r"unknown key.*'racks'"):
        GameConfig("nine_ball", racks="perfect")
    with pytest.raises(ValueError, match=r"unknown key.*'tabel'.*equipment section"):
        GameConfig("nine_ball", equipment={"tabel": "pool"})
    p = tmp_path / "bad.yaml"
    p.write_text("game: eight_ball\nversion: 2\nequipment: {noise: tournament, solvr: step}\n")
    with pytest.raises(ValueError, match=r"bad.yaml.*'solvr'"):
        GameConfig.from_yaml(p)


def test_current_version_keys_at_the_top_level_say_where_they_belong():
    base = _read(CONFIG_DIR / "pot_one.yaml")
    with pytest.raises(ValueError, match=r"\['noise'\].*belong in its 'equipment' section.*version: 1"):
        TaskConfig.from_dict({**base, "noise": "high"})
    with pytest.raises(ValueError, match=r"\['table_size_ft'\].*'equipment' section"):
        GameConfig.from_dict({"game": "nine_ball", "version": 2, "table_size_ft": 7})


# ------------------------------------------------------------- version 1 files
def test_a_saved_version_1_task_file_loads_as_it_was_written(tmp_path):
    p = tmp_path / "v1.yaml"
    p.write_text(V1_RUN_OUT)
    cfg = TaskConfig.from_yaml(p)
    assert cfg.version == 2 and cfg.table_size_ft == 8 and cfg.min_draw == 0.02 and not cfg.effects.spin
    assert cfg.models == Models(cushion="mathavan2010") and cfg.noise == NoiseConfig.preset("tournament")
    assert cfg.n_balls == 3 and cfg.reward.pocket == 2.0
    assert cfg == TaskConfig.default("run_out", n_balls=3, table_size_ft=8, min_draw=0.02, effects={"spin": False},
                                     models={"cushion": "mathavan2010"}, reward=_read(p)["reward"],
                                     noise=_read(p)["noise"])
    env = gym.make("Billiards-RunOut-v1", config=str(p)).unwrapped
    assert env.config == cfg and env.table.name == "pool 8 ft"
    cfg.to_yaml(tmp_path / "v2.yaml")  # written back in the current layout
    assert _read(tmp_path / "v2.yaml")["equipment"]["table_size_ft"] == 8 and TaskConfig.from_yaml(tmp_path / "v2.yaml") == cfg
    # the test's own toy task still ships a version-1 file (tests/envs/tasks/toy_pot_any.yaml)
    assert _read(ROOT / "tests/envs/tasks/toy_pot_any.yaml")["version"] == 1


def test_version_errors_name_the_change():
    v1 = yaml.safe_load(V1_RUN_OUT)
    with pytest.raises(ValueError, match="version 1 has no 'equipment' section"):
        TaskConfig.from_dict({**v1, "equipment": {"noise": "none"}})
    with pytest.raises(ValueError, match="version 3 is not supported"):
        TaskConfig.from_dict({**v1, "version": 3})
    with pytest.raises(ValueError, match="version True is not supported"):
        TaskConfig.from_dict({**v1, "version": True})
    with pytest.raises(ValueError, match="version 1 is not supported.*converts"):
        TaskConfig("run_out", version=1)  # the dataclass itself holds the current layout only
    g = GameConfig.from_dict({"game": "ten_ball", "version": 1, "noise": "high", "max_shots": 50})  # converted
    assert g == GameConfig("ten_ball", noise="high", max_shots=50)


# ------------------------------------------------------------------ overrides
def test_flat_overrides_go_into_the_section():
    env = gym.make("Billiards-PotOne-v1", noise="high", table_size_ft=7, models={"cushion": "mathavan2010"}).unwrapped
    eq = env.config.equipment
    assert eq.noise == NOISE_LEVELS["high"] and env.config.noise == NoiseConfig.preset("high")
    assert eq.table_size_ft == 7 and env.table.name == "pool 7 ft" and env.models.cushion == "mathavan2010"
    cfg = TaskConfig.default("run_out", equipment={"solver": "step", "dt": 1e-4}, n_balls=2)
    assert (cfg.solver, cfg.dt, cfg.n_balls, cfg.table) == ("step", 1e-4, 2, "pool")  # the rest of the file kept
    assert cfg == TaskConfig.default("run_out", solver="step", dt=1e-4, n_balls=2)
    with pytest.raises(ValueError, match=r"\['noise'\] given both"):
        TaskConfig.default("pot_one", noise="high", equipment={"noise": "none"})
    with pytest.raises(ValueError, match="'variable' draws a factor per game"):
        gym.make("Billiards-PotOne-v1", noise="variable")

    game = gym.make(GAMES["nine_ball"].env_id, noise="variable", table_size_ft=8, max_shots=40).unwrapped.core
    assert game.config.noise.name == "variable" and game.config.max_shots == 40 and game.table.name == "pool 8 ft"
    three = GameConfig("three_cushion", equipment={"noise": "tournament"})  # a partial section: the rest is the game's
    assert three.table == "carom" and three.physics == "carom" and three.noise.name == "tournament"
    cfg = GameConfig("snooker", noise="high")
    again = dataclasses.replace(cfg, min_draw=0.02, max_shots=9)  # make_config's way with a GameConfig and keywords
    assert again.equipment == dataclasses.replace(cfg.equipment, min_draw=0.02) and again.max_shots == 9
    with pytest.raises(ValueError, match="is played on the 'carom' table"):
        GameConfig("three_cushion", table="pool")
    with pytest.raises(ValueError, match="size_ft must be one of"):
        GameConfig("eight_ball", table_size_ft=10)


def test_standard_physics_stands_for_the_games_own_balls():
    assert GameConfig("three_cushion", physics="standard").physics == "carom"
    assert GameConfig("snooker", physics="standard").params() == PhysicsParams.preset("snooker")
    assert GameConfig("three_cushion", physics="seed").physics == "seed"
    assert GameConfig("nine_ball", physics="standard").physics == "standard"


def test_a_game_file_gives_only_what_it_changes(tmp_path):
    p = tmp_path / "mine.yaml"
    p.write_text("game: three_cushion\nequipment: {noise: variable}\nrule_options: {target: 15}\n")
    env = gym.make(GAMES["three_cushion"].env_id, config=str(p), max_shots=30).unwrapped
    cfg = env.core.config
    assert cfg == GameConfig("three_cushion", noise="variable", rule_options={"target": 15}, max_shots=30)
    assert cfg.table == "carom" and cfg.rack == "realistic"
    with pytest.raises(ValueError, match="config is for 'three_cushion', this env plays 'nine_ball'"):
        gym.make(GAMES["nine_ball"].env_id, config=str(p))


def test_a_games_default_file_must_give_every_key(tmp_path, monkeypatch):
    d = _read(GAME_CONFIG_DIR / "nine_ball.yaml")
    del d["rack"], d["equipment"]["min_draw"]
    (tmp_path / "nine_ball.yaml").write_text(yaml.safe_dump(d))
    monkeypatch.setattr(game_core, "GAME_CONFIG_DIR", tmp_path)
    with pytest.raises(ValueError, match=r"nine_ball.yaml: missing key\(s\) \['rack', 'equipment.min_draw'\]"):
        GameConfig("nine_ball")
    (tmp_path / "nine_ball.yaml").unlink()
    with pytest.raises(FileNotFoundError, match="no default configuration for game 'nine_ball'"):
        GameConfig("nine_ball")


# --------------------------------------------------------------- the section
def test_the_section_validates_once_and_round_trips():
    eq = EquipmentConfig.from_dict({"table": "snooker", "physics": "snooker", "noise": {"preset": "tournament",
                                                                                      "aim_deg": 0.2}})
    assert eq.make_table().style == "snooker" and eq.noise == NoiseLevel.of({"preset": "tournament", "aim_deg": 0.2})
    assert EquipmentConfig.from_dict(eq.to_dict()) == eq and eq.to_dict()["noise"]["aim_deg"] == 0.2
    assert EquipmentConfig.from_dict(None) == EquipmentConfig() and EquipmentConfig().to_dict()["noise"] == "none"
    assert EquipmentConfig(noise="variable").to_dict()["noise"] == "variable"
    with pytest.raises(ValueError, match="only the named levels"):
        EquipmentConfig(noise=NoiseLevel("wild", NoiseConfig.preset("high"), (0.0, 2.0))).to_dict()
    assert EquipmentConfig(table="carom").make_table().name == Table.carom().name
    for bad, msg in (({"table": "round"}, "table must be one of"), ({"solver": "step"}, "positive time step dt"),
                     ({"min_draw": 0.0}, r"min_draw must lie in \(0, max_draw"), ({"physics": "ice"}, "unknown physics"),
                     ({"dt": "fast"}, "dt must be a finite number"), ({"table_size_ft": True}, "positive integer"),
                     ({"noise": "loud"}, "unknown noise level")):
        with pytest.raises(ValueError, match=msg):
            EquipmentConfig(**bad)


def test_the_tables_a_config_may_name_are_the_pool_table_the_box_and_the_games_own():
    """The section's tables come from the games' registry (a game's rules' ``table_style``, built by the ``Table``
    constructor of that name), so a game on a table of its own brings it; the pool table and the box are the
    section's own."""
    styles = {spec.rules.table_style for spec in GAMES.values()}
    assert set(tables()) == set(OWN_TABLES) | styles and {"carom", "snooker"} <= styles
    for name in tables():
        assert EquipmentConfig(table=name).make_table().style == ("pool" if name == "pocketless" else name)
