"""The rule-aware ghost-ball game policy (``ghost``, ``ghost-safety``): see
``agents.game_policies`` for what it plays. Its own module because the agent
machinery on the games (``agents.game_view``) places ball in hand, picks
targets and breaks as it does, without the policies that build on the
trained models and the one-player search (``agents.game_policies``)."""
from __future__ import annotations

import math

import numpy as np

from billiards_env.envs.games import GameCore
from billiards_env.envs.games.setup import FOOT_SPOT, HEAD_STRING, KITCHEN_GAP
from billiards_env.envs.target_frame import CORNER_ACCEPT_DEG, SIDE_ACCEPT_DEG
from billiards_env.envs.tasks.nine_ball import break_shots
from billiards_env.physics import simulate, strike_velocity
from billiards_env.physics.strike import Shots
from billiards_env.envs.games.core import rails_after_contact
from billiards_env.rules import ShotInput
from billiards_env.rules import records as R

from . import game_geometry as GG
from . import geometry as G

APPROACH_CORNER = math.radians(CORNER_ACCEPT_DEG)  # steepest approach to a corner pocket a pot accepts
APPROACH_SIDE = math.radians(SIDE_ACCEPT_DEG)      # and to a side pocket (envs/target_frame.py)
BLOCK_CLEAR = 0.005                 # m: a pot's paths keep this clear of other balls beyond 2R (execution noise)
MAX_CUT = math.radians(70)          # a pot with a larger cut angle is "not likely": play a safety instead
PLACE_BACK = (0.2, 0.35, 0.5)       # m: distances behind the ghost ball tried for a ball-in-hand placement
PLACE_CLEAR = 1e-3                  # m: a placement keeps this clear of every ball beyond 2R
SAFETY_SPEEDS = (0.8, 3.0)          # m/s: range of the safety candidates' speeds
FALLBACK_SPEED = 1.5                # m/s: the full hit played when no pot is likely (reaches a rail, seldom pockets)
EIGHT_SPEEDS = (0.8, 1.0, 1.3)      # speed factors tried on the 8
EIGHT_HEIGHTS = (-0.3, 0.0, 0.3)    # height offsets (R) tried on the 8
EIGHT_DRAWS = 4                     # executions of each variant on the 8 (one noise-free)
KICK_K = 8                          # candidates of the legal-shot search when no legal target is in sight
SOFT_SPEED = 0.8                    # m/s: the shot on the 8 when the planned one would lose
BREAK_SPEED = 8.0                   # m/s: the break's nominal speed (as the one-player NineBall's)


def native_game(env) -> GameCore:
    """The ``GameCore`` under a game env (vector, single-agent or AEC) or the core itself."""
    for _ in range(5):
        if isinstance(env, GameCore):
            return env
        nxt = getattr(env, "core", None) or getattr(env, "unwrapped", None)
        if nxt is None or nxt is env:
            break
        env = nxt
    raise TypeError("a game policy needs a two-player game env (with .core) or a GameCore")


class GameGhostPolicy:
    """Rule-aware ghost-ball play: see the module docstring."""

    name = "ghost"

    def __init__(self, env, seed: int = 0, safety: bool = False, safety_k: int = 16, dist_weight: float = 0.5):
        self.core = native_game(env)
        self.rng = np.random.default_rng(seed)
        self.safety, self.safety_k, self.dist_weight = safety, int(safety_k), dist_weight
        t = self.core.table
        self._aims = np.ascontiguousarray(G.pocket_aim_points(t, inset=0.0))
        self._axes = np.ascontiguousarray(G.pocket_axes(t))
        self._limits = GG.pocket_limits(t, APPROACH_CORNER, APPROACH_SIDE)
        self.name = "ghost-safety" if safety else "ghost"

    # --- pots ---------------------------------------------------------------
    def best_pots(self, pos: np.ndarray, on: np.ndarray, targets: np.ndarray) -> dict:
        """The easiest ghost-ball pot per table over the legal targets and
        pockets (``game_geometry.best_pots``): arrays [n] ``cost`` (inf: none
        open), ``phi``, ``speed``, ``pocket``, ``ball``, ``cut``."""
        p = self.core.params
        n = len(pos)
        out = dict(cost=np.empty(n), phi=np.zeros(n), d_cg=np.zeros(n), d_op=np.zeros(n), cut=np.zeros(n),
                   pocket=np.zeros(n, dtype=np.int64), ball=np.zeros(n, dtype=np.int64))
        GG.best_pots(np.ascontiguousarray(pos), np.ascontiguousarray(on), np.ascontiguousarray(targets), self._aims,
                     self._axes, self._limits, p.R, BLOCK_CLEAR, MAX_CUT, self.dist_weight, out["cost"], out["phi"],
                     out["d_cg"], out["d_op"], out["cut"], out["pocket"], out["ball"])
        out["speed"] = G.required_speed(out["d_cg"], out["d_op"], out["cut"], p, b=0.0, margin=1.0)
        return out

    # --- ball in hand -----------------------------------------------------------
    def placements(self, pos: np.ndarray, on: np.ndarray, targets: np.ndarray, kitchen: np.ndarray) -> np.ndarray:
        """A cue-ball spot [n, 2] per table for a short straight-in shot on a
        legal target (``game_geometry.straight_in_spots``: behind the ghost
        ball on the line pocket -> ball, ``PLACE_BACK`` metres away, on the
        allowed area, clear of every ball, both paths open; the shortest
        object-ball run wins). Tables with no such spot get the head spot
        (behind the head string) or the table's centre (anywhere), which the
        env then makes legal."""
        t, R_ = self.core.table, self.core.params.R
        spot = np.where(kitchen[:, None], [t.width / 2, HEAD_STRING * t.length], [t.width / 2, t.length / 2])
        spot = np.ascontiguousarray(spot, dtype=np.float64)
        y_hi = np.where(kitchen, HEAD_STRING * t.length - KITCHEN_GAP, t.length - R_ - PLACE_CLEAR)
        on_c = np.ascontiguousarray(on).copy()
        on_c[:, 0] = False  # the cue ball is in hand
        GG.straight_in_spots(np.ascontiguousarray(pos), on_c, np.ascontiguousarray(targets), y_hi, self._aims,
                             np.array(PLACE_BACK), t.width, R_, PLACE_CLEAR, self.core.pockets, spot)
        return spot

    def eight_ball_shot(self, idx, pos, phi, speed, pocket):
        """The pot on the 8 played as the variant (speed x ``EIGHT_SPEEDS``,
        height ``EIGHT_HEIGHTS``) that wins most often over ``EIGHT_DRAWS``
        executions with the table's shot noise (the first one without); if
        none wins, a soft hit (``SOFT_SPEED``)."""
        n = len(idx)
        V = len(EIGHT_SPEEDS) * len(EIGHT_HEIGHTS)
        sf, hb = (np.array(v, dtype=np.float64).ravel() for v in np.meshgrid(EIGHT_SPEEDS, EIGHT_HEIGHTS))
        rep = np.repeat(np.arange(n), V * EIGHT_DRAWS)
        var = np.tile(np.repeat(np.arange(V), EIGHT_DRAWS), n)
        ph, sp, bb = phi[rep], np.minimum(speed[rep] * sf[var], self.core.params.max_speed), hb[var]
        nz, R_ = self.core.cfg.noise, self.core.params.R
        scale = self.core.noise_scale[idx][rep] * (np.tile(np.arange(EIGHT_DRAWS), n * V) > 0)
        z = self.rng.normal(size=(len(rep), 3)) * scale[:, None]
        ph = ph + z[:, 0] * math.radians(nz.aim_deg)
        sp = np.clip(sp + z[:, 1] * nz.speed, 0.05, self.core.params.max_speed)
        bb = bb + z[:, 2] * nz.height_mm * 1e-3 / R_
        rec = self.judge(idx, pos, Shots(ph, sp, np.zeros(len(rep)), bb), pocket, rep)
        wins = (rec.winner == rec.shooter).reshape(n, V, EIGHT_DRAWS)
        score = wins.sum(axis=2) + 0.5 * wins[:, :, 0]
        k = np.argmax(score, axis=1)
        ok = score[np.arange(n), k] > 0
        return (phi, np.where(ok, np.minimum(speed * sf[k], self.core.params.max_speed), SOFT_SPEED),
                np.where(ok, hb[k], 0.0))

    def refine(self, idx, rows, pos, balls, phi, speed, a, b) -> None:
        """Improve the planned pots of tables ``idx[rows]`` in place (``GameSearchPolicy``); none here."""

    def judge(self, idx: np.ndarray, pos: np.ndarray, shots: Shots, pocket: np.ndarray, rep=None):
        """Simulate ``shots`` (no noise) on tables ``idx`` with the cue ball at
        ``pos[:, 0]`` (rows ``rep`` of them, if given) and judge them by the
        rules with ``pocket`` called: the ``ShotRecord``, the state after and
        the next constraints."""
        core = self.core
        rep = np.arange(len(idx)) if rep is None else rep
        start = core.state.take(idx[rep])
        start.pos[:, 0] = pos[rep, 0]
        start.pocket[:, 0] = -1
        res = simulate(strike_velocity(start, *shots, core.params), core.table, core.params,
                       effects=core.effects, models=core.models, validate=False)
        shot = ShotInput(start.pocket, res.state.pocket, res.first_contact, rails_after_contact(res),
                         res.cushion_hits, called_pocket=np.asarray(pocket)[rep] if len(np.shape(pocket)) else None)
        rec, g2 = core.rules.judge(core.game.take(idx[rep]), shot)
        self.last_judged = (res, core.rules.constraints(g2, res.state.pocket))
        return rec

    # --- safeties --------------------------------------------------------------
    def safeties(self, idx: np.ndarray, pos: np.ndarray, k: int | None = None) -> tuple[Shots, np.ndarray]:
        """A safety per table ``idx`` (cue ball at ``pos[:, 0]``): the best of
        ``safety_k`` soft shots at the legal targets, simulated and judged.
        Returns the shots and whether each is a legal shot."""
        core = self.core
        K, n = (k or self.safety_k), len(idx)
        c = core.constraints()
        tg = c.targets[idx]
        on = core.state.pocket[idx] < 0
        rep = np.repeat(np.arange(n), K)
        # a random legal target per candidate, hit between its edges (cut up to ~70 deg either side)
        w = (tg & on).astype(np.float64)
        w[w.sum(axis=1) == 0, 1:] = 1.0
        cdf = np.cumsum(w, axis=1) / w.sum(axis=1, keepdims=True)
        ball = (self.rng.random((n * K, 1)) > cdf[rep]).sum(axis=1)
        d = pos[rep, ball] - pos[rep, 0]
        dist = np.maximum(np.linalg.norm(d, axis=1), 2 * core.params.R)
        half = np.arcsin(np.minimum(2 * core.params.R / dist, 1.0)) * 0.95
        phi = np.arctan2(d[:, 1], d[:, 0]) + half * self.rng.uniform(-1, 1, n * K)
        speed = np.exp(self.rng.uniform(*np.log(SAFETY_SPEEDS), n * K))
        b = self.rng.uniform(-0.3, 0.3, n * K)
        rec = self.judge(idx, pos, Shots(phi, speed, np.zeros(n * K), b), np.full(n, -1), rep)
        res, nxt = self.last_judged
        open_line = np.empty(n * K, dtype=bool)
        GG.open_lines(res.state.pos, res.state.pocket < 0, nxt.targets, core.params.R, open_line)
        good = rec.legal & ~rec.game_over & rec.turn_over
        score = good * 2.0 + (good & ~open_line) * 1.0 + (rec.winner == rec.shooter) * 10.0
        score = score.reshape(n, K) - 0.01 * speed.reshape(n, K)
        k = np.argmax(score, axis=1)
        pick = np.arange(n) * K + k
        return Shots(phi[pick], speed[pick], np.zeros(n), b[pick]), good[pick]

    # --- acting ------------------------------------------------------------------
    def act(self, obs=None, idx=None) -> np.ndarray:
        core = self.core
        idx = np.arange(core.n_envs) if idx is None else np.asarray(idx, dtype=np.int64)
        n = len(idx)
        c = core.constraints()
        s = core.state
        t, p = core.table, core.params
        pos = s.pos[idx].copy()
        on = s.pocket[idx] < 0
        tg = c.targets[idx]
        hand = c.ball_in_hand[idx]
        placement = np.full((n, 2), np.nan)
        phi, speed = np.zeros(n), np.zeros(n)
        a, b = np.zeros(n), np.zeros(n)
        brk = c.is_break[idx]
        if brk.any():
            r = np.nonzero(brk)[0]
            apex = np.tile([t.width / 2, FOOT_SPOT * t.length], (len(r), 1))
            u = self.rng.random((len(r), 5))
            u[:, 1] *= 0.45  # the cue ball on or behind the head string's side of the break area
            cue, phi[r], speed[r], a[r], b[r] = break_shots(t, apex, BREAK_SPEED, u, self.rng.normal(size=len(r)))
            placement[r] = cue
        play = ~brk & ~c.over[idx]
        h = np.nonzero(play & (hand != R.IN_HAND_NONE))[0]
        if len(h):
            want = self.placements(pos[h], on[h], tg[h], hand[h] == R.IN_HAND_KITCHEN)
            placement[h], _ = core.legal_placement(want, idx[h])
            pos[h, 0] = placement[h]
            on[h, 0] = True
        rows = np.nonzero(play)[0]
        pots = self.best_pots(pos[rows], on[rows], tg[rows])
        pocket = np.zeros(n, dtype=np.int64)
        has = np.isfinite(pots["cost"])
        phi[rows[has]], speed[rows[has]] = pots["phi"][has], pots["speed"][has]
        pocket[rows] = pots["pocket"]
        declare = np.zeros(n, dtype=bool)
        declare[rows[~has]] = c.may_pass[idx[rows[~has]]]           # no pot after a push-out: hand it back
        none = rows[~has & ~declare[rows]]
        if len(none):
            tgt = np.empty(len(none), dtype=np.int64)
            seen = np.empty(len(none), dtype=bool)
            GG.nearest_open_target(np.ascontiguousarray(pos[none]), np.ascontiguousarray(on[none]),
                                   np.ascontiguousarray(c.targets[idx[none]]), p.R, tgt, seen)
            d = pos[none, np.maximum(tgt, 0)] - pos[none, 0]
            phi[none], speed[none] = np.arctan2(d[:, 1], d[:, 0]), FALLBACK_SPEED  # full on the nearest in sight
            on8 = c.call_needed[idx[none]]
            if on8.any():  # a full hit on the 8: soft, calling the pocket straight ahead of it
                k = none[on8]
                u = d[on8] / np.linalg.norm(d[on8], axis=1, keepdims=True)
                to_p = self._aims[None] - pos[k, 8][:, None]
                along = np.einsum("npi,ni->np", to_p, u)
                off = np.linalg.norm(to_p - along[..., None] * u[:, None], axis=-1)
                pocket[k] = np.argmin(np.where(along > 0, off, np.inf), axis=1)
                speed[k] = SOFT_SPEED
            search = none if self.safety else none[~seen]  # no target in sight: search for a legal shot
            if len(search):
                sh, _ = self.safeties(idx[search], pos[search], None if self.safety else KICK_K)
                phi[search], speed[search], b[search] = sh.phi, sh.speed, sh.b
        speed = np.clip(speed, 0.05, p.max_speed)
        self.refine(idx, rows[has & ~c.call_needed[idx[rows]]], pos, pots["ball"][has & ~c.call_needed[idx[rows]]],
                    phi, speed, a, b)
        lose = np.zeros(0, dtype=np.int64)
        if core.rules.name == "eight_ball":  # a pot that would sink the 8 (early or on a scratch) loses the game:
            chk = rows[~declare[rows] & ~c.call_needed[idx[rows]]]  # play pots and full hits in the simulator
            chk = chk[~np.isin(chk, search)] if len(none) else chk  # first; if one loses, search instead
            if len(chk):
                rec = self.judge(idx[chk], pos[chk], Shots(phi[chk], speed[chk], a[chk], b[chk]), pocket[chk])
                lose = chk[rec.winner == 1 - rec.shooter]
                if len(lose):
                    sh, _ = self.safeties(idx[lose], pos[lose], KICK_K)
                    phi[lose], speed[lose], a[lose], b[lose] = sh.phi, sh.speed, sh.a, sh.b
        mode = np.full(n, "pot", dtype=object)
        mode[brk], mode[declare] = "break", "pass"
        if len(none):
            mode[none] = "full"
            mode[search] = "search"
        mode[lose] = "search"
        eight = np.nonzero(c.call_needed[idx] & play & np.isfinite(pots_cost(rows, pots, n)))[0]
        mode[eight] = "eight"
        self.last_mode = mode  # what each table's shot is (diagnostics)
        if len(eight):  # the game hangs on this shot: pick its speed and draw in the simulator
            phi[eight], speed[eight], b[eight] = self.eight_ball_shot(idx[eight], pos[eight], phi[eight],
                                                                      speed[eight], pocket[eight])
        return core.actions_for(Shots(phi, speed, a, b), idx, placement, declare, pocket).astype(np.float32)


def pots_cost(rows, pots, n) -> np.ndarray:
    """The pot cost of every table [n] (inf where none, or where not computed)."""
    out = np.full(n, np.inf)
    out[rows] = pots["cost"]
    return out
