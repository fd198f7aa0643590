"""``GameLookahead``: the lookahead's search (the package docstring says what it does)."""
from __future__ import annotations

import dataclasses

import numpy as np

from ...contract.plan import ShotPlan
from ...physics.strike import Shots
from ..ghost import GhostBot
from ..serial import serial_act
from .breaks import Breaks
from .budget import BUDGETS, CHUNK, REPLY_BUDGET, Budget
from .candidates import Candidates
from .pots import PocketModel
from .valuation import Valuation


class GameLookahead(Valuation, Candidates, Breaks):
    """Two-player lookahead: see the package docstring."""

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

    @serial_act
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
            declarations(self, view, play, (phi, speed, a, b), placement, declare, value, kind)
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

    def replies(self, view, pvn, judged, prow, opt=None):
        """The 2-ply judgement of the best noisy candidates: ``judged`` (their sample values [k, S], means [k],
        safe [k], local row [k], rows n), ``pvn`` their noisy previews (k x S, candidate-major) on view rows
        ``prow``. The ``reply_eval`` best per row (``reply_safe`` kept for safeties and kicks) are selected; on
        their first ``reply_samples`` outcomes where the turn passes, the opponent's reply is searched from the
        leave (``self.reply.decide`` on ``view.after``) and the leave is worth 1 minus its value; with
        ``reply_keep``, on the outcomes where the mover keeps the table too, the mover's own next shot searched the
        same way, and the leave is worth its value. Each selected
        mean moves by the mean change over those samples (the other samples keep their one-shot value):
        (selected [k], means [k]). ``opt`` [k S] (champion's, 10-ball; None: none): the outcomes that hand the
        opponent the option to pass back, where the leave is worth the lesser of the reply's value and 1 minus it."""
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
            if opt is not None:
                r = np.where(opt[part], np.minimum(r, 1.0 - r), r)
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


def declarations(la, view, play, shots, placement, declare, value, kind) -> None:
    """The declarations of rows ``play`` after their best shots are chosen, in place (``shots``: the phi, speed,
    a, b arrays; ``value`` the chosen shots' values): where a push-out is allowed, ``la``'s best push
    (``push_values``) is declared when it beats the shot; after the opponent's push-out, the shot is passed back
    where it is worth less than 1/2 (the opponent would then shoot the same table)."""
    phi, speed, a, b = shots
    push = play[view.push_out_allowed[play]]
    if len(push) and la.n_push:
        (pph, psp), pval = la.push_values(view, push)
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
