"""``carom<K>``: the three-cushion bot. Candidate cue-ball paths searched in
the simulator, scored by the point's probability under noise.

Per table: ``k`` candidate strikes (aims spread evenly over the circle with
a random offset, speeds, side and height spin drawn uniformly) are played
without noise through ``view.preview`` (the rules judge each from the order
of the cue ball's contacts); the ``top`` candidates that score (or, where
none does, those whose cue ball reached both balls with the most cushions
before the second, else those with the most cushions) are played again
``samples`` times each under the env's own noise, and the one that scores
most often is chosen (ties: the one found first). With noise off the
estimate is the exact outcome. Everything is one batched ``preview`` call
per stage over all the view's tables.

With the cue ball touching a ball (``GameView.may_replace``) the same
search runs on the starting position the balls would be replaced on, and
the bot has them replaced (``ShotPlan.replace``) where the best point found
there is likelier than from where the balls lie.
"""
from __future__ import annotations

import numpy as np

from ..physics import constants as C
from ..physics.strike import Shots
from ..rules import bot_games
from ..rules.three_cushion import point_made
from ..contract.plan import ShotPlan

FAMILY = "carom"     # its name in bots.registry (carom<K>), which the games it plays list in their own_bots
DEFAULT_K = 96       # candidate strikes per table
TOP = 6              # candidates re-played under noise
SAMPLES = 6          # noisy plays per re-played candidate
SPEED = (1.5, 7.0)   # m/s: the cue-ball speeds searched (a three-cushion path needs 2-6 m/s)
SIDE, HEIGHT = 0.4, 0.3  # largest side / height tip offsets searched (units of R, inside the miscue disc)


class CaromBot:
    """Three-cushion bot (module docstring); ``k`` candidates per table."""

    def __init__(self, seed: int | None = 0, k: int = DEFAULT_K, top: int = TOP, samples: int = SAMPLES,
                 replace: bool = True):
        if k < 1 or top < 1 or samples < 1:
            raise ValueError(f"carom bot: k, top and samples must be positive, got {k}, {top}, {samples}")
        self.rng = np.random.default_rng(seed)
        self.k, self.top, self.samples = int(k), int(min(top, k)), int(samples)
        self.name = f"carom{self.k}"
        self.replace = bool(replace)  # with the cue ball touching a ball: search the starting position too
        self.last_estimate: np.ndarray | None = None  # [n] the chosen shots' estimated point probability

    def _candidates(self, n: int, max_speed: float) -> Shots:
        k, rng = self.k, self.rng
        phi = (np.arange(k)[None, :] + rng.random((n, 1))) * (2 * np.pi / k)
        speed = rng.uniform(SPEED[0], min(SPEED[1], max_speed), (n, k))
        return Shots(phi.ravel(), speed.ravel(), rng.uniform(-SIDE, SIDE, n * k), rng.uniform(-HEIGHT, HEIGHT, n * k))

    def act(self, view) -> ShotPlan:
        if view.game not in bot_games(FAMILY):
            raise ValueError(f"the carom bot plays {' and '.join(bot_games(FAMILY))} only, not {view.game!r}")
        shots, prob = self._search(view)
        replace = np.zeros(view.n, dtype=bool)
        if self.replace and view.may_replace is not None and view.may_replace.any():
            # balls in contact: the same search from the starting position the replace would give; replaced where
            # its best point is the likelier
            r = np.nonzero(view.may_replace)[0]
            pv = view.preview(ShotPlan.of(Shots(0.0, 0.0, 0.0, 0.0), replace=np.ones(len(r), dtype=bool)), r)
            _, p_start = self._search(view.after(pv, np.arange(len(r)), r))
            replace[r] = p_start > prob[r]
            prob[r] = np.maximum(prob[r], p_start)
        self.last_estimate = prob
        return ShotPlan.of(shots, replace=replace)

    def _search(self, view) -> tuple[Shots, np.ndarray]:
        """The chosen strike per view row and its estimated point probability [n]."""
        n, k, top, m = view.n, self.k, self.top, self.samples
        shots = self._candidates(n, view.params.max_speed)
        rows = np.repeat(np.arange(n), k)
        pre = view.preview(ShotPlan.of(shots), rows)
        # rank: a point first, then both balls reached with the most cushions before the second, then cushions
        _, before = point_made(pre.contacts, pre.n_contacts)
        both = reached_both(pre.contacts, pre.n_contacts)
        score = (pre.record.points > 0) * 1000 + both * 100 + np.minimum(before, 99)
        score = score.reshape(n, k) + self.rng.random((n, k)) * 1e-3  # random tie-break among equals
        best = np.argsort(-score, axis=1)[:, :top]                        # [n, top]
        pick = (np.arange(n)[:, None] * k + best).ravel()
        cand = Shots(*(np.asarray(v)[pick] for v in shots))
        if view.noise is not None and view.noise.enabled:
            rep = np.repeat(np.arange(n * top), m)
            noisy = view.preview(ShotPlan.of(Shots(*(np.asarray(v)[rep] for v in cand))), np.repeat(np.arange(n), top * m),
                                 noise="env", rng=self.rng)
            prob = (noisy.record.points > 0).reshape(n, top, m).mean(axis=2)
        else:
            prob = (pre.record.points[pick] > 0).reshape(n, top).astype(float)
        j = np.argmax(prob, axis=1)
        chosen = np.arange(n) * top + j
        return Shots(*(np.asarray(v)[chosen] for v in cand)), prob[np.arange(n), j]


def reached_both(contacts: np.ndarray, n_contacts: np.ndarray) -> np.ndarray:
    """Whether each cue ball touched both object balls (contacts in the rules' frame)."""
    K = contacts.shape[1]
    valid = np.arange(K)[None, :] < np.minimum(n_contacts, K)[:, None]
    ball = valid & (contacts[..., 0] == C.EV_BALL_BALL)
    return (ball & (contacts[..., 1] == 1)).any(axis=1) & (ball & (contacts[..., 1] == 2)).any(axis=1)
