"""The structured shot space the proposal network speaks (docs/expert_iteration.md): every shot of a pool table
as a (slot, turn, variant) triple, laid out on a batch of tables (``Layout``) and decoded to plans.

- **Slots** (what the shot is about): a pot of each object ball into each pocket (``POT``, aimed through the
  pocket's measured window, ``windows``), a contact line on each object ball (``SAFE``: full or half-ball either
  side, ``FULLNESS``), a one-rail kick at each object ball off each rail (``BANK``: aimed at its mirror image) and
  ``N_FAN`` directions of a 360-degree fan (``FAN``). A game of B balls and P pockets has
  (B - 1) (P + len(FULLNESS) + 4) + N_FAN slots.
- **Turns** (only with ball in hand, only for pots): the cue ball placed ``HAND_DCG`` behind the pot's ghost ball,
  on the pot's line or turned about the ghost ball by lookahead's ``HAND_TURNS`` (a cut that sends the cue ball
  elsewhere). Every other slot is played from where the cue ball lies, or with ball in hand from the spot of the
  easiest pot's straight line (the table's centre or the head spot if no pot is open).
- **Variants**: a speed bin times a tip-height bin (``HEIGHTS``, champion's draw, stun and follow). A pot's speed
  is a factor of the speed that just drops the ball (champion's ``SPEEDS``); a contact line's and a kick's is the
  arrival speed at the ball; a fan shot's is absolute.

A proposal's joint index is ``(slot * T + turn) * V + variant``. ``Layout.mask`` says which (slot, turn) pairs are
legal on each table: pots of legal balls whose window admits the approach and whose cut is under champion's
``MAX_CUT`` (a blocked path stays legal: it is only unlikely), contact lines and kicks at legal balls, every fan
direction, and turns only for pots with ball in hand. ``decode`` turns proposals into shots and ``refine`` corrects
the pots' aims for throw (``aim``), the local refinement in the simulator; ``encode`` maps any plan to its nearest
proposal, so the space round-trips.
"""
from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from ...rules import records as RR
from .. import geometry as G
from ..game_lookahead.candidates import HAND_TURNS
from . import aim as AIM
from .candidates import HEIGHTS, MISCUE_MARGIN, SPEEDS, pot_options
from .leave import HAND_DCG, MIN_AIM_SIGMA
from .windows import windows_of

POT, SAFE, BANK, FAN = range(4)                   # slot kinds
KINDS = ("pot", "safe", "bank", "fan")
FULLNESS = (-0.5, 0.0, 0.5)                       # contact lines: impact parameter / 2R (half-ball, full, half-ball)
N_RAILS = 4                                       # a kick off each rail (geometry.kick_shots' order)
N_FAN = 16                                        # fan directions: 22.5 degrees apart (the search refines within)
TURNS = tuple(HAND_TURNS)                         # rad: ball-in-hand turns about the ghost ball (lookahead's)
CENTRE = TURNS.index(0.0)                         # the turn of every shot played without ball in hand
POT_SPEEDS = tuple(SPEEDS)                        # factors of the speed that just drops the ball (champion's)
SAFE_ARRIVALS = (0.25, 0.6, 1.2, 2.4)             # m/s at the object ball: a touch, soft, firm, hard
BANK_ARRIVALS = (0.5, 1.0, 2.0, 3.5)              # m/s at the ball after the rail (as if it took nothing)
FAN_SPEEDS = (1.2, 2.0, 3.0, 4.5)                 # m/s: the fan's strike speeds
SPEED_BINS = len(POT_SPEEDS)
HEIGHT_BINS = len(HEIGHTS)
ENCODE_SCALE = (0.01, 0.05, 0.1, 0.01)            # encode's distance units: rad of aim, log speed, R of height, m


class ShotSpace:
    """The slots of a game of ``n_balls`` balls (the cue ball included) and ``n_pockets`` pockets: ``kind``,
    ``ball``, ``pocket`` (POT), ``line`` (SAFE: fullness index, BANK: rail, FAN: direction) per slot."""

    def __init__(self, n_balls: int, n_pockets: int):
        self.n_balls, self.n_pockets = int(n_balls), int(n_pockets)
        O, P = self.n_balls - 1, self.n_pockets
        F = len(FULLNESS)
        parts = [(POT, np.repeat(np.arange(1, O + 1), P), np.tile(np.arange(P), O), np.zeros(O * P, np.int64)),
                 (SAFE, np.repeat(np.arange(1, O + 1), F), np.full(O * F, -1), np.tile(np.arange(F), O)),
                 (BANK, np.repeat(np.arange(1, O + 1), N_RAILS), np.full(O * N_RAILS, -1),
                  np.tile(np.arange(N_RAILS), O)),
                 (FAN, np.zeros(N_FAN, np.int64), np.full(N_FAN, -1), np.arange(N_FAN))]
        self.kind = np.concatenate([np.full(len(b), k) for k, b, _, _ in parts]).astype(np.int64)
        self.ball = np.concatenate([b for _, b, _, _ in parts]).astype(np.int64)
        self.pocket = np.concatenate([p for _, _, p, _ in parts]).astype(np.int64)
        self.line = np.concatenate([x for _, _, _, x in parts]).astype(np.int64)
        self.start = {k: int(np.argmax(self.kind == k)) for k in range(4)}
        self.S, self.T, self.V = len(self.kind), len(TURNS), SPEED_BINS * HEIGHT_BINS

    @property
    def size(self) -> int:
        return self.S * self.T * self.V

    def index(self, slot, turn, var) -> np.ndarray:
        return (np.asarray(slot) * self.T + np.asarray(turn)) * self.V + np.asarray(var)

    def split(self, joint) -> tuple:
        joint = np.asarray(joint, dtype=np.int64)
        return joint // (self.T * self.V), (joint // self.V) % self.T, joint % self.V

    def pot_slot(self, ball, pocket) -> np.ndarray:
        return (np.asarray(ball) - 1) * self.n_pockets + np.asarray(pocket)


@lru_cache(maxsize=None)
def shot_space(n_balls: int, n_pockets: int) -> ShotSpace:
    """The shot space of a game (one object per size)."""
    return ShotSpace(n_balls, n_pockets)


def space_of(view) -> ShotSpace:
    return shot_space(view.n_balls, len(view.pockets))


class Layout:
    """The shot space laid out on view rows ``rows``: per table ``hand`` [n]; per (table, slot, turn) the cue
    ball's spot ``cue`` [n, S, T, 2], the nominal aim ``phi``, the speed base ``base`` (pots: the speed that just
    drops the ball; contact lines and kicks: the cue ball's path length), ``prob`` (pots' success estimate, champion's
    ``pot_options``), ``open_`` (the path clear), ``cut``, ``dcg``, ``dop``, ``half`` (pots' window half-width),
    ``want`` (pots: the object ball's direction) and ``mask`` (legal); ``call`` [n] the pocket an 8-ball safety
    calls (the 8's best pot)."""

    def __init__(self, view, rows, helper):
        self.view, self.rows, self.space = view, np.asarray(rows, np.int64), space_of(view)
        self.la = helper                                   # a GameLookahead: its pot speed model
        sp, n = self.space, len(self.rows)
        shape = (n, sp.S, sp.T)
        self.hand = view.in_hand[self.rows] & ~view.is_break[self.rows]
        self.cue = np.broadcast_to(view.pos[self.rows, 0][:, None, None], shape + (2,)).copy()
        for name in ("phi", "base", "prob", "cut", "dcg", "dop", "half", "want"):
            setattr(self, name, np.zeros(shape))
        self.open_, self.mask = np.zeros(shape, bool), np.zeros(shape, bool)
        legal = view.targets[self.rows] & view.on_table[self.rows]
        legal[:, 0] = False
        self.legal = legal
        self._pots(view)
        self._others(view)
        eight = (self.space.ball == 8) & (self.space.kind == POT)
        self.call = np.zeros(n, np.int64)
        if eight.any():
            self.call = self.space.pocket[eight][np.argmax(self.prob[:, eight, CENTRE], axis=1)]

    # --- pots --------------------------------------------------------------------------------------------------
    def _pots(self, view):
        sp, rows, n = self.space, self.rows, len(self.rows)
        R, P, O = view.params.R, sp.n_pockets, sp.n_balls - 1
        w = windows_of(view)
        aim_sigma = max(math.radians(view.noise.aim_deg), MIN_AIM_SIGMA)
        li, b, p = (x.ravel() for x in np.meshgrid(np.arange(n), np.arange(1, O + 1), np.arange(P), indexing="ij"))
        obj = view.pos[rows[li], b]
        th, half, aimpt, dop = w.aim(p, obj)
        # the same aims per (table, ball, pocket), ball 0 unused: pot_options' from where the cue ball lies
        aims = [np.concatenate([np.zeros((n, 1, P) + x.shape[1:]), x.reshape((n, O, P) + x.shape[1:])], axis=1)
                for x in (th, half, aimpt, dop)]
        slot = sp.pot_slot(b, p)
        self.half[li, slot] = half[:, None]
        self.dop[li, slot] = dop[:, None]
        hand = self.hand[li]
        # starts: the cue ball where it lies (one per table), or per (pot, turn) a spot behind the ghost ball
        starts = [(np.flatnonzero(~self.hand), None)]
        if hand.any():
            h = np.flatnonzero(hand)
            T = len(TURNS)
            ang = th[h, None] + np.asarray(TURNS)[None]
            ghost = obj[h] - 2 * R * np.column_stack([np.cos(th[h]), np.sin(th[h])])
            spot = ghost[:, None] - HAND_DCG * np.stack([np.cos(ang), np.sin(ang)], axis=-1)
            hrow = np.repeat(li[h], T)
            spot, _ = view.legal_placement(spot.reshape(-1, 2), rows[hrow])
            self.cue[hrow, np.repeat(slot[h], T), np.tile(np.arange(T), len(h))] = spot
            starts.append((np.arange(len(h) * T), (hrow, np.repeat(b[h], T), np.repeat(slot[h], T),
                                                   np.tile(np.arange(T), len(h)), spot)))
        for ids, where in starts:
            if not len(ids):
                continue
            if where is None:   # the cue ball where it lies: every legal ball into every pocket
                srow, cue, tg = ids, view.pos[rows[ids], 0], self.legal[ids]
            else:               # one ball from each ball-in-hand spot
                srow, ball, _, _, cue = where
                tg = np.zeros((len(srow), sp.n_balls), bool)
                tg[np.arange(len(srow)), ball] = True
            pos = view.pos[rows[srow]].copy()
            pos[:, 0] = cue
            on = view.on_table[rows[srow]].copy()
            on[:, 0] = True
            o = pot_options(view, pos, on, tg, cue, aim_sigma, aims=None if where else [x[srow] for x in aims])
            if where is None:
                li_o, s_o, t_o = srow[o["start"]], sp.pot_slot(o["ball"], o["pocket"]), np.full(len(o["start"]), CENTRE)
                keep = np.ones(len(li_o), bool)
            else:
                li_o, s_o, t_o = where[0][o["start"]], where[2][o["start"]], where[3][o["start"]]
                keep = sp.pot_slot(o["ball"], o["pocket"]) == s_o      # the pocket this spot was placed for
            li_o, s_o, t_o = li_o[keep], s_o[keep], t_o[keep]
            o = {k: v[keep] for k, v in o.items()}
            idx = (li_o, s_o, t_o)
            self.mask[idx] = True
            self.phi[idx], self.want[idx], self.prob[idx] = o["phi0"], o["want"], o["prob"]
            self.cut[idx], self.dcg[idx], self.open_[idx] = o["cut"], o["dcg"], o["prob"] > 0
            self.base[idx] = self.la.pot_speed(view, o["dcg"], o["dop"], o["cut"])

    # --- contact lines, kicks and the fan ------------------------------------------------------------------------
    def _others(self, view):
        sp, rows, n = self.space, self.rows, len(self.rows)
        R, O = view.params.R, sp.n_balls - 1
        spot = self.hand_spot(view)
        self.cue[:, sp.kind != POT] = spot[:, None, None]
        legal = self.legal.copy()
        legal[~legal.any(axis=1), 1:] = True                       # nothing legal in sight: any ball (champion's rule)
        legal &= view.on_table[rows]
        li, b = (x.ravel() for x in np.meshgrid(np.arange(n), np.arange(1, O + 1), indexing="ij"))
        pos = view.pos[rows[li]].copy()
        pos[:, 0] = spot[li]
        on = view.on_table[rows[li]].copy()
        on[:, 0] = True
        ok = legal[li, b]
        phi, path, blocked = G.contact_shots(pos, on, b, np.asarray(FULLNESS), R, view.table.width, view.table.length)
        s = sp.start[SAFE] + (b - 1)[:, None] * len(FULLNESS) + np.arange(len(FULLNESS))[None]
        self._fill(li[:, None], s, phi, path, ~blocked, ok[:, None])
        phi, path, blocked = G.kick_shots(pos, on, b, R, view.table.width, view.table.length, view.pockets)
        s = sp.start[BANK] + (b - 1)[:, None] * N_RAILS + np.arange(N_RAILS)[None]
        self._fill(li[:, None], s, phi, path, ~blocked, ok[:, None])
        fan = sp.start[FAN] + np.arange(N_FAN)
        self.phi[:, fan, CENTRE] = 2 * np.pi * np.arange(N_FAN) / N_FAN
        self.mask[:, fan, CENTRE] = True

    def _fill(self, li, s, phi, path, open_, ok):
        self.phi[li, s, CENTRE], self.base[li, s, CENTRE] = phi, path
        self.open_[li, s, CENTRE], self.mask[li, s, CENTRE] = open_, np.broadcast_to(ok, s.shape)

    def hand_spot(self, view) -> np.ndarray:
        """[n, 2] where the cue ball is played from for every shot but a placed pot: where it lies, or with ball
        in hand the straight-line spot of the easiest pot (the head spot behind the head string, else the table's
        centre, when no pot is open)."""
        sp = self.space
        spot = view.pos[self.rows, 0].copy()
        h = np.flatnonzero(self.hand)
        if len(h):
            pots = np.flatnonzero(sp.kind == POT)
            prob = np.where(self.mask[h][:, pots, CENTRE], self.prob[h][:, pots, CENTRE], -1.0)
            best = pots[np.argmax(prob, axis=1)]
            spot[h] = self.cue[h, best, CENTRE]
            none = prob.max(axis=1) <= 0
            if none.any():
                kitchen = view.ball_in_hand[self.rows[h]] == RR.IN_HAND_KITCHEN
                fallback = np.where(kitchen[:, None], view.marks.head_spot, [view.table.width / 2,
                                                                             view.table.length / 2])
                spot[h[none]], _ = view.legal_placement(fallback[none], self.rows[h[none]])
        return spot


def decode(layout: Layout, li, joint) -> dict:
    """The shots of proposals ``joint`` [k] on layout rows ``li`` [k] (not yet refined): a candidate dict of flat
    arrays (row, phi, speed, a, b, placement, pocket, ball, safe, prob, kind, joint, cue, obj, want), as champion's
    candidates."""
    view, sp = layout.view, layout.space
    li, joint = np.asarray(li, np.int64), np.asarray(joint, np.int64)
    s, t, v = sp.split(joint)
    si, hi = v // HEIGHT_BINS, v % HEIGHT_BINS
    kind, params = sp.kind[s], view.params
    base, height = layout.base[li, s, t], np.asarray(HEIGHTS)[hi]
    speed = np.select([kind == POT, kind == SAFE, kind == BANK],
                      [base * np.asarray(POT_SPEEDS)[si],
                       G.rolling_strike_speed(base, np.asarray(SAFE_ARRIVALS)[si], params),
                       G.rolling_strike_speed(base, np.asarray(BANK_ARRIVALS)[si], params)],
                      np.asarray(FAN_SPEEDS)[si])
    speed = np.clip(speed, 0.05, params.max_speed)
    a = np.zeros(len(li))
    b = height / np.maximum(np.abs(height) / (MISCUE_MARGIN * params.miscue_limit), 1.0)  # inside the miscue disc
    cue = layout.cue[li, s, t]
    row = layout.rows[li]
    hand = layout.hand[li]
    calls_ball = bool(getattr(view.rules, "calls_ball", False))
    pot = kind == POT
    ball = np.where(pot, sp.ball[s], 0) if calls_ball else np.full(len(li), -1)
    pocket = np.where(pot, sp.pocket[s], np.where(view.call_needed[row], layout.call[li], 0))
    obj = view.pos[row, np.maximum(sp.ball[s], 0)]
    return dict(row=row, phi=layout.phi[li, s, t].copy(), speed=speed, a=a, b=b,
                placement=np.where(hand[:, None], cue, np.nan), pocket=pocket.astype(np.int64),
                ball=ball.astype(np.int64), safe=~pot, prob=np.where(pot, layout.prob[li, s, t], 0.0), kind=kind,
                joint=joint, cue=cue, obj=obj, want=layout.want[li, s, t])


def refine(view, c: dict) -> dict:
    """The pots of candidates ``c`` with their aims corrected for throw (``aim.corrected``), in place."""
    pot = np.flatnonzero(c["kind"] == POT)
    if len(pot):
        c["phi"][pot] = AIM.corrected(view, c["cue"][pot], c["obj"][pot], c["want"][pot], c["phi"][pot],
                                      c["speed"][pot], c["a"][pot], c["b"][pot])
    return c


def legal_proposals(layout: Layout, li: int) -> np.ndarray:
    """Every legal proposal's joint index on layout row ``li``."""
    sp = layout.space
    s, t = np.nonzero(layout.mask[li])
    return (sp.index(s, t, 0)[:, None] + np.arange(sp.V)[None]).ravel()


def encode(layout: Layout, li, plan) -> np.ndarray:
    """[k] the legal proposal nearest to each plan row (plan row j played on layout row ``li[j]``): the least sum
    of the aim's, the log speed's, the tip height's and (with ball in hand) the placement's differences in
    ``ENCODE_SCALE`` units. A decoded proposal (not refined) comes back as itself."""
    out = np.empty(len(li), np.int64)
    d_aim, d_speed, d_height, d_place = ENCODE_SCALE
    for j, r in enumerate(np.asarray(li, np.int64)):
        cand = legal_proposals(layout, r)
        c = decode(layout, np.full(len(cand), r), cand)
        dphi = np.abs((c["phi"] - plan.phi[j] + np.pi) % (2 * np.pi) - np.pi) / d_aim
        dist = (dphi + np.abs(np.log(c["speed"] / max(plan.speed[j], 1e-6))) / d_speed
                + np.abs(c["b"] - plan.b[j]) / d_height)
        if layout.hand[r] and np.isfinite(plan.placement[j]).all():
            dist = dist + np.linalg.norm(c["cue"] - plan.placement[j], axis=1) / d_place
        out[j] = cand[np.argmin(dist)]
    return out
