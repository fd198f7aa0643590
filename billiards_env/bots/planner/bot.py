"""``Champion``: the game bot of ``bots.planner`` (``make_bot("champion")``).

Per table to move: the candidates (``candidates``: window-aimed, throw-corrected pots from the cue ball or from
searched ball-in-hand spots; safeties (lookahead's and a grid of soft shots), kicks, a 360-degree kick fan, and on
a hooked table the kicks found by scanning the simulator) are previewed once without noise and
valued with the one-ply leave (``leave.values``: a win 1, a loss 0, else ``position_value`` of the next
shooter's best pot's ease, in the planner's window model; ``Parts(own_leave=False)``: lookahead's); the best few
per table go through successive halving under the env's noise (``halving``); the best sampled ones (``REPLY``)
get lookahead's reply search on the leaves where the turn passes (``two_plies``), which moves their means, and the
best is played. Where the env adds no noise the noise-free preview is the outcome itself, and the best noise-free
value is played. 9-ball and 10-ball push-outs and passes as lookahead decides them (a push that beats the shot; a
pass when the shot is worth less than 1/2); 10-ball pots call their ball and pocket. The break is searched once
per game and table (``breaks``).
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from ...contract.plan import ShotPlan
from ...physics.strike import Shots
from ...rules import records as RR
from ..game_lookahead import Budget, GameLookahead
from ..game_lookahead.search import declarations
from ..serial import serial_act
from . import candidates as CAND
from . import breaks as BR
from . import leave as LEAVE
from .breaks import BreakSearch
from .halving import ROUNDS, halve

CHUNK = 128                # tables decided per batch of previews (memory stays bounded)
FIRST_POTS = 20            # pots per table entering the noisy rounds (by the prior: value times success estimate)
MISS_VALUE = 0.25          # the mover's value after a missed pot (the opponent usually has a shot)
FIRST_SAFE = 16            # safeties and kicks per table entering them (8 before the safety grid)
MIN_AIM_SIGMA = math.radians(0.125)  # rad: aim noise the pot ranking assumes at least (tournament level)
# the lookahead whose parts are reused: its starts, safeties, leave valuation, pushes and break strikes
HELPER = dict(reply_eval=0, n_safe=16, n_kick=8, n_bank=16, n_push=24, hand_pots=3)
# with ``replies``: lookahead's two plies on the best survivors (the opponent's reply searched from the leaves
# where the turn passes, ``GameLookahead.replies``): that many per table, of them kept for safeties, samples
REPLY = dict(reply_eval=6, reply_safe=3, reply_samples=8)
HAND_VALUE = 0.6           # 10-ball: the least an opponent's ball in hand after a foul is worth to it
EXACT_K = 6                # without noise: candidates of a table whose next shot is searched too (``exact``)
EXACT_BREAKS = 64          # without noise: break strikes previewed on the rack itself (``exact_break``)


@dataclasses.dataclass(frozen=True)
class Parts:
    """The parts of the search, each on by default (``ablations`` takes one out): ``throw`` (pots aimed
    corrected for throw), ``windows`` (pots aimed into the measured pocket windows; off: lookahead's pots),
    ``searched_break``, ``own_leave`` (the window model's leave; off: lookahead's), ``replies`` (lookahead's
    reply search on the best survivors) and ``escapes`` (jump and massé strokes out of a hook, where the
    equipment lets balls fly: ``candidates.escapes``; nothing changes where it does not), ``hand_safe``
    (safeties from ball-in-hand spots that see a legal ball: ``candidates.hand_safeties``) and ``option``
    (10-ball: an illegal pot's option and the opponent's ball in hand valued as ``Champion.values`` says),
    ``kick_scan`` (kicks found by scanning the simulator on hooked tables: ``candidates.kick_scan``),
    ``safe_fill`` (a table with fewer pots than the first round's places gives the spare ones to its safeties)
    and ``safety_grid`` (soft shots on a grid at the nearest legal balls: ``candidates.safety_grid``)."""

    throw: bool = True
    windows: bool = True
    searched_break: bool = True
    own_leave: bool = True
    replies: bool = True
    escapes: bool = True
    hand_safe: bool = True
    option: bool = True
    kick_scan: bool = True
    safe_fill: bool = True
    safety_grid: bool = True


class PlanRows:
    """A batch's plan as it is filled in: every table's strike, placement, declaration, pocket and called ball,
    and the chosen shot's value and kind ("break", "pot", "safety", "pass", ...). Champion and the Expert
    Iteration players fill it alike: the break rows, then the chosen candidate of each row, then the declarations."""

    def __init__(self, n: int):
        self.phi, self.speed, self.a, self.b = np.zeros(n), np.ones(n), np.zeros(n), np.zeros(n)
        self.theta = np.zeros(n)  # the cue's elevation (escapes; 0: the level cue)
        self.placement, self.declare = np.full((n, 2), np.nan), np.zeros(n, bool)
        self.pocket, self.ball = np.zeros(n, np.int64), np.full(n, -1, np.int64)
        self.value, self.kind = np.full(n, np.nan), np.full(n, "break", dtype=object)

    def breaks(self, rows, g) -> None:
        """Rows ``rows`` break with ``g`` (``GameLookahead.break_plan``'s strike and placement)."""
        self.phi[rows], self.speed[rows], self.a[rows], self.b[rows] = g.phi, g.speed, g.a, g.b
        self.placement[rows] = g.placement

    def choose(self, rows, c, best, value) -> None:
        """Rows ``rows`` play candidate ``best`` of the candidates ``c`` (a dict of arrays), worth ``value``."""
        self.phi[rows], self.speed[rows], self.a[rows], self.b[rows] = (c["phi"][best], c["speed"][best],
                                                                        c["a"][best], c["b"][best])
        self.placement[rows], self.pocket[rows], self.ball[rows] = c["placement"][best], c["pocket"][best], \
            c["ball"][best]
        if "theta" in c:
            self.theta[rows] = c["theta"][best]
        self.value[rows] = value
        self.kind[rows] = np.where(c["safe"][best], "safety", "pot")

    def declarations(self, la, view, rows) -> None:
        """Push-outs and passes on rows ``rows`` as the lookahead ``la`` declares them."""
        declarations(la, view, rows, (self.phi, self.speed, self.a, self.b), self.placement, self.declare,
                     self.value, self.kind)
        self.theta[rows[self.kind[rows] == "push"]] = 0.0  # a push-out is lookahead's level stroke
    def plan(self, view) -> ShotPlan:
        """The plan, speeds clipped to the table's range."""
        speed = np.clip(self.speed, 0.05, view.params.max_speed)
        return ShotPlan.of(Shots(self.phi, speed, self.a, self.b, self.theta), self.placement, self.declare,
                           self.pocket, self.ball)


class Champion:
    name = "champion"

    def __init__(self, seed: int = 0, parts: Parts = Parts(), rounds=ROUNDS, first_pots: int = FIRST_POTS,
                 first_safe: int = FIRST_SAFE, variants: dict | None = None, reply: dict = REPLY,
                 exact_plies: int = 2, exact_k: int = EXACT_K, exact_breaks: int = EXACT_BREAKS):
        self.rng = np.random.default_rng(seed)
        self.reply = dict(reply)
        helper = dict(HELPER, **(self.reply if parts.replies else {}))
        self.la = GameLookahead(seed=int(self.rng.integers(2 ** 31)), budget=Budget(**helper))
        self.replies = parts.replies
        self.throw, self.windows, self.rounds = parts.throw, parts.windows, tuple(rounds)
        self.first_pots, self.first_safe = first_pots, first_safe
        self.breaks = BreakSearch() if parts.searched_break else None
        self.own_leave = parts.own_leave
        self.escapes = parts.escapes
        self.hand_safe, self.option = parts.hand_safe, parts.option
        self.kick_scan, self.safe_fill = parts.kick_scan, parts.safe_fill
        self.safety_grid = parts.safety_grid
        self.variants = dict(variants or {})   # the pots' speed factors, tip heights and sides (candidates.pots)
        self.exact_plies, self.exact_k = int(exact_plies), int(exact_k)  # without noise: plies searched exactly
        self.exact_breaks = int(exact_breaks)  # without noise: break strikes tried on each rack itself
        self.sims = 0
        self.last_value = self.last_kind = None

    # --- acting -------------------------------------------------------------------------------------------------
    @serial_act
    def act(self, view) -> ShotPlan:
        if not view.table.has_pockets:
            raise ValueError(f"champion pots balls: it cannot play {view.game} on a table without pockets")
        p = PlanRows(view.n)
        brk = np.flatnonzero(view.is_break)
        if len(brk):
            if self.breaks is not None:
                s = self.breaks.strike(self, view, brk)
            else:
                s = np.array([0.0, 0.0, 8.0, -0.025])
            if view.noise.enabled or self.exact_breaks < 1:
                p.breaks(brk, self.la.break_plan(view, brk, np.broadcast_to(s, (len(brk), 4))))
            else:
                p.breaks(brk, self.exact_break(view, brk, s))
        play = np.flatnonzero(~view.is_break)
        for lo in range(0, len(play), CHUNK):
            rows = play[lo:lo + CHUNK]
            p.choose(rows, *self.decide(view, rows))
        if len(play):  # push-outs and passes as lookahead declares them
            p.declarations(self.la, view, play)
        self.last_value, self.last_kind = p.value, p.kind
        return p.plan(view)

    # --- the search ---------------------------------------------------------------------------------------------
    def candidates(self, view, rows, grid: bool = True):
        """The candidates of view rows ``rows`` (module docstring); ``grid``: with the safety grid (the exact
        search's next shots go without it: in 8-ball without noise it took champion from 36 to 70 ms a shot)."""
        srow, cue, placed = self.la.starts(view, rows)
        aim_sigma = max(math.radians(view.noise.aim_deg), MIN_AIM_SIGMA)
        if self.windows:
            pots = CAND.pots(self, view, srow, cue, placed, aim_sigma, throw=self.throw, **self.variants)
        else:
            pots = self.lookahead_pots(view, rows)
        first = np.searchsorted(srow, rows)
        saf = CAND.safeties(self, view, rows, cue[first], placed[first])
        parts = [pots, saf]
        if self.hand_safe and getattr(view.rules, "calls_ball", False):
            # 10-ball: safeties from spots that see a legal ball, where the first start sees none (in 9-ball,
            # 250 racks at seed 7, they moved champion from 0.592 to 0.572 against lookahead-2026.12)
            extra = CAND.hand_safeties(self, view, rows, cue[first], placed[first], pots)
            if extra is not None:
                parts.append(extra)
        if self.safety_grid and grid:
            g = CAND.safety_grid(self, view, rows, cue[first], placed[first])
            if g is not None:
                parts.append(g)
        if self.kick_scan:
            scan = CAND.kick_scan(self, view, rows, cue[first], placed[first])
            if scan is not None:
                parts.append(scan)
        esc = CAND.escapes(self, view, rows, cue[first], placed[first], pots) if self.escapes else None
        if esc is not None:  # jump and massé strokes out of a hook, where balls fly
            parts.append(esc)
        for part in parts:
            part.setdefault("theta", np.zeros(len(part["row"])))
        c = {k: np.concatenate([part[k] for part in parts]) for k in parts[-1]}
        if not getattr(view.rules, "calls_ball", False):
            c["ball"][:] = -1
        o = np.argsort(c["row"], kind="stable")
        return {k: v[o] for k, v in c.items()}

    def lookahead_pots(self, view, rows):
        """The ablation without windows: lookahead's own pot candidates (centre-aimed, its overcut variants)."""
        c = self.la.candidates(view, rows)
        pot = ~c["safe"]
        out = {k: v[pot] for k, v in c.items()}
        out["ball"] = np.full(pot.sum(), -1, np.int64)
        out["prob"] = np.zeros(pot.sum())
        return out

    def values(self, view, pv):
        """The mover's one-ply value of previewed shots: the planner's leave (``leave``), or lookahead's."""
        v = LEAVE.values(view, pv) if self.own_leave else self.la.values(view, pv)
        opt = self.options(view, pv)
        if opt is None:
            return v
        # 10-ball: the opponent's ball in hand is worth HAND_VALUE at least (a table where no pot is open for it
        # is still one where it places the cue ball for a safety), and an option the lesser of v and 1 - v
        foul = (pv.next.ball_in_hand != RR.IN_HAND_NONE) & (pv.next.shooter != pv.record.shooter) \
            & ~pv.record.game_over
        v = np.where(foul, np.minimum(v, 1.0 - HAND_VALUE), v)
        return np.where(opt, np.minimum(v, 1.0 - v), v)

    def options(self, view, pv):
        """[k] the previewed shots that hand the opponent the option to shoot or pass back (10-ball: a ball
        pocketed without a foul but not as called), None where the game has none: the opponent takes the better
        of the two, so the mover is left the lesser of its value v and 1 - v."""
        if not (self.option and getattr(view.rules, "calls_ball", False)):
            return None
        return pv.next.may_pass & (pv.next.shooter != pv.record.shooter) & ~pv.record.game_over

    def plan(self, c, idx):
        theta = c["theta"][idx] if "theta" in c else 0.0  # the level cue where no escape was made (the ExIt search)
        return ShotPlan.of(Shots(c["phi"][idx], c["speed"][idx], c["a"][idx], c["b"][idx], theta),
                           placement=c["placement"][idx], pocket=c["pocket"][idx], ball=c["ball"][idx])

    def decide(self, view, rows, plies: int | None = None):
        """(candidates, the chosen candidate of each row [n], its value [n]) for view rows ``rows``; ``plies``
        (without noise; default ``exact_plies``): the shots searched exactly, this one included (``exact``)."""
        c = self.candidates(view, rows, grid=plies is None)
        n = len(rows)
        local = np.searchsorted(rows, c["row"])
        allidx = np.arange(len(local))
        pv = view.preview(self.plan(c, allidx), c["row"])
        self.sims += len(local)
        v0 = self.values(view, pv)
        # a pot's noise-free value says where the cue ball goes, not how likely the ball drops: weigh it by the
        # pot's success estimate (``candidates.pot_options``) before choosing the first round's entrants
        prior = np.where(c["safe"], v0, c["prob"] * v0 + (1 - c["prob"]) * MISS_VALUE)
        # the first noisy round: the best pots and the best safeties of each table by that prior
        safe_quota = self.first_safe
        if self.safe_fill:  # a table with fewer pots than places gives the spare places to its safeties
            n_pots = np.bincount(local[~c["safe"]], minlength=n)
            safe_quota = (self.first_safe + np.maximum(self.first_pots - n_pots, 0))[local]
        first = (_rank(-prior, local, n, ~c["safe"]) < self.first_pots) | (_rank(-prior, local, n, c["safe"])
                                                                             < safe_quota)
        noise = self.la.noise(view)

        def judge(idx, draws):
            p = view.preview(self.plan(c, idx), c["row"][idx], noise=noise, draws=draws)
            self.sims += len(idx)
            return self.values(view, p)

        if not view.noise.enabled:
            # the env strikes every shot exactly as planned: the noise-free preview is the outcome itself
            plies = self.exact_plies if plies is None else plies
            if plies > 1:
                v0 = self.exact(view, c, local, n, pv, v0, plies)
            score = v0 + 1e-6 * prior
            o = np.lexsort((-score, local))
            best = o[np.searchsorted(local[o], np.arange(n))]
            return c, best, v0[best]
        mean, count = halve(judge, local, n, prior, first, self.rng, self.rounds)
        top = count == np.maximum.reduceat(count, np.searchsorted(local, np.arange(n)))[local]
        score = np.where(top & (count > 0), mean + 1e-3 * v0, -np.inf)
        if self.replies:
            score = self.two_plies(view, c, local, n, mean, count, noise)
        o = np.lexsort((-score, local))
        best = o[np.searchsorted(local[o], np.arange(n))]
        val = np.where(np.isfinite(score[best]), mean[best], v0[best])
        return c, best, val


    def exact_break(self, view, rows, strike):
        """Without noise, the break of each rack in ``rows`` searched on that rack: the searched break ``strike``
        [4] and ``exact_breaks`` - 1 strikes drawn over its ranges (``breaks``), each previewed exactly and
        valued as any shot, the best few by the shot after them (``exact``); the best strike's plan."""
        m, K = len(rows), self.exact_breaks
        lo, hi = np.array(BR.STRIKE_LOW), np.array(BR.STRIKE_HIGH)
        cand = self.rng.uniform(lo, hi, (m, K, 4))
        cand[:, 0] = strike
        r = np.repeat(rows, K)
        plan = self.la.break_plan(view, r, cand.reshape(-1, 4))
        pv = view.preview(plan, r)
        self.sims += len(r)
        v = self.values(view, pv)
        local = np.repeat(np.arange(m), K)
        if self.exact_plies > 1:
            v = self.exact(view, {"row": r}, local, m, pv, v, self.exact_plies)
        best = np.arange(m) * K + np.argmax(v.reshape(m, K), axis=1)  # ties: the searched break first
        return plan.take(best)

    def exact(self, view, c, local, n, pv, v0, plies):
        """Without noise: the ``exact_k`` best candidates of each row by ``v0`` whose game goes on are valued by
        the next shooter's best shot, searched the same way (without the safety grid) from the exact outcome
        (``plies`` - 1 more shots):
        the mover's value is that shot's if the mover shoots again, else 1 minus it. Returns the values [k]: a
        candidate that ends the game keeps its exact value, one not searched so is out of the choice (-inf)."""
        live = ~pv.record.game_over
        pick = np.flatnonzero((_rank(-v0, local, n, live) < self.exact_k) & live)
        if not len(pick):
            return v0
        after = view.after(pv, pick, c["row"][pick])
        v = np.empty(len(pick))
        for lo in range(0, len(pick), CHUNK):
            sub = np.arange(lo, min(lo + CHUNK, len(pick)))
            brk = after.is_break[sub]
            _, _, val = self.decide(after, sub, plies - 1)
            v[sub] = np.where(brk, v0[pick[sub]], val)
        same = pv.next.shooter[pick] == pv.record.shooter[pick]
        out = np.where(live, -np.inf, v0)
        out[pick] = np.where(same, v, 1.0 - v)
        return out

    def two_plies(self, view, c, local, n, mean, count, noise):
        """Scores [k] after lookahead's reply search on the best sampled candidates of each row (``REPLY``):
        the halving mean moved by the change the searched replies make on ``reply_samples`` fresh outcomes;
        -inf for those not judged so."""
        k_eval, k_safe, S = self.reply["reply_eval"], self.reply["reply_safe"], self.reply["reply_samples"]
        m = np.where(count > 0, mean, -np.inf)
        pick = np.flatnonzero(((_rank(-m, local, n, count > 0) < k_eval - k_safe)
                               | (_rank(-m, local, n, c["safe"] & (count > 0)) < k_safe)) & (count > 0))
        rep = np.repeat(pick, S)
        z = self.rng.normal(size=(n, S, 4))
        prow = c["row"][rep]
        pvn = view.preview(self.plan(c, rep), prow, noise=noise,
                           draws=z[local[rep], np.tile(np.arange(S), len(pick))])
        self.sims += len(rep)
        vs = self.values(view, pvn).reshape(len(pick), S)
        vn = vs.mean(axis=1)
        before = self.la.sims
        judged = (vs, vn, c["safe"][pick], local[pick], n)
        opt = self.options(view, pvn)
        sel, v2 = self.la.replies(view, pvn, judged, prow, opt)
        self.sims += self.la.sims - before
        score = np.full(len(local), -np.inf)
        score[pick] = np.where(sel, mean[pick] + (v2 - vn), -np.inf)
        return score


def _rank(key, row, n, mask):
    """[k] each masked entry's place (0 first) within its row by ``key`` (unmasked entries: a large rank)."""
    order = np.lexsort((key, ~mask, row))
    starts = np.searchsorted(row[order], np.arange(n))
    rank = np.empty(len(order), np.int64)
    rank[order] = np.arange(len(order)) - np.repeat(starts, np.diff(np.append(starts, len(order))))
    return np.where(mask, rank, 1 << 30)


def champion(seed: int = 0, **kw) -> Champion:
    """The ``champion`` bot (``bots.make_bot("champion")``); ``kw``: ``Champion``'s settings (``parts``,
    ``rounds``, ...)."""
    return Champion(seed=seed, **kw)
