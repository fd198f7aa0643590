"""``snooker``: a snooker bot through the bot API (``GameView`` in,
``ShotPlan`` out), built on the ghost-ball geometry of ``GhostBot``.

- Pots: the easiest ghost-ball pot on a ball on (``GhostBot.best_pots``:
  open paths, the cut at most 70 deg, a short run), nominating the ball it
  pots (the colour after a red, or the free ball after a foul).
- In hand in the D: the spot of ``D_SPOTS`` from which the easiest pot is
  open (the cue ball then lies where the rules allow).
- Safeties: when no pot is likely, ``safety_k`` soft candidates at the
  balls on (each nominating the ball it aims at) are previewed in one
  batched call (``GameView.preview``, judged by the rules); it keeps a legal
  one that leaves the opponent no straight line to a ball on and the cue
  ball far from them, else any legal one.
- The break-off: ``break_k`` candidates from the D at the side of the reds,
  previewed and scored as safeties (the cue ball back towards baulk).

- After the opponent's foul and a miss (``GameView.may_replace``): where it
  has no pot it has the balls replaced (``ShotPlan.replace``), so the
  offender must try the escape again; where it has a pot it plays on.

It never puts the offender back in after a foul.
"""
from __future__ import annotations

import numpy as np

from ..physics.strike import Shots
from ..rules import records as R
from . import geometry as G
from .ghost import GhostBot
from ..contract.plan import ShotPlan

# Points of the D tried for ball in hand: (fraction of the radius, angle from the baulk line's +x end, deg).
D_SPOTS = ((0.0, 90.0), (0.5, 10.0), (0.5, 90.0), (0.5, 170.0), (0.95, 20.0), (0.95, 90.0), (0.95, 160.0),
           (0.25, 45.0), (0.25, 135.0))
SAFETY_SPEEDS = (0.6, 2.5)        # m/s: the safety candidates' speeds
BREAK_SPEEDS = (3.0, 6.0)         # m/s: the break-off candidates' speeds
LEAVE_WEIGHT = 0.3                # score per metre between the cue ball and the nearest ball on the opponent's
D_MARGIN = 1e-3                   # m: D spots kept this far inside its line and arc


class SnookerBot(GhostBot):
    """See the module docstring."""

    name = "snooker"

    def __init__(self, seed: int = 0, safety_k: int = 24, break_k: int = 24, replace: bool = True):
        super().__init__(seed=seed, safety=False, safety_k=safety_k)
        self.break_k = int(break_k)
        self.replace = bool(replace)  # have the balls replaced after a foul and a miss, where no pot is on
        self.name = "snooker"

    def d_spots(self, table) -> np.ndarray:
        m = table.marks
        r = np.array([f for f, _ in D_SPOTS]) * (m.d_radius - D_MARGIN)
        a = np.radians([180.0 + ang for _, ang in D_SPOTS])
        return np.stack([m.d_centre[0] + r * np.cos(a), m.d_centre[1] - D_MARGIN + r * np.sin(a)], axis=1)

    def place_in_d(self, view, geo, rows, pos, on, tg) -> np.ndarray:
        """The D spot per row with the cheapest open pot (legal spots via the view)."""
        spots = self.d_spots(view.table)
        S, n = len(spots), len(rows)
        rep = np.repeat(np.arange(n), S)
        p = pos[rep].copy()
        p[:, 0] = np.tile(spots, (n, 1))
        o = on[rep].copy()
        o[:, 0] = True
        cost = self.best_pots(geo, p, o, tg[rep])["cost"].reshape(n, S)
        want = spots[np.argmin(cost, axis=1)]
        place, _ = view.legal_placement(want, rows)
        return place

    def candidates(self, view, rows, pos, k, speeds, side_edge=False):
        """``k`` candidate soft shots per row at random balls on, between
        their edges (``side_edge``: thin on either edge): (rep, shots, ball)."""
        n = len(rows)
        rep, ball, d, half = self.target_lines(view, rows, pos, k)
        u = self.rng.uniform(-1, 1, n * k)
        if side_edge:
            u = np.sign(u) * (0.7 + 0.3 * np.abs(u))
        phi = np.arctan2(d[:, 1], d[:, 0]) + half * u
        speed = np.exp(self.rng.uniform(*np.log(speeds), n * k))
        a = self.rng.uniform(-0.3, 0.3, n * k)
        b = self.rng.uniform(-0.3, 0.3, n * k)
        return rep, Shots(phi, speed, a, b), ball

    def best_safety(self, view, rows, pos, rep, shots, ball, k):
        """Preview the candidates and keep the best per row: legal, turn over,
        no open line for the opponent, the cue ball far from the balls on."""
        n = len(rows)
        plan = ShotPlan.of(shots, placement=pos[rep, 0], ball=ball)
        pv = view.preview(plan, rows[rep])
        rec = pv.record
        open_line = np.empty(n * k, dtype=bool)
        G.open_lines(pv.pos, pv.on_table, pv.next.targets, view.params.R, open_line)
        d = np.linalg.norm(pv.pos - pv.pos[:, :1], axis=2)
        near = np.where(pv.next.targets & pv.on_table, d, np.inf).min(axis=1)
        near = np.where(np.isfinite(near), near, 0.0)
        good = rec.legal & rec.turn_over & ~rec.game_over
        score = good * 2.0 + (good & ~open_line) * 1.0 + good * LEAVE_WEIGHT * near + rec.points * 0.5
        score = score - rec.penalty * 0.5
        pick = np.arange(n) * k + np.argmax(score.reshape(n, k), axis=1)
        return Shots(shots.phi[pick], shots.speed[pick], shots.a[pick], shots.b[pick]), ball[pick]

    def act(self, view) -> ShotPlan:
        geo = self.geometry(view)
        n = view.n
        p = view.params
        pos = view.pos.copy()
        on = view.on_table.copy()
        tg = view.targets
        placement = np.full((n, 2), np.nan)
        phi, speed, a, b = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
        ball = np.full(n, R.CALL_NONE, dtype=np.int64)
        brk = view.is_break
        h = np.nonzero(~brk & (view.ball_in_hand != R.IN_HAND_NONE))[0]
        if len(h):
            placement[h] = self.place_in_d(view, geo, h, pos[h], on[h], tg[h])
            pos[h, 0], on[h, 0] = placement[h], True
        if brk.any():  # from the D's yellow side, thin on a red
            r = np.nonzero(brk)[0]
            m = view.table.marks
            want = np.tile([m.d_centre[0] + 0.6 * m.d_radius, m.d_centre[1] - D_MARGIN], (len(r), 1))
            placement[r], _ = view.legal_placement(want, r)
            pos[r, 0], on[r, 0] = placement[r], True
            rep, sh, bl = self.candidates(view, r, pos[r], self.break_k, BREAK_SPEEDS, side_edge=True)
            s, bl = self.best_safety(view, r, pos[r], rep, sh, bl, self.break_k)
            phi[r], speed[r], a[r], b[r], ball[r] = s.phi, s.speed, s.a, s.b, bl
        rows = np.nonzero(~brk)[0]
        if len(rows):
            pots = self.best_pots(geo, pos[rows], on[rows], tg[rows])
            has = np.isfinite(pots["cost"])
            pr = rows[has]
            phi[pr], speed[pr], ball[pr] = pots["phi"][has], pots["speed"][has], pots["ball"][has]
            safe = rows[~has]
            if len(safe):
                rep, sh, bl = self.candidates(view, safe, pos[safe], self.safety_k, SAFETY_SPEEDS)
                s, bl = self.best_safety(view, safe, pos[safe], rep, sh, bl, self.safety_k)
                phi[safe], speed[safe], a[safe], b[safe], ball[safe] = s.phi, s.speed, s.a, s.b, bl
        mode = np.full(n, "pot", dtype=object)
        mode[brk] = "break"
        if len(rows):
            mode[rows[~has]] = "safety"
        self.last_mode = mode
        speed = np.clip(speed, 0.05, p.max_speed)
        # a nomination only where the rules ask for one (a colour after a red, a free ball)
        ball = np.where(view.call_needed, ball, R.CALL_NONE)
        replace = np.zeros(n, dtype=bool)
        if self.replace and view.may_replace is not None:
            replace = view.may_replace & (mode == "safety")
            mode[replace] = "replace"
        return ShotPlan.of(Shots(phi, speed, a, b), placement, np.zeros(n, dtype=bool), np.full(n, -1), ball,
                           replace=replace)
