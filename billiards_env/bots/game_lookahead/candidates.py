"""The lookahead's candidate shots: ball-in-hand spots behind the easiest
pots' ghost balls (``starts``), the easiest open pots in their variants
(overcuts against throw, speeds, tip heights), safeties, kicks and
one-rail kicks (``safeties``), and 9-ball push-outs (``push_values``)."""
from __future__ import annotations

import math

import numpy as np

from ...contract.plan import ShotPlan
from ...physics.strike import Shots
from ...rules import records as RR

THROW = (0.0, math.radians(2.0))   # rad: object-ball overcut tried against collision-induced throw
SPEEDS = (1.1, 1.5, 2.2, 3.2)      # factors of the speed that just drops the ball (4 measured above 3: docs/games.md)
HEIGHTS = (-0.35, 0.0, 0.35)       # tip heights (units of R): draw, stun, follow
HAND_BACKS = (0.18, 0.4)           # m: ball-in-hand spots behind the ghost ball
HAND_TURNS = (-math.radians(25), 0.0, math.radians(25))  # rad: and turned about it (a cut for position)
SAFE_SPEEDS = (0.5, 3.5)           # m/s: range of the safeties' speeds
KICK_SPEEDS = (1.0, 5.0)           # m/s: range of the kicks' speeds
BANK_SPEEDS = (1.5, 5.0)           # m/s: range of the one-rail kicks' speeds
PUSH_SPEEDS = (0.3, 1.6)           # m/s: range of the push-outs' speeds


class Candidates:
    """The candidates of ``GameLookahead`` (a mixin: it reads the bot's sizes and ``rng`` and uses its
    ``pot_table``, ``pot_speed``, ``leave_ease`` and ``position_value``)."""

    def starts(self, view, rows):
        """(row of each start, cue-ball spot [S, 2], placed [S]): the cue ball where it lies, or searched
        ball-in-hand spots."""
        hand = view.in_hand[rows]
        srow, cue, placed = [rows[~hand]], [view.pos[rows[~hand], 0]], [np.zeros((~hand).sum(), bool)]
        h = rows[hand]
        if len(h):
            pos, on = view.pos[h], view.on_table[h].copy()
            on[:, 0] = False
            pt = self.pot_table(view, pos, on, view.targets[h], pos[:, 0], np.ones(len(h), bool))
            flat = pt["prob"].reshape(len(h), -1)
            k = min(self.hand_pots, flat.shape[1])
            top = np.argsort(-flat, axis=1)[:, :k]                      # [h, k] easiest (ball, pocket)
            P = pt["prob"].shape[2]
            ball, pk = top // P, top % P
            aims = self.pockets(view).aims
            ob = pos[np.arange(len(h))[:, None], ball]                    # [h, k, 2]
            u = aims[pk] - ob
            u /= np.maximum(np.linalg.norm(u, axis=-1, keepdims=True), 1e-9)
            ghost = ob - 2 * view.params.R * u
            back = np.asarray(HAND_BACKS)[None, None, :, None, None]
            turn = np.asarray(HAND_TURNS)[None, None, None, :]
            ang = np.arctan2(u[..., 1], u[..., 0])[:, :, None, None] + turn        # [h, k, 1, T]
            d = np.stack([np.cos(ang), np.sin(ang)], axis=-1)[:, :, None]          # [h, k, 1, 1, T, 2]
            spot = ghost[:, :, None, None, None] - back[..., None] * d              # [h, k, Bk, 1, T, 2]
            spot = spot.reshape(len(h), -1, 2)
            # no open pot at all: the head spot or the centre (made legal below)
            none = flat.max(axis=1) <= 0
            kitchen = view.ball_in_hand[h] == RR.IN_HAND_KITCHEN
            spot[none] = np.where(kitchen[none, None], view.marks.head_spot,
                                  [view.table.width / 2, view.table.length / 2])[:, None]
            per = spot.shape[1]
            r_h = np.repeat(h, per)
            legal, _ = view.legal_placement(spot.reshape(-1, 2), r_h)
            srow.append(r_h)
            cue.append(legal)
            placed.append(np.ones(len(r_h), bool))
        srow, cue, placed = np.concatenate(srow), np.concatenate(cue), np.concatenate(placed)
        o = np.argsort(srow, kind="stable")
        return srow[o], cue[o], placed[o]

    def candidates(self, view, rows):
        """Candidate shots of view rows ``rows``: dict of flat arrays (row, phi, speed, a, b, placement, pocket,
        safe)."""
        p = view.params
        srow, cue, placed = self.starts(view, rows)
        pos = view.pos[srow].copy()
        pos[:, 0] = cue
        on = view.on_table[srow].copy()
        on[:, 0] = True
        tg = view.targets[srow]
        pt = self.pot_table(view, pos, on, tg, cue, np.zeros(len(srow), bool))
        S, B, P = pt["prob"].shape
        flat = {k: v.reshape(S, -1) for k, v in pt.items()}
        k = min(self.n_pots, B * P)
        top = np.argsort(-flat["prob"], axis=1)[:, :k]                       # [S, k]
        take = lambda a: np.take_along_axis(a, top, axis=1)
        ok = take(flat["prob"]) > 0
        ok[placed, 1:] = False                                              # a placed start: its best pot only
        si, ki = np.nonzero(ok)
        t = top[si, ki]
        ball, pk = t // P, t % P
        phi0 = flat["phi"][si, t]
        cut = flat["cut"][si, t]
        v0 = self.pot_speed(view, flat["dcg"][si, t], flat["dop"][si, t], cut)
        # the overcut's side: the cue ball hits the ghost from the side the cut turns it
        cue_dir = phi0
        ob = pos[si, ball]
        aims = self.pockets(view).aims[pk]
        ob_dir = np.arctan2(aims[:, 1] - ob[:, 1], aims[:, 0] - ob[:, 0])
        side = np.sign(np.sin(ob_dir - cue_dir))
        dcg = np.maximum(flat["dcg"][si, t], 2 * p.R)
        tw, sp, hb = (np.asarray(v, dtype=np.float64).ravel() for v in np.meshgrid(self.throws, self.speeds, self.heights,
                                                                                    indexing="ij"))
        V = len(tw)
        rep = np.repeat(np.arange(len(si)), V)
        var = np.tile(np.arange(V), len(si))
        # an object-ball overcut of dtheta needs the cue aim turned by about dtheta 2R cos(cut) / d_cg, away
        dphi = -side[rep] * tw[var] * 2 * p.R * np.cos(cut[rep]) / dcg[rep]
        c = dict(row=srow[si][rep], phi=phi0[rep] + dphi, speed=np.minimum(v0[rep] * sp[var], p.max_speed),
                 a=np.zeros(len(rep)), b=hb[var], placement=np.where(placed[si][rep, None], cue[si][rep], np.nan),
                 pocket=pk[rep], safe=np.zeros(len(rep), bool))
        # safeties and kicks: from the cue ball where it lies, or from each row's first ball-in-hand spot
        first = np.searchsorted(srow, rows)
        parts = [c, self.safeties(view, rows, cue[first], placed[first])]
        out = {key: np.concatenate([q[key] for q in parts]) for key in c}
        return out

    def eight_pocket(self, view, rows) -> np.ndarray:
        """The pocket each row's 8 is easiest into from where the cue ball lies (0 where no pot is open)."""
        pos = view.pos[rows]
        tg = np.zeros(view.targets[rows].shape, bool)
        tg[:, 8] = True
        pt = self.pot_table(view, pos, view.on_table[rows], tg, pos[:, 0], np.zeros(len(rows), bool))
        return np.argmax(pt["prob"][:, 8], axis=1)

    def safeties(self, view, rows, cue, placed):
        """``n_safe`` soft shots at the legal targets, ``n_bank`` one-rail kicks at them (aimed at a legal ball's
        mirror image in a random cushion's line) and ``n_kick`` shots in any direction per row, the cue ball at
        ``cue`` [n, 2] (``placed``: there by ball in hand)."""
        R_ = view.params.R
        n, Ks, Kk, Kb = len(rows), self.n_safe, self.n_kick, self.n_bank
        rng = self.rng
        w = (view.targets[rows] & view.on_table[rows]).astype(np.float64)
        w[:, 0] = 0.0
        w[w.sum(axis=1) == 0, 1:] = 1.0
        cdf = np.cumsum(w, axis=1) / w.sum(axis=1, keepdims=True)
        rep = np.repeat(np.arange(n), Ks)
        ball = np.minimum((rng.random((n * Ks, 1)) > cdf[rep]).sum(axis=1), view.n_balls - 1)
        d = view.pos[rows[rep], ball] - cue[rep]
        dist = np.maximum(np.linalg.norm(d, axis=1), 2 * R_)
        half = np.arcsin(np.minimum(2 * R_ / dist, 1.0)) * 0.95
        phi_s = np.arctan2(d[:, 1], d[:, 0]) + half * rng.uniform(-1, 1, n * Ks)
        sp_s = np.exp(rng.uniform(*np.log(SAFE_SPEEDS), n * Ks))
        repk = np.repeat(np.arange(n), Kk)
        phi_k = rng.uniform(0, 2 * np.pi, n * Kk)
        sp_k = rng.uniform(*KICK_SPEEDS, n * Kk)
        repb = np.repeat(np.arange(n), Kb)
        ball_b = np.minimum((rng.random((n * Kb, 1)) > cdf[repb]).sum(axis=1), view.n_balls - 1)
        img = view.pos[rows[repb], ball_b].copy()
        rail = rng.integers(0, 4, n * Kb)                     # the cushion lines x = R, x = W - R, y = R, y = L - R
        line = np.array([R_, view.table.width - R_, R_, view.table.length - R_])[rail]
        axis = (rail >= 2).astype(np.int64)
        img[np.arange(n * Kb), axis] = 2 * line - img[np.arange(n * Kb), axis]
        db = img - cue[repb]
        half_b = np.arcsin(np.minimum(2 * R_ / np.maximum(np.linalg.norm(db, axis=1), 2 * R_), 1.0)) * 0.5
        phi_b = np.arctan2(db[:, 1], db[:, 0]) + half_b * rng.uniform(-1, 1, n * Kb)
        sp_b = rng.uniform(*BANK_SPEEDS, n * Kb)
        allrep = np.concatenate([rep, repk, repb])
        m = len(allrep)
        pocket = np.zeros(n, dtype=np.int64)
        call = view.call_needed[rows]
        if call.any():
            pocket[call] = self.eight_pocket(view, rows[call])
        return dict(row=rows[allrep], phi=np.concatenate([phi_s, phi_k, phi_b]),
                    speed=np.concatenate([sp_s, sp_k, sp_b]),
                    a=np.zeros(m), b=rng.uniform(-0.3, 0.3, m),
                    placement=np.where(placed[allrep, None], cue[allrep], np.nan),
                    pocket=pocket[allrep], safe=np.ones(m, bool))

    def _plan(self, c, idx=None):
        idx = slice(None) if idx is None else idx
        return ShotPlan.of(Shots(c["phi"][idx], c["speed"][idx], c["a"][idx], c["b"][idx]),
                           placement=c["placement"][idx], pocket=c["pocket"][idx])

    def push_values(self, view, rows):
        """The best push-out per row: (shots, value)."""
        n, K = len(rows), self.n_push
        rep = np.repeat(np.arange(n), K)
        phi = self.rng.uniform(0, 2 * np.pi, n * K)
        speed = np.exp(self.rng.uniform(*np.log(PUSH_SPEEDS), n * K))
        plan = ShotPlan.of(Shots(phi, speed, 0.0, 0.0))
        pv = view.preview(plan, rows[rep])
        self.sims += n * K
        on = pv.on_table
        tg = np.zeros_like(on)
        low = np.argmax(on[:, 1:], axis=1) + 1              # 9-ball: the lowest ball on the table is the target
        tg[np.arange(len(low)), low] = True
        scratch = ~on[:, 0]
        e = self.leave_ease(view, pv.pos, on, tg, scratch)
        v = self.position_value(view, e, on, tg)
        val = np.where(scratch, 1.0 - v, np.minimum(v, 1.0 - v))
        val = np.where(pv.record.game_over, (pv.record.winner == pv.record.shooter) * 1.0, val)
        val = val.reshape(n, K)
        k = np.argmax(val, axis=1)
        pick = np.arange(n) * K + k
        return (phi[pick], speed[pick]), val[np.arange(n), k]
