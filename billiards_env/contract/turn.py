"""One turn of a two-player game, played the one way: ``play_turn``.

The env's step (``envs.games.GameCore.step``) and a bot's preview
(``GameView.preview`` / ``GameView.after``) both play a turn through this
function, so what a bot previews is what the env plays: the same shot under
the same noise draws gives the same record, the same balls and the same
game state, bit for bit (``tests/contract/test_turn.py`` checks it in every
game).

A turn, for each of ``n`` tables (a ``ShotPlan`` row, absolute aim):

1. a pass (``declare`` where the constraints allow a pass, ``may_pass``)
   plays no shot; nor does a replace (``replace`` where the constraints
   allow it, ``may_replace``): after the ruling the balls go back where
   snooker's miss was played from (``GameState.miss_pos``), or, in
   three-cushion, to the starting position (``ShotRecord.restart``);
2. with ball in hand the cue ball goes to the plan's placement made legal
   (the nearest legal spot under the constraint: anywhere, behind the head
   string, in the D); a placement is ignored without ball in hand (the cue
   ball is played from where it lies);
3. ``declare`` where a push-out is allowed declares one; the called pocket
   and (10-ball) the called ball or (snooker) the nominated ball count
   where the constraints ask for a call;
4. the shot's execution noise: ``noise`` times the standard normal draws
   ``draw(rows)`` gives for the shooting rows (the env draws them from the
   tables' streams, a preview from its ``rng`` or from the draws it is
   handed), in ``physics.noise.perturb``'s order;
5. the strike and the simulation to rest with the game's equipment
   (``Equipment``: table, physics, effects, models, solver); the cue
   strikes the shooter's cue ball, or where the plan names another ball
   (``ShotPlan.struck``, games where each player has a cue ball:
   three-cushion's wrong cue ball) that ball, with the same arithmetic;
   elevated (``ShotPlan.theta``; the noise leaves the elevation as planned)
   only where the equipment's effects have ``airborne`` on: the struck
   tables then carry ``BallState.air`` (zeros before the strike), so the
   cue's drive into the slate makes the ball jump, and a ball may leave the
   table (``ShotInput.off_table``, ruled by every game);
6. the rules' ruling from the game state, then the balls the ruling puts
   back (respotted object balls, snooker's colours, the re-placed carom
   balls), and in games where each player has a cue ball, the incoming
   player's ball to slot 0.
"""
from __future__ import annotations

import dataclasses
import time
from typing import Callable

import numpy as np

from ..physics import BallState, Effects, Models, PhysicsParams, SimOptions, Table, simulate
from ..physics.noise import NoiseConfig, perturb
from ..physics.strike import apply_strike
from ..rules import records as R
from ..rules.placement import d_of, legal_spots
from ..rules.records import Constraints, GameState, ShotInput, ShotRecord
from ..rules.respot import hand_over, restart_position
from .plan import ShotPlan, check_theta


@dataclasses.dataclass(frozen=True, eq=False)
class Equipment:
    """What a game's shots are simulated with: the ``table``, the physics
    ``params``, the ``effects`` and ``models`` switched on, and the
    ``solver`` (``"event"``, or ``"step"`` with its time step ``dt``)."""

    table: Table
    params: PhysicsParams
    effects: Effects = dataclasses.field(default_factory=Effects)
    models: Models = dataclasses.field(default_factory=Models)
    solver: str = "event"
    dt: float | None = None

    @property
    def pockets(self) -> np.ndarray:
        """Pocket centres and capture radii [P, 3] (x, y, r), in ``Table.pockets`` order."""
        return np.ascontiguousarray(self.table.geometry(True)[3], dtype=np.float64)

    def place(self, xy, pos, pocket, kitchen) -> tuple[np.ndarray, np.ndarray]:
        """The legal cue-ball spots nearest to ``xy`` [n, 2] on tables ``pos`` /
        ``pocket`` (behind the head string where ``kitchen``; in the D on a
        snooker table): (spots [n, 2], moved [n]); a legal spot is kept as it is."""
        t = self.table
        spots, moved = legal_spots(xy, pos, pocket, kitchen, t.width, t.length, self.params.R, self.pockets, d_of(t))
        return np.where(moved[:, None], spots, xy), moved

    def simulate(self, struck: BallState, contacts: int = 0, record: bool = False):
        """Simulate ``struck`` (a state the caller owns) to rest in place: the ``physics.SimResult``."""
        return simulate(struck, self.table, self.params, solver=self.solver, dt=self.dt, record=record,
                        effects=self.effects, models=self.models,
                        options=SimOptions(validate=False, contacts=contacts, inplace=True))


@dataclasses.dataclass(eq=False)
class Turn:
    """What one turn did on each of ``n`` tables: the rules' ``record``, the
    game ``state`` after it and the next shooter's constraints ``next``; the
    balls after it (``pos`` [n, B, 2], ``pocket`` [n, B], respots applied);
    ``shot`` (the ``rules.ShotInput`` the rules judged: pocketed balls,
    first contact, cushions, declarations, calls); where the cue ball was
    played from (``placed`` [n, 2]) and whether a ball-in-hand placement
    was moved to be legal (``moved`` [n]); the simulation's ``n_events``
    [n] and ``sim_time`` [n]; ``start`` (the tables as struck from, a
    ``BallState`` at rest) and ``events`` (per shooting table, the event
    log when recorded, else None)."""

    record: ShotRecord
    state: GameState
    pos: np.ndarray
    pocket: np.ndarray
    shot: ShotInput
    placed: np.ndarray
    moved: np.ndarray
    n_events: np.ndarray
    sim_time: np.ndarray
    start: BallState
    shoot: np.ndarray
    events: list | None = None
    sim_wall: float = 0.0  # s: wall time of the simulation (the rest is the rules' and the bookkeeping's)
    rules: object = None
    _next: Constraints | None = None

    @property
    def next(self) -> Constraints:
        """The next shooter's ``Constraints`` on each table (computed on first use)."""
        if self._next is None:
            self._next = self.rules.constraints(self.state, self.pocket,
                                                **({"pos": self.pos} if self.rules.reads_position else {}))
        return self._next


def play_turn(rules, eq: Equipment, game: GameState, c: Constraints, pos: np.ndarray, pocket: np.ndarray,
              plan: ShotPlan, noise: NoiseConfig | None = None, draw: Callable | None = None,
              record: bool = False) -> Turn:
    """Play ``plan`` on ``n`` tables (``pos`` [n, B, 2], ``pocket`` [n, B],
    not modified) from game states ``game`` under constraints ``c`` (both
    for these n tables), as the module docstring says. ``noise``: the
    execution noise (None or disabled: none); ``draw(rows) -> [k, 4]``: the
    standard normal draws (times each table's noise factor) of the shooting
    rows ``rows``. ``record``: keep each shot's event log (``Turn.events``)."""
    n, B = plan.n, pos.shape[1]
    if (plan.struck != 0).any() and not rules.own_cue_balls:
        raise ValueError(f"{rules.name}: ShotPlan.struck names another ball than the cue ball; only games where each "
                         "player has a cue ball (three-cushion) rule a shot with the wrong ball")
    if ((plan.struck < 0) | (plan.struck >= B)).any():
        raise ValueError(f"ShotPlan.struck must be a ball 0..{B - 1}, got {plan.struck}")
    check_elevation(plan.theta, eq.effects)
    replaced = c.may_replace & plan.replace
    passed = c.may_pass & plan.declare & ~replaced
    push = c.push_out_allowed & plan.declare
    called = np.where(c.call_needed, plan.pocket, -1)
    if rules.calls_ball:  # 10-ball: the called ball, -1 meaning the nominal target (the lowest legal ball)
        ball = np.where(plan.ball < 0, np.maximum(R.nominal_target(c.targets), 0), plan.ball)
        ball = np.where(c.call_needed, ball, R.CALL_NONE)
    else:
        ball = np.full(n, R.CALL_NONE, dtype=np.int64)
    start = BallState(np.array(pos, dtype=np.float64), np.zeros((n, B, 2)), np.zeros((n, B, 3)),
                      np.array(pocket, dtype=np.int64))
    moved = np.zeros(n, dtype=bool)
    h = np.nonzero((c.ball_in_hand != R.IN_HAND_NONE) & ~passed & ~replaced)[0]
    if len(h):
        want = np.where(np.isnan(plan.placement[h]), start.pos[h, 0], plan.placement[h])
        kitchen = c.ball_in_hand[h] == R.IN_HAND_KITCHEN
        start.pos[h, 0], moved[h] = eq.place(want, start.pos[h], start.pocket[h], kitchen)
        start.pocket[h, 0] = -1
    shoot = np.nonzero(~passed & ~replaced)[0]
    if (start.pocket[shoot, 0] >= 0).any():
        raise RuntimeError("the cue ball is pocketed without ball in hand: the game has ended, reset it")
    pocket_after, pos_after = start.pocket.copy(), start.pos.copy()
    first = np.full(n, -1, dtype=np.int64)
    rails = np.zeros((n, B), dtype=np.int64)
    object_rails = np.zeros((n, B), dtype=np.int64)
    n_events, sim_time = np.zeros(n, dtype=np.int64), np.zeros(n)
    K = rules.contacts
    contacts = np.full((n, K, 2), -1, dtype=np.int64) if K else None
    n_contacts = np.zeros(n, dtype=np.int64) if K else None
    events, sim_wall = None, 0.0
    if len(shoot):
        shots = plan.take(shoot).shots
        if noise is not None and noise.enabled:
            shots = perturb(shots, draw(shoot), noise, eq.params)
        struck = airborne_state(start.take(shoot), eq.effects)  # a copy, struck in place
        theta = plan.theta[shoot]
        apply_strike(struck, *(np.ascontiguousarray(v, dtype=np.float64) for v in shots), eq.params.R,
                     np.ascontiguousarray(theta) if (theta != 0).any() else None)
        _strike_other(struck, plan.struck[shoot])
        t0 = time.perf_counter()
        res = eq.simulate(struck, K, record)
        sim_wall = time.perf_counter() - t0
        pocket_after[shoot], pos_after[shoot] = res.state.pocket, res.state.pos
        first[shoot] = res.first_contact
        rails[shoot] = res.cushion_hits_after_contact
        object_rails[shoot] = res.cushion_hits
        n_events[shoot], sim_time[shoot] = res.n_events, res.time
        if K:
            contacts[shoot], n_contacts[shoot] = res.contacts, res.n_contacts
        events = res.events
    # the shot as it ended (a copy: the balls the ruling puts back below stay pocketed in ``shot.pocketed``)
    shot = ShotInput(start.pocket, pocket_after.copy(), first, rails, object_rails, push, called, passed, ball,
                     contacts, n_contacts, pos_before=start.pos if rules.reads_position else None,
                     replaced=replaced, struck=np.where(replaced | passed, 0, plan.struck))
    rec, after = rules.judge(game, shot)
    _put_back(rules, eq, pos_after, pocket_after, rec)
    if game.miss_pos is not None and rec.replaced.any():  # snooker: the balls where the miss was played from
        pos_after[rec.replaced], pocket_after[rec.replaced] = game.miss_pos[rec.replaced], game.miss_pocket[rec.replaced]
    return Turn(rec, after, pos_after, pocket_after, shot, start.pos[:, 0].copy(), moved, n_events, sim_time,
                start, shoot, events, sim_wall, rules)


def _strike_other(struck: BallState, ball: np.ndarray) -> None:
    """Where ``ball`` [k] names another ball than the cue ball (``ShotPlan.struck``),
    the strike ``apply_strike`` gave the cue ball goes to that ball instead, in
    place (the same velocity and spin: the cue does not know which ball it hits)."""
    r = np.nonzero(ball != 0)[0]
    if len(r):
        j = ball[r]
        struck.vel[r, j], struck.omega[r, j] = struck.vel[r, 0], struck.omega[r, 0]
        struck.vel[r, 0], struck.omega[r, 0] = 0.0, 0.0
        if struck.air is not None:  # an elevated cue's drive into the slate
            struck.air[r, j], struck.air[r, 0] = struck.air[r, 0], 0.0


def airborne_state(state: BallState, effects: Effects) -> BallState:
    """``state`` ready to be struck with ``effects``: with ``airborne`` on, the
    same arrays with ``air`` zeros (every ball resting on the slate) where it
    has none, so that ``apply_strike`` keeps an elevated cue's velocity into
    the slate and the simulator makes it jump; else ``state`` itself."""
    if not effects.airborne or state.air is not None:
        return state
    return BallState(state.pos, state.vel, state.omega, state.pocket, np.zeros(state.pos.shape[:2] + (2,)))


def check_elevation(theta: np.ndarray, effects: Effects) -> None:
    """Shots that elevate the cue (``theta`` [n], ``ShotPlan.theta``) are
    played only with ``Effects(airborne=True)``: elsewhere a ValueError naming
    the switch (the planar simulator would drop the drive into the slate and
    play another shot than the one planned). Elevations lie in [0, pi/2]."""
    if not np.any(theta != 0):
        return
    if not effects.airborne:
        r = int(np.argmax(theta != 0))
        raise ValueError(f"ShotPlan.theta elevates the cue ({theta[r]} rad at row {r}) but the equipment's "
                         "effects have airborne off: elevated shots are played with Effects(airborne=True) (the "
                         "envs' effects={'airborne': True}); a level shot has theta 0")
    check_theta(theta)


def _put_back(rules, eq: Equipment, pos: np.ndarray, pocket: np.ndarray, rec: ShotRecord) -> None:
    """The balls the ruling puts back, in place: respotted balls (snooker's
    colours on their spots), and in the games where each player has a cue
    ball, the incoming player's ball to slot 0 and the balls back at the
    starting position where the ruling restarts (three-cushion's last
    inning with equal innings, and balls in contact the shooter had
    replaced)."""
    t = eq.table
    rules.respot(pos, pocket, rec.respot, t, eq.params.R, eq.pockets)
    if rules.own_cue_balls:
        hand_over(pos, rec.turn_over & ~rec.game_over)
        if rec.restart is not None:  # three-cushion: from the starting position
            restart_position(pos, rec.restart, t, eq.params.R)

