"""The one-ply leave, in the planner's own pot model: a table after a shot is worth ``position_value`` of the
ease of its next shooter's best pot, the ease being that pot's success estimate with the aim through the
measured pocket window (``windows``) and the aim noise carried through the contact, as ``candidates`` ranks its
pots (lookahead's own leave aims at pocket centres: side pots at angles it calls closed or misjudges).
"""
from __future__ import annotations

import math

import numba
import numpy as np

from ...rules import records as RR
from ..game_lookahead import position_value
from ..geometry.lines import blocked
from .candidates import CLEAR, MAX_CUT, SIGMA_MODEL
from .windows import ANGLES, windows_of

HAND_DCG = 0.3      # m: the cue-to-ghost distance a shooter with ball in hand is assumed to place
MIN_AIM_SIGMA = math.radians(0.125)  # rad: the aim noise leaves are judged with at least (tournament level)
MIN_COS = 0.15      # the contact error's 1 / cos(cut) is capped here (the thinnest cuts)
V_NONE = 0.5        # a table with no pot: a safety battle, even (lookahead's V_NONE)
V_FULL = 0.9        # a sure pot: the run may still end (lookahead's V_FULL)


@numba.njit(cache=True, nogil=True)
def _window(win, p, th):
    """Pocket ``p``'s measured window at approach angle ``th``: (centre offset, half-width), interpolated in
    ``win`` = (centre [P, A], half [P, A], base [P], ref [P, 2], first angle, angle step); (0, 0) outside."""
    centre, half, base, _, a0, da = win
    rel = (th - base[p] + math.pi) % (2 * math.pi) - math.pi
    x = (rel - a0) / da
    A = centre.shape[1]
    if x < 0 or x > A - 1:
        return 0.0, 0.0
    i = min(int(math.floor(x)), A - 2)
    f = x - i
    return (1 - f) * centre[p, i] + f * centre[p, i + 1], min(half[p, i], half[p, i + 1])


@numba.njit(cache=True, nogil=True)
def _ease(pos, on, targets, hand, win, lim, out):
    """out[e]: the best success estimate over table e's legal pots (0: none, or no cue ball); ``win``: the
    windows as ``_window`` takes them."""
    ref = win[3]
    R, clear, max_cut, sig_aim, sig_model, hand_dcg, min_cos = lim
    d2 = (2 * R + clear) ** 2
    for e in range(pos.shape[0]):
        best = 0.0
        if hand[e] or on[e, 0]:
            cx, cy = pos[e, 0, 0], pos[e, 0, 1]
            for b in range(1, pos.shape[1]):
                if not (targets[e, b] and on[e, b]):
                    continue
                ox, oy = pos[e, b, 0], pos[e, b, 1]
                for p in range(ref.shape[0]):
                    th = math.atan2(ref[p, 1] - oy, ref[p, 0] - ox)
                    c, h = 0.0, 0.0
                    tx, ty = ref[p, 0], ref[p, 1]
                    for _ in range(2):
                        c, h = _window(win, p, th)
                        tx, ty = ref[p, 0] - c * math.sin(th), ref[p, 1] + c * math.cos(th)
                        th = math.atan2(ty - oy, tx - ox)
                    c, h = _window(win, p, th)
                    if h <= 0.0:
                        continue
                    dop = math.hypot(tx - ox, ty - oy)
                    ux, uy = math.cos(th), math.sin(th)
                    gx, gy = ox - 2 * R * ux, oy - 2 * R * uy
                    if hand[e]:
                        dcg, cosc = hand_dcg, 1.0
                    else:
                        vx, vy = gx - cx, gy - cy
                        dcg = math.hypot(vx, vy)
                        if dcg < 1e-9:
                            continue
                        cosc = (vx * ux + vy * uy) / dcg
                        if cosc < math.cos(max_cut):
                            continue
                    sig = math.hypot(sig_aim * dcg / (2 * R * max(cosc, min_cos)), sig_model)
                    q = math.erf(math.atan2(h, max(dop, 1e-6)) / (math.sqrt(2.0) * sig))
                    if q <= best:
                        continue
                    if blocked(pos[e], on[e], b, -1, ox, oy, tx, ty, d2):
                        continue
                    if not hand[e] and blocked(pos[e], on[e], b, -1, cx, cy, gx, gy, d2):
                        continue
                    best = q
        out[e] = best


def leave_ease(view, pos, on, targets, hand) -> np.ndarray:
    """[k] the ease of the next shooter's best pot on tables ``pos`` [k, B, 2] (``hand`` [k]: ball in hand)."""
    w = windows_of(view)
    out = np.empty(len(pos))
    lim = (view.params.R, CLEAR, MAX_CUT, max(math.radians(view.noise.aim_deg), MIN_AIM_SIGMA), SIGMA_MODEL,
           HAND_DCG, MIN_COS)
    _ease(np.ascontiguousarray(pos), np.ascontiguousarray(on, dtype=np.bool_),
          np.ascontiguousarray(targets, dtype=np.bool_), np.ascontiguousarray(hand, dtype=np.bool_),
          (np.ascontiguousarray(w.centre), np.ascontiguousarray(w.half), np.ascontiguousarray(w.base),
           np.ascontiguousarray(w.ref), float(ANGLES[0]), float(ANGLES[1] - ANGLES[0])), lim, out)
    return out


def values(view, pv) -> np.ndarray:
    """The mover's value of each previewed shot: 1 a win, 0 a loss; keeping the table, ``position_value`` of
    the leave's ease; handing it over, 1 minus the opponent's (with ball in hand after a foul)."""
    rec, nxt = pv.record, pv.next
    hand = nxt.ball_in_hand != RR.IN_HAND_NONE
    v = position_value(leave_ease(view, pv.pos, pv.on_table, nxt.targets, hand), V_NONE, V_FULL)
    val = np.where(nxt.shooter == rec.shooter, v, 1.0 - v)
    return np.where(rec.game_over, (rec.winner == rec.shooter).astype(np.float64), val)
