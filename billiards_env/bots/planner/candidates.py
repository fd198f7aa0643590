"""The shots the search considers, as flat arrays (row, phi, speed, a, b, placement, pocket, ball, safe):

- **pots** from every start (the cue ball where it lies, or searched ball-in-hand spots): every legal ball into
  every pocket whose measured window (``windows``) admits the approach, the paths clear, ranked by a success
  estimate (the window's angular half-width against the aim noise carried through the contact), the best few in
  speed and tip-height variants, each aim corrected for throw (``aim``);
- **safeties and kicks**: ``GameLookahead``'s soft shots at the legal balls and one-rail kicks, plus a 360-degree
  fan of cue directions at a few speeds (the preview keeps what the rules call legal); a grid of soft shots at the
  nearest legal balls (``safety_grid``); on a hooked table, the kicks found by scanning the simulator
  (``kick_scan``);
- **escapes** from a hook, where the equipment lets balls fly (``Effects(airborne=True)``): jump strokes over the
  blocker and massé strokes that curve around it, at the nearest legal balls of the tables with no open pot; the
  preview (which flies them as the env does) judges them with the safeties.
"""
from __future__ import annotations

import math

import numba
import numpy as np

from ...contract.plan import ShotPlan
from ...physics.strike import Shots
from ...rules import records as RR
from ..geometry.lines import blocked
from . import aim as AIM
from .windows import windows_of

MAX_CUT = math.radians(80)        # a cut thinner than this is not tried (the contact error explodes)
CLEAR = 0.003                     # m: a pot's paths keep this clear of other balls beyond 2R
SIGMA_MODEL = 0.004               # rad: object-ball direction error left after the throw correction
N_POTS = 8                        # pots tried per start (cue ball where it lies)
N_POTS_HAND = 2                   # and per ball-in-hand spot
SPEEDS = (1.15, 1.6, 2.3, 3.3)    # factors of the speed that just drops the ball (soft to firm, for position)
HEIGHTS = (-0.4, 0.0, 0.4)        # tip heights (units of R): draw, stun, follow
SIDES = (0.0,)                    # tip side offsets (units of R): centre ball (side spin measured no gain here)
MISCUE_MARGIN = 0.98              # tip offsets kept within this fraction of the miscue limit (the check is strict)
FAN_DIRS = 48                     # the kick scan: this many cue directions around the full circle
FAN_SPEEDS = (1.2, 2.6, 4.5)      # m/s: at these speeds
HOOKED_PROB = 0.2                 # a table whose best pot from where the cue ball lies is less likely is hooked
ESCAPE_TARGETS = 3                # escapes try this many legal balls, the nearest first
JUMP_THETAS = tuple(math.radians(d) for d in (30, 45, 55))  # jump strokes: the cue this steep ...
JUMP_SPEEDS = (3.0, 4.5, 6.0)                               # ... at these speeds (m/s), at the ball's centre
MASSE_THETAS = tuple(math.radians(d) for d in (50, 60))     # massé strokes: a steep cue, at most the env action's ...
MASSE_SIDE = 0.45                 # ... with this much side (units of R; inside the miscue disc) ...
MASSE_TURNS = tuple(math.radians(d) for d in (10, 20, 35))  # ... aimed this far off the ball, the curve bringing it back
MASSE_SPEEDS = (2.0, 3.5)         # m/s


@numba.njit(cache=True, nogil=True)
def _paths_open(pos, on, srow, ball, cue, ghost, aimpt, d2, out):
    """out[k]: cue -> ghost and ball -> aim point clear of every other ball on table srow[k]."""
    for k in range(len(out)):
        e, b = srow[k], ball[k]
        out[k] = not (blocked(pos[e], on[e], b, -1, cue[k, 0], cue[k, 1], ghost[k, 0], ghost[k, 1], d2)
                      or blocked(pos[e], on[e], b, -1, pos[e, b, 0], pos[e, b, 1], aimpt[k, 0], aimpt[k, 1], d2))


def pot_options(view, pos, on, tg, cue, aim_sigma, aims=None):
    """Every open pot of the legal balls from cue balls ``cue`` [S, 2] on tables ``pos`` [S, B, 2]: dict of flat
    arrays (start, ball, pocket, want (the object ball's direction), phi0 (ghost-ball aim), prob, dcg, dop, cut).
    ``aims``: the windows' aims (``Windows.aim``: direction, half-width, aim point, distance) of every ball into
    every pocket, [S, B, P] (the point [S, B, P, 2]), when the caller has them already."""
    R = view.params.R
    w = windows_of(view)
    S, B = pos.shape[:2]
    P = len(w.ref)
    s_i, b_i, p_i = np.nonzero((tg & on)[:, :, None] & np.ones((1, 1, P), bool))
    keep = b_i > 0
    s_i, b_i, p_i = s_i[keep], b_i[keep], p_i[keep]
    obj = pos[s_i, b_i]
    th, half, aimpt, dop = w.aim(p_i, obj) if aims is None else (x[s_i, b_i, p_i] for x in aims)
    u = np.column_stack([np.cos(th), np.sin(th)])
    ghost = obj - 2 * R * u
    v = ghost - cue[s_i]
    dcg = np.linalg.norm(v, axis=1)
    cos_cut = np.einsum("ij,ij->i", v, u) / np.maximum(dcg, 1e-9)
    cut = np.arccos(np.clip(cos_cut, -1, 1))
    ok = (half > 0) & (cut < MAX_CUT) & (dcg > 1e-6)
    s_i, b_i, p_i, th, half, aimpt, dop, ghost, dcg, cut = (x[ok] for x in (s_i, b_i, p_i, th, half, aimpt, dop,
                                                                           ghost, dcg, cut))
    opened = np.zeros(len(s_i), np.bool_)
    _paths_open(np.ascontiguousarray(pos), np.ascontiguousarray(on), s_i, b_i, np.ascontiguousarray(cue[s_i]),
                np.ascontiguousarray(ghost), np.ascontiguousarray(aimpt), (2 * R + CLEAR) ** 2, opened)
    sig = np.hypot(aim_sigma * dcg / (2 * R * np.maximum(np.cos(cut), 0.15)), SIGMA_MODEL)
    tol = np.arctan2(half, np.maximum(dop, 1e-6))
    prob = np.where(opened, np.array([math.erf(x) for x in (tol / (math.sqrt(2) * sig))]), 0.0)
    vg = ghost - cue[s_i]
    phi0 = np.arctan2(vg[:, 1], vg[:, 0])
    return dict(start=s_i, ball=b_i, pocket=p_i, want=th, phi0=phi0, prob=prob, dcg=dcg, dop=dop, cut=cut)


def top_per_start(start, prob, n_start, k_of_start):
    """Indices of the ``k_of_start[s]`` most probable options of each start (probability > 0)."""
    order = np.lexsort((-prob, start))
    st = start[order]
    first = np.searchsorted(st, np.arange(n_start))
    rank = np.arange(len(order)) - first[st]
    sel = order[(rank < k_of_start[st]) & (prob[order] > 0)]
    return np.sort(sel)


def pots(bot, view, srow, cue, placed, aim_sigma, throw=True, speeds=SPEEDS, heights=HEIGHTS, sides=SIDES):
    """The pot candidates of starts (view rows ``srow`` [S], cue balls ``cue`` [S, 2], ``placed`` [S])."""
    pos = view.pos[srow].copy()
    pos[:, 0] = cue
    on = view.on_table[srow].copy()
    on[:, 0] = True
    o = pot_options(view, pos, on, view.targets[srow], cue, aim_sigma)
    k = np.where(placed, N_POTS_HAND, N_POTS)
    sel = top_per_start(o["start"], o["prob"], len(srow), k)
    o = {key: val[sel] for key, val in o.items()}
    sp, hb, sd = (np.asarray(x, dtype=np.float64).ravel() for x in np.meshgrid(speeds, heights, sides, indexing="ij"))
    V = len(sp)
    rep = np.repeat(np.arange(len(sel)), V)
    var = np.tile(np.arange(V), len(sel))
    st = o["start"][rep]
    v0 = bot.la.pot_speed(view, o["dcg"], o["dop"], o["cut"])[rep]
    speed = np.minimum(v0 * sp[var], view.params.max_speed)
    a, b = sd[var], hb[var]
    r = np.hypot(a, b) / (MISCUE_MARGIN * view.params.miscue_limit)   # tip offsets kept inside the miscue disc
    a, b = a / np.maximum(r, 1.0), b / np.maximum(r, 1.0)
    phi = o["phi0"][rep]
    if throw and len(rep):
        phi = AIM.corrected(view, cue[st], pos[st, o["ball"][rep]], o["want"][rep], phi, speed, a, b)
    m = len(rep)
    return dict(row=srow[st], phi=phi, speed=speed, a=a, b=b,
                placement=np.where(placed[st, None], cue[st], np.nan), pocket=o["pocket"][rep],
                ball=o["ball"][rep], safe=np.zeros(m, bool), prob=o["prob"][rep])


def safeties(bot, view, rows, cue, placed):
    """``GameLookahead``'s safeties and one-rail kicks, and the kick fan, from cue balls ``cue`` [n, 2]."""
    c = bot.la.safeties(view, rows, cue, placed)
    n = len(rows)
    F = FAN_DIRS * len(FAN_SPEEDS)
    rep = np.repeat(np.arange(n), F)
    phi = np.tile(np.repeat(np.linspace(0, 2 * np.pi, FAN_DIRS, endpoint=False), len(FAN_SPEEDS)), n)
    phi = phi + bot.rng.uniform(0, 2 * np.pi / FAN_DIRS, n)[rep]     # the fan turned at random per table
    speed = np.tile(np.asarray(FAN_SPEEDS, dtype=np.float64), FAN_DIRS * n)
    call = np.zeros(n, np.int64)
    need = view.call_needed[rows]
    if need.any():
        call[need] = bot.la.eight_pocket(view, rows[need])            # the pocket lookahead's safeties call
    pocket = call[rep]
    fan = dict(row=rows[rep], phi=phi, speed=speed, a=np.zeros(len(rep)), b=np.zeros(len(rep)),
               placement=np.where(placed[rep, None], cue[rep], np.nan), pocket=pocket, safe=np.ones(len(rep), bool))
    out = {key: np.concatenate([c[key], fan[key]]) for key in fan}
    out["ball"] = np.full(len(out["row"]), -1, np.int64)
    out["prob"] = np.zeros(len(out["row"]))
    return out


def _nearest_targets(view, rows, cue, k):
    """The ``k`` nearest legal balls of each table among ``rows`` from cue balls ``cue`` [n, 2]: (the local row of
    each pair [m], its ball [m], the vector from the cue ball to it [m, 2])."""
    on = view.on_table[rows] & view.targets[rows]
    on[:, 0] = False
    d = np.where(on, np.hypot(*(view.pos[rows] - cue[:, None]).transpose(2, 0, 1)), np.inf)
    order = np.argsort(d, axis=1, kind="stable")[:, :k]
    t_row, t_k = np.nonzero(np.take_along_axis(d, order, axis=1) < np.inf)
    ball = order[t_row, t_k]
    return t_row, ball, view.pos[rows[t_row], ball] - cue[t_row]


def _calls(bot, view, rows):
    """[n] the pocket a safety on each table among ``rows`` calls: lookahead's choice for the 8 where a call is
    needed (8-ball), else -1."""
    call = np.full(len(rows), -1, np.int64)
    need = view.call_needed[rows]
    if need.any():
        call[need] = bot.la.eight_pocket(view, rows[need])
    return call


SCAN_DIRS = 360                   # the kick scan of a hooked table: this many cue directions, noise-free ...
SCAN_SPEED = 2.5                  # m/s: ... at this speed, finding the direction runs that hit a legal ball legally
SCAN_RUNS = 6                     # the widest runs kept per table ...
SCAN_SPEEDS = (1.6, 2.5, 4.0)     # m/s: ... each struck at its centre at these speeds (and off-centre where wide)
SCAN_WIDE = 3                     # a run this many directions wide or wider is also struck a quarter in from each end


def kick_scan(bot, view, rows, cue, placed):
    """Kicks found by scanning the simulator (champion's): on the tables among ``rows`` whose cue ball lies where
    it is (``cue`` [n, 2], not ``placed``) and meets no legal ball full along a clear line, ``SCAN_DIRS``
    directions around the circle are previewed without noise at ``SCAN_SPEED``; the runs of neighbouring
    directions whose shot is legal (first a legal ball, then a rail) are where a kick gets there, the widest the
    most forgiving of aim error. The ``SCAN_RUNS`` widest give candidates at their centres (and, from
    ``SCAN_WIDE`` directions, a quarter in from each end) at ``SCAN_SPEEDS``. None where no table needs them."""
    R_ = view.params.R
    on = view.on_table[rows].copy()
    on[:, 0] = False
    tg = view.targets[rows] & on
    seen = np.empty(len(rows), np.bool_)
    _hittable(np.ascontiguousarray(view.pos[rows]), np.ascontiguousarray(on), np.ascontiguousarray(tg),
              np.ascontiguousarray(cue), R_, (2 * R_ + CLEAR) ** 2, seen)
    hooked = np.flatnonzero(~seen & ~placed)
    if not len(hooked):
        return None
    hr = rows[hooked]
    D = SCAN_DIRS
    step = 2 * np.pi / D
    rep = np.repeat(hr, D)
    phi = np.tile(np.arange(D) * step, len(hr)) + bot.rng.uniform(0, step, len(hr)).repeat(D)
    call = _calls(bot, view, hr)
    plan = ShotPlan.of(Shots(phi, np.full(len(rep), SCAN_SPEED), 0.0, 0.0), pocket=call.repeat(D))
    pv = view.preview(plan, rep)
    bot.sims += len(rep)
    legal = (pv.record.foul == RR.FOUL_NONE).reshape(len(hr), D)
    out_row, out_phi = [], []
    for i in range(len(hr)):
        runs = _runs(legal[i])
        for start, length in runs[:SCAN_RUNS]:
            mid = phi[i * D] + (start + (length - 1) / 2) * step
            offs = [0.0] + ([-length / 4 * step, length / 4 * step] if length >= SCAN_WIDE else [])
            out_phi += [mid + o for o in offs]
            out_row += [i] * len(offs)
    if not out_row:
        return None
    k = np.repeat(np.asarray(out_row, np.int64), len(SCAN_SPEEDS))
    m = len(k)
    return dict(row=hr[k], phi=np.repeat(np.asarray(out_phi), len(SCAN_SPEEDS)) % (2 * np.pi),
                speed=np.tile(np.asarray(SCAN_SPEEDS, np.float64), len(out_row)), a=np.zeros(m), b=np.zeros(m),
                placement=np.full((m, 2), np.nan), pocket=call[k], safe=np.ones(m, bool),
                ball=np.full(m, -1, np.int64), prob=np.zeros(m))


def _runs(ok):
    """[(start, length)] of the runs of True in the circular bool array ``ok``, the longest first."""
    n = len(ok)
    if ok.all():
        return [(0, n)]
    if not ok.any():
        return []
    shift = int(np.argmin(ok))           # start the walk at a False so no run wraps
    o = np.roll(ok, -shift)
    edges = np.diff(np.concatenate([[0], o.astype(np.int8), [0]]))
    starts, ends = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
    runs = [((s + shift) % n, e - s) for s, e in zip(starts, ends)]
    return sorted(runs, key=lambda r: -r[1])


GRID_BALLS = 2                    # the safety grid: soft shots at this many nearest legal balls of a table ...
GRID_CUTS = 9                     # ... at this many contact offsets across each, full to 0.95 of the thinnest ...
GRID_SPEEDS = (0.6, 1.0, 1.6, 2.4, 3.4)   # m/s: ... at these speeds ...
GRID_HEIGHTS = (-0.3, 0.0, 0.3)   # ... and tip heights (units of R): draw, stun, follow


def safety_grid(bot, view, rows, cue, placed):
    """Soft shots on a grid (champion's safeties, beside lookahead's random ones): at the ``GRID_BALLS`` nearest
    legal balls of each table, ``GRID_CUTS`` contact offsets across the ball (the cue ball's line from through
    the centre to 0.95 of the thinnest hit) x ``GRID_SPEEDS`` x ``GRID_HEIGHTS``, from cue balls ``cue`` [n, 2]."""
    R_ = view.params.R
    t_row, _, to = _nearest_targets(view, rows, cue, GRID_BALLS)
    if not len(t_row):
        return None
    dist = np.maximum(np.hypot(to[:, 0], to[:, 1]), 2 * R_)
    half = np.arcsin(np.minimum(2 * R_ / dist, 1.0)) * 0.95
    cut, sp, hb = (x.ravel() for x in np.meshgrid(np.linspace(-1, 1, GRID_CUTS), GRID_SPEEDS, GRID_HEIGHTS,
                                                  indexing="ij"))
    k = len(cut)
    rep = np.repeat(np.arange(len(t_row)), k)
    phi = np.arctan2(to[:, 1], to[:, 0])[rep] + half[rep] * np.tile(cut, len(t_row))
    r = t_row[rep]
    call = _calls(bot, view, rows)
    m = len(rep)
    return dict(row=rows[r], phi=phi, speed=np.tile(np.asarray(sp, np.float64), len(t_row)), a=np.zeros(m),
                b=np.tile(np.asarray(hb, np.float64), len(t_row)),
                placement=np.where(placed[r, None], cue[r], np.nan), pocket=call[r], safe=np.ones(m, bool),
                ball=np.full(m, -1, np.int64), prob=np.zeros(m))


HAND_SAFE_DISTS = (0.35, 0.15, 0.7)  # m: ball-in-hand safety spots this far from a legal ball ...
HAND_SAFE_DIRS = 16                  # ... in these directions around it (taken spread: 0, 180, 90, 270 deg, ...)
HAND_SAFE_SPOTS = 3                  # spots per table


@numba.njit(cache=True, nogil=True)
def _hittable(pos, on, targets, cue, R, d2, out):
    """out[k]: the cue ball at ``cue[k]`` meets some legal ball of table k full, its path (to where it touches
    the ball) clear of every other ball."""
    for k in range(pos.shape[0]):
        out[k] = False
        for b in range(1, pos.shape[1]):
            if not (targets[k, b] and on[k, b]):
                continue
            dx, dy = pos[k, b, 0] - cue[k, 0], pos[k, b, 1] - cue[k, 1]
            d = math.hypot(dx, dy)
            if d <= 2 * R:
                continue
            gx, gy = pos[k, b, 0] - 2 * R * dx / d, pos[k, b, 1] - 2 * R * dy / d
            if not blocked(pos[k], on[k], b, -1, cue[k, 0], cue[k, 1], gx, gy, d2):
                out[k] = True
                break


def _spread(n):
    """0 .. n-1 (a power of 2) ordered so that every prefix is spread around the circle: 0, n/2, n/4, 3n/4, ..."""
    bits = n.bit_length() - 1
    return [int(format(i, f"0{bits}b")[::-1], 2) for i in range(n)]


def hand_safeties(bot, view, rows, cue, placed, pots=None):
    """Safeties from better ball-in-hand spots (champion plays them in 10-ball): on the tables among ``rows``
    with the cue ball in hand whose first start ``cue`` [n, 2] (the spot of their best pot; with no open pot the
    table's centre or the head spot) sees no legal ball in a straight clear line (with ``pots``: or where no pot's
    success estimate reaches ``HOOKED_PROB``), ``GameLookahead``'s safeties and kicks from up to ``HAND_SAFE_SPOTS``
    legal spots that do (around the legal balls, spread in direction); None if no table
    needs them. (With the cue ball placed at the centre and the lowest ball hidden, a 10-ball table's safety
    from there fouled: 23 of champion's 91 ball-in-hand shots at seed 1, 40 racks.)"""
    R_ = view.params.R
    hand = placed & view.in_hand[rows]
    if not hand.any():
        return None
    d2 = (2 * R_ + CLEAR) ** 2
    on = view.on_table[rows].copy()
    on[:, 0] = False
    tg = view.targets[rows] & on
    ok = np.ones(len(rows), bool)
    h = np.flatnonzero(hand)
    out = np.empty(len(h), np.bool_)
    _hittable(np.ascontiguousarray(view.pos[rows[h]]), np.ascontiguousarray(on[h]), np.ascontiguousarray(tg[h]),
              np.ascontiguousarray(cue[h]), R_, d2, out)
    ok[h] = out
    if pots is not None:
        # also where no pot is likely from any start (the lowest ball tied up; then the starts are the centre's
        # fallback, whose safeties, even where it sees the ball, fouled a third of the time)
        best = np.zeros(view.n)
        np.maximum.at(best, pots["row"], pots["prob"])
        ok &= ~hand | (best[rows] >= HOOKED_PROB)
    need = np.flatnonzero(~ok)
    if not len(need):
        return None
    dirs = 2 * np.pi * np.asarray(_spread(HAND_SAFE_DIRS)) / HAND_SAFE_DIRS
    srow, spots = [], []
    for i in need:
        r = rows[i]
        got = []
        for b in np.flatnonzero(tg[i]):
            for dist in HAND_SAFE_DISTS:
                xy = view.pos[r, b] + dist * np.stack([np.cos(dirs), np.sin(dirs)], axis=1)
                legal, moved = view.legal_placement(xy, np.full(len(xy), r))
                test = np.empty(len(xy), np.bool_)
                one = np.zeros_like(tg[i])
                one[b] = True
                _hittable(np.ascontiguousarray(np.repeat(view.pos[r][None], len(xy), axis=0)),
                          np.ascontiguousarray(np.repeat(on[i][None], len(xy), axis=0)),
                          np.ascontiguousarray(np.repeat(one[None], len(xy), axis=0)), np.ascontiguousarray(legal),
                          R_, d2, test)
                got += [legal[j] for j in np.flatnonzero(test)][:HAND_SAFE_SPOTS - len(got)]
                if len(got) >= HAND_SAFE_SPOTS:
                    break
            if len(got) >= HAND_SAFE_SPOTS:
                break
        srow += [r] * len(got)
        spots += got
    if not srow:
        return None
    srow, spots = np.asarray(srow, np.int64), np.asarray(spots, np.float64)
    out = bot.la.safeties(view, srow, spots, np.ones(len(srow), bool))
    out["ball"] = np.full(len(out["row"]), -1, np.int64)
    out["prob"] = np.zeros(len(out["row"]))
    return out


def escapes(bot, view, rows, cue, placed, pots):
    """Jump and massé strokes (``ShotPlan.theta``) at the ``ESCAPE_TARGETS`` nearest legal balls of the tables
    among ``rows`` that are hooked: the cue ball where it lies (not in hand) and no pot from there with a success
    estimate of ``HOOKED_PROB`` (``pots``: ``pots``' candidates). Only where balls fly (the view's effects);
    else nothing. Right side with the cue raised curves the ball right (``physics.strike``), so each massé turns
    the aim away from the ball on the side the curve comes back from."""
    if not view.effects.airborne or not len(rows):
        return None
    best = np.zeros(view.n)
    from_lie = np.isnan(pots["placement"][:, 0])
    np.maximum.at(best, pots["row"][from_lie], pots["prob"][from_lie])
    keep = ~placed & (best[rows] < HOOKED_PROB)
    rows, cue = rows[keep], cue[keep]
    if not len(rows):
        return None
    t_row, _, to = _nearest_targets(view, rows, cue, ESCAPE_TARGETS)
    aim = np.arctan2(to[:, 1], to[:, 0])
    strokes = [(th, v, 0.0, 0.0) for th in JUMP_THETAS for v in JUMP_SPEEDS]
    strokes += [(th, v, side * MASSE_SIDE, turn * side) for th in MASSE_THETAS for v in MASSE_SPEEDS
                for turn in MASSE_TURNS for side in (1.0, -1.0)]
    th, v, a, turn = (np.asarray(x) for x in zip(*strokes))
    k = len(strokes)
    rep = np.repeat(np.arange(len(t_row)), k)
    n = len(rep)
    out = dict(row=rows[t_row][rep], phi=aim[rep] + np.tile(turn, len(t_row)), speed=np.tile(v, len(t_row)),
               a=np.tile(a, len(t_row)), b=np.zeros(n), theta=np.tile(th, len(t_row)),
               placement=np.full((n, 2), np.nan), pocket=_calls(bot, view, rows)[t_row][rep],  # 8-ball: the 8's
               safe=np.ones(n, bool), ball=np.full(n, -1, np.int64), prob=np.zeros(n))
    return out
