"""Batched task logic shared by the single-table and vector environments.

``BilliardsCore`` holds ``n_envs`` tables and steps any subset of them with
one batched ``strike_velocity`` + ``simulate`` call. Randomness (placement,
break shot, shot noise) is drawn from per-table counter-based streams
(``streams.TableStreams``, one stream per table, drawn for many tables in
one numba call): a table's draws depend only on its own stream, so table k
of a vector env seeded with ``seed`` behaves exactly like a single env
seeded with ``seed + k``.
"""
from __future__ import annotations

import math

import numba
import numpy as np

from ..physics import BallState, simulate, strike_velocity
from ..physics.state import diamond_slots
from .config import TaskConfig
from .streams import TableStreams, free_spot, place_balls

OFFSET_SAFETY = 1.0 - 1e-9  # radial clip just inside the miscue limit (strict check in strike)


# Per-step bookkeeping over all tables, fused into single passes (numpy would
# take one pass, and a temporary, per operation).
_jit = numba.njit(cache=True, nogil=True)


@_jit
def _targets(pos, pocket, pockets, diag, tgt, phi, aim, ang):
    """Per table: the legal target (lowest-numbered object ball on the table,
    -1 if none) into ``tgt``, Phi = -(its distance to the nearest pocket
    centre) / diag (0 without target or pockets) into ``phi`` and, if
    ``aim``, the direction cue ball -> target (rad, 0 without target) into
    ``ang``."""
    for e in range(pos.shape[0]):
        t = -1
        for b in range(1, pos.shape[1]):
            if pocket[e, b] < 0:
                t = b
                break
        tgt[e] = t
        phi[e] = 0.0
        ang[e] = 0.0
        if t < 0:
            continue
        if aim:
            ang[e] = math.atan2(pos[e, t, 1] - pos[e, 0, 1], pos[e, t, 0] - pos[e, 0, 0])
        if pockets.shape[0] == 0:
            continue
        d2 = math.inf
        for p in range(pockets.shape[0]):
            dx, dy = pos[e, t, 0] - pockets[p, 0], pos[e, t, 1] - pockets[p, 1]
            d2 = min(d2, dx * dx + dy * dy)
        phi[e] = -math.sqrt(d2) / diag


@_jit
def _clip_offset(a, b, limit):
    """(a, b) scaled radially just inside the disc of radius ``limit``."""
    lim = limit * OFFSET_SAFETY
    r = math.hypot(a, b)
    f = lim / max(r, 1e-300) if r > lim else 1.0
    return a * f, b * f


@_jit
def _clip_offsets(a, b, limit):
    for e in range(a.shape[0]):
        a[e], b[e] = _clip_offset(a[e], b[e], limit)


@_jit
def _action_to_shot(actions, base, lo, hi, limit, out):
    """Actions [n, 4] -> rows (phi, draw, a, b) of ``out`` [4, n]: clipped to
    [-1, 1]; phi = base + pi * a0 wrapped to [-pi, pi); (a, b) scaled
    radially just inside the miscue limit (``_clip_offset``)."""
    for e in range(actions.shape[0]):
        a0 = min(max(actions[e, 0], -1.0), 1.0)
        a1 = min(max(actions[e, 1], -1.0), 1.0)
        a2 = min(max(actions[e, 2], -1.0), 1.0)
        a3 = min(max(actions[e, 3], -1.0), 1.0)
        out[0, e] = (base[e] + math.pi * a0 + math.pi) % (2 * math.pi) - math.pi
        out[1, e] = lo + (a1 + 1.0) * 0.5 * (hi - lo)
        out[2, e], out[3, e] = _clip_offset(a2 * limit, a3 * limit, limit)


@_jit
def _observe(pos, pocket, shots, max_shots, width, length, obs):
    """Fill the zeroed observations ``obs`` [N, 4B + 1] (layout: see billiards._COMMON_DOC)."""
    B = pos.shape[1]
    for e in range(pos.shape[0]):
        t = -1
        for b in range(B):
            if pocket[e, b] < 0:
                obs[e, 3 * b] = min(max(pos[e, b, 0] / width, 0.0), 1.0)
                obs[e, 3 * b + 1] = min(max(pos[e, b, 1] / length, 0.0), 1.0)
                obs[e, 3 * b + 2] = 1.0
                if t < 0 and b > 0:
                    t = b
        if t >= 0:
            obs[e, 3 * B + t] = 1.0
        obs[e, 4 * B] = min(shots[e] / max_shots, 1.0)


class BilliardsCore:
    def __init__(self, cfg: TaskConfig, n_envs: int, record: bool = False):
        if not isinstance(n_envs, (int, np.integer)) or n_envs < 1:
            raise ValueError(f"num_envs must be a positive integer, got {n_envs!r}")
        self.cfg = cfg
        self.n_envs = int(n_envs)
        self.table = cfg.make_table()
        self.params = cfg.params()
        self.effects = cfg.effects
        self.record = record
        self.n_balls = cfg.n_balls + 1  # cue ball + object balls
        self.obs_dim = 4 * self.n_balls + 1
        self.diag = math.hypot(self.table.width, self.table.length)
        self.state: BallState | None = None
        self.shots = np.zeros(self.n_envs, dtype=np.int64)
        self.last_start: list = [None] * self.n_envs   # BallState of one table before its last shot
        self.last_events: list = [None] * self.n_envs  # EventLog of its last shot (record=True)
        self.speed_per_draw = self.params.k * self.params.contact_time / self.params.m
        self.streams = TableStreams(self.n_envs)  # seeded by the env's reset
        self._every = np.arange(self.n_envs)
        self._pockets = np.ascontiguousarray(self.table.geometry(self.effects.pockets)[3], dtype=np.float64)
        if cfg.task == "nine_ball":
            self._diamond = diamond_slots(self.table, self.params.R)  # slot 0 apex, 4 centre

    # --- geometry helpers -------------------------------------------------
    def legal_target(self) -> np.ndarray:
        """Legal target ball of every table (-1 if none)."""
        return self.targets(self.state.pos, self.state.pocket, aim=False)[0]

    def targets(self, pos: np.ndarray, pocket: np.ndarray, aim: bool = True):
        """Of tables at ``pos`` [n, B, 2], ``pocket`` [n, B]: (legal target [n]
        (-1 if none), potential Phi [n], aim origin [n] (rad, see
        ``base_angle``; all 0 unless ``aim``))."""
        n = len(pos)
        tgt, phi, ang = np.empty(n, dtype=np.int64), np.empty(n), np.empty(n)
        _targets(pos, pocket, self._pockets, self.diag, tgt, phi, aim and self.cfg.aim != "absolute", ang)
        return tgt, phi, ang

    def potential(self, pos: np.ndarray, pocket: np.ndarray) -> np.ndarray:
        """Phi = -(distance of the legal target to its nearest pocket) / diagonal; 0 without target."""
        return self.targets(pos, pocket, aim=False)[1]

    def observe(self) -> np.ndarray:
        s = self.state
        obs = np.zeros((self.n_envs, self.obs_dim), dtype=np.float32)
        _observe(s.pos, s.pocket, self.shots, float(self.cfg.max_shots), self.table.width, self.table.length, obs)
        return obs

    # --- actions ----------------------------------------------------------
    @staticmethod
    def validate_actions(actions, n: int) -> np.ndarray:
        a = np.asarray(actions, dtype=np.float64)
        if a.shape != (n, 4):
            raise ValueError(f"actions must have shape ({n}, 4), got {a.shape}")
        if not np.all(np.isfinite(a)):
            bad = np.argwhere(~np.isfinite(a))[0]
            raise ValueError(f"action contains NaN or infinite values (first at index {tuple(bad)}): {a[bad[0]]}")
        return a

    def base_angle(self, idx) -> np.ndarray:
        """Aim origin (rad): 0 for absolute aim, else the direction cue -> legal target."""
        return self.targets(self.state.pos[idx], self.state.pocket[idx])[2]

    def action_to_shot(self, actions: np.ndarray, idx, base: np.ndarray | None = None):
        """Clipped actions [n, 4] of tables ``idx`` -> (phi, draw, a, b);
        ``base``: their aim origins (``base_angle``), if already known."""
        actions = np.ascontiguousarray(actions, dtype=np.float64)
        out = np.empty((4, len(actions)))
        _action_to_shot(actions, self.base_angle(idx) if base is None else base,
                        self.cfg.min_draw, self.params.max_draw, self.params.miscue_limit, out)
        return out[0], out[1], out[2], out[3]

    def shot_to_action(self, phi, draw, a, b, idx) -> np.ndarray:
        n = len(idx)
        phi, draw, a, b = (np.broadcast_to(np.asarray(v, dtype=np.float64), (n,)) for v in (phi, draw, a, b))
        rel = (phi - self.base_angle(idx)) / math.pi
        rel = (rel + 1.0) % 2.0 - 1.0
        lo, hi = self.cfg.min_draw, self.params.max_draw
        out = np.stack([rel, 2.0 * (draw - lo) / (hi - lo) - 1.0,
                        a / self.params.miscue_limit, b / self.params.miscue_limit], axis=1)
        return np.clip(out, -1.0, 1.0).astype(np.float32)

    def apply_noise(self, phi, speed, a, b, idx):
        """Shot noise for tables ``idx``, drawn from their streams (4 normals each)."""
        nz = self.cfg.noise
        if not nz.enabled:
            return phi, speed, a, b
        z = self.streams.normal(idx, 4)
        R = self.params.R
        phi = phi + z[:, 0] * math.radians(nz.aim_deg)
        speed = np.clip(speed + z[:, 1] * nz.speed, 0.0, self.params.max_speed)
        a = a + z[:, 2] * nz.side_mm * 1e-3 / R
        b = b + z[:, 3] * nz.height_mm * 1e-3 / R
        _clip_offsets(a, b, self.params.miscue_limit)  # a, b are new arrays here
        return phi, speed, a, b

    # --- simulation -------------------------------------------------------
    def _simulate(self, state: BallState):
        c = self.cfg
        return simulate(state, self.table, self.params, solver=c.solver, dt=c.dt,
                        record=self.record, effects=self.effects, validate=False)  # states are ours, already checked

    @staticmethod
    def _at_rest(s: BallState) -> BallState:
        return BallState(s.pos.copy(), np.zeros_like(s.vel), np.zeros_like(s.omega), s.pocket.copy())

    def _all(self, idx: np.ndarray) -> bool:
        """Whether ``idx`` lists every table in order (then slices replace fancy indexing)."""
        return len(idx) == self.n_envs and bool((idx == self._every).all())

    def _set(self, idx, s: BallState) -> None:
        sel = Ellipsis if self._all(idx) else idx
        for f in ("pos", "vel", "omega", "pocket"):
            getattr(self.state, f)[sel] = getattr(s, f)

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
        self._set(idx, self._at_rest(state))
        self.shots[idx] = 0
        self._forget_last_shot(idx)

    def _forget_last_shot(self, idx) -> None:
        if self.record:  # otherwise never set: nothing to clear
            for k in idx:
                self.last_start[k] = None
                self.last_events[k] = None

    # --- reset ------------------------------------------------------------
    def reset_tables(self, idx) -> None:
        """New episodes on tables ``idx``, drawn from their streams."""
        idx = np.asarray(idx, dtype=np.int64)
        B = self.n_balls
        if self.cfg.task == "nine_ball":
            states = self._break(idx)
        else:
            states = BallState.from_positions(self._place(idx))
        if self.state is None:
            E = self.n_envs
            self.state = BallState(np.zeros((E, B, 2)), np.zeros((E, B, 2)), np.zeros((E, B, 3)),
                                   np.full((E, B), -1, dtype=np.int64))
        self._set(idx, states)
        self.shots[idx] = 0
        self._forget_last_shot(idx)

    def _place(self, idx, max_tries: int = 10_000) -> np.ndarray:
        """Uniform random non-overlapping positions [n, B, 2] for tables
        ``idx``, at least ``margin`` clear of each other and of the cushions,
        outside every pocket's capture circle. Each table rejection-samples
        its balls one after another from its own stream (numba kernel), so
        the result does not depend on which other tables are placed in the
        same call."""
        R, m, B, t = self.params.R, self.cfg.margin, self.n_balls, self.table
        out = np.empty((len(idx), B, 2))
        ok = place_balls(self.streams.keys, self.streams.counters, np.ascontiguousarray(idx, dtype=np.int64),
                         B, R + m, R + m, t.width - R - m, t.length - R - m, self._pockets,
                         2 * R + m, max_tries, out)
        if not ok.all():
            raise ValueError(f"could not place {B} balls without overlap on {t.name}")
        return out

    def _break(self, idx) -> BallState:
        """Seeded 9-ball rack and break: cue ball near the head spot, struck at
        ~break_speed towards the 1-ball with small random variation; a 9 or
        cue ball pocketed on the break is respotted (foot / head spot)."""
        t, p, c = self.table, self.params, self.cfg
        n = len(idx)
        u = self.streams.uniform(idx, 12)  # 7 rack shuffle, 2 cue position, speed, 2 offsets
        z = self.streams.normal(idx, 1)[:, 0]  # aim
        pos = np.empty((n, 10, 2))
        pos[:, 1] = self._diamond[0]  # apex: the 1-ball on the foot spot
        pos[:, 9] = self._diamond[4]  # centre: the 9-ball
        others = self._diamond[[1, 2, 3, 5, 6, 7, 8]]
        pos[np.arange(n)[:, None], 2 + np.argsort(u[:, :7], axis=1)] = others  # balls 2..8 shuffled
        pos[:, 0, 0] = t.width / 2 + (-0.15 + 0.3 * u[:, 7])
        pos[:, 0, 1] = 0.25 * t.length + (-0.03 + 0.06 * u[:, 8])
        d = pos[:, 1] - pos[:, 0]
        phi = np.arctan2(d[:, 1], d[:, 0]) + np.radians(0.3 * z)
        speed = c.break_speed * (1.0 + (-0.05 + 0.1 * u[:, 9]))
        a = -0.05 + 0.1 * u[:, 10]
        b = -0.1 + 0.15 * u[:, 11]
        start = BallState.from_positions(pos)
        res = self._simulate(strike_velocity(start, phi, speed, a, b, p))
        out = self._at_rest(res.state)
        foot, head = (t.width / 2, 0.75 * t.length), (t.width / 2, 0.25 * t.length)
        for e in np.nonzero((out.pocket[:, 9] >= 0) | (out.pocket[:, 0] >= 0))[0]:
            for ball, spot, dy in ((9, foot, 1.0), (0, head, -1.0)):
                if out.pocket[e, ball] >= 0:  # respot the 9 (foot spot) or the cue ball (head spot)
                    x, y, found = free_spot(out.pos[e], out.pocket[e] < 0, spot[0], spot[1], 0.0, dy,
                                            t.width, t.length, p.R, self._pockets)
                    if not found:
                        raise RuntimeError("no free spot on the table to respot a ball")
                    out.pos[e, ball] = (x, y)
                    out.pocket[e, ball] = -1
        return out

    # --- one shot ---------------------------------------------------------
    def step(self, actions: np.ndarray, idx) -> dict:
        """Shoot tables ``idx`` with validated actions [n, 4]; update their
        state; return the outcome as arrays over ``idx``."""
        idx = np.asarray(idx, dtype=np.int64)
        c, w, p = self.cfg, self.cfg.reward, self.params
        sel = Ellipsis if self._all(idx) else idx
        clipped = (np.abs(actions) > 1.0).any(axis=1)
        start = self.state.copy() if sel is Ellipsis else self.state.take(idx)
        if (start.pocket[:, 0] >= 0).any():
            raise RuntimeError("the cue ball is pocketed: the episode has ended, call reset()")
        tgt, phi0, base = self.targets(start.pos, start.pocket)
        phi, draw, sa, sb = self.action_to_shot(actions, idx, base)
        speed = p.k * p.contact_time * draw / p.m  # exactly as physics.strike computes it
        phi, speed, sa, sb = self.apply_noise(phi, speed, sa, sb, idx)
        res = self._simulate(strike_velocity(start, phi, speed, sa, sb, p))
        end = self._at_rest(res.state)

        new = (end.pocket >= 0) & (start.pocket < 0)
        scratch = new[:, 0]
        fc = res.first_contact
        contact = (fc == tgt) & (tgt > 0)
        foul = ~contact if c.task == "nine_ball" else (fc < 1)
        n_obj = new[:, 1:].sum(axis=1)
        legal = ~foul & ~scratch
        cleared = np.all(end.pocket[:, 1:] >= 0, axis=1)
        if c.task == "pot_one":
            success = new[:, 1] & ~scratch
            terminated = np.ones(len(idx), dtype=bool)
        elif c.task == "run_out":
            success = legal & cleared
            terminated = scratch | foul | (n_obj == 0) | cleared
        else:  # nine_ball
            nine = new[:, 9]
            success = legal & nine
            terminated = scratch | foul | nine
        self.shots[sel] += 1
        shots = self.shots[sel].copy()
        truncated = ~terminated & ((shots >= c.max_shots) | res.truncated)

        phi1 = np.where(terminated, 0.0, self.potential(end.pos, end.pocket))
        terms = {
            "pocket": w.pocket * n_obj * legal,
            "scratch": w.scratch * scratch,
            "foul": w.foul * foul,
            "contact": w.contact * contact,
            "success": w.success * success,
            "shaping": w.shaping * (w.gamma * phi1 - phi0),
        }
        terms = {k: v + 0.0 for k, v in terms.items()}  # float64 (weights are floats); + 0.0: no negative zeros
        reward = sum(terms.values())

        self._set(idx, end)
        if res.events is not None:  # kept for rendering the last shot's paths
            for j, k in enumerate(idx):
                self.last_start[k] = start.take([j])
                self.last_events[k] = res.events[j]
        return dict(reward=reward, terminated=terminated, truncated=truncated, terms=terms,
                    info=dict(pocketed=new, n_pocketed=n_obj, first_contact=fc, legal_target=tgt,
                              foul=foul, scratch=scratch, success=success, n_events=res.n_events,
                              sim_time=res.time, sim_truncated=res.truncated, action_clipped=clipped,
                              shot=shots))
