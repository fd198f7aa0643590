"""``search<K>``: ``ghost-safety`` whose pots are searched.

``SearchBot`` plays as ``GhostBot(safety=True)`` except on its pots: ``k``
candidate shots per table on the planned ball (the one-player
``SearchPolicy``'s candidates: every pocket's ghost-ball shot, then jittered
aims, speeds and spins) previewed in one batched call and judged by the
rules; it plays the best (a win, else a legal shot that keeps the table with
the easiest next pot, else the ghost-ball plan), preferring candidates close
to the nominal shots. In 10-ball every candidate calls the planned ball
into the planned pocket.
"""
from __future__ import annotations

import numpy as np

from ..physics import BallState
from ..physics.strike import Shots
from .ghost import GhostBot
from .one_player import SearchPolicy


class SearchBot(GhostBot):
    def __init__(self, seed: int = 0, k: int = 64):
        super().__init__(seed=seed, safety=True)
        self.k, self.search_seed = int(k), seed
        self.search: SearchPolicy | None = None
        self.name = f"search{k}"

    def refine(self, view, rows, pos, balls, shots: Shots, pockets=None) -> None:
        if not len(rows):
            return
        if self.search is None:  # one candidate generator per bot (its own random stream)
            self.search = SearchPolicy(k=self.k, seed=self.search_seed)
        K = self.k
        st = BallState(pos[rows].copy(), np.zeros_like(pos[rows]), np.zeros(pos[rows].shape[:2] + (3,)),
                       view.pocket[rows].copy())
        st.pocket[:, 0] = -1
        cph, csp, ca, cb, close = self.search.candidates(view, st, balls)
        rep = np.repeat(rows, K)
        called = np.full(view.n, -1)
        if pockets is not None and getattr(view.rules, "calls_ball", False):  # 10-ball: the planned ball and pocket
            called[rows] = pockets                                              # are called on every candidate
        rec = self.judge(view, np.arange(view.n), pos, Shots(cph.ravel(), csp.ravel(), ca.ravel(), cb.ravel()),
                         called, rep)
        win, loss = rec.winner == rec.shooter, rec.winner == 1 - rec.shooter
        pv = self.last_judged
        keeps = rec.legal & ~rec.turn_over & ~rec.game_over
        follow = self.best_pots(self.geometry(view), pv.pos, pv.on_table, pv.next.targets)["cost"]  # the next pot's cost
        position = np.where(keeps & np.isfinite(follow), 2.0 - np.minimum(follow, 2.0), 0.0)
        score = (10.0 * win - 10.0 * loss + 3.0 * keeps + position).reshape(len(rows), K)
        score = score - 0.01 * close
        k = np.argmax(score, axis=1)
        ok = score[np.arange(len(rows)), k] > 1.0
        r, kk = rows[ok], k[ok]
        ar = np.nonzero(ok)[0]
        shots.phi[r], shots.speed[r], shots.a[r], shots.b[r] = cph[ar, kk], csp[ar, kk], ca[ar, kk], cb[ar, kk]
