"""``preview``: try candidate shots in the simulator and judge them by the
rules, the one way every bot looks ahead.

``preview(view, plan, rows)`` strikes ``plan`` row k on a copy of the table
of view row ``rows[k]`` (the cue ball at ``plan.placement[k]`` where that is
given, else where it lies), optionally with execution noise, simulates
every copy to rest in one ``physics.simulate`` call (which runs large
batches in chunks, so memory stays bounded however many candidates a bot
tries), and judges each
shot with the game's rules from the row's game state, the plan's called
pocket (and, in 10-ball, called ball) included. Push-outs and passes are
not previewed (a plan's ``declare`` is ignored).

Noise: ``None`` strikes exactly as planned; ``"env"`` applies the env's own
noise (``view.noise`` times ``view.noise_scale``); a ``NoiseConfig`` (or a
preset name) applies that. Noise needs ``rng`` (a ``numpy.random.Generator``):
four standard normals per shot, in ``physics.noise.perturb``'s order.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from ..physics import BallState, SimOptions, simulate, strike_velocity
from ..physics.noise import NoiseConfig, perturb
from ..rules import Constraints, ShotInput, ShotRecord


@dataclasses.dataclass(eq=False)
class Preview:
    """The outcome of previewed shots, one row per shot: ``record`` (the
    rules' ``ShotRecord``: legal, foul, turn over, winner, ...), ``pos`` [k,
    B, 2] and ``pocket`` [k, B] after the shot, ``first_contact`` [k],
    ``next`` (the next shooter's ``Constraints``) and, where the rules read
    them (three-cushion), the cue ball's ``contacts`` [k, K, 2] in order and
    ``n_contacts`` [k] (``physics.SimResult``'s); ``state`` the rules' ``GameState`` after the shots (two-player
    games: what a bot looking past the next shooter's reply previews from)."""

    record: ShotRecord
    pos: np.ndarray
    pocket: np.ndarray
    first_contact: np.ndarray
    next: Constraints
    contacts: np.ndarray | None = None
    n_contacts: np.ndarray | None = None
    state: object = None

    @property
    def on_table(self) -> np.ndarray:
        return self.pocket < 0


@dataclasses.dataclass(eq=False)
class TaskPreview:
    """The outcome of previewed shots on a one-player task, one row per shot:
    ``outcome`` (the ``envs.tasks.ShotOutcome`` the task judges), ``judged``
    (the task's ruling: ``success``, ``terminated``, ...), ``pos`` [k, B, 2]
    and ``pocket`` [k, B] after the shot."""

    outcome: object
    judged: object
    pos: np.ndarray
    pocket: np.ndarray

    @property
    def on_table(self) -> np.ndarray:
        return self.pocket < 0


def _noise_of(view, spec, rows):
    if spec is None:
        return None, None
    if isinstance(spec, str) and spec == "env":
        scale = getattr(view, "noise_scale", None)
        return view.noise, None if scale is None else scale[rows]
    return NoiseConfig.from_any(spec), None


def rest_state(view, rows=None) -> BallState:
    """The tables of view rows ``rows`` (default: all) as a ``BallState`` at rest (copies)."""
    rows = np.arange(view.n) if rows is None else np.asarray(rows, dtype=np.int64)
    k, B = len(rows), view.n_balls
    # indexing with an integer array copies (and the copies are writeable): no second copy
    return BallState(view.pos[rows], np.zeros((k, B, 2)), np.zeros((k, B, 3)), view.pocket[rows])


def play_shots(view, start: BallState, shots, noise=None, rng=None, rows=None):
    """Strike ``shots`` on the tables of ``start`` (with ``noise``, see the
    module docstring; ``rows``: the view rows, for the env noise's per-table
    factor) and simulate them to rest with the view's equipment: the
    ``physics.SimResult``. What every preview is made of."""
    cfg, scale = _noise_of(view, noise, np.arange(start.n_envs) if rows is None else rows)
    if cfg is not None and cfg.enabled:
        if rng is None:
            raise ValueError("preview with noise needs rng (a numpy.random.Generator)")
        z = rng.normal(size=(start.n_envs, 4))
        if scale is not None:
            z *= scale[:, None]
        shots = perturb(shots, z, cfg, view.params)
    struck = strike_velocity(start, *shots, view.params)
    # the cue ball's contacts in order where the rules read them (three-cushion)
    return simulate(struck, view.table, view.params, effects=view.effects, models=view.models,
                    options=SimOptions(validate=False, contacts=getattr(view.rules, "contacts", 0), inplace=True))


def preview(view, plan, rows=None, noise=None, rng=None, start: BallState | None = None):
    """See the module docstring. ``start`` (one-player views only): tables to
    play from instead of the view's rows (a bot looking past its first shot)."""
    if not hasattr(view, "call_needed"):
        return _task_preview(view, plan, rows, (noise, rng), start)
    rows = np.arange(view.n) if rows is None else np.asarray(rows, dtype=np.int64)
    k = len(rows)
    if plan.n != k:
        raise ValueError(f"preview: the plan has {plan.n} rows, rows selects {k} tables")
    start = rest_state(view, rows)
    place = ~np.isnan(plan.placement[:, 0])
    start.pos[place, 0] = plan.placement[place]
    start.pocket[:, 0] = -1
    res = play_shots(view, start, plan.shots, noise, rng, rows)
    pos, pocket, first = res.state.pos, res.state.pocket, res.first_contact
    rails, object_rails = res.cushion_hits_after_contact, res.cushion_hits
    called = np.where(view.call_needed[rows], plan.pocket, -1)
    ball = None
    if getattr(view.rules, "calls_ball", False):  # 10-ball: the called ball (-1: the nominal target)
        ball = np.where(plan.ball < 0, np.maximum(view.nominal_target()[rows], 0), plan.ball)
        ball = np.where(view.call_needed[rows], ball, -1)
    where = getattr(view.rules, "reads_position", False)  # snooker's free ball reads the position
    shot = ShotInput(start.pocket, pocket, first, rails, object_rails, called_pocket=called, called_ball=ball,
                     contacts=res.contacts, n_contacts=res.n_contacts, pos_before=start.pos if where else None)
    rec, after = view.rules.judge(view.state.take(rows), shot)
    return Preview(rec, pos, pocket, first, view.rules.constraints(after, pocket, **({"pos": pos} if where else {})),
                   res.contacts, res.n_contacts, after)


def _task_preview(view, plan, rows, noise_rng, start) -> TaskPreview:
    from ..envs.tasks.base import ShotOutcome
    if start is None:
        rows = np.arange(view.n) if rows is None else np.asarray(rows, dtype=np.int64)
        start = rest_state(view, rows)
    if plan.n != start.n_envs:
        raise ValueError(f"preview: the plan has {plan.n} rows for {start.n_envs} tables")
    res = play_shots(view, start, plan.shots, *noise_rng, rows)
    pocket = res.state.pocket
    task = view.rules
    outcome = ShotOutcome(pocketed=(pocket >= 0) & (start.pocket < 0), pocket_after=pocket,
                          first_contact=res.first_contact, target=task.legal_target(start.pos, start.pocket))
    return TaskPreview(outcome, task.judge(outcome), res.state.pos, pocket)
