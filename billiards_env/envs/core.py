"""Batched, task-agnostic env logic shared by the single-table and vector environments.

``BilliardsCore`` holds ``n_envs`` tables and steps any subset of them with
one batched ``apply_strike`` + ``simulate`` call. It knows no task: the
``Task`` of its config (``envs/tasks/``) supplies the start states, the legal
target, the rulings and the reward terms. Randomness (placement, break shot,
shot noise) is drawn from per-table counter-based streams
(``streams.TableStreams``, one stream per table, drawn for many tables in one
numba call): a table's draws depend only on its own stream, so table k of a
vector env seeded with ``seed`` behaves exactly like a single env seeded with
``seed + k``.

Shot space: an action [4] in [-1, 1] maps to a ``Shots`` row (phi, speed, a,
b) relative to the table's *shot context* (legal target, aim origin,
potential), computed once per state change for every table
(``shot_context``) and shared by the mapping, the reward, the observation and
the policies. With the equipment's ``effects={"airborne": True}`` (off by
default) the action is [5]: a4 the cue's elevation
(``contract.codec.MAX_ACTION_ELEVATION``), the balls fly and the info
reports the balls driven off the table (``off_table``).
"""
from __future__ import annotations

import math

import numba
import numpy as np

from ..physics import BallState, SimOptions, simulate
from ..physics.noise import perturb
from ..physics.strike import Shots, apply_strike, draw_to_speed
from ..contract.codec import MAX_ACTION_ELEVATION, ShotContext, _action_to_shot, _context, shot_actions
from ..contract.outcome import ShotOutcome
from ..contract.turn import airborne_state, check_elevation
from ..contract.pockets import pocket_accept_cos, pocket_axes
from ..contract.view import TaskView
from . import target_frame
from .config import TaskConfig
from .impact import impact_actions, impact_phis
from .streams import TableStreams, place_balls
from .tasks.registry import get_task



_jit = numba.njit(cache=True, nogil=True)


@_jit
def _observe(pos, pocket, tgt, shots, max_shots, width, length, obs):
    """Fill the zeroed observations ``obs`` [N, 4B + 1] (layout: see billiards._COMMON_DOC)."""
    B = pos.shape[1]
    for e in range(pos.shape[0]):
        for b in range(B):
            if pocket[e, b] < 0:
                obs[e, 3 * b] = min(max(pos[e, b, 0] / width, 0.0), 1.0)
                obs[e, 3 * b + 1] = min(max(pos[e, b, 1] / length, 0.0), 1.0)
                obs[e, 3 * b + 2] = 1.0
        if tgt[e] > 0:
            obs[e, 3 * B + tgt[e]] = 1.0
        obs[e, 4 * B] = min(shots[e] / max_shots, 1.0)


class BilliardsCore:
    def __init__(self, cfg: TaskConfig, n_envs: int, record: bool = False):
        if not isinstance(n_envs, (int, np.integer)) or n_envs < 1:
            raise ValueError(f"num_envs must be a positive integer, got {n_envs!r}")
        self.cfg = cfg
        self.task = get_task(cfg.task)
        self.n_envs = int(n_envs)
        self.table = cfg.make_table()
        self.params = cfg.params()
        self.effects = cfg.effects
        self.models = cfg.models
        self.airborne = bool(self.effects.airborne)  # the option: balls fly, a4 the cue's elevation
        self.action_dim = 4 + int(self.airborne)
        self.record = record
        self.n_balls = cfg.n_balls + 1  # cue ball + object balls
        self.diag = math.hypot(self.table.width, self.table.length)
        self.state: BallState | None = None
        self.shots = np.zeros(self.n_envs, dtype=np.int64)
        self.last_start: list = [None] * self.n_envs   # BallState of one table before its last shot
        self.last_events: list = [None] * self.n_envs  # EventLog of its last shot (record=True)
        self.streams = TableStreams(self.n_envs)  # seeded by the env's reset
        self._every = np.arange(self.n_envs)
        self.pockets = np.ascontiguousarray(self.table.geometry(self.effects.pockets)[3], dtype=np.float64)
        # observation: size and lower bound (the upper bound is 1); see billiards._COMMON_DOC, envs/target_frame.py
        if cfg.observation == "target_frame":
            self.obs_dim, self.obs_low = target_frame.obs_size(self.n_balls, len(self.pockets)), -1.0
            self.pocket_axes = pocket_axes(self.pockets, self.table.width, self.table.length)
            self.pocket_accept = pocket_accept_cos(self.pockets, self.table.length)
        else:
            self.obs_dim, self.obs_low = 4 * self.n_balls + 1, 0.0
        self._context: ShotContext | None = None  # of the current state; None: to be computed

    # --- shot context: computed once per state change ------------------------
    def shot_context(self) -> ShotContext:
        """The ``ShotContext`` of every table's current state (cached until the state changes)."""
        if self._context is None:
            s = self.state
            tgt = np.ascontiguousarray(self.task.legal_target(s.pos, s.pocket), dtype=np.int64)
            phi, ang = np.empty(self.n_envs), np.empty(self.n_envs)
            _context(s.pos, tgt, self.pockets, self.diag, self.cfg.aim != "absolute", phi, ang)
            self._context = ShotContext(tgt, ang, phi)
        return self._context

    def legal_target(self) -> np.ndarray:
        """Legal target ball of every table (-1 if none)."""
        return self.shot_context().target

    def observe(self) -> np.ndarray:
        s = self.state
        obs = np.zeros((self.n_envs, self.obs_dim), dtype=np.float32)
        if self.cfg.observation == "target_frame":
            target_frame.observe_target_frame(s.pos, s.pocket, self.shot_context().target, self.shots,
                                              float(self.cfg.max_shots), self.pockets, self.pocket_axes,
                                              self.pocket_accept, self.diag, obs)
        else:
            _observe(s.pos, s.pocket, self.shot_context().target, self.shots, float(self.cfg.max_shots),
                     self.table.width, self.table.length, obs)
        return obs

    # --- actions <-> shots ----------------------------------------------------
    def validate_actions(self, actions, n: int) -> np.ndarray:
        a = np.asarray(actions, dtype=np.float64)
        if a.shape != (n, self.action_dim):
            raise ValueError(f"actions must have shape ({n}, {self.action_dim}), got {a.shape}")
        if not np.all(np.isfinite(a)):
            bad = np.argwhere(~np.isfinite(a))[0]
            raise ValueError(f"action contains NaN or infinite values (first at index {tuple(bad)}): {a[bad[0]]}")
        return a

    def actions_to_shots(self, actions: np.ndarray, idx) -> Shots:
        """Validated actions [n, action_dim] of tables ``idx`` -> ``Shots`` (after clipping;
        see billiards._COMMON_DOC for the mapping)."""
        actions = np.ascontiguousarray(actions, dtype=np.float64)
        theta = None
        if self.airborne:  # a4: the cue's elevation, -1 the level cue
            theta = (np.clip(actions[:, 4], -1.0, 1.0) + 1.0) * 0.5 * MAX_ACTION_ELEVATION
            actions = np.ascontiguousarray(actions[:, :4])
        out = np.empty((4, len(actions)))
        ctx = self.shot_context()
        _action_to_shot(actions, ctx.aim_origin[idx], self.cfg.min_draw, self.params.max_draw,
                        self.params.miscue_limit, out)
        if self.cfg.aim == "impact":  # a0 is the impact parameter, not an angle (envs/impact.py)
            impact_phis(np.ascontiguousarray(actions[:, 0]), ctx.aim_origin[idx], ctx.target[idx],
                        self.state.pos[idx], self.params.R, out[0])
        if self.cfg.speed_scale == "log":  # a1 spans min_draw..max_draw geometrically
            lo, hi = self.cfg.min_draw, self.params.max_draw
            out[1] = lo * (hi / lo) ** (0.5 * (np.clip(actions[:, 1], -1.0, 1.0) + 1.0))
        return Shots.of_arrays(out[0], draw_to_speed(out[1], self.params), out[2], out[3], theta)

    def shots_to_actions(self, shots: Shots, idx) -> np.ndarray:
        """``Shots`` of tables ``idx`` -> actions [n, action_dim] (float64, clipped to
        [-1, 1]); the inverse of ``actions_to_shots`` on the unclipped range.
        An elevated shot (``Shots.theta``) needs the option (a ValueError
        otherwise) and an elevation in [0, ``MAX_ACTION_ELEVATION``]."""
        n = len(idx)
        if not isinstance(shots, Shots):
            raise TypeError(f"shots must be a Shots, got {type(shots).__name__}")
        theta = np.broadcast_to(np.asarray(shots.theta, dtype=np.float64), (n,))
        check_elevation(theta, self.effects)
        if (theta > MAX_ACTION_ELEVATION * (1 + 1e-12)).any():
            r = int(np.argmax(theta > MAX_ACTION_ELEVATION * (1 + 1e-12)))
            raise ValueError(f"the cue's elevation must lie in [0, {MAX_ACTION_ELEVATION:.6g}] rad (the action's "
                             f"{np.degrees(MAX_ACTION_ELEVATION):g} degrees), got {theta[r]} at shot {r}")
        ctx = self.shot_context()
        out = shot_actions(shots, ctx.aim_origin[idx], self.cfg.min_draw, self.params, self.cfg.speed_scale == "log")
        if self.cfg.aim == "impact":  # a0 is the impact parameter (envs/impact.py)
            phi, rel = np.broadcast_to(np.asarray(shots.phi, dtype=np.float64), (n,)), np.empty(n)
            impact_actions(np.ascontiguousarray(phi), ctx.aim_origin[idx], ctx.target[idx],
                           self.state.pos[idx], self.params.R, rel)
            out[:, 0] = rel
        if self.airborne:
            out = np.concatenate([out, (2.0 * theta / MAX_ACTION_ELEVATION - 1.0)[:, None]], axis=1)
        return np.clip(out, -1.0, 1.0)

    # --- bots ----------------------------------------------------------------
    def view(self, idx=None) -> TaskView:
        """The read-only ``TaskView`` of tables ``idx`` (default: all) that a bot acts on."""
        idx = self._every_table() if idx is None else np.asarray(idx, dtype=np.int64)
        s = self.state
        return TaskView.build(task=self.cfg.task, rows=idx.copy(), pos=s.pos[idx], pocket=s.pocket[idx],
                              target=self.legal_target()[idx], shots=self.shots[idx], table=self.table,
                              params=self.params, effects=self.effects, models=self.models, noise=self.cfg.noise,
                              min_draw=self.cfg.min_draw, rules=self.task, solver=self.cfg.solver, dt=self.cfg.dt,
                              _observe=lambda: self.observe()[idx])

    def actions_of(self, plan, idx=None) -> np.ndarray:
        """The actions [n, action_dim] (float32, clipped) that play a bot's ``ShotPlan``
        on tables ``idx`` (the env's inverse mapping of its shots); a bot's
        own actions [n, action_dim] are returned as they are."""
        if isinstance(plan, np.ndarray):
            return plan
        idx = self._every_table() if idx is None else idx
        return np.clip(np.asarray(self.shots_to_actions(plan.shots, idx), dtype=np.float32), -1.0, 1.0)

    def _every_table(self) -> np.ndarray:
        return np.arange(self.n_envs)

    def apply_noise(self, shots: Shots, idx, scale: np.ndarray | None = None) -> Shots:
        """Shot noise for tables ``idx``, drawn from their streams (4 normals
        each); ``scale`` [n] multiplies each table's standard deviations."""
        nz = self.cfg.noise
        if not nz.enabled:
            return shots
        z = self.streams.normal(idx, 4)
        if scale is not None:
            z *= np.asarray(scale, dtype=np.float64)[:, None]
        return perturb(shots, z, nz, self.params)

    # --- simulation -------------------------------------------------------
    def simulate(self, state: BallState):
        """Simulate struck tables to rest with this env's table, physics, solver, effects and models.
        ``state``: a struck state the caller has just made; the kernel works in its arrays."""
        c = self.cfg
        k = self.task.contacts  # the cue ball's contacts in order, where the task reads them (0: none)
        return simulate(state, self.table, self.params, solver=c.solver, dt=c.dt,
                        record=self.record, effects=self.effects, models=self.models,
                        options=SimOptions(validate=False, contacts=k, inplace=True))  # states are ours, checked

    @staticmethod
    def at_rest(s: BallState) -> BallState:
        return BallState(s.pos.copy(), np.zeros_like(s.vel), np.zeros_like(s.omega), s.pocket.copy())

    def _all(self, idx: np.ndarray) -> bool:
        """Whether ``idx`` lists every table in order (then slices replace fancy indexing)."""
        return len(idx) == self.n_envs and bool((idx == self._every).all())

    def _set(self, idx, s: BallState) -> None:
        sel = Ellipsis if self._all(idx) else idx
        for f in ("pos", "vel", "omega", "pocket"):
            getattr(self.state, f)[sel] = getattr(s, f)
        self._context = None

    def set_state(self, state, idx) -> None:
        if not isinstance(state, BallState):
            state = BallState.from_positions(state)
        if state.n_envs != len(idx) or state.n_balls != self.n_balls:
            raise ValueError(f"state must hold {len(idx)} table(s) of {self.n_balls} balls, "
                             f"got {state.n_envs} x {state.n_balls}")
        if np.any(state.pocket[:, 0] >= 0):
            raise ValueError("the cue ball must be on the table")
        if self.state is None:
            raise RuntimeError("call reset() before set_state()")
        from ..physics.validation import check_finite, check_placement
        check_finite(state)
        check_placement(state, self.table, self.params, self.effects.pockets)
        self._set(idx, self.at_rest(state))
        self.shots[idx] = 0
        self._forget_last_shot(idx)

    def _forget_last_shot(self, idx) -> None:
        if self.record:  # otherwise never set: nothing to clear
            for k in idx:
                self.last_start[k] = None
                self.last_events[k] = None

    # --- reset ------------------------------------------------------------
    def reset_tables(self, idx) -> None:
        """New episodes on tables ``idx``, drawn from their streams by the task."""
        idx = np.asarray(idx, dtype=np.int64)
        B = self.n_balls
        states = self.task.reset(self, idx)
        if self.state is None:
            E = self.n_envs
            self.state = BallState(np.zeros((E, B, 2)), np.zeros((E, B, 2)), np.zeros((E, B, 3)),
                                   np.full((E, B), -1, dtype=np.int64))
        self._set(idx, states)
        self.shots[idx] = 0
        self._forget_last_shot(idx)

    def place(self, idx, max_tries: int = 10_000) -> np.ndarray:
        """Uniform random non-overlapping positions [n, B, 2] for tables
        ``idx``, at least ``margin`` clear of each other and of the cushions,
        outside every pocket's capture circle. Each table rejection-samples
        its balls one after another from its own stream (numba kernel), so
        the result does not depend on which other tables are placed in the
        same call."""
        R, m, B, t = self.params.R, self.cfg.margin, self.n_balls, self.table
        out = np.empty((len(idx), B, 2))
        ok = place_balls(self.streams, idx, B, (R + m, R + m, t.width - R - m, t.length - R - m), self.pockets,
                         2 * R + m, max_tries, out)
        if not ok.all():
            raise ValueError(f"could not place {B} balls without overlap on {t.name}")
        return out

    # --- one shot ---------------------------------------------------------
    def step(self, actions: np.ndarray, idx) -> dict:
        """Shoot tables ``idx`` with validated actions [n, 4]; update their
        state; return the outcome as arrays over ``idx``."""
        idx = np.asarray(idx, dtype=np.int64)
        c, p = self.cfg, self.params
        sel = Ellipsis if self._all(idx) else idx
        clipped = (np.abs(actions) > 1.0).any(axis=1)
        start = self.state.copy() if sel is Ellipsis else self.state.take(idx)
        if (start.pocket[:, 0] >= 0).any():
            raise RuntimeError("the cue ball is pocketed: the episode has ended, call reset()")
        ctx = self.shot_context()
        tgt, phi0 = ctx.target[sel], ctx.potential[sel]
        shots = self.actions_to_shots(actions, sel)
        theta = shots.elevated  # None: the level cue's arithmetic (the noise leaves the elevation as it is)
        shots = self.apply_noise(shots, idx)
        struck = airborne_state(start.copy(), self.effects)
        apply_strike(struck, *shots, p.R, theta)  # actions were checked at the env's boundary
        res = self.simulate(struck)
        rest = res.state  # simulate's own arrays: no copy needed
        end = BallState(rest.pos, np.zeros_like(rest.vel), np.zeros_like(rest.omega), rest.pocket)

        shot = ShotOutcome.of(start.pocket, end.pocket, first_contact=res.first_contact, target=tgt,
                              contacts=res.contacts, n_contacts=res.n_contacts)
        more = {"off_table": shot.off_table} if self.airborne else {}  # the option's own entry
        judged = self.task.judge(shot)
        self.shots[sel] += 1
        n_shots = self.shots[sel].copy()
        truncated = ~judged.terminated & ((n_shots >= c.max_shots) | res.truncated)

        self._set(idx, end)
        phi1 = self.shot_context().potential[sel]
        terms = self.task.reward_terms(c.reward, shot, judged, phi0, phi1)
        reward = sum(terms.values())

        if res.events is not None:  # kept for rendering the last shot's paths
            for j, k in enumerate(idx):
                self.last_start[k] = start.take([j])
                self.last_events[k] = res.events[j]
        return dict(reward=reward, terminated=judged.terminated, truncated=truncated, terms=terms,
                    info=dict(pocketed=shot.pocketed, n_pocketed=shot.n_pocketed, first_contact=shot.first_contact,
                              legal_target=tgt, foul=judged.foul, scratch=shot.scratch, success=judged.success,
                              n_events=res.n_events, sim_time=res.time, sim_truncated=res.truncated,
                              action_clipped=clipped, shot=n_shots, **more))
