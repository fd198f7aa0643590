"""Batched task logic shared by the single-table and vector environments.

``BilliardsCore`` holds ``n_envs`` tables and steps any subset of them with
one batched ``strike_velocity`` + ``simulate`` call. Randomness (placement,
break shot, shot noise) is drawn per table from a ``numpy.random.Generator``
passed in by the caller, so table k of a vector env seeded with ``seed``
behaves exactly like a single env seeded with ``seed + k``.
"""
from __future__ import annotations

import math

import numpy as np

from ..physics import BallState, rack, simulate, strike_velocity
from .config import TaskConfig

OFFSET_SAFETY = 1.0 - 1e-9  # radial clip just inside the miscue limit (strict check in strike)


def legal_target(pocket: np.ndarray) -> np.ndarray:
    """Lowest-numbered object ball still on the table, per table; -1 if none."""
    on = pocket[:, 1:] < 0
    tgt = np.argmax(on, axis=1) + 1
    return np.where(on.any(axis=1), tgt, -1).astype(np.int64)


def clip_offsets(a: np.ndarray, b: np.ndarray, limit: float):
    """Scale (a, b) radially into the disc of radius ``limit`` (just inside it)."""
    r = np.hypot(a, b)
    lim = limit * OFFSET_SAFETY
    f = np.where(r > lim, lim / np.maximum(r, 1e-300), 1.0)
    return a * f, b * f


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

    # --- geometry helpers -------------------------------------------------
    def legal_target(self) -> np.ndarray:
        return legal_target(self.state.pocket)

    def potential(self, pos: np.ndarray, pocket: np.ndarray) -> np.ndarray:
        """Phi = -(distance of the legal target to its nearest pocket) / diagonal; 0 without target."""
        tgt = legal_target(pocket)
        pk = self.table.geometry(self.effects.pockets)[3]
        if len(pk) == 0:
            return np.zeros(len(pos))
        p = pos[np.arange(len(pos)), np.maximum(tgt, 0)]
        d = np.hypot(p[:, None, 0] - pk[None, :, 0], p[:, None, 1] - pk[None, :, 1]).min(axis=1)
        return np.where(tgt >= 0, -d / self.diag, 0.0)

    def observe(self) -> np.ndarray:
        s = self.state
        N, B = self.n_envs, self.n_balls
        on = s.pocket < 0
        obs = np.zeros((N, self.obs_dim), dtype=np.float32)
        xy = np.clip(s.pos / np.array([self.table.width, self.table.length]), 0.0, 1.0)
        xy[~on] = 0.0
        per = obs[:, :3 * B].reshape(N, B, 3)
        per[:, :, :2] = xy
        per[:, :, 2] = on
        tgt = legal_target(s.pocket)
        rows = np.nonzero(tgt >= 0)[0]
        obs[rows, 3 * B + tgt[rows]] = 1.0
        obs[:, 4 * B] = np.minimum(self.shots / self.cfg.max_shots, 1.0)
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
        if self.cfg.aim == "absolute":
            return np.zeros(len(idx))
        pos = self.state.pos[idx]
        tgt = legal_target(self.state.pocket[idx])
        d = pos[np.arange(len(idx)), np.maximum(tgt, 0)] - pos[:, 0]
        return np.where(tgt > 0, np.arctan2(d[:, 1], d[:, 0]), 0.0)

    def action_to_shot(self, actions: np.ndarray, idx):
        """Clipped actions [n, 4] of tables ``idx`` -> (phi, draw, a, b)."""
        a = np.clip(actions, -1.0, 1.0)
        phi = self.base_angle(idx) + math.pi * a[:, 0]
        phi = (phi + math.pi) % (2 * math.pi) - math.pi
        lo, hi = self.cfg.min_draw, self.params.max_draw
        draw = lo + (a[:, 1] + 1.0) * 0.5 * (hi - lo)
        side, height = clip_offsets(a[:, 2] * self.params.miscue_limit, a[:, 3] * self.params.miscue_limit,
                                    self.params.miscue_limit)
        return phi, draw, side, height

    def shot_to_action(self, phi, draw, a, b, idx) -> np.ndarray:
        n = len(idx)
        phi, draw, a, b = (np.broadcast_to(np.asarray(v, dtype=np.float64), (n,)) for v in (phi, draw, a, b))
        rel = (phi - self.base_angle(idx)) / math.pi
        rel = (rel + 1.0) % 2.0 - 1.0
        lo, hi = self.cfg.min_draw, self.params.max_draw
        out = np.stack([rel, 2.0 * (draw - lo) / (hi - lo) - 1.0,
                        a / self.params.miscue_limit, b / self.params.miscue_limit], axis=1)
        return np.clip(out, -1.0, 1.0).astype(np.float32)

    def apply_noise(self, phi, speed, a, b, rngs):
        nz = self.cfg.noise
        if not nz.enabled:
            return phi, speed, a, b
        z = np.stack([rng.standard_normal(4) for rng in rngs])
        R = self.params.R
        phi = phi + z[:, 0] * math.radians(nz.aim_deg)
        speed = np.clip(speed + z[:, 1] * nz.speed, 0.0, self.params.max_speed)
        a = a + z[:, 2] * nz.side_mm * 1e-3 / R
        b = b + z[:, 3] * nz.height_mm * 1e-3 / R
        a, b = clip_offsets(a, b, self.params.miscue_limit)
        return phi, speed, a, b

    # --- simulation -------------------------------------------------------
    def _simulate(self, state: BallState):
        c = self.cfg
        return simulate(state, self.table, self.params, solver=c.solver, dt=c.dt,
                        record=self.record, effects=self.effects, validate=False)  # states are ours, already checked

    @staticmethod
    def _at_rest(s: BallState) -> BallState:
        return BallState(s.pos.copy(), np.zeros_like(s.vel), np.zeros_like(s.omega), s.pocket.copy())

    def _set(self, idx, s: BallState) -> None:
        for f in ("pos", "vel", "omega", "pocket"):
            getattr(self.state, f)[idx] = getattr(s, f)

    def _free_spot(self, pos, on, preferred, step_dir) -> np.ndarray:
        """``preferred`` if free, else the nearest free point along ``step_dir`` (both ways), then sideways."""
        R = self.params.R
        step = 2 * R + 1e-3
        d = np.asarray(step_dir, float)
        cand = [np.asarray(preferred, float)]
        for k in range(1, 60):
            cand += [preferred + k * step * d, preferred - k * step * d]
        perp = np.array([-d[1], d[0]])
        for j in range(1, 20):
            for k in range(0, 30):
                for s1 in (1, -1):
                    cand.append(preferred + s1 * j * step * perp + k * step * d)
        others = pos[on]
        for p in cand:
            if not self.table.contains(p[None], R + 1e-4, 0.0, self.effects.pockets)[0]:
                continue
            if len(others) and np.min(np.hypot(*(others - p).T)) < 2 * R + 1e-6:
                continue
            return p
        raise RuntimeError("no free spot on the table to respot a ball")

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
        for k in idx:
            self.last_start[k] = None
            self.last_events[k] = None

    # --- reset ------------------------------------------------------------
    def reset_tables(self, idx, rngs) -> None:
        idx = np.asarray(idx, dtype=np.int64)
        c, B = self.cfg, self.n_balls
        if c.task == "nine_ball":
            states = self._break(rngs)
        else:
            states = BallState.from_positions(self._place(rngs))
        if self.state is None:
            E = self.n_envs
            self.state = BallState(np.zeros((E, B, 2)), np.zeros((E, B, 2)), np.zeros((E, B, 3)),
                                   np.full((E, B), -1, dtype=np.int64))
        self._set(idx, states)
        self.shots[idx] = 0
        for k in idx:
            self.last_start[k] = None
            self.last_events[k] = None

    def _place(self, rngs, chunk: int = 64) -> np.ndarray:
        """Uniform random non-overlapping positions [n, B, 2], at least ``margin``
        clear of each other and of the cushions. Each table draws candidates
        in chunks from its own RNG and accepts them greedily in order (a
        candidate is taken if it is legal and clear of the balls already
        taken), so the result does not depend on which other tables are
        placed in the same call. The greedy pass is vectorised over tables,
        one ball slot at a time."""
        R, m, B, t = self.params.R, self.cfg.margin, self.n_balls, self.table
        lo = np.array([R + m, R + m])
        hi = np.array([t.width - R - m, t.length - R - m])
        n = len(rngs)
        out = np.zeros((n, B, 2))
        count = np.zeros(n, dtype=np.int64)
        for _ in range(200):
            todo = np.nonzero(count < B)[0]
            if len(todo) == 0:
                return out
            cand = lo + (hi - lo) * np.stack([rngs[e].random((chunk, 2)) for e in todo])
            ok = t.contains(cand.reshape(-1, 2), R + m, 0.0, self.effects.pockets).reshape(len(todo), chunk)
            nxt = np.zeros(len(todo), dtype=np.int64)  # first candidate not yet considered
            for _slot in range(B):
                live = np.nonzero(count[todo] < B)[0]
                if len(live) == 0:
                    break
                placed = out[todo[live]]  # [k, B, 2]; slots >= count are ignored below
                d = np.linalg.norm(cand[live][:, :, None, :] - placed[:, None, :, :], axis=-1)
                taken = np.arange(B)[None, None, :] < count[todo[live]][:, None, None]
                clear = ~np.any(taken & (d < 2 * R + m), axis=2)
                valid = ok[live] & clear & (np.arange(chunk)[None, :] >= nxt[live][:, None])
                has = valid.any(axis=1)
                first = np.argmax(valid, axis=1)
                sel = live[has]
                out[todo[sel], count[todo[sel]]] = cand[sel, first[has]]
                count[todo[sel]] += 1
                nxt[sel] = first[has] + 1
                nxt[live[~has]] = chunk
        raise ValueError(f"could not place {B} balls without overlap on {t.name}")

    def _break(self, rngs) -> BallState:
        """Seeded 9-ball rack and break: cue ball near the head spot, struck at
        ~break_speed towards the 1-ball with small random variation."""
        t, p, c = self.table, self.params, self.cfg
        racks, phi, speed, a, b = [], [], [], [], []
        for rng in rngs:
            s = rack(t, p, "nine", 1, seed=rng)
            cue = np.array([t.width / 2 + rng.uniform(-0.15, 0.15), 0.25 * t.length + rng.uniform(-0.03, 0.03)])
            s.pos[0, 0] = cue
            d = s.pos[0, 1] - cue
            phi.append(math.atan2(d[1], d[0]) + math.radians(rng.normal(0.0, 0.3)))
            speed.append(c.break_speed * (1.0 + rng.uniform(-0.05, 0.05)))
            a.append(rng.uniform(-0.05, 0.05)); b.append(rng.uniform(-0.1, 0.05))
            racks.append(s)
        start = BallState.stack(racks)
        res = self._simulate(strike_velocity(start, np.array(phi), np.array(speed), np.array(a), np.array(b), p))
        out = self._at_rest(res.state)
        foot, head = np.array([t.width / 2, 0.75 * t.length]), np.array([t.width / 2, 0.25 * t.length])
        for e in range(out.n_envs):
            for ball, spot, d in ((9, foot, (0.0, 1.0)), (0, head, (0.0, -1.0))):
                if out.pocket[e, ball] >= 0:  # respot the 9 (foot spot) or the cue ball (head spot)
                    on = out.pocket[e] < 0
                    out.pos[e, ball] = self._free_spot(out.pos[e], on, spot, d)
                    out.pocket[e, ball] = -1
        return out

    # --- one shot ---------------------------------------------------------
    def step(self, actions: np.ndarray, idx, rngs) -> dict:
        """Shoot tables ``idx`` with validated actions [n, 4]; update their
        state; return the outcome as arrays over ``idx``."""
        idx = np.asarray(idx, dtype=np.int64)
        c, w, p = self.cfg, self.cfg.reward, self.params
        clipped = np.any(np.abs(actions) > 1.0, axis=1)
        phi, draw, sa, sb = self.action_to_shot(actions, idx)
        speed = p.k * p.contact_time * draw / p.m  # exactly as physics.strike computes it
        phi, speed, sa, sb = self.apply_noise(phi, speed, sa, sb, rngs)
        start = self.state.take(idx)
        if np.any(start.pocket[:, 0] >= 0):
            raise RuntimeError("the cue ball is pocketed: the episode has ended, call reset()")
        res = self._simulate(strike_velocity(start, phi, speed, sa, sb, p))
        end = self._at_rest(res.state)

        new = (end.pocket >= 0) & (start.pocket < 0)
        scratch = new[:, 0]
        tgt = legal_target(start.pocket)
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
        self.shots[idx] += 1
        truncated = ~terminated & ((self.shots[idx] >= c.max_shots) | res.truncated)

        phi0 = self.potential(start.pos, start.pocket)
        phi1 = np.where(terminated, 0.0, self.potential(end.pos, end.pocket))
        terms = {
            "pocket": w.pocket * n_obj * legal,
            "scratch": w.scratch * scratch,
            "foul": w.foul * foul,
            "contact": w.contact * contact,
            "success": w.success * success,
            "shaping": w.shaping * (w.gamma * phi1 - phi0),
        }
        terms = {k: v.astype(np.float64) + 0.0 for k, v in terms.items()}  # + 0.0: no negative zeros
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
                              shot=self.shots[idx].copy()))
