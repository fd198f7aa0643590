"""``preview``: try candidate shots in the simulator and judge them by the
rules, exactly as the env plays them; the one way every bot looks ahead.

Two-player games: ``preview(view, plan, rows)`` plays ``plan`` row k on a
copy of the table of view row ``rows[k]`` through ``contract.turn.play_turn``,
the function the env's step plays every turn with: the placement counts
only with ball in hand (made legal first), a declared push-out is judged as
a push-out, a pass plays no shot, the called pocket and ball count where a
call is needed, and the balls the ruling puts back (the 9 spotted after a
foul, snooker's colours, the carom balls re-placed) are back on the table
in ``Preview.pos``, ``pocket`` and ``view.after``. The same plan under the
same noise draws gives what ``env.step`` gives, bit for bit
(``tests/contract/test_turn.py``). One ``physics.simulate`` call runs every
copy (in chunks: memory stays bounded however many candidates a bot tries).

One-player tasks: ``preview(view, plan, rows)`` (or ``start=``, a
``BallState`` to play from) strikes and simulates each shot and judges it
with the task: ``TaskPreview``.

Elevated shots (``ShotPlan.theta``) are previewed where the view's effects
have ``airborne`` on, as the env plays them: the tables carry
``BallState.air`` and the ball jumps (``contract.turn.airborne_state``);
elsewhere a plan with the cue elevated is refused (a ValueError).

Noise (``noise=``):

- ``None`` (default): the shot exactly as planned;
- ``"env"``: the env's own noise, ``view.noise`` times each table's
  ``view.noise_scale``;
- a ``NoiseConfig`` (``physics.noise``) or a preset name (``"tournament"``,
  ``"high"``): that noise.

The standard normal draws behind it (four per shot, in
``physics.noise.perturb``'s order: aim, speed, side, height) come from
``draws=`` [k, 4] when given, so a bot can judge several candidates on the
same draws (common random numbers: ``common_draws``), else from ``rng`` (a
``numpy.random.Generator``), fresh for every shot. A pass draws nothing.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from ..physics import BallState, strike_velocity
from ..physics.noise import NoiseConfig, perturb
from ..rules import Constraints, ShotRecord
from .outcome import ShotOutcome
from .turn import Turn, airborne_state, check_elevation, play_turn


@dataclasses.dataclass(eq=False)
class Preview:
    """The outcome of previewed shots, one row per shot: ``record`` (the
    rules' ``ShotRecord``: legal, foul, turn over, winner, ...), ``pos`` [k,
    B, 2] and ``pocket`` [k, B] after the shot (respots applied, as the env
    leaves the table), ``first_contact`` [k], ``next`` (the next shooter's
    ``Constraints``) and, where the rules read them (three-cushion), the cue
    ball's ``contacts`` [k, K, 2] in order and ``n_contacts`` [k]
    (``physics.SimResult``'s); ``state`` the rules' ``GameState`` after the
    shots (what a bot looking past the next shooter's reply previews from,
    ``GameView.after``); ``turn``: the whole ``contract.turn.Turn``
    (pocketed balls, where the cue ball was played from, events, ...);
    ``off_table`` [k, B] the balls the shot drove off the table (the
    ruling's ``FOUL_OFF_TABLE``; ``pocket`` shows them back on the table where
    the ruling respotted them)."""

    record: ShotRecord
    pos: np.ndarray
    pocket: np.ndarray
    first_contact: np.ndarray
    next: Constraints
    contacts: np.ndarray | None = None
    n_contacts: np.ndarray | None = None
    state: object = None
    turn: Turn | None = None

    @property
    def on_table(self) -> np.ndarray:
        return self.pocket < 0

    @property
    def off_table(self) -> np.ndarray:
        """[k, B] the balls the previewed shot drove off the table (``ShotInput.off_table``)."""
        return self.turn.shot.off_table


@dataclasses.dataclass(eq=False)
class TaskPreview:
    """The outcome of previewed shots on a one-player task, one row per shot:
    ``outcome`` (the ``ShotOutcome`` the task judges), ``judged`` (the task's
    ruling: ``success``, ``terminated``, ...), ``pos`` [k, B, 2] and
    ``pocket`` [k, B] after the shot."""

    outcome: ShotOutcome
    judged: object
    pos: np.ndarray
    pocket: np.ndarray

    @property
    def on_table(self) -> np.ndarray:
        return self.pocket < 0


def common_draws(groups, rng: np.random.Generator) -> np.ndarray:
    """Standard normal draws [k, 4] for ``preview(..., draws=)`` in which every
    shot of the same group (``groups`` [k], e.g. the sample number of each
    candidate's repeat) gets the same four numbers: candidates compared on
    common random numbers."""
    groups = np.asarray(groups, dtype=np.int64)
    _, inv = np.unique(groups, return_inverse=True)
    return rng.normal(size=(int(inv.max()) + 1 if len(inv) else 0, 4))[inv]


def _noise_of(view, spec, rows):
    """(NoiseConfig or None, the per-row factor [k] or None) of a ``noise=`` argument."""
    if spec is None:
        return None, None
    if isinstance(spec, str) and spec == "env":
        scale = getattr(view, "noise_scale", None)
        return view.noise, None if scale is None else scale[rows]
    return NoiseConfig.from_any(spec), None


def _drawer(cfg, scale, rng, draws, k: int):
    """``draw(rows) -> [len(rows), 4]``: the given draws, or fresh ones from ``rng``, times the row factors."""
    if cfg is None or not cfg.enabled:
        return None
    if draws is not None:
        draws = np.asarray(draws, dtype=np.float64)
        if draws.shape != (k, 4):
            raise ValueError(f"preview: draws must have shape ({k}, 4), one row per shot, got {draws.shape}")
    elif rng is None:
        raise ValueError("preview with noise needs rng (a numpy.random.Generator) or draws [k, 4]")

    def draw(rows):
        z = draws[rows].copy() if draws is not None else rng.normal(size=(len(rows), 4))
        if scale is not None:
            z *= scale[rows][:, None]
        return z
    return draw


def rest_state(view, rows=None) -> BallState:
    """The tables of view rows ``rows`` (default: all) as a ``BallState`` at rest (copies)."""
    rows = np.arange(view.n) if rows is None else np.asarray(rows, dtype=np.int64)
    k, B = len(rows), view.n_balls
    # indexing with an integer array copies (and the copies are writeable): no second copy
    return BallState(view.pos[rows], np.zeros((k, B, 2)), np.zeros((k, B, 3)), view.pocket[rows])


def play_shots(view, start: BallState, shots, noise=None, rng=None, rows=None, draws=None):
    """Strike ``shots`` on the tables of ``start`` (with ``noise``, see the
    module docstring; ``rows``: the view rows, for the env noise's per-table
    factor) and simulate them to rest with the view's equipment: the
    ``physics.SimResult``. The one-player tasks' preview."""
    k = start.n_envs
    effects = view.equipment.effects
    theta = np.broadcast_to(np.asarray(getattr(shots, "theta", 0.0), dtype=np.float64), (k,))  # the noise leaves the elevation
    check_elevation(theta, effects)
    cfg, scale = _noise_of(view, noise, np.arange(k) if rows is None else rows)
    draw = _drawer(cfg, None if scale is None else np.asarray(scale), rng, draws, k)
    if draw is not None:
        shots = perturb(shots, draw(np.arange(k)), cfg, view.params)
    struck = strike_velocity(airborne_state(start, effects), *shots, view.params, theta=theta)
    # the cue ball's contacts in order where the rules read them (three-cushion)
    return view.equipment.simulate(struck, getattr(view.rules, "contacts", 0))


def preview(view, plan, rows=None, noise=None, rng=None, start: BallState | None = None, draws=None):
    """See the module docstring. ``start`` (one-player views only): tables to
    play from instead of the view's rows (a bot looking past its first shot)."""
    if not hasattr(view, "call_needed"):
        return _task_preview(view, plan, rows, noise, rng, start, draws)
    rows = np.arange(view.n) if rows is None else np.asarray(rows, dtype=np.int64)
    k = len(rows)
    if plan.n != k:
        raise ValueError(f"preview: the plan has {plan.n} rows, rows selects {k} tables")
    cfg, scale = _noise_of(view, noise, rows)
    draw = _drawer(cfg, None if scale is None else np.asarray(scale), rng, draws, k)
    turn = play_turn(view.rules, view.equipment, view.state.take(rows), view.constraints.take(rows),
                     view.pos[rows], view.pocket[rows], plan, cfg, draw)
    return Preview(turn.record, turn.pos, turn.pocket, turn.shot.first_contact, turn.next, turn.shot.contacts,
                   turn.shot.n_contacts, turn.state, turn)


def _task_preview(view, plan, rows, noise, rng, start, draws) -> TaskPreview:
    if start is None:
        rows = np.arange(view.n) if rows is None else np.asarray(rows, dtype=np.int64)
        start = rest_state(view, rows)
    if plan.n != start.n_envs:
        raise ValueError(f"preview: the plan has {plan.n} rows for {start.n_envs} tables")
    res = play_shots(view, start, plan.shots, noise, rng, rows, draws)
    pocket = res.state.pocket
    task = view.rules
    outcome = ShotOutcome.of(start.pocket, pocket, first_contact=res.first_contact,
                             target=task.legal_target(start.pos, start.pocket))
    return TaskPreview(outcome, task.judge(outcome), res.state.pos, pocket)
