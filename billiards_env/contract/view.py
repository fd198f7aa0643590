"""``GameView``: what a bot of the two-player games is handed, a read-only
picture of a batch of tables (one row per table where the bot is to move).

A bot never touches an env: the env (or the match harness) builds a view of
the tables where the bot's player is to move, the bot returns a
``ShotPlan`` with one row per view row, and the env plays it. Everything a
bot needs is on the view:

- the balls: ``pos`` [n, B, 2] (m, float64; ball 0 the cue ball, a ball in a
  pocket keeps its last position), ``pocket`` [n, B] (the pocket each ball
  fell in, -1 on the table) and ``on_table`` [n, B];
- the game: ``to_move`` (player 0 or 1), ``groups`` [n, 2] (8-ball:
  ``rules.GROUP_*`` of each player), ``fouls`` [n, 2] (consecutive fouls of
  each player), ``shots`` (taken in the game);
- the shooter's constraints: ``ball_in_hand`` (``rules.IN_HAND_*``),
  ``targets`` [n, B] (the balls the cue ball may legally hit first),
  ``push_out_allowed``, ``may_pass``, ``call_needed``, ``is_break``;
- the equipment and physics: ``table`` (``physics.Table``: ``width`` across,
  x; ``length`` along, y, from the head rail at y = 0; ``pockets``),
  ``params`` (``physics.PhysicsParams``), ``effects``, ``models``, and
  ``marks`` (the head string, the head and foot spots);
- the execution noise the env applies to every shot: ``noise``
  (``physics.noise.NoiseConfig``) times ``noise_scale`` [n] (the per-game
  factor of ``variable`` noise; 1 otherwise);
- helpers: ``legal_placement`` (the ball-in-hand test), ``preview`` (try
  candidate shots in the simulator and judge them by the rules: see
  ``contract.preview``), ``take`` (a view of some rows);
- for learned bots that act in the env's own action space: ``observation()``
  (the env's float32 observation rows) and ``codec`` (the env's action
  convention, ``contract.codec.ActionCodec``: ``encode`` shots, the aim
  origin, ``placement_to_actions``); such a bot may return actions [n, 8].

All arrays are read-only; copy one to change it.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from ..physics import Effects, Models, PhysicsParams, Table
from ..physics.noise import NoiseConfig
from ..rules import records as R
from ..rules.placement import FOOT_SPOT, HEAD_STRING, KITCHEN_GAP
from .turn import Equipment


@dataclasses.dataclass(frozen=True)
class TableMarks:
    """The marks the rules name, in table coordinates (m): the head string
    ``y = head_string``, the ``head_spot`` (where the break's cue ball
    starts) and the ``foot_spot`` (the rack's apex; where balls are
    respotted); ``kitchen_y_max``: the largest y of a cue ball placed behind
    the head string."""

    head_string: float
    head_spot: tuple
    foot_spot: tuple
    kitchen_y_max: float

    @classmethod
    def of(cls, table: Table) -> "TableMarks":
        y = HEAD_STRING * table.length
        return cls(y, (table.width / 2, y), (table.width / 2, FOOT_SPOT * table.length), y - KITCHEN_GAP)


def _frozen(a) -> np.ndarray:
    """``a`` made read-only: an array that owns its data (a fancy-indexed
    row selection, as the envs hand over) is frozen in place, anything
    else (a view into someone's array) is copied first."""
    a = a if isinstance(a, np.ndarray) and a.flags.owndata else np.array(a)
    a.flags.writeable = False
    return a


@dataclasses.dataclass(frozen=True, eq=False)
class GameView:
    game: str
    rows: np.ndarray              # [n] the env's table numbers of the rows (for a bot's own bookkeeping)
    pos: np.ndarray               # [n, B, 2]
    pocket: np.ndarray            # [n, B] the pocket each ball fell in (-1: on the table)
    to_move: np.ndarray           # [n]
    ball_in_hand: np.ndarray      # [n]
    targets: np.ndarray           # [n, B]
    push_out_allowed: np.ndarray  # [n]
    may_pass: np.ndarray          # [n]
    call_needed: np.ndarray       # [n]
    is_break: np.ndarray          # [n]
    groups: np.ndarray            # [n, 2]
    fouls: np.ndarray             # [n, 2]
    shots: np.ndarray             # [n]
    table: Table
    params: PhysicsParams
    effects: Effects
    models: Models
    noise: NoiseConfig
    noise_scale: np.ndarray       # [n]
    min_draw: float               # m: the shortest cue draw the env plays (its slowest shot)
    rules: object                 # the ruleset (``rules.get_rules(game)``): ``preview`` judges with it
    state: R.GameState            # the rows' game states (``preview`` judges from them)
    codec: object = None          # the env's action convention (``contract.codec.ActionCodec``), for learned bots
    solver: str = "event"         # the env's solver (``"event"``, or ``"step"`` with time step ``dt``)
    dt: float | None = None
    may_replace: np.ndarray | None = None  # [n] snooker, after a foul and a miss: the balls may be replaced
    touching: np.ndarray | None = None     # [n, B] snooker: the balls the cue ball touches (play away from them)
    _observe: object = None       # () -> float32 observation rows, or None

    @classmethod
    def build(cls, **fields) -> "GameView":
        """A view from arrays (copied and made read-only)."""
        arrays = {k: _frozen(v) for k, v in fields.items() if isinstance(v, np.ndarray)}
        return cls(**{**fields, **arrays})

    # --- sizes and marks ----------------------------------------------------
    @property
    def n(self) -> int:
        return len(self.rows)

    @property
    def n_balls(self) -> int:
        return self.pos.shape[1]

    @property
    def marks(self) -> TableMarks:
        return TableMarks.of(self.table)

    @property
    def pockets(self) -> np.ndarray:
        """Pocket centres and capture radii [P, 3] (x, y, r), in ``Table.pockets`` order."""
        return np.ascontiguousarray(self.table.geometry(True)[3], dtype=np.float64)

    @property
    def equipment(self) -> Equipment:
        """What the env simulates every shot with (``contract.turn.Equipment``)."""
        return Equipment(self.table, self.params, self.effects, self.models, self.solver, self.dt)

    @property
    def constraints(self) -> R.Constraints:
        """The rows' shooter constraints as the rules' ``Constraints``."""
        return R.Constraints(self.to_move, self.ball_in_hand, self.targets, self.push_out_allowed, self.may_pass,
                             self.call_needed, self.is_break, np.zeros(self.n, dtype=bool), self.may_replace,
                             self.touching)

    @property
    def on_table(self) -> np.ndarray:
        """[n, B] bool: the ball is on the table."""
        return self.pocket < 0

    @property
    def in_hand(self) -> np.ndarray:
        """[n] bool: the shooter places the cue ball (anywhere or behind the head string)."""
        return self.ball_in_hand != R.IN_HAND_NONE

    def nominal_target(self) -> np.ndarray:
        """[n] the lowest-numbered legal target (-1 none)."""
        return R.nominal_target(self.targets)

    # --- helpers --------------------------------------------------------------
    def legal_placement(self, xy, rows=None) -> tuple[np.ndarray, np.ndarray]:
        """The legal cue-ball spots nearest to ``xy`` [k, 2] on view rows
        ``rows`` (default: all) under their ball-in-hand constraint
        (behind the head string when ``ball_in_hand`` is ``IN_HAND_KITCHEN``;
        clear of the cushions, every ball and every pocket): (spots [k, 2],
        moved [k]). A spot that is already legal is returned unchanged."""
        rows = np.arange(self.n) if rows is None else np.asarray(rows, dtype=np.int64)
        return self.equipment.place(xy, self.pos[rows], self.pocket[rows], self.ball_in_hand[rows] == R.IN_HAND_KITCHEN)

    def preview(self, plan, rows=None, noise=None, rng=None, draws=None):
        """Play ``plan`` (one row per entry of ``rows``, default one per view
        row) on copies of the rows' tables exactly as the env plays it:
        ``contract.preview.Preview``. See ``contract.preview.preview``."""
        from .preview import preview
        return preview(self, plan, rows, noise, rng, draws=draws)

    def after(self, pv, idx, rows) -> "GameView":
        """The view of the next shooter on the tables that previewed shots ``idx`` [m] (rows of ``pv``, a
        ``contract.preview.Preview`` of this view) leave; ``rows`` [m]: the view rows those shots were played on
        (their noise factor carries over). A bot looking at the reply to its shot previews from it."""
        idx, rows = np.asarray(idx, dtype=np.int64), np.asarray(rows, dtype=np.int64)
        if pv.state is None:
            raise ValueError("GameView.after needs a Preview with its state (contract.preview.preview keeps it)")
        if len(idx) != len(rows):
            raise ValueError(f"GameView.after: {len(idx)} previewed shots, {len(rows)} view rows")
        nx, st = pv.next, pv.state
        return GameView.build(
            game=self.game, rows=self.rows[rows], pos=pv.pos[idx], pocket=pv.pocket[idx], to_move=nx.shooter[idx],
            ball_in_hand=nx.ball_in_hand[idx], targets=nx.targets[idx], push_out_allowed=nx.push_out_allowed[idx],
            may_pass=nx.may_pass[idx], call_needed=nx.call_needed[idx], is_break=nx.is_break[idx],
            groups=st.group[idx], fouls=st.fouls[idx], shots=st.shots[idx], table=self.table, params=self.params,
            effects=self.effects, models=self.models, noise=self.noise, noise_scale=self.noise_scale[rows],
            min_draw=self.min_draw, rules=self.rules, state=st.take(idx), solver=self.solver, dt=self.dt,
            may_replace=nx.may_replace[idx], touching=nx.touching[idx])

    def take(self, rows) -> "GameView":
        """A view of some of this view's rows."""
        rows = np.asarray(rows, dtype=np.int64)
        sub = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}
        for k, v in sub.items():
            if isinstance(v, np.ndarray):
                sub[k] = _frozen(v[rows])
        sub["state"] = self.state.take(rows)
        sub["codec"] = None if self.codec is None else self.codec.take(rows)
        obs = self._observe
        sub["_observe"] = None if obs is None else (lambda: obs()[rows])
        return GameView(**sub)

    def observation(self) -> np.ndarray:
        """The env's observation rows [n, obs_dim] (float32; ``envs.games``' layout)."""
        if self._observe is None:
            raise RuntimeError("this view was built without the env's observation")
        return self._observe()


@dataclasses.dataclass(frozen=True, eq=False)
class TaskView:
    """What a bot of the one-player tasks is handed: the same kind of
    read-only picture as ``GameView``, for the tables of a one-player env.

    ``pos`` [n, B, 2], ``pocket`` [n, B] and ``on_table`` as in ``GameView``;
    ``target`` [n] the legal target ball (-1: none); ``shots`` [n] taken in
    the episode; the equipment (``table``, ``params``, ``effects``,
    ``models``), the env's ``noise`` and slowest shot (``min_draw``), and
    ``rules``: the task (``envs.tasks``), whose ``legal_target(pos, pocket)``
    and ``judge(ShotOutcome)`` rule any table a bot simulates."""

    task: str
    rows: np.ndarray
    pos: np.ndarray
    pocket: np.ndarray
    target: np.ndarray
    shots: np.ndarray
    table: Table
    params: PhysicsParams
    effects: Effects
    models: Models
    noise: NoiseConfig
    min_draw: float
    rules: object
    solver: str = "event"
    dt: float | None = None
    _observe: object = None

    def preview(self, plan, rows=None, noise=None, rng=None, start=None, draws=None):
        """Play ``plan`` on copies of the rows' tables (or on ``start``, a
        ``BallState``) and judge each shot by the task: ``contract.preview.TaskPreview``."""
        from .preview import preview
        return preview(self, plan, rows, noise, rng, start, draws=draws)

    build = classmethod(GameView.build.__func__)
    n = GameView.n
    n_balls = GameView.n_balls
    equipment = GameView.equipment
    on_table = GameView.on_table
    observation = GameView.observation
