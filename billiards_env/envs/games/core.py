"""Batched two-player games: ``GameCore`` holds ``n_envs`` tables, each with
its game state, and plays one shot (or one pass) per table per step through
the rules layer (``billiards_env.rules``).

It plays every turn through ``contract.turn.play_turn`` (the function a
bot's preview plays too), with the games' action convention
(``contract.codec.ActionCodec``); what it holds is the two-player part:
the racks, the game states, the noise factor of each game and the
observation.

**Action** (``Box(-1, 1, (8,), float32)``; 10-ball ``(9,)``):

===  ========================================================================
a0   aim: phi = angle(cue -> nominal target) + pi * a0; the nominal target is
     the lowest-numbered legal target (the foot spot on the break), taken
     after the cue ball is placed
a1   cue draw, a2 side and a3 height offsets: as in the one-player tasks
a4   cue-ball x with ball in hand: R + (a4 + 1) / 2 * (width - 2R)
a5   cue-ball y with ball in hand: R + (a5 + 1) / 2 * (length - 2R); behind
     the head string only when the constraints say so. An illegal spot
     (overlapping a ball or a pocket, or beyond the head string) is moved to
     the nearest legal one and ``info["placement_moved"]`` is set
a6   > 0: declare a push-out (9-ball, 10-ball, when allowed), or, right
     after the opponent's push-out (10-ball: or illegal pot), hand the shot
     back (``may_pass``: no shot is played)
a7   the called pocket when a call is needed (8-ball, on the 8; 10-ball,
     every shot but the break and a push-out): pocket
     floor((a7 + 1) / 2 * 6), in the order of ``Table.pockets``
a8   10-ball only, the called ball when a call is needed: ball
     floor((a8 + 1) / 2 * 11) (1..10; 0, a8 < -9/11, calls a safety).
     Snooker: the nominated ball (a colour after a red, or the free ball):
     ball floor((a8 + 1) / 2 * 22) (16..21 the colours yellow .. black)
===  ========================================================================

Snooker (``game="snooker"``): the 12 ft table and snooker balls; a4, a5
place the cue ball in the D (the nearest point of it, ``placement_moved``);
after a foul a6 > 0.5 puts the offender back in (``may_pass``), and after a
foul and a miss 0 < a6 <= 0.5 has the balls replaced where they were before
the foul and the offender play again (``may_replace``; elsewhere ignored).

**The cue's elevation** (an option, off by default): with the equipment's
``effects={"airborne": True}`` the balls fly (jump and massé strokes, balls
driven off the table) and the action gains one last component (a8; 10-ball
a9): the cue's elevation theta = (a + 1) / 2 * 60 degrees
(``contract.codec.MAX_ACTION_ELEVATION``), a = -1 the level cue; ``info``
gains ``off_table`` [B] (the balls the shot drove off the table, each game
ruling them: ``rules.FOUL_OFF_TABLE``). Off, the action, the observation and
the info are the planar env's.

Components outside [-1, 1] are clipped (``info["action_clipped"]``);
components the constraints do not use are ignored.
"""
from __future__ import annotations

import dataclasses
import inspect
import math
import time
from importlib import resources
from pathlib import Path

import numpy as np

from ...contract.codec import ACTION_DIM, MAX_ACTION_ELEVATION, ActionCodec, ShotContext, _context, placement_to_actions
from ...contract.turn import Equipment, play_turn
from ...contract.view import GameView
from ...physics import BallState
from ...physics.strike import Shots
from ...physics.validation import check_keys
from ...rules import DEFAULT_GAME, GAMES, GameState, get_game, get_rules
from ...rules import records as R
from ..core import _observe
from ..equipment import (CONFIG_VERSION, KEYS, SECTION, EquipmentConfig, Equipped, check_config_keys, read_yaml,
                         upgrade, with_overrides)
from ..streams import TableStreams
from ...rules.placement import FOOT_SPOT, HEAD_STRING
from .setup import RACKS, loosen

EXTRA_OBS = 13  # observation entries after the one-player layout (see ``observation_doc``)
BREAK_NINE = ("wins", "spotted")  # 9-ball: the 9 pocketed on a legal break wins, or is spotted (some pro events)
BREAK_OPTION = "spot_break_nine"  # the rules' setting "spotted" stands for (NineBallRules); a game without it: "wins"


# The built-in games' default configurations are package data, so an installed wheel finds them.
GAME_CONFIG_DIR = Path(str(resources.files("billiards_env.envs.games") / "defaults"))


def game_config_path(game: str) -> Path:
    """The YAML file of a game's defaults: its ``GameSpec.config_path``, or
    ``billiards_env/envs/games/defaults/<game>.yaml``."""
    spec = get_game(game)
    return Path(spec.config_path) if spec.config_path is not None else GAME_CONFIG_DIR / f"{game}.yaml"


@dataclasses.dataclass(frozen=True, init=False)
class GameConfig(Equipped):
    """A two-player game instance; its defaults are the game's YAML file
    (``billiards_env/envs/games/defaults/<game>.yaml``, ``game_config_path``),
    the single source of them.

    - ``game``: a registered game (``nine_ball``, ``eight_ball``,
      ``ten_ball``, ``three_cushion``, ``snooker``: ``rules.games``);
    - ``version``: of the layout (``CONFIG_VERSION``, the tasks' one);
    - ``equipment``: the tasks' section (``EquipmentConfig``,
      docs/configuration.md): the table (the rules' ``table_style``: the
      carom match table in three-cushion, the 12 ft snooker table in snooker;
      ``table_size_ft`` for pool), ``physics`` (``standard`` stands for the
      game's own preset where its rules name one, ``Rules.physics``: carom
      balls and cloth in three-cushion, snooker balls in snooker), ``solver``
      and ``dt``, ``min_draw``, ``effects``, ``models`` and ``noise`` (a
      ``NoiseLevel``: ``none``, ``tournament``, ``high`` = 5x tournament,
      ``variable`` = tournament times a factor uniform in [0, 5] drawn per
      game; or the deviations, the level ``custom``); its keys read flat
      (``cfg.noise``);
    - ``max_shots``: a game not over after this many shots is truncated, a draw;
    - ``rack`` (the pool games): ``realistic`` (seeded gaps and offsets
      between the balls, ``setup.loosen``) or ``perfect`` (every ball
      frozen; snooker's reds are always racked frozen, three-cushion's balls
      start on their spots);
    - ``break_nine`` (9-ball): ``wins`` (the 9 pocketed on a legal break wins)
      or ``spotted`` (it is respotted and the breaker shoots on);
    - ``rule_options``: the ruleset's own settings (``rules.get_rules(game,
      **rule_options)``: three-cushion's ``target``, ``max_innings``,
      ``equal_innings``).

    ``GameConfig(game, **keys)``: the game's defaults with ``keys`` over
    them: any key, the equipment's keys flat (``noise="tournament"``) or
    ``equipment=`` (a mapping over the section, or an ``EquipmentConfig``).
    ``GameConfig.from_dict`` / ``from_yaml`` read a saved configuration the
    same way (a partial one keeps the game's defaults for what it leaves out)."""

    game: str
    version: int
    equipment: EquipmentConfig
    max_shots: int
    rack: str
    break_nine: str
    rule_options: dict

    def __init__(self, game: str = DEFAULT_GAME, **keys):
        if game not in GAMES:
            raise ValueError(f"game must be one of {tuple(GAMES)} (the games' registry, rules.games), "
                             f"got {game!r}")
        d = with_overrides(_defaults(game), keys)
        check_config_keys(type(self), {**d, "game": game}, "game config")
        equipment = d[SECTION] if isinstance(d[SECTION], EquipmentConfig) else EquipmentConfig.from_dict(d[SECTION])
        own = get_game(game).rules.physics
        if equipment.physics == "standard" and own:  # "standard" has always stood for the game's own balls here
            equipment = dataclasses.replace(equipment, physics=own)
        for f in dataclasses.fields(self):
            object.__setattr__(self, f.name, game if f.name == "game" else equipment if f.name == SECTION
                               else d[f.name])
        self._validate()

    def _validate(self) -> None:
        if self.version != CONFIG_VERSION:
            raise ValueError(f"config version {self.version!r} is not supported (expected {CONFIG_VERSION}; "
                             f"GameConfig.from_dict converts a version-1 mapping)")
        style = get_game(self.game).rules.table_style
        if self.equipment.table != style:
            raise ValueError(f"{self.game} is played on the {style!r} table (its rules' table_style), "
                             f"got table={self.equipment.table!r}")
        if not isinstance(self.rule_options, dict):
            raise TypeError(f"rule_options must be a dict, got {type(self.rule_options).__name__}")
        if self.rule_options:
            get_rules(self.game, **self.rule_options)  # unknown or bad settings fail here
        if self.rack not in RACKS:
            raise ValueError(f"rack must be one of {RACKS}, got {self.rack!r}")
        if self.break_nine not in BREAK_NINE:
            raise ValueError(f"break_nine must be one of {BREAK_NINE}, got {self.break_nine!r}")
        takes = BREAK_OPTION in inspect.signature(get_game(self.game).rules).parameters
        if self.break_nine != "wins" and not takes:
            raise ValueError(f"break_nine={self.break_nine!r} is a 9-ball option, of the rules that take "
                             f"{BREAK_OPTION} (10-ball always spots the 10 on the break, 8-ball the 8), "
                             f"got game={self.game!r}")
        if isinstance(self.max_shots, bool) or not isinstance(self.max_shots, int) or self.max_shots < 1:
            raise ValueError(f"max_shots must be a positive integer, got {self.max_shots!r}")

    @classmethod
    def from_dict(cls, d: dict, **overrides) -> "GameConfig":
        """From a mapping such as a YAML file's (a version-1 one converted; it
        names its ``game``), over the game's defaults, with ``overrides`` over it."""
        d = with_overrides(upgrade(d, "game config"), overrides)
        if "game" not in d:
            raise ValueError("game config needs a 'game' key")
        return cls(**d)

    @classmethod
    def default(cls, game: str, **overrides) -> "GameConfig":
        """The game's shipped configuration (its YAML file), with ``overrides``: ``GameConfig(game, **overrides)``."""
        return cls(game, **overrides)


def _defaults(game: str) -> dict:
    """The game's default configuration, read from its YAML file: every key given (it is their only source)."""
    path = game_config_path(game)
    if not path.exists():
        raise FileNotFoundError(
            f"no default configuration for game {game!r}: {path} does not exist. A built-in game's YAML is package "
            f"data in billiards_env/envs/games/defaults/; a game of your own names its file with "
            f"GameSpec.config_path")
    try:
        d = upgrade(read_yaml(path), "game config")
        check_keys(GameConfig, d, "game config")
        missing = [f.name for f in dataclasses.fields(GameConfig) if f.name not in d]
        section = d.get(SECTION)
        missing += [f"{SECTION}.{k}" for k in KEYS if not isinstance(section, dict) or k not in section]
        if missing:
            raise ValueError(f"missing key(s) {missing}: a game's default configuration gives every key")
        if d["game"] != game:
            raise ValueError(f"the file is game {d['game']!r}'s configuration, not {game!r}'s")
    except ValueError as exc:
        raise ValueError(f"{path}: {exc}") from exc
    return d


class GameCore:
    """``n_envs`` tables of one game; see the module docstring for the action."""

    def __init__(self, cfg: GameConfig, n_envs: int, record: bool = False):
        if not isinstance(n_envs, (int, np.integer)) or n_envs < 1:
            raise ValueError(f"num_envs must be a positive integer, got {n_envs!r}")
        self.config = cfg
        rules_options = {BREAK_OPTION: True} if cfg.break_nine == "spotted" else {}
        self.rules = get_rules(cfg.game, **rules_options, **cfg.rule_options)
        self.n_envs = int(n_envs)
        self.table = cfg.make_table()  # the rules' table style (GameConfig checks it)
        self.params = cfg.params()
        self.effects, self.models, self.record = cfg.effects, cfg.models, record
        self.n_balls = self.rules.n_balls + 1
        self.base_dim = ACTION_DIM + int(self.rules.calls_ball)  # a8: the called ball (10-ball)
        self.airborne = bool(self.effects.airborne)  # the option: balls fly, the cue's elevation the last component
        self.action_dim = self.base_dim + int(self.airborne)
        self.obs_dim = 4 * self.n_balls + 1 + EXTRA_OBS + self.rules.extra_obs
        self.diag = math.hypot(self.table.width, self.table.length)
        self.state: BallState | None = None
        self.game: GameState | None = None
        self.noise_scale = np.ones(self.n_envs)
        self.streams = TableStreams(self.n_envs)
        self.pockets = np.ascontiguousarray(self.table.geometry(True)[3], dtype=np.float64)
        self.last_start: list = [None] * self.n_envs
        self.last_events: list = [None] * self.n_envs
        self._context: ShotContext | None = None
        self._constraints = None
        self.timers = {"simulate": 0.0, "rules": 0.0}  # seconds spent, cumulative (``games_bench``)
        # Observers of every step (e.g. rendering.GameRecorder): ``before_step(core, idx, actions)`` and
        # ``after_step(core, idx, out)``; they read the core and change nothing.
        self.listeners: list = []

    # --- what the shooter faces -------------------------------------------------
    def constraints(self) -> R.Constraints:
        """The ``Constraints`` of every table's next shooter (cached until the state changes)."""
        if self._constraints is None:
            pos = {"pos": self.state.pos} if self.rules.reads_position else {}  # snooker: the free ball
            self._constraints = self.rules.constraints(self.game, self.state.pocket, **pos)
        return self._constraints

    def shot_context(self) -> ShotContext:
        """``ShotContext`` of every table: the nominal target (lowest legal
        target), the aim origin (cue -> nominal target; cue -> foot spot on
        the break) and its potential."""
        if self._context is None:
            s, c = self.state, self.constraints()
            tgt = np.ascontiguousarray(c.nominal_target())
            phi, ang = np.empty(self.n_envs), np.empty(self.n_envs)
            _context(s.pos, tgt, self.pockets, self.diag, True, phi, ang)
            brk = c.is_break
            if brk.any():
                t = self.table
                ang[brk] = np.arctan2(FOOT_SPOT * t.length - s.pos[brk, 0, 1], t.width / 2 - s.pos[brk, 0, 0])
            self._context = ShotContext(tgt, ang, phi)
        return self._context

    def _changed(self) -> None:
        self._context = None
        self._constraints = None

    def observe(self) -> np.ndarray:
        s, g, c = self.state, self.game, self.constraints()
        B = self.n_balls
        obs = np.zeros((self.n_envs, self.obs_dim), dtype=np.float32)
        _observe(s.pos, s.pocket, np.full(self.n_envs, -1, dtype=np.int64), g.shots, float(self.config.max_shots),
                 self.table.width, self.table.length, obs)
        obs[:, 3 * B:4 * B] = c.targets
        x = obs[:, 4 * B + 1:]
        ar = np.arange(self.n_envs)
        x[:, 0] = g.shooter
        x[ar, 1 + np.minimum(c.ball_in_hand, R.IN_HAND_KITCHEN)] = 1.0  # snooker's D as "behind the head string"
        x[:, 4], x[:, 5], x[:, 6], x[:, 7] = c.push_out_allowed, c.may_pass, c.call_needed, c.is_break
        x[ar, 8 + g.group[ar, g.shooter]] = 1.0
        x[:, 11] = np.minimum(g.fouls[ar, g.shooter] / 3.0, 1.0)
        x[:, 12] = np.minimum(g.fouls[ar, 1 - g.shooter] / 3.0, 1.0)
        if self.rules.extra_obs:  # the game's own entries (three-cushion: scores, innings; snooker: scores,
            # points left, free ball: it reads the table and the constraints too)
            more = {"pocket": s.pocket, "constraints": c} if self.rules.reads_position else {}
            x[:, EXTRA_OBS:] = self.rules.observe_extra(g, **more)
        return obs

    # --- new games --------------------------------------------------------------
    def reset_tables(self, idx, breaker=None) -> None:
        """New games on tables ``idx``: a rack drawn from each table's stream,
        the cue ball on the head spot (in hand for the break); ``breaker`` [n]
        (0 or 1; None: drawn from the stream); the noise factor of the game."""
        idx = np.asarray(idx, dtype=np.int64)
        n, B, t = len(idx), self.n_balls, self.table
        u = self.streams.uniform(idx, 16)  # 14 rack, breaker, noise factor
        spec = get_game(self.config.game)
        pos = spec.rack(t, self.params.R, u[:, :spec.rack_draws])
        if not self.rules.own_cue_balls and t.marks is None:  # the pool racks (three-cushion's places each
            # player's ball itself, snooker's puts the cue ball in the D)
            pos[:, 0] = (t.width / 2, HEAD_STRING * t.length)
            if self.config.rack == "realistic":  # drawn after the 16 above: breaker and noise factor as with "perfect"
                loosen(pos, t, self.params.R, self.streams.uniform(idx, 2 * (B - 1)))
        brk = (u[:, 14] < 0.5).astype(np.int64) if breaker is None else np.broadcast_to(breaker, (n,))
        lo, hi = self.config.noise.spread
        if self.state is None:
            E = self.n_envs
            self.state = BallState(np.zeros((E, B, 2)), np.zeros((E, B, 2)), np.zeros((E, B, 3)),
                                   np.full((E, B), -1, dtype=np.int64))
            self.game = self.rules.new_game(np.zeros(E, dtype=np.int64))
        self.state.pos[idx] = pos
        self.state.pocket[idx] = -1
        self.game.put(idx, self.rules.new_game(brk))
        self.noise_scale[idx] = lo + (hi - lo) * u[:, 15]
        self._changed()
        if self.record:
            for k in idx:
                self.last_start[k] = self.last_events[k] = None

    # --- actions ------------------------------------------------------------------
    def validate_actions(self, actions, n: int) -> np.ndarray:
        a = np.asarray(actions, dtype=np.float64)
        if a.shape != (n, self.action_dim):
            raise ValueError(f"actions must have shape ({n}, {self.action_dim}), got {a.shape}")
        if not np.all(np.isfinite(a)):
            bad = np.argwhere(~np.isfinite(a))[0]
            raise ValueError(f"action contains NaN or infinite values (first at index {tuple(bad)})")
        return a

    def placement_to_actions(self, xy: np.ndarray) -> np.ndarray:
        """Cue-ball positions [n, 2] (m) -> action components a4, a5 [n, 2]."""
        return placement_to_actions(xy, self.table, self.params)

    def legal_placement(self, xy: np.ndarray, idx) -> tuple[np.ndarray, np.ndarray]:
        """The legal cue-ball spots nearest to ``xy`` [n, 2] on tables
        ``idx`` under their ball-in-hand constraint: (spots [n, 2], moved [n])."""
        idx = np.asarray(idx, dtype=np.int64)
        kitchen = self.constraints().ball_in_hand[idx] == R.IN_HAND_KITCHEN
        return self._place(xy, self.state.pos[idx], self.state.pocket[idx], kitchen)

    def _place(self, xy, pos, pocket, kitchen):
        return self.equipment.place(xy, pos, pocket, kitchen)  # snooker: in hand means in the D

    # --- one shot -------------------------------------------------------------------
    def step(self, actions: np.ndarray, idx) -> dict:
        """Play validated actions [n, action_dim] on tables ``idx`` (each table's
        shooter's): decode them (``ActionCodec.decode``), then play the turn
        (``contract.turn.play_turn``: place the cue ball, shoot or pass,
        judge, respot), the one way a bot's preview plays it too; return the
        record, the reward of the player who played and the info."""
        idx = np.asarray(idx, dtype=np.int64)
        for listener in self.listeners:
            listener.before_step(self, idx, actions)
        clipped = (np.abs(actions) > 1.0).any(axis=1)
        c = self.constraints().take(idx)
        plan, moved = self.codec(idx).decode(actions)
        scale = self.noise_scale
        draw = lambda rows: self.streams.normal(idx[rows], 4) * scale[idx[rows]][:, None]  # noqa: E731
        t0 = time.perf_counter()
        turn = play_turn(self.rules, self.equipment, self.game.take(idx), c, self.state.pos[idx],
                         self.state.pocket[idx], plan, self.config.noise.config, draw, self.record)
        self.timers["simulate"] += turn.sim_wall
        self.timers["rules"] += time.perf_counter() - t0 - turn.sim_wall
        if turn.events is not None:
            for j, k in enumerate(idx[turn.shoot]):
                self.last_start[k] = turn.start.take([turn.shoot[j]])
                self.last_events[k] = turn.events[j]
        rec, game, shot = turn.record, turn.state, turn.shot
        self.state.pos[idx], self.state.pocket[idx] = turn.pos, turn.pocket
        self.game.put(idx, game)
        self._changed()
        truncated = ~game.over & (game.shots >= self.config.max_shots)
        reward = np.where(rec.winner < 0, 0.0, np.where(rec.winner == rec.shooter, 1.0, -1.0))
        info = dict(legal=rec.legal, foul=rec.foul, turn_over=rec.turn_over, game_over=rec.game_over,
                    winner=rec.winner, end=rec.end, push_out=rec.push_out, passed=rec.passed | rec.replaced,
                    shooter=rec.shooter,
                    respotted=rec.respot, option=rec.option, pocketed=shot.pocketed, first_contact=shot.first_contact,
                    called_pocket=shot.called_pocket, called_ball=shot.called_ball, points=rec.points,
                    score=game.score.copy(), placement=turn.placed, placement_moved=moved & ~shot.passed,
                    action_clipped=clipped, n_events=turn.n_events, sim_time=turn.sim_time, shot=game.shots.copy())
        if self.rules.foul_points:  # snooker: a foul's points to the opponent, a miss
            info["penalty"] = rec.penalty
            info["miss"] = rec.miss
        if self.rules.replaces:  # snooker after a miss, three-cushion with balls in contact: the balls replaced
            info["replaced"] = rec.replaced
        if self.airborne:  # the option's own entry (a new key would change the planar envs' fingerprints)
            info["off_table"] = shot.off_table
        out = dict(record=rec, reward=reward, terminated=game.over.copy(), truncated=truncated, info=info)
        for listener in self.listeners:
            listener.after_step(self, idx, out)
        return out

    @property
    def equipment(self) -> Equipment:
        """The table, physics, effects, models and solver every shot of these tables is played with."""
        c = self.config
        return Equipment(self.table, self.params, self.effects, self.models, c.solver, c.dt)

    # --- bots ------------------------------------------------------------------------
    def view(self, idx) -> GameView:
        """The read-only ``GameView`` of tables ``idx`` that a bot acts on."""
        idx = np.asarray(idx, dtype=np.int64)
        s, g, c = self.state, self.game, self.constraints()
        pos, in_hand = s.pos[idx], c.ball_in_hand[idx]
        pocket, kitchen = s.pocket[idx], in_hand == R.IN_HAND_KITCHEN
        place = lambda xy, r: self._place(xy, pos[r], pocket[r], kitchen[r])  # noqa: E731  (the view's own rows)
        codec = self._codec(idx, pos, c.is_break[idx], in_hand != R.IN_HAND_NONE, place)
        return GameView.build(
            game=self.config.game, rows=idx.copy(), pos=pos, pocket=pocket, to_move=c.shooter[idx],
            ball_in_hand=in_hand, targets=c.targets[idx], push_out_allowed=c.push_out_allowed[idx],
            may_pass=c.may_pass[idx], call_needed=c.call_needed[idx], is_break=c.is_break[idx],
            groups=g.group[idx], fouls=g.fouls[idx], shots=g.shots[idx], table=self.table, params=self.params,
            may_replace=c.may_replace[idx], touching=c.touching[idx], effects=self.effects, models=self.models, noise=self.config.noise.config,
            noise_scale=self.noise_scale[idx], min_draw=self.config.min_draw, rules=self.rules, state=g.take(idx),
            codec=codec, solver=self.config.solver, dt=self.config.dt, _observe=lambda: self.observe()[idx])

    def codec(self, idx) -> ActionCodec:
        """The ``ActionCodec`` (the action convention) of tables ``idx``."""
        idx = np.asarray(idx, dtype=np.int64)
        c = self.constraints()
        return self._codec(idx, self.state.pos[idx], c.is_break[idx], c.ball_in_hand[idx] != R.IN_HAND_NONE,
                           lambda xy, r: self.legal_placement(xy, idx[r]))

    def _codec(self, idx, pos, is_break, in_hand, place) -> ActionCodec:
        """The codec of tables ``idx`` (``pos``, ``is_break`` and ``in_hand``
        their rows); the nominal target comes from the cached shot context."""
        t, ctx = self.table, self.shot_context()
        tgt = np.maximum(ctx.target[idx], 0)
        aim = np.where(is_break[:, None], np.array([t.width / 2, FOOT_SPOT * t.length]), pos[np.arange(len(idx)), tgt])
        return ActionCodec(ctx.aim_origin[idx], aim, in_hand, place, t, self.params, self.config.min_draw,
                           tgt, self.base_dim if self.rules.calls_ball else 0, self.n_balls, pos[:, 0], is_break,
                           self.rules.replaces, MAX_ACTION_ELEVATION if self.airborne else 0.0)

    def actions_to_shots(self, actions: np.ndarray, idx) -> Shots:
        """Actions [n, >= 4] of tables ``idx`` -> ``Shots`` (aim relative to the origin with the cue ball where it
        lies; ``ActionCodec.shots_of``)."""
        return self.codec(idx).shots_of(actions)

    def shots_to_actions(self, shots: Shots, idx) -> np.ndarray:
        """``Shots`` of tables ``idx`` -> a0..a3 [n, 4] (``ActionCodec.actions_of_shots``)."""
        return self.codec(idx).actions_of_shots(shots)

    def actions_of(self, plan, idx, codec: ActionCodec | None = None) -> np.ndarray:
        """The actions [n, action_dim] (float64, validated) that play a bot's
        ``ShotPlan`` on tables ``idx`` (``ActionCodec.encode_plan``:
        placements made legal first, the aim taken relative to the origin
        seen from the placed cue ball). A bot may also return the env's own
        actions [n, action_dim] (a learned policy): they are validated and played as
        they are. ``codec``: the tables' codec, if the caller has it (a view's)."""
        if isinstance(plan, np.ndarray):
            return self.validate_actions(plan, len(idx))
        return (codec or self.codec(idx)).encode_plan(plan)
