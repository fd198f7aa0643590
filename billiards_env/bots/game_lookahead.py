"""``lookahead`` for the two-player games: shots chosen by the position they leave, under sampled noise.

For every table where the bot is to move (all tables at once, in batched ``GameView.preview`` calls):

1. **Starts.** The cue ball where it lies, or, with ball in hand, ``hand_pots`` x ``len(HAND_BACKS)`` x
   ``len(HAND_TURNS)`` searched spots: behind the ghost ball of each of the easiest pots (by ``pot_table``, the
   cue ball placed ideally), at two distances and three angles (a straight-in pot and two cuts that send the cue
   ball different ways), each made legal by ``view.legal_placement``.
2. **Candidates.** From each start: the ``n_pots`` easiest open ghost-ball pots on the legal targets (every
   legal ball and pocket weighed by ``pot_table``'s success probability), each in ``len(THROW)`` aims (the ghost
   ball's and one overcut against collision-induced throw), ``len(SPEEDS)`` speeds (factors of the speed that just
   drops the ball) and ``len(HEIGHTS)`` tip heights (draw, stun, follow); from the cue ball where it lies (or the
   first ball-in-hand spot) also ``n_safe`` safeties (soft shots across the legal targets), ``n_bank`` one-rail
   kicks (aimed at a legal ball's mirror image in a cushion's line) and ``n_kick`` shots in any direction. On
   the 8 the pot's pocket is called; a safety calls the pocket the 8 is easiest into.
3. **Rules and leave.** Every candidate is previewed once without noise and judged by the rules. Its value for
   the mover: 1 for a win, 0 for a loss; if the mover keeps the table, ``position_value`` of the leave (the ease
   of the mover's best next pot, ``leave_ease``); if the turn passes, 1 minus the opponent's ``position_value``
   (their best pot's ease, with ball in hand after a foul). ``position_value(e) = V_NONE + (V_FULL - V_NONE) e``:
   a table with no pot is worth ``V_NONE`` (a safety battle), a sure pot ``V_FULL``.
4. **Noise.** The ``n_eval`` best candidates (``n_eval_safe`` of them kept for safeties and kicks) are previewed
   again ``n_samples`` times each under sampled execution noise (the env's own noise; the ``tournament`` preset
   when the env has none) and valued the same way; the best mean is played.
   **Two plies** (``reply_eval`` > 0): the ``reply_eval`` best of them per table (``reply_safe`` kept for
   safeties and kicks) are judged again on their first ``reply_samples`` noisy outcomes where the turn passes:
   the opponent's reply is searched from the leave with this same machinery at the smaller ``REPLY_BUDGET``
   (``GameView.after`` builds the opponent's view from the preview), and the leave is worth 1 minus that reply's
   noisy value. Each such candidate's mean moves by the mean change over those outcomes, and the best of them is
   played (``replies``). With ``reply_keep`` (off; ``BUDGETS["deep"]``) the outcomes where the mover keeps the table
   are searched too: the leave is worth the mover's own searched next shot (a third ply along a run).
5. **Declarations (9-ball).** Where a push-out is allowed, ``n_push`` soft pushes are previewed; a push leaving
   ease ``e`` is worth ``min(v, 1 - v)`` with ``v = position_value(e)`` (the opponent chooses whether to shoot),
   and is declared when it beats the best shot's value. After the opponent's push-out, the shot is passed back
   when the best shot's value is below 1/2 (the opponent would then shoot the same table).
6. **Breaks** are searched once per game and table and kept (``searched_break``): ``break_search`` candidate
   strikes (the cue ball along the head string, the aim across the front ball, speed, tip height), each
   previewed under noise on the first ``break_racks`` breaking racks and valued as any shot; with
   ``break_search=0``, ``GhostBot``'s seeded standard break.

``pot_table`` and ``leave_ease`` are the geometric part (numba kernels here): the ghost-ball shot of a ball into a
pocket; a pot is open when both paths are clear of other balls (by 2R + ``BLOCK_CLEAR``), the cut is below
``MAX_CUT`` and the approach to the pocket is within its mouth (``CORNER_APPROACH``, ``SIDE_APPROACH``); its
success probability is ``erf(tol / (sqrt(2) sigma))`` with the pocket's angular tolerance ``tol`` (its accepted
half-width over the ball's distance to it) and the object ball's direction error ``sigma`` (the aim error
propagated through the contact, ``sigma_aim d_cg / (2R cos cut)``, plus ``SIGMA_MODEL``).

Cost per decision: about ``starts x n_pots x variants + n_safe + n_bank + n_kick (+ n_push)`` noise-free previews plus
``n_eval x n_samples`` noisy ones, plus with two plies a reply search (``REPLY_BUDGET``) per searched leave
(``sims`` counts them all).
"""
from __future__ import annotations

import dataclasses
import math
from typing import NamedTuple

import numba
import numpy as np

from ..physics.noise import NoiseConfig
from ..physics.strike import Shots
from ..rules import records as RR
from .geometry.lines import blocked, ghost_ball
from .ghost import GhostBot
from ..contract.plan import ShotPlan

_jit = numba.njit(cache=True, nogil=True)

BLOCK_CLEAR = 0.004                # m: a pot's paths keep this clear of other balls beyond 2R (execution noise)
MAX_CUT = math.radians(75)         # a pot cut more than this is not tried
CORNER_APPROACH = math.radians(60)  # steepest approach to a corner pocket, from its axis, a pot accepts
SIDE_APPROACH = math.radians(50)   # and to a side pocket (a side pocket's mouth faces straight across the table)
CORNER_INSET = 0.5                 # corner aim point: this fraction of the capture radius into the table
POCKET_TOL = 0.6                   # a pot's accepted half-width: this fraction of the pocket's capture radius
SIGMA_MODEL = 0.012                # rad: object-ball direction error the ghost-ball model makes beyond the aim noise
MIN_AIM_SIGMA = math.radians(0.125)  # rad: the aim noise the leave is judged with at least (tournament level)
HAND_DCG = 0.3                     # m: cue-to-ghost distance assumed for a shooter with ball in hand
ROLL_MIN = 0.35                    # m/s: speed the object ball should still have at the pocket's line
V_NONE = 0.5                       # value of a table whose shooter has no pot (a safety battle: even)
V_FULL = 0.9                       # value of a table whose shooter has a sure pot (the run may still end)
Q_RUN = 0.0                        # each further ball of a run continues with this (0: the value ignores balls left)
THROW = (0.0, math.radians(2.0))   # rad: object-ball overcut tried against collision-induced throw
SPEEDS = (1.1, 1.5, 2.2, 3.2)      # factors of the speed that just drops the ball (4 measured above 3: docs/games.md)
HEIGHTS = (-0.35, 0.0, 0.35)       # tip heights (units of R): draw, stun, follow
HAND_BACKS = (0.18, 0.4)           # m: ball-in-hand spots behind the ghost ball
HAND_TURNS = (-math.radians(25), 0.0, math.radians(25))  # rad: and turned about it (a cut for position)
SAFE_SPEEDS = (0.5, 3.5)           # m/s: range of the safeties' speeds
KICK_SPEEDS = (1.0, 5.0)           # m/s: range of the kicks' speeds
BANK_SPEEDS = (1.5, 5.0)           # m/s: range of the one-rail kicks' speeds
PUSH_SPEEDS = (0.3, 1.6)           # m/s: range of the push-outs' speeds
COMBO_CUT = math.radians(60)       # 9-ball combinations: both cuts (cue -> legal ball, legal ball -> 9) below this
COMBO_REACH = 1.2                  # m: and the legal ball within this of the 9's ghost ball
COMBO_SPEEDS = (2.5, 4.5)          # m/s: the combinations' speeds
BREAK_BEHIND = 0.02                # m: a searched break's cue ball this far behind the head string
BREAK_X = 0.35                     # m: and within this of the table's long axis
BREAK_OFF = 0.6                    # the aim at the front ball's centre, offset across by up to this (units of R)
BREAK_SPEEDS = (6.0, 9.0)          # m/s: range of the searched breaks' speeds
BREAK_HEIGHTS = (-0.5, 0.2)        # range of their tip heights (units of R): draw to follow
BREAK_REFINE = 6                   # the best searched breaks re-judged with BREAK_REFINE_X times the samples
BREAK_REFINE_X = 4
CHUNK = 128                        # tables decided per batch of previews (memory stays bounded)
# the opponent's reply searched from a leave (Budget.reply_eval > 0): the same machinery at about a sixth of the
# previews per table (3 pots in 9 variants, 12 safeties and kicks, 8 re-judged 8 times under noise), since it runs
# on every leave of the reply_eval x reply_samples outcomes of a table; 4 samples of 6 measured weaker (docs/games.md)
REPLY_BUDGET = dict(n_pots=3, hand_pots=2, n_safe=6, n_kick=2, n_bank=4, n_push=0, n_eval=8, n_eval_safe=2,
                    n_samples=8, throws=(0.0,), speeds=(1.15, 1.8, 2.8), break_search=0, reply_eval=0)


class PocketModel:
    """The pockets as the kernels take them: aim points [P, 2], outward axes [P, 2], steepest approach [P] (rad)
    and accepted half-widths [P] (m)."""

    def __init__(self, view):
        pk = view.pockets
        W, L = view.table.width, view.table.length
        cx, cy = pk[:, 0] - W / 2, pk[:, 1] - L / 2
        ax = np.stack([np.sign(cx) * (np.abs(cx) > W / 4), np.sign(cy) * (np.abs(cy) > L / 4)], axis=1)
        ax = ax / np.linalg.norm(ax, axis=1, keepdims=True)
        corner = np.abs(ax[:, 0] * ax[:, 1]) > 0
        self.aims = np.ascontiguousarray(pk[:, :2] - (corner * CORNER_INSET * pk[:, 2])[:, None] * ax)
        self.axes = np.ascontiguousarray(ax)
        self.approach = np.where(corner, CORNER_APPROACH, SIDE_APPROACH).astype(np.float64)
        self.half = np.ascontiguousarray(POCKET_TOL * pk[:, 2])
        self.table, self.params = view.table, view.params

    def arrays(self):
        return self.aims, self.axes, self.approach, self.half


# --- geometry kernels (the ghost ball and the blocked-path test come from bots.geometry.lines) ------------------
@_jit
def _pot(pos, on, b, p, cx, cy, hand, pockets, lim):
    """The ghost-ball pot of ball ``b`` into pocket ``p`` with the cue ball at (cx, cy) (``hand``: placed at will):
    (success probability, aim phi, cue-ghost distance, ball-pocket distance, cut); probability 0 if it is not open.
    ``pockets``: ``PocketModel.arrays()``; ``lim``: (R, clear, max cut, sigma aim, sigma model, hand distance)."""
    aims, axes, approach, half = pockets
    R, clear, max_cut, sig_aim, sig_model, hand_dcg = lim
    ox, oy = pos[b, 0], pos[b, 1]
    dop = math.hypot(aims[p, 0] - ox, aims[p, 1] - oy)
    if dop < 1e-9:
        return 0.0, 0.0, 0.0, 0.0, 0.0
    ux, uy, gx, gy = ghost_ball(ox, oy, aims[p, 0], aims[p, 1], R, dop)
    app = math.acos(min(max(ux * axes[p, 0] + uy * axes[p, 1], -1.0), 1.0))
    if app > approach[p]:
        return 0.0, 0.0, 0.0, 0.0, 0.0
    d2 = (2 * R + clear) ** 2
    if hand:
        dcg, cut, phi = hand_dcg, 0.0, math.atan2(uy, ux)
    else:
        vx, vy = gx - cx, gy - cy
        dcg = math.hypot(vx, vy)
        if dcg < 1e-9:
            return 0.0, 0.0, 0.0, 0.0, 0.0
        cut = math.acos(min(max((vx * ux + vy * uy) / dcg, -1.0), 1.0))
        if cut > max_cut or blocked(pos, on, b, -1, cx, cy, gx, gy, d2):
            return 0.0, 0.0, 0.0, 0.0, 0.0
        phi = math.atan2(vy, vx)
    if blocked(pos, on, b, -1, ox, oy, aims[p, 0], aims[p, 1], d2):
        return 0.0, 0.0, 0.0, 0.0, 0.0
    sig = math.hypot(sig_aim * dcg / (2 * R * max(math.cos(cut), 0.2)), sig_model)
    tol = half[p] * (0.5 + 0.5 * math.cos(app)) / dop
    return math.erf(tol / (math.sqrt(2.0) * sig)), phi, dcg, dop, cut


@_jit
def _pot_table(pos, on, targets, cue, hand, pockets, lim, out):
    """Every legal ball's pot into every pocket, per table e (cue ball at ``cue[e]``): ``out``, ``PotArrays`` [n, B, P]."""
    prob, phi, dcg, dop, cut = out
    for e in range(pos.shape[0]):
        for b in range(1, pos.shape[1]):
            for p in range(pockets[0].shape[0]):
                prob[e, b, p] = 0.0
                if targets[e, b] and on[e, b]:
                    r = _pot(pos[e], on[e], b, p, cue[e, 0], cue[e, 1], hand[e], pockets, lim)
                    prob[e, b, p], phi[e, b, p], dcg[e, b, p], dop[e, b, p], cut[e, b, p] = r


@_jit
def _leave_ease(pos, on, targets, hand, pockets, lim, out):
    """The success probability of the shooter's easiest pot, per table [n] (0: none open, or no cue ball)."""
    for e in range(pos.shape[0]):
        best = 0.0
        if hand[e] or on[e, 0]:
            for b in range(1, pos.shape[1]):
                if targets[e, b] and on[e, b]:
                    for p in range(pockets[0].shape[0]):
                        q = _pot(pos[e], on[e], b, p, pos[e, 0, 0], pos[e, 0, 1], hand[e], pockets, lim)[0]
                        best = max(best, q)
        out[e] = best


@_jit
def _leave_ease2(pos, on, targets, hand, rotation, game_ball, pockets, lim, w_next, out):
    """``_leave_ease`` looking two balls deep, per table [n]: the best over the shooter's pots (ball b, pocket p;
    success q) of q ((1 - w_next) + w_next e2), where e2 is the ease of the best pot on the ball after b from b's
    ghost ball (the cue ball stunned there; 1 if b is the game's ball). The ball after b: in rotation games
    (``rotation``) the lowest left on the table, else the other legal targets, or the game's ball when none."""
    aims = pockets[0]
    R = lim[0]
    for e in range(pos.shape[0]):
        best = 0.0
        if hand[e] or on[e, 0]:
            for b in range(1, pos.shape[1]):
                if not (targets[e, b] and on[e, b]):
                    continue
                for p in range(aims.shape[0]):
                    q = _pot(pos[e], on[e], b, p, pos[e, 0, 0], pos[e, 0, 1], hand[e], pockets, lim)[0]
                    if q * 1.0 <= best:  # cannot beat the best so far (the second factor is at most 1)
                        continue
                    if b == game_ball:
                        best = q
                        continue
                    ox, oy = pos[e, b, 0], pos[e, b, 1]
                    dop = math.hypot(aims[p, 0] - ox, aims[p, 1] - oy)
                    gx, gy = ox - 2 * R * (aims[p, 0] - ox) / dop, oy - 2 * R * (aims[p, 1] - oy) / dop
                    on[e, b] = False
                    any_target = False
                    if not rotation:
                        for c in range(1, pos.shape[1]):
                            if c != b and targets[e, c] and on[e, c]:
                                any_target = True
                    e2 = 0.0
                    for c in range(1, pos.shape[1]):
                        if not on[e, c]:
                            continue
                        if rotation:
                            nxt = True
                            for d in range(1, c):
                                if on[e, d]:
                                    nxt = False
                        else:
                            nxt = (c != b and targets[e, c]) if any_target else c == game_ball
                        if not nxt:
                            continue
                        for p2 in range(aims.shape[0]):
                            e2 = max(e2, _pot(pos[e], on[e], c, p2, gx, gy, False, pockets, lim)[0])
                    on[e, b] = True
                    best = max(best, q * ((1.0 - w_next) + w_next * e2))
        out[e] = best


def position_value(ease: np.ndarray, v_none: float = V_NONE, v_full: float = V_FULL, left=None,
                   q_run: float = 0.0) -> np.ndarray:
    """The chance the shooter of a table wins, from the ease of their best pot (see the module docstring);
    with ``left`` [n] (the balls the shooter still has to pocket, the game's ball included) and ``q_run`` > 0,
    a sure pot is worth ``v_full + (1 - v_full) q_run ** (left - 1)``: 1 on the game ball, ``v_full`` with many
    balls left (a run of ``left`` balls continues each with ``q_run``)."""
    full = v_full if left is None or not q_run else v_full + (1.0 - v_full) * q_run ** np.maximum(left - 1, 0)
    return v_none + (full - v_none) * ease


def balls_left(game: str, on: np.ndarray, targets: np.ndarray) -> np.ndarray:
    """[n] the object balls the next shooter still has to pocket, the game's ball included: every object ball
    on the table in rotation games; in 8-ball the legal targets on the table, plus the 8 while it is not one."""
    tg = (targets & on)[:, 1:]
    if game != "eight_ball":
        return on[:, 1:].sum(axis=1)
    return tg.sum(axis=1) + ~tg[:, 7]


class PotArrays(NamedTuple):
    """A pot table's outputs, each [n, B, P]: success probability, aim, cue-ghost and ball-pocket distances, cut."""
    prob: np.ndarray
    phi: np.ndarray
    dcg: np.ndarray
    dop: np.ndarray
    cut: np.ndarray


@dataclasses.dataclass(frozen=True)
class Budget:
    """What ``GameLookahead`` searches: candidate counts (pots tried per
    table, and with ball in hand; safeties, kicks, one-rail kicks, push-outs),
    how many candidates are re-judged under noise (pots, safeties) and with
    how many noise samples, the pots' variants (overcuts against throw, speed
    factors, tip heights), and the leave model (``sigma_model``; ``v_none``,
    ``v_full``, ``q_run``: see ``position_value``). Off by default, tried
    and measured without a gain (docs/games.md): ``q_run`` (a sure pot worth
    more as the balls run out), ``combos`` (9-ball combinations on the 9,
    ``combo_shots``), ``w_next`` (the leave looked at two balls deep,
    ``_leave_ease2``) and ``reply_keep`` (the mover's own next shot searched
    on the kept tables; docs/league.md). On by default: ``reply_eval`` (two plies: the
    opponent's reply searched from the best candidates' leaves, ``replies``;
    ``reply_eval=0`` is the one-shot leave alone, ``one-ply`` in ``BUDGETS``)."""

    n_pots: int = 6
    hand_pots: int = 3
    n_safe: int = 16
    n_kick: int = 8
    n_bank: int = 16
    n_push: int = 24
    n_eval: int = 32
    n_eval_safe: int = 8
    n_samples: int = 12
    throws: tuple = THROW
    speeds: tuple = SPEEDS
    heights: tuple = HEIGHTS
    sigma_model: float = SIGMA_MODEL
    v_none: float = V_NONE
    v_full: float = V_FULL
    q_run: float = Q_RUN
    combos: bool = False
    w_next: float = 0.0
    break_search: int = 128    # candidate breaks searched once per game and table (0: ghost's standard break)
    break_racks: int = 16      # the racks (the first breaking rows) each candidate break is judged on
    break_samples: int = 2     # noise samples per candidate and rack
    reply_eval: int = 6        # candidates per table whose turn-passing leaves get the opponent's reply searched
    reply_safe: int = 4        # of them kept for safeties and kicks
    reply_samples: int = 8     # the noisy outcomes (at most n_samples) per candidate whose leaves are searched
    reply: tuple = ()          # (field, value) changes to REPLY_BUDGET, the opponent's search
    reply_keep: bool = False   # also search the mover's own next shot on those outcomes where the mover keeps the table


# --- the bot ------------------------------------------------------------------------------------------------------
class GameLookahead:
    """Two-player lookahead: see the module docstring."""

    name = "lookahead"

    def __init__(self, seed: int = 0, budget: "Budget | None" = None, leaf_value=None, **changes):
        """``budget``: the search's sizes and the leave model (``Budget``; the
        default if None), with ``changes`` to its fields applied. ``leaf_value``: the valuer of the
        leaves, ``leaf_value(view, pos, on, targets, ball_in_hand, ease) -> [k]`` the next shooter's chance
        to win (``bots.learned.value``); None: ``position_value`` of the ease (the default)."""
        self.leaf_value = leaf_value
        bud = dataclasses.replace(budget or Budget(), **changes)
        if bud.n_safe + bud.n_kick + bud.n_bank < 1:
            raise ValueError("GameLookahead needs n_safe + n_kick + n_bank >= 1 (every table keeps a candidate)")
        self.budget = bud
        self.rng = np.random.default_rng(seed)
        self.ghost = GhostBot(seed=seed)
        self.n_pots, self.hand_pots, self.n_safe, self.n_kick, self.n_push = (bud.n_pots, bud.hand_pots, bud.n_safe,
                                                                              bud.n_kick, bud.n_push)
        self.n_bank = int(bud.n_bank)
        self.n_eval, self.n_eval_safe, self.n_samples = bud.n_eval, bud.n_eval_safe, bud.n_samples
        self.throws, self.speeds, self.heights = tuple(bud.throws), tuple(bud.speeds), tuple(bud.heights)
        self.sigma_model, self.v_none, self.v_full = float(bud.sigma_model), float(bud.v_none), float(bud.v_full)
        self.q_run, self.combos, self.w_next = float(bud.q_run), bool(bud.combos), float(bud.w_next)
        if bud.reply_eval and not (0 <= bud.reply_safe < bud.reply_eval and bud.reply_samples >= 1):
            raise ValueError(f"GameLookahead: reply_safe ({bud.reply_safe}) must be below reply_eval "
                             f"({bud.reply_eval}) and reply_samples ({bud.reply_samples}) at least 1")
        self.reply = None  # the opponent's search from a leave (``replies``)
        if bud.reply_eval:
            self.reply = GameLookahead(seed=int(self.rng.integers(2 ** 31)), budget=Budget(**REPLY_BUDGET),
                                       leaf_value=leaf_value, **dict(bud.reply))
        self.model: PocketModel | None = None
        self.break_strikes: dict = {}  # (game, table, params) -> the searched break (``search_break``)
        self.sims = 0        # shots previewed so far (cost accounting)
        self.last_value = None  # [n] the value of the played shot at the last decision (diagnostics)
        self.last_kind = None   # [n] what it is: "break", "pot", "safety" (safeties and kicks), "push", "pass"

    # --- geometry -------------------------------------------------------------------------------------------------
    def pockets(self, view) -> PocketModel:
        m = self.model
        if m is None or m.table is not view.table or m.params is not view.params:
            self.model = m = PocketModel(view)
        return m

    def _lim(self, view):
        aim = max(math.radians(view.noise.aim_deg), MIN_AIM_SIGMA)
        return (view.params.R, BLOCK_CLEAR, MAX_CUT, aim, self.sigma_model, HAND_DCG)

    def pot_table(self, view, pos, on, targets, cue, hand):
        """``_pot_table`` over tables (cue ball at ``cue`` [n, 2], ``hand`` [n]): dict of [n, B, P] arrays."""
        n, B = pos.shape[:2]
        P = len(self.pockets(view).aims)
        out = PotArrays(*(np.zeros((n, B, P)) for _ in PotArrays._fields))
        _pot_table(np.ascontiguousarray(pos), np.ascontiguousarray(on), np.ascontiguousarray(targets),
                   np.ascontiguousarray(cue, dtype=np.float64), np.ascontiguousarray(hand, dtype=np.bool_),
                   self.pockets(view).arrays(), self._lim(view), out)
        return out._asdict()

    def leave_ease(self, view, pos, on, targets, hand) -> np.ndarray:
        """[n] the ease of the shooter's best pot on tables after a shot (``hand``: ball in hand); with
        ``w_next`` > 0, looking two balls deep (``_leave_ease2``)."""
        out = np.empty(len(pos))
        if self.w_next:
            game_ball = {"nine_ball": 9, "ten_ball": 10}.get(view.game, 8)
            _leave_ease2(np.ascontiguousarray(pos), np.array(on, dtype=np.bool_), np.ascontiguousarray(targets),
                         np.ascontiguousarray(hand, dtype=np.bool_), view.game != "eight_ball", game_ball,
                         self.pockets(view).arrays(), self._lim(view), self.w_next, out)
            return out
        _leave_ease(np.ascontiguousarray(pos), np.ascontiguousarray(on), np.ascontiguousarray(targets),
                    np.ascontiguousarray(hand, dtype=np.bool_), self.pockets(view).arrays(), self._lim(view), out)
        return out

    def pot_speed(self, view, dcg, dop, cut) -> np.ndarray:
        """The cue-ball speed that just drops a ball (rolling after a stun hit, slowed by rolling resistance)."""
        p = view.params
        dec = 2.0 * p.mu_r * p.g
        v_ob = np.sqrt(dec * dop + ROLL_MIN ** 2) * 7.0 / 5.0
        v_c = v_ob / np.maximum(np.cos(cut), 0.25)
        return np.sqrt(v_c ** 2 + dec * dcg) * 7.0 / 5.0

    # --- valuing outcomes -----------------------------------------------------------------------------------------
    def values(self, view, pv) -> np.ndarray:
        """The mover's value of each previewed shot (module docstring, step 3)."""
        rec, nxt = pv.record, pv.next
        hand = nxt.ball_in_hand != RR.IN_HAND_NONE
        e = self.leave_ease(view, pv.pos, pv.on_table, nxt.targets, hand)
        if self.leaf_value is None:
            v = self.position_value(view, e, pv.on_table, nxt.targets)
        else:
            v = self.leaf_value(view, pv.pos, pv.on_table, nxt.targets, nxt.ball_in_hand, e)
        keep = nxt.shooter == rec.shooter
        val = np.where(keep, v, 1.0 - v)
        return np.where(rec.game_over, (rec.winner == rec.shooter).astype(np.float64), val)

    def position_value(self, view, ease, on, targets) -> np.ndarray:
        """``position_value`` of tables after shots, with the balls their next shooter has left."""
        left = balls_left(view.game, on, targets) if self.q_run else None
        return position_value(ease, self.v_none, self.v_full, left, self.q_run)

    def noise(self, view):
        return "env" if view.noise.enabled else NoiseConfig.from_any("tournament")

    # --- candidates -----------------------------------------------------------------------------------------------
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
        if view.game == "nine_ball" and self.combos:
            parts.append(self.combo_shots(view, rows, cue[first], placed[first]))
        out = {key: np.concatenate([q[key] for q in parts]) for key in c}
        return out

    def combo_shots(self, view, rows, cue, placed):
        """9-ball combinations: the legal ball driven into the 9 so that the 9 drops, into each pocket where both
        cuts are below ``COMBO_CUT`` (ghost balls of the 9 and of the legal ball; paths are not checked: the
        preview judges), at ``COMBO_SPEEDS``, the cue ball at ``cue`` [n, 2]."""
        R_ = view.params.R
        aims = self.pockets(view).aims                                     # [P, 2]
        on, tg = view.on_table[rows], view.targets[rows] & view.on_table[rows]
        low = np.argmax(tg, axis=1)
        ok_row = on[:, 9] & (low > 0) & (low != 9)
        L, G = view.pos[rows, low], view.pos[rows, 9]                      # [n, 2]
        u9 = aims[None] - G[:, None]                                       # [n, P, 2]
        u9 /= np.maximum(np.linalg.norm(u9, axis=-1, keepdims=True), 1e-9)
        g9 = G[:, None] - 2 * R_ * u9
        u2 = g9 - L[:, None]
        d2 = np.maximum(np.linalg.norm(u2, axis=-1, keepdims=True), 1e-9)
        u2 = u2 / d2
        gl = L[:, None] - 2 * R_ * u2
        vc = gl - cue[:, None]
        dc = np.maximum(np.linalg.norm(vc, axis=-1), 1e-9)
        cut1 = np.arccos(np.clip((vc * u2).sum(-1) / dc, -1, 1))
        cut2 = np.arccos(np.clip((u2 * u9).sum(-1), -1, 1))
        ok = ok_row[:, None] & (cut1 < COMBO_CUT) & (cut2 < COMBO_CUT) & (d2[..., 0] < COMBO_REACH)
        ri, pi = np.nonzero(ok)
        V = len(COMBO_SPEEDS)
        rep, var = np.repeat(np.arange(len(ri)), V), np.tile(np.arange(V), len(ri))
        r = ri[rep]
        phi = np.arctan2(vc[ri, pi, 1], vc[ri, pi, 0])[rep]
        m = len(rep)
        return dict(row=rows[r], phi=phi, speed=np.asarray(COMBO_SPEEDS)[var], a=np.zeros(m), b=np.zeros(m),
                    placement=np.where(placed[r, None], cue[r], np.nan), pocket=pi[rep], safe=np.zeros(m, bool))

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

    # --- pushes ---------------------------------------------------------------------------------------------------
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

    # --- breaks ---------------------------------------------------------------------------------------------------
    def break_plan(self, view, rows, strikes) -> ShotPlan:
        """Breaks on view rows ``rows`` [m] from ``strikes`` [m, 4]: (the cue ball's offset across the table's
        long axis (m), the aim's offset across the front ball (units of R), speed, tip height); the cue ball
        ``BREAK_BEHIND`` behind the head string (made legal), aimed at the rack's front ball (the object ball
        nearest to it)."""
        W, L, R_ = view.table.width, view.table.length, view.params.R
        want = np.column_stack([W / 2 + strikes[:, 0], np.full(len(rows), view.marks.head_string - BREAK_BEHIND)])
        cue, _ = view.legal_placement(want, rows)
        pos, on = view.pos[rows], view.on_table[rows]
        d = pos[:, 1:] - cue[:, None]
        dist = np.where(on[:, 1:], np.linalg.norm(d, axis=-1), np.inf)
        front = np.argmin(dist, axis=1)
        u = d[np.arange(len(rows)), front] / dist[np.arange(len(rows)), front][:, None]
        aim = pos[np.arange(len(rows)), front + 1] + (strikes[:, 1] * R_)[:, None] * np.column_stack([-u[:, 1], u[:, 0]])
        phi = np.arctan2(aim[:, 1] - cue[:, 1], aim[:, 0] - cue[:, 0])
        return ShotPlan.of(Shots(phi, np.minimum(strikes[:, 2], view.params.max_speed), 0.0, strikes[:, 3]),
                           placement=cue)

    def searched_break(self, view, rows) -> np.ndarray:
        """The break strike [4] (``break_plan``) this bot plays in ``view.game`` on ``view.table``, searched on
        the first call and kept (the racks differ only by their gaps and the balls' order): ``break_search``
        candidates (the first one ``ghost``'s nominal break), each previewed ``break_samples`` times under noise
        on each of up to ``break_racks`` of the breaking rows ``rows`` and valued as any shot (``values``: the
        9 on the break wins; keeping the table is worth the leave; a foul gives the opponent ball in hand); the
        ``BREAK_REFINE`` best judged again with ``BREAK_REFINE_X`` times the samples; the best mean is kept."""
        key = (view.game, id(view.table), id(view.params))
        hit = self.break_strikes.get(key)
        if hit is not None and hit[0] is view.table and hit[1] is view.params:
            return hit[2]
        C, racks = self.budget.break_search, rows[:self.budget.break_racks]
        rng = np.random.default_rng(self.rng.integers(2 ** 63))
        cand = np.column_stack([rng.uniform(-BREAK_X, BREAK_X, C), rng.uniform(-BREAK_OFF, BREAK_OFF, C),
                                rng.uniform(*BREAK_SPEEDS, C), rng.uniform(*BREAK_HEIGHTS, C)])
        cand[0] = (0.0, 0.0, 8.0, -0.025)  # ghost's nominal break (bots.ghost.BREAK_SPEED, its mean tip height)

        def judge(idx, samples):
            rep = np.repeat(idx, len(racks) * samples)
            r = np.tile(np.repeat(racks, samples), len(idx))
            pv = view.preview(self.break_plan(view, r, cand[rep]), r, noise=self.noise(view), rng=rng)
            self.sims += len(r)
            return self.values(view, pv).reshape(len(idx), -1).mean(axis=1)

        S = self.budget.break_samples
        v = judge(np.arange(C), S)
        top = np.argsort(-v, kind="stable")[:BREAK_REFINE]
        v2 = (v[top] + BREAK_REFINE_X * judge(top, BREAK_REFINE_X * S)) / (1 + BREAK_REFINE_X)
        best = cand[top[np.argmax(v2)]].copy()
        self.break_strikes[key] = (view.table, view.params, best)
        self.last_break_search = dict(candidates=cand, value=v, refined=top, refined_value=v2)
        return best

    # --- acting ---------------------------------------------------------------------------------------------------
    def act(self, view) -> ShotPlan:
        if not view.table.has_pockets:
            raise ValueError(f"the lookahead bot pots balls: it cannot play {view.game} on a table without pockets "
                             "(three-cushion: the carom bot, make_bot('carom'))")
        n = view.n
        phi, speed, a, b = np.zeros(n), np.ones(n), np.zeros(n), np.zeros(n)
        placement, declare, pocket = np.full((n, 2), np.nan), np.zeros(n, bool), np.zeros(n, dtype=np.int64)
        value = np.full(n, np.nan)
        kind = np.full(n, "break", dtype=object)
        brk = np.nonzero(view.is_break)[0]
        if len(brk) and self.budget.break_search:
            g = self.break_plan(view, brk, np.broadcast_to(self.searched_break(view, brk), (len(brk), 4)))
            phi[brk], speed[brk], a[brk], b[brk] = g.phi, g.speed, g.a, g.b
            placement[brk] = g.placement
        elif len(brk):
            g = self.ghost.act(view.take(brk))
            phi[brk], speed[brk], a[brk], b[brk] = g.phi, g.speed, g.a, g.b
            placement[brk], pocket[brk] = g.placement, g.pocket
        play = np.nonzero(~view.is_break)[0]
        for lo in range(0, len(play), CHUNK):
            rows = play[lo:lo + CHUNK]
            sh, pl, pk, val, safe = self.decide(view, rows)
            phi[rows], speed[rows], a[rows], b[rows] = sh
            placement[rows], pocket[rows], value[rows] = pl, pk, val
            kind[rows] = np.where(safe, "safety", "pot")
        if len(play):
            # 9-ball declarations: a push-out that beats the shot; a pass where the shot is worth less than 1/2
            push = play[view.push_out_allowed[play]]
            if len(push) and self.n_push:
                (pph, psp), pval = self.push_values(view, push)
                use = pval > value[push]
                r = push[use]
                declare[r] = True
                phi[r], speed[r], a[r], b[r] = pph[use], psp[use], 0.0, 0.0
                placement[r] = np.nan
                value[r] = pval[use]
                kind[r] = "push"
            pas = play[view.may_pass[play] & (value[play] < 0.5)]
            declare[pas] = True
            value[pas] = 1.0 - value[pas]
            kind[pas] = "pass"
        self.last_value, self.last_kind = value, kind
        speed = np.clip(speed, 0.05, view.params.max_speed)
        return ShotPlan.of(Shots(phi, speed, a, b), placement, declare, pocket)

    def decide(self, view, rows):
        """The best candidate of each view row in ``rows``: (shots, placement, pocket, value, whether it is a
        safety or kick)."""
        c = self.candidates(view, rows)
        n = len(rows)
        local = np.searchsorted(rows, c["row"])                       # rows are increasing
        pv = view.preview(self._plan(c), c["row"])
        self.sims += len(c["row"])
        v0 = self.values(view, pv)
        # the n_eval best per row (n_eval_safe of them kept for safeties and kicks), in one noisy batch
        rank = _rank_in_row((-v0,), local, n)                           # best first
        srank = _rank_in_row((-v0, ~c["safe"]), local, n)               # safeties first, best first
        pick = np.nonzero((rank < self.n_eval - self.n_eval_safe) | (c["safe"] & (srank < self.n_eval_safe)))[0]
        S = self.n_samples
        rep = np.repeat(pick, S)
        lp = local[pick]
        if S:
            pvn = view.preview(self._plan(c, rep), c["row"][rep], noise=self.noise(view), rng=self.rng)
            self.sims += len(rep)
            vs = self.values(view, pvn).reshape(len(pick), S)
            vn = vs.mean(axis=1)
        else:
            vn = v0[pick]
        # the best noisy mean per row (ties: the noise-free value)
        score = vn + 1e-3 * v0[pick]
        if self.reply is not None and S:
            sel, vn = self.replies(view, pvn, (vs, vn, c["safe"][pick], lp, n), c["row"][rep])
            score = np.where(sel, vn + 1e-3 * v0[pick], -np.inf)
        o = np.lexsort((-score, lp))
        first = o[np.searchsorted(lp[o], np.arange(n))]
        best = pick[first]
        return ((c["phi"][best], c["speed"][best], c["a"][best], c["b"][best]), c["placement"][best],
                c["pocket"][best], vn[first], c["safe"][best])

    def replies(self, view, pvn, judged, prow):
        """The 2-ply judgement of the best noisy candidates: ``judged`` (their sample values [k, S], means [k],
        safe [k], local row [k], rows n), ``pvn`` their noisy previews (k x S, candidate-major) on view rows
        ``prow``. The ``reply_eval`` best per row (``reply_safe`` kept for safeties and kicks) are selected; on
        their first ``reply_samples`` outcomes where the turn passes, the opponent's reply is searched from the
        leave (``self.reply.decide`` on ``view.after``) and the leave is worth 1 minus its value; with
        ``reply_keep``, on the outcomes where the mover keeps the table too, the mover's own next shot searched the
        same way, and the leave is worth its value. Each selected
        mean moves by the mean change over those samples (the other samples keep their one-shot value):
        (selected [k], means [k])."""
        vs, vn, safe, lp, n = judged
        k, S = vs.shape
        ra, rs = self.budget.reply_eval, self.budget.reply_safe
        sel = (_rank_in_row((-vn,), lp, n) < ra - rs) | (safe & (_rank_in_row((-vn, ~safe), lp, n) < rs))
        j = np.nonzero(sel)[0]
        S2 = min(self.budget.reply_samples, S)
        ids = (j[:, None] * S + np.arange(S2)).ravel()
        rec, nxt = pvn.record, pvn.next
        keep = nxt.shooter == rec.shooter
        ids = ids[~rec.game_over[ids] & (self.budget.reply_keep | ~keep[ids])]
        delta = np.zeros(k * S)
        for lo in range(0, len(ids), 4 * CHUNK):
            part = ids[lo:lo + 4 * CHUNK]
            r = self.reply_value(view.after(pvn, part, prow[part]))
            delta[part] = np.where(keep[part], 1.0 - r, r) - vs.ravel()[part]
        vn = vn + delta.reshape(k, S)[:, :S2].sum(axis=1) / S2
        return sel, vn

    def reply_value(self, leaves) -> np.ndarray:
        """[m] a leave's value to the player who left it: 1 minus the value of the opponent's best reply,
        searched by ``self.reply`` (``REPLY_BUDGET``) on ``leaves``, the view of the tables with the opponent to
        move (``GameView.after``)."""
        if self.reply is None:
            raise ValueError("reply_value needs Budget.reply_eval > 0 (the opponent's search)")
        before = self.reply.sims
        opp = self.reply.decide(leaves, np.arange(leaves.n))[3]
        self.sims += self.reply.sims - before
        return 1.0 - opp


def _rank_in_row(keys, row, n):
    """[k] each entry's place (0 first) within its row (``row`` [k] in 0..n-1), ordered by ``keys`` (a tuple of
    [k] arrays, as ``np.lexsort`` takes them: the last one first)."""
    order = np.lexsort((*keys, row))
    starts = np.searchsorted(row[order], np.arange(n))
    rank = np.empty(len(order), dtype=np.int64)
    rank[order] = np.arange(len(order)) - np.repeat(starts, np.diff(np.append(starts, len(order))))
    return rank


def game_lookahead(seed: int = 0, **kw) -> GameLookahead:
    """The ``lookahead`` game bot (``bots.make_bot("lookahead")``)."""
    return GameLookahead(seed=seed, **kw)


# smaller search budgets, for measuring strength against compute (``module:factory`` entrants of scripts/match.py)
BUDGETS = dict(fast=dict(n_pots=3, n_eval=8, n_eval_safe=4, n_samples=4, reply_eval=0),
               medium=dict(n_pots=4, n_eval=16, n_eval_safe=4, n_samples=8, reply_eval=0),
               wide=dict(n_eval=64, n_samples=16),
               deep=dict(reply_keep=True),  # the mover's own next shot searched too, where the mover keeps the table
               **{"one-ply": dict(reply_eval=0)})  # without the 2-ply judgement (the default before it)


def lookahead_fast(seed: int = 0) -> GameLookahead:
    """``lookahead`` with the ``fast`` budget (about a quarter of the default's previews)."""
    bot = GameLookahead(seed=seed, **BUDGETS["fast"])
    bot.name = "lookahead-fast"
    return bot


def lookahead_medium(seed: int = 0) -> GameLookahead:
    """``lookahead`` with the ``medium`` budget (about half the default's previews)."""
    bot = GameLookahead(seed=seed, **BUDGETS["medium"])
    bot.name = "lookahead-medium"
    return bot
