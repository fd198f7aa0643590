"""``ghost`` and ``ghost-safety``: rule-aware ghost-ball bots for the two-player games.

``GhostBot`` plays the ghost-ball shot (``bots.geometry``, its kernels in
``bots.geometry.game``) on the easiest legal target and pocket; the seeded
standard break; with ball in hand, the cue ball placed for a short
straight-in shot on a legal target; after the opponent's push-out, it passes
when it has no pot. When no pot is likely (every pot blocked or cut more
than 70 deg) it hits the nearest legal target in sight full at 1.5 m/s (a
legal contact that reaches a rail), or, with no legal target in sight,
searches for a legal shot like a safety (8 candidates). With
``safety=True`` (``ghost-safety``) it always plays a safety: ``safety_k``
candidate soft shots at the legal targets previewed in one batched call,
judged by the rules, keeping a legal one that leaves the opponent no
straight line to any of their legal targets (else any legal one). On the 8
it chooses the speed and draw of its pot in the simulator under the env's
noise (``eight_ball_shot``); in 8-ball every other pot or full hit is first
previewed (no noise) and replaced by a searched legal shot if it would lose
the game. In 10-ball it calls every shot: a pot calls its ball and pocket,
a full hit its target into the pocket straight ahead of it, a searched
shot (a safety) a safety; a pot on the 10 is chosen in the simulator as
the 8 is.

It acts on a ``GameView`` and returns a ``ShotPlan`` (``contract.view``,
``contract.plan``); every look ahead goes through ``GameView.preview``.
"""
from __future__ import annotations

import math

import numpy as np

from ..contract.pockets import CORNER_ACCEPT_DEG, SIDE_ACCEPT_DEG
from .geometry.breaks import break_shots
from ..physics.noise import perturb
from ..physics.strike import Shots
from ..rules import records as R
from ..rules.placement import FOOT_SPOT, HEAD_STRING, KITCHEN_GAP
from . import geometry as G
from ..contract.plan import ShotPlan

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
TEN = 10                            # 10-ball: the ball that wins


def pocket_ahead(aims: np.ndarray, ball_pos: np.ndarray, d: np.ndarray) -> np.ndarray:
    """Per row: the pocket (of ``aims`` [P, 2]) closest to the line through
    ``ball_pos`` [n, 2] along ``d`` [n, 2] (the cue ball's direction to it),
    among the pockets ahead of the ball: where a full hit sends it."""
    u = d / np.maximum(np.linalg.norm(d, axis=1, keepdims=True), 1e-12)
    to_p = aims[None] - ball_pos[:, None]
    along = np.einsum("npi,ni->np", to_p, u)
    off = np.linalg.norm(to_p - along[..., None] * u[:, None], axis=-1)
    return np.argmin(np.where(along > 0, off, np.inf), axis=1)


class PotGeometry:
    """The pockets' aim points, axes and approach limits of one table, as
    the kernels take them (computed once per table)."""

    def __init__(self, table, params):
        self.table, self.params = table, params
        self.aims = np.ascontiguousarray(G.pocket_aim_points(table, inset=0.0))
        self.axes = np.ascontiguousarray(G.pocket_axes(table))
        self.limits = G.pocket_limits(table, APPROACH_CORNER, APPROACH_SIDE)
        self.pockets = np.ascontiguousarray(table.geometry(True)[3], dtype=np.float64)


class GhostBot:
    """Rule-aware ghost-ball play: see the module docstring."""

    name = "ghost"

    def __init__(self, seed: int = 0, safety: bool = False, safety_k: int = 16, dist_weight: float = 0.5):
        self.rng = np.random.default_rng(seed)
        self.safety, self.safety_k, self.dist_weight = safety, int(safety_k), dist_weight
        self.geo: PotGeometry | None = None
        self.name = "ghost-safety" if safety else "ghost"

    def geometry(self, view) -> PotGeometry:
        """The ``PotGeometry`` of the view's table (kept while the table is the same)."""
        if self.geo is None or self.geo.table is not view.table or self.geo.params is not view.params:
            self.geo = PotGeometry(view.table, view.params)
        return self.geo

    # --- pots ---------------------------------------------------------------
    def best_pots(self, geo: PotGeometry, pos: np.ndarray, on: np.ndarray, targets: np.ndarray) -> dict:
        """The easiest ghost-ball pot per table over the legal targets and
        pockets (``geometry.best_pots``): arrays [n] ``cost`` (inf: none
        open), ``phi``, ``speed``, ``pocket``, ``ball``, ``cut``."""
        p = geo.params
        n = len(pos)
        out = dict(cost=np.empty(n), phi=np.zeros(n), d_cg=np.zeros(n), d_op=np.zeros(n), cut=np.zeros(n),
                   pocket=np.zeros(n, dtype=np.int64), ball=np.zeros(n, dtype=np.int64))
        G.best_pots(np.ascontiguousarray(pos), np.ascontiguousarray(on), np.ascontiguousarray(targets), geo.aims,
                     geo.axes, geo.limits, G.PotLimits(p.R, BLOCK_CLEAR, MAX_CUT, self.dist_weight), out)
        out["speed"] = G.required_speed(out["d_cg"], out["d_op"], out["cut"], p, b=0.0, margin=1.0)
        return out

    # --- ball in hand -----------------------------------------------------------
    def placements(self, geo: PotGeometry, pos: np.ndarray, on: np.ndarray, targets: np.ndarray,
                   kitchen: np.ndarray) -> np.ndarray:
        """A cue-ball spot [n, 2] per table for a short straight-in shot on a
        legal target (``geometry.straight_in_spots``: behind the ghost
        ball on the line pocket -> ball, ``PLACE_BACK`` metres away, on the
        allowed area, clear of every ball, both paths open; the shortest
        object-ball run wins). Tables with no such spot get the head spot
        (behind the head string) or the table's centre (anywhere), which
        ``GameView.legal_placement`` then makes legal."""
        t, R_ = geo.table, geo.params.R
        spot = np.where(kitchen[:, None], [t.width / 2, HEAD_STRING * t.length], [t.width / 2, t.length / 2])
        spot = np.ascontiguousarray(spot, dtype=np.float64)
        y_hi = np.where(kitchen, HEAD_STRING * t.length - KITCHEN_GAP, t.length - R_ - PLACE_CLEAR)
        on_c = np.ascontiguousarray(on).copy()
        on_c[:, 0] = False  # the cue ball is in hand
        G.straight_in_spots(np.ascontiguousarray(pos), on_c, np.ascontiguousarray(targets), y_hi, geo.aims,
                             np.array(PLACE_BACK), G.SpotLimits(t.width, R_, PLACE_CLEAR), geo.pockets, spot)
        return spot

    def eight_ball_shot(self, view, rows, pos, shots: Shots, pocket):
        """The pot on the 8 played as the variant (speed x ``EIGHT_SPEEDS``,
        height ``EIGHT_HEIGHTS``) that wins most often over ``EIGHT_DRAWS``
        executions with the env's shot noise (``physics.noise.perturb``, the
        first execution without); if none wins, a soft hit (``SOFT_SPEED``)."""
        phi, speed = shots.phi, shots.speed
        n = len(rows)
        V = len(EIGHT_SPEEDS) * len(EIGHT_HEIGHTS)
        sf, hb = (np.array(v, dtype=np.float64).ravel() for v in np.meshgrid(EIGHT_SPEEDS, EIGHT_HEIGHTS))
        rep = np.repeat(np.arange(n), V * EIGHT_DRAWS)
        var = np.tile(np.repeat(np.arange(V), EIGHT_DRAWS), n)
        planned = Shots(phi[rep], np.minimum(speed[rep] * sf[var], view.params.max_speed), 0.0, hb[var])
        scale = view.noise_scale[rows][rep] * (np.tile(np.arange(EIGHT_DRAWS), n * V) > 0)
        z = self.rng.normal(size=(len(rep), 4)) * scale[:, None]
        rec = self.judge(view, rows, pos, perturb(planned, z, view.noise, view.params), pocket, rep)
        wins = (rec.winner == rec.shooter).reshape(n, V, EIGHT_DRAWS)
        score = wins.sum(axis=2) + 0.5 * wins[:, :, 0]
        k = np.argmax(score, axis=1)
        ok = score[np.arange(n), k] > 0
        return (phi, np.where(ok, np.minimum(speed * sf[k], view.params.max_speed), SOFT_SPEED),
                np.where(ok, hb[k], 0.0))

    def refine(self, view, rows, pos, balls, shots: Shots, pockets=None) -> None:
        """Improve the planned pots of view rows ``rows`` (of ``balls`` into
        ``pockets``, the planned pockets) in place (``SearchBot``); none here."""

    def judge(self, view, rows, pos: np.ndarray, shots: Shots, pocket: np.ndarray, rep=None):
        """Preview ``shots`` (no noise) on view rows ``rows`` with the cue
        ball at ``pos[:, 0]`` (rows ``rep`` of them, if given) and ``pocket``
        called: the ``ShotRecord``; the whole ``Preview`` is kept in
        ``last_judged``."""
        rows = np.asarray(rows, dtype=np.int64)
        rep = np.arange(len(rows)) if rep is None else rep
        plan = ShotPlan.of(shots, placement=pos[rep, 0], pocket=np.broadcast_to(pocket, (len(rows),))[rep])
        self.last_judged = view.preview(plan, rows[rep])
        return self.last_judged.record

    # --- safeties --------------------------------------------------------------
    def target_lines(self, view, rows, pos, K: int):
        """``K`` random legal targets per view row ``rows`` (cue ball at
        ``pos[:, 0]``; any object ball where none is legal), for candidates
        that hit them between their edges (a cut up to ~70 deg either side):
        (rep [n K] the row of each, ball [n K], d [n K, 2] cue ball -> ball,
        half [n K] the half-angle within which the cue ball still hits it)."""
        R_, n = view.params.R, len(rows)
        rep = np.repeat(np.arange(n), K)
        w = (view.targets[rows] & view.on_table[rows]).astype(np.float64)
        w[w.sum(axis=1) == 0, 1:] = 1.0
        cdf = np.cumsum(w, axis=1) / w.sum(axis=1, keepdims=True)
        ball = (self.rng.random((n * K, 1)) > cdf[rep]).sum(axis=1)
        d = pos[rep, ball] - pos[rep, 0]
        dist = np.maximum(np.linalg.norm(d, axis=1), 2 * R_)
        return rep, ball, d, np.arcsin(np.minimum(2 * R_ / dist, 1.0)) * 0.95

    def safeties(self, view, rows: np.ndarray, pos: np.ndarray, k: int | None = None) -> tuple[Shots, np.ndarray]:
        """A safety per view row ``rows`` (cue ball at ``pos[:, 0]``): the best
        of ``safety_k`` soft shots at the legal targets, previewed and judged.
        Returns the shots and whether each is a legal shot."""
        R_ = view.params.R
        K, n = (k or self.safety_k), len(rows)
        rep, ball, d, half = self.target_lines(view, rows, pos, K)
        phi = np.arctan2(d[:, 1], d[:, 0]) + half * self.rng.uniform(-1, 1, n * K)
        speed = np.exp(self.rng.uniform(*np.log(SAFETY_SPEEDS), n * K))
        b = self.rng.uniform(-0.3, 0.3, n * K)
        rec = self.judge(view, rows, pos, Shots(phi, speed, np.zeros(n * K), b), np.full(n, -1), rep)
        pv = self.last_judged
        open_line = np.empty(n * K, dtype=bool)
        G.open_lines(pv.pos, pv.on_table, pv.next.targets, R_, open_line)
        good = rec.legal & ~rec.game_over & rec.turn_over
        score = good * 2.0 + (good & ~open_line) * 1.0 + (rec.winner == rec.shooter) * 10.0
        score = score.reshape(n, K) - 0.01 * speed.reshape(n, K)
        k = np.argmax(score, axis=1)
        pick = np.arange(n) * K + k
        return Shots(phi[pick], speed[pick], np.zeros(n), b[pick]), good[pick]

    # --- acting ------------------------------------------------------------------
    def act(self, view) -> ShotPlan:
        if not view.table.has_pockets:
            raise ValueError(f"the {self.name} bot pots balls: it cannot play {view.game} on a table without "
                             "pockets (three-cushion: the carom bot, make_bot('carom'))")
        geo = self.geometry(view)
        n = view.n
        t, p = view.table, view.params
        pos = view.pos.copy()
        on = view.on_table.copy()
        tg = view.targets
        hand = view.ball_in_hand
        placement = np.full((n, 2), np.nan)
        phi, speed = np.zeros(n), np.zeros(n)
        a, b = np.zeros(n), np.zeros(n)
        brk = view.is_break
        calls = getattr(view.rules, "calls_ball", False)
        on_call = np.zeros(n, dtype=bool) if calls else view.call_needed  # 8-ball: the shot is on the 8
        # the shots the game hangs on, played as the 8 is: the 8, and in 10-ball a pot of the 10
        decisive = on_call | (view.call_needed & view.targets[:, TEN]) if calls else on_call
        if brk.any():
            r = np.nonzero(brk)[0]
            apex = np.tile([t.width / 2, FOOT_SPOT * t.length], (len(r), 1))
            u = self.rng.random((len(r), 5))
            u[:, 1] *= 0.45  # the cue ball on or behind the head string's side of the break area
            cue, phi[r], speed[r], a[r], b[r] = break_shots(t, apex, BREAK_SPEED, u, self.rng.normal(size=len(r)))
            placement[r] = cue
        play = ~brk
        h = np.nonzero(play & (hand != R.IN_HAND_NONE))[0]
        if len(h):
            want = self.placements(geo, pos[h], on[h], tg[h], hand[h] == R.IN_HAND_KITCHEN)
            placement[h], _ = view.legal_placement(want, h)
            pos[h, 0] = placement[h]
            on[h, 0] = True
        rows = np.nonzero(play)[0]
        pots = self.best_pots(geo, pos[rows], on[rows], tg[rows])
        pocket = np.zeros(n, dtype=np.int64)
        has = np.isfinite(pots["cost"])
        phi[rows[has]], speed[rows[has]] = pots["phi"][has], pots["speed"][has]
        pocket[rows] = pots["pocket"]
        declare = np.zeros(n, dtype=bool)
        declare[rows[~has]] = view.may_pass[rows[~has]]           # no pot after a push-out: hand it back
        none = rows[~has & ~declare[rows]]
        search = np.zeros(0, dtype=np.int64)
        if len(none):
            tgt = np.empty(len(none), dtype=np.int64)
            seen = np.empty(len(none), dtype=bool)
            G.nearest_open_target(np.ascontiguousarray(pos[none]), np.ascontiguousarray(on[none]),
                                   np.ascontiguousarray(tg[none]), p.R, tgt, seen)
            d = pos[none, np.maximum(tgt, 0)] - pos[none, 0]
            phi[none], speed[none] = np.arctan2(d[:, 1], d[:, 0]), FALLBACK_SPEED  # full on the nearest in sight
            on8 = on_call[none]
            if on8.any():  # a full hit on the 8: soft, calling the pocket straight ahead of it
                k = none[on8]
                u = d[on8] / np.linalg.norm(d[on8], axis=1, keepdims=True)
                to_p = geo.aims[None] - pos[k, 8][:, None]
                along = np.einsum("npi,ni->np", to_p, u)
                off = np.linalg.norm(to_p - along[..., None] * u[:, None], axis=-1)
                pocket[k] = np.argmin(np.where(along > 0, off, np.inf), axis=1)
                speed[k] = SOFT_SPEED
            search = none if self.safety else none[~seen]  # no target in sight: search for a legal shot
            if len(search):
                sh, _ = self.safeties(view, search, pos[search], None if self.safety else KICK_K)
                phi[search], speed[search], b[search] = sh.phi, sh.speed, sh.b
        speed = np.clip(speed, 0.05, p.max_speed)
        pot_rows = has & ~decisive[rows]
        shots = Shots.of_arrays(phi, speed, a, b)
        self.refine(view, rows[pot_rows], pos, pots["ball"][pot_rows], shots, pocket[rows[pot_rows]])
        phi, speed, a, b = shots
        lose = np.zeros(0, dtype=np.int64)
        if getattr(view.rules, "game_ball_loses", False):  # a pot sinking the 8 early or on a scratch loses (8-ball):
            chk = rows[~declare[rows] & ~view.call_needed[rows]]  # preview pots and full hits first;
            chk = chk[~np.isin(chk, search)]                      # if one loses, search instead
            if len(chk):
                rec = self.judge(view, chk, pos[chk], Shots(phi[chk], speed[chk], a[chk], b[chk]), pocket[chk])
                lose = chk[rec.winner == 1 - rec.shooter]
                if len(lose):
                    sh, _ = self.safeties(view, lose, pos[lose], KICK_K)
                    phi[lose], speed[lose], a[lose], b[lose] = sh.phi, sh.speed, sh.a, sh.b
        mode = np.full(n, "pot", dtype=object)
        mode[brk], mode[declare] = "break", "pass"
        if len(none):
            mode[none] = "full"
            mode[search] = "search"
        mode[lose] = "search"
        cost = np.full(n, np.inf)
        cost[rows] = pots["cost"]
        eight = np.nonzero(decisive & play & np.isfinite(cost))[0]
        mode[eight] = "eight"
        self.last_mode = mode  # what each table's shot is (diagnostics)
        if len(eight):  # the game hangs on this shot: pick its speed and draw in the previews
            phi[eight], speed[eight], b[eight] = self.eight_ball_shot(
                view, eight, pos[eight], Shots(phi[eight], speed[eight], a[eight], b[eight]), pocket[eight])
        ball = self.calls(view, geo, rows, has, pots, none, search, pos, pocket)
        return ShotPlan.of(Shots(phi, speed, a, b), placement, declare, pocket, ball)

    def calls(self, view, geo: PotGeometry, rows, has, pots, none, search, pos, pocket) -> np.ndarray | None:
        """10-ball's called balls [n] (``pocket`` [n] is updated in place): a
        pot calls its ball into its pocket; a full hit (rows ``none``) its
        target into the pocket straight ahead of the target; a searched shot
        (rows ``search``, judged in the previews without a call) a safety.
        None in the games without ball calls."""
        if not getattr(view.rules, "calls_ball", False):
            return None
        ball = np.full(view.n, -1, dtype=np.int64)  # -1: the nominal target (the break and passes ignore it)
        ball[rows[has]] = pots["ball"][has]
        if len(none):
            tgt = np.maximum(view.nominal_target()[none], 0)
            ball[none] = tgt
            pocket[none] = pocket_ahead(geo.aims, pos[none, tgt], pos[none, tgt] - pos[none, 0])
        ball[search] = R.CALL_SAFETY
        return ball
