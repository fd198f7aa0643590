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


@numba.njit(cache=True, nogil=True)
def _pot(pos_e, on_e, b, cx, cy, hand, win, lim):
    """Ball ``b``'s best pot on one table from a cue ball at (cx, cy) (``hand``: placed at ``HAND_DCG``), in
    ``_ease``'s model: (success estimate, ghost x, y, the object ball's direction x, y); (0, ...) with none."""
    ref = win[3]
    R, clear, max_cut, sig_aim, sig_model, hand_dcg, min_cos = lim
    d2 = (2 * R + clear) ** 2
    best, bgx, bgy, bux, buy = 0.0, 0.0, 0.0, 0.0, 0.0
    ox, oy = pos_e[b, 0], pos_e[b, 1]
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
        if hand:
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
        if blocked(pos_e, on_e, b, -1, ox, oy, tx, ty, d2):
            continue
        if not hand and blocked(pos_e, on_e, b, -1, cx, cy, gx, gy, d2):
            continue
        best, bgx, bgy, bux, buy = q, gx, gy, ux, uy
    return best, bgx, bgy, bux, buy


@numba.njit(cache=True, nogil=True)
def _chain(pos, on, targets, hand, rotation, game_ball, depth, box, win, lim, v_none, v_full, out):
    """out[e]: the next shooter's value of table e looking ``depth`` pots ahead: greedily the best pot of the
    legal balls (``_pot``), then from where its cue ball may stop (the ghost ball and 0.25 m back, 0.25 and 0.5 m
    on along the object ball's line, inside ``box`` = (x min, x max, y min, y max)) the best pot of the next legal
    ball (rotation games: the lowest left; groups: the targets left, then the game ball), and so on; each pot
    of success q turns the value v of what follows into v_none + (v - v_none) q; the game ball potted is 1, the
    last level's continuation v_full. ``depth`` 1 is ``position_value`` of ``_ease``'s best pot."""
    B = pos.shape[1]
    for e in range(pos.shape[0]):
        pe = pos[e].copy()
        oe = on[e].copy()
        tg = targets[e].copy()
        qs = np.zeros(depth)
        final = np.zeros(depth, dtype=np.bool_)
        n = 0
        starts = np.zeros((4, 2))
        n_starts = 1
        starts[0, 0], starts[0, 1] = pe[0, 0], pe[0, 1]
        in_hand = hand[e] or not oe[0]
        if not (hand[e] or oe[0]):
            out[e] = v_none
            continue
        for k in range(depth):
            best, bb, gx, gy, ux, uy = 0.0, -1, 0.0, 0.0, 0.0, 0.0
            for si in range(n_starts):
                for b in range(1, B):
                    if not (tg[b] and oe[b]):
                        continue
                    q, x, y, dx, dy = _pot(pe, oe, b, starts[si, 0], starts[si, 1], in_hand, win, lim)
                    if q > best:
                        best, bb, gx, gy, ux, uy = q, b, x, y, dx, dy
            if bb < 0:
                break
            qs[n] = best
            final[n] = bb == game_ball
            n += 1
            if final[n - 1]:
                break
            oe[bb] = False
            pe[0, 0], pe[0, 1] = gx, gy
            in_hand = False
            n_starts = 0
            for t in (0.0, -0.25, 0.25, 0.5):
                sx = min(max(gx + t * ux, box[0]), box[1])
                sy = min(max(gy + t * uy, box[2]), box[3])
                starts[n_starts, 0], starts[n_starts, 1] = sx, sy
                n_starts += 1
            # the next legal balls
            left = 0
            if rotation:
                for b in range(B):
                    tg[b] = False
                for b in range(1, B):
                    if oe[b]:
                        tg[b] = True
                        left = 1
                        break
            else:
                tg[bb] = False
                for b in range(1, B):
                    if tg[b] and oe[b]:
                        left += 1
                if left == 0 and game_ball > 0 and oe[game_ball]:
                    tg[game_ball] = True
                    left = 1
            if left == 0:
                break
        if n == 0:
            out[e] = v_none
            continue
        v = 1.0 if final[n - 1] else v_full
        for k in range(n - 1, -1, -1):
            v = v_none + (v - v_none) * qs[k]
        out[e] = v


def chain_value(view, pos, on, targets, hand, depth: int) -> np.ndarray:
    """[k] the next shooter's value of tables ``pos`` [k, B, 2] looking ``depth`` pots ahead (``_chain``)."""
    w = windows_of(view)
    out = np.empty(len(pos))
    rules, t, R = view.rules, view.table, view.params.R
    lim = (R, CLEAR, MAX_CUT, max(math.radians(view.noise.aim_deg), MIN_AIM_SIGMA), SIGMA_MODEL,
           HAND_DCG, MIN_COS)
    _chain(np.ascontiguousarray(pos), np.ascontiguousarray(on, dtype=np.bool_),
           np.ascontiguousarray(targets, dtype=np.bool_), np.ascontiguousarray(hand, dtype=np.bool_),
           not rules.groups, int(rules.game_ball), int(depth), (2 * R, t.width - 2 * R, 2 * R, t.length - 2 * R),
           (np.ascontiguousarray(w.centre), np.ascontiguousarray(w.half), np.ascontiguousarray(w.base),
            np.ascontiguousarray(w.ref), float(ANGLES[0]), float(ANGLES[1] - ANGLES[0])), lim, V_NONE, V_FULL, out)
    return out


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


def values(view, pv, depth: int = 1) -> np.ndarray:
    """The mover's value of each previewed shot: 1 a win, 0 a loss; keeping the table, ``position_value`` of
    the leave's ease (``depth`` > 1: ``chain_value``, that many pots ahead); handing it over, 1 minus the
    opponent's (with ball in hand after a foul)."""
    rec, nxt = pv.record, pv.next
    hand = nxt.ball_in_hand != RR.IN_HAND_NONE
    if depth > 1:
        v = chain_value(view, pv.pos, pv.on_table, nxt.targets, hand, depth)
    else:
        v = position_value(leave_ease(view, pv.pos, pv.on_table, nxt.targets, hand), V_NONE, V_FULL)
    val = np.where(nxt.shooter == rec.shooter, v, 1.0 - v)
    return np.where(rec.game_over, (rec.winner == rec.shooter).astype(np.float64), val)
