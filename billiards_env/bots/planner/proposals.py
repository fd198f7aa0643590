"""The search over proposals: champion's machinery run over candidates drawn from a prior over the structured shot
space (``shot_space``), and the search's allocation as a policy target (docs/expert_iteration.md).

Per table: the ``k`` best proposals of the prior (its top k, or with ``explore`` a Gumbel-top-k sample: k drawn
without replacement, as Gumbel MuZero draws its root actions), ``k_safe`` of them kept for contact lines, kicks
and the fan; decoded and throw-corrected (``shot_space.refine``), previewed once without noise and valued by the
planner's one-ply leave (``leave.values``; with ``value_weight``, mixed with a learned value of the leaves); the
``first`` best by champion's prior (a pot's value times its success estimate) go through successive halving under
the env's noise on common random numbers (``halving``), and the best of the most-sampled is played.

The prior is the proposal network's (``bots.learned.proposal_bot``) or, before there is one, ``hand_logits``: a
pot's log success estimate, contact lines and kicks with an open path at ``SAFE_PRIOR``, the rest lower; every
variant and turn alike.

The policy target (``targets``) is the search's allocation over its candidates and the rest of the space:

- ``completed_q`` (Gumbel MuZero, Danihelka et al. 2022; mctx's ``qtransform_completed_by_mix_value``): each
  candidate's value (its halving mean, or its noise-free estimate if it was never sampled), the rest at the mixed
  value ``v_mix`` of the root value and the sampled means; rescaled to [0, 1] over the table; the target is
  ``softmax(log prior + (c_visit + max N) c_scale q)`` over the candidates and one bucket for everything else
  (whose share keeps the prior's proportions within it);
- ``visits``: each candidate's share of the noisy samples (the chosen one alone where the env has no noise).
"""
from __future__ import annotations

import dataclasses

import numpy as np

from . import leave as LEAVE
from . import shot_space as SS
from .bot import MISS_VALUE, _rank
from .halving import halve

TARGETS = ("completed_q", "visits")
SAFE_PRIOR = 0.05        # the hand prior's weight of a contact line or kick with an open path (a pot: its estimate)
CLOSED_PRIOR = 0.005     # and of a closed one, a fan direction or a blocked pot
EPS = 1e-8               # mctx's epsilon in the rescaling of Q


@dataclasses.dataclass(frozen=True)
class SearchBudget:
    """The search's sizes (module docstring). ``c_visit``, ``c_scale``: mctx's defaults."""

    k: int = 32                   # proposals per table previewed without noise: the candidate budget
    k_safe: int = 8               # of them kept for contact lines, kicks and the fan
    first: int = 10               # candidates per table entering the noisy rounds
    first_safe: int = 3           # of them kept for contact lines, kicks and the fan
    rounds: tuple = (4, 8, 16)    # new noise draws per survivor, round by round (champion's halving)
    explore: bool = False         # Gumbel-top-k sampling of the k (self-play), else the prior's top k
    value_weight: float = 0.0     # the learned value's weight at the leaves (the rest: the planner's leave)
    c_visit: float = 50.0
    c_scale: float = 0.1
    target: str = "completed_q"

    def __post_init__(self):
        if not (1 <= self.first <= self.k and 0 <= self.k_safe <= self.k and 0 <= self.first_safe <= self.first):
            raise ValueError(f"SearchBudget: need 1 <= first <= k, k_safe <= k, first_safe <= first; got {self}")
        if self.target not in TARGETS:
            raise ValueError(f"SearchBudget.target must be one of {TARGETS}, got {self.target!r}")

    @property
    def previews(self) -> int:
        """The most previews one table costs (without push-outs): ``k`` noise-free, ``first x sum(rounds)``."""
        return self.k + self.first * sum(self.rounds)


def hand_logits(layout) -> np.ndarray:
    """[n, S * T * V] the hand prior's log weights (module docstring; -inf: not legal)."""
    sp = layout.space
    pot = (sp.kind == SS.POT)[None, :, None]
    w = np.where(pot, np.where(layout.open_, layout.prob, CLOSED_PRIOR),
                 np.where(layout.open_ & ((sp.kind == SS.SAFE) | (sp.kind == SS.BANK))[None, :, None], SAFE_PRIOR,
                          CLOSED_PRIOR))
    logit = np.where(layout.mask, np.log(np.maximum(w, CLOSED_PRIOR)), -np.inf)
    return np.repeat(logit[..., None], sp.V, axis=3).reshape(len(logit), -1)


def log_softmax(x: np.ndarray) -> np.ndarray:
    """Row-wise log-softmax of [n, m] logits with -inf entries."""
    top = np.max(x, axis=1, keepdims=True)
    z = np.exp(x - top)
    return x - top - np.log(z.sum(axis=1, keepdims=True))


def select(logp: np.ndarray, safe_of_joint: np.ndarray, budget: SearchBudget, rng) -> tuple:
    """(layout rows [m], joints [m]) of each table's candidates, sorted by row: the ``k`` best by ``logp`` [n, J]
    (plus Gumbel noise with ``explore``), ``k_safe`` of them kept for ``safe_of_joint`` [J] proposals."""
    score = logp + (rng.gumbel(size=logp.shape) if budget.explore else 0.0)
    rows, joints = [], []
    for r in range(len(score)):
        legal = np.flatnonzero(np.isfinite(score[r]))
        order = legal[np.argsort(-score[r, legal], kind="stable")]
        safe = order[safe_of_joint[order]][:budget.k_safe]
        rest = order[~np.isin(order, safe)][:budget.k - len(safe)]
        pick = np.sort(np.concatenate([safe, rest]))
        rows.append(np.full(len(pick), r))
        joints.append(pick)
    return np.concatenate(rows), np.concatenate(joints)


@dataclasses.dataclass
class SearchResult:
    """One search over a layout's tables: the candidates ``c`` (``shot_space.decode``'s dict, refined) on layout
    rows ``li``; their noise-free values ``v0``, prior estimates ``est``, halving ``mean`` and ``count``, prior
    log-probabilities ``logp`` and the rest's ``rest_logp`` [n]; ``best`` [n] (candidate indices), ``value`` [n]
    (the chosen shot's value), and the policy target: ``y`` [m] per candidate and ``y_rest`` [n]."""

    c: dict
    li: np.ndarray
    v0: np.ndarray
    est: np.ndarray
    mean: np.ndarray
    count: np.ndarray
    logp: np.ndarray
    rest_logp: np.ndarray
    best: np.ndarray
    value: np.ndarray
    y: np.ndarray | None = None
    y_rest: np.ndarray | None = None


class ProposalSearch:
    """The search (module docstring) with ``budget``; ``owner`` is the bot whose ``rng``, ``la`` (a
    ``GameLookahead``: the pot speed, the noise) and ``sims`` (previews counted) it uses; ``leaf(view, pv)`` -> [k]
    the learned value of previewed shots to their mover (with ``value_weight`` > 0)."""

    def __init__(self, budget: SearchBudget, owner, leaf=None):
        self.budget, self.owner, self.leaf = budget, owner, leaf

    def values(self, view, pv) -> np.ndarray:
        v = LEAVE.values(view, pv)
        w = self.budget.value_weight
        if w > 0 and self.leaf is not None:
            v = np.where(pv.record.game_over, v, (1 - w) * v + w * self.leaf(view, pv))
        return v

    def run(self, layout, logp: np.ndarray, v_root=None) -> SearchResult:
        """Search the tables of ``layout`` under the prior log-probabilities ``logp`` [n, J] (-inf: not legal);
        ``v_root`` [n]: the root's value for the target's mixed value (None: the candidates' prior-weighted
        estimates)."""
        view, sp, b, owner = layout.view, layout.space, self.budget, self.owner
        n = len(layout.rows)
        safe_of_joint = np.repeat(sp.kind != SS.POT, sp.T * sp.V)
        li, joint = select(logp, safe_of_joint, b, owner.rng)
        c = SS.refine(view, SS.decode(layout, li, joint))
        plan = owner.plan(c, np.arange(len(li)))
        pv = view.preview(plan, c["row"])
        owner.sims += len(li)
        v0 = self.values(view, pv)
        est = np.where(c["safe"], v0, c["prob"] * v0 + (1 - c["prob"]) * MISS_VALUE)
        if view.noise.enabled:
            first = (_rank(-est, li, n, ~c["safe"]) < b.first - b.first_safe) | (_rank(-est, li, n, c["safe"])
                                                                               < b.first_safe)
            noise = owner.la.noise(view)

            def judge(idx, draws):
                p = view.preview(owner.plan(c, idx), c["row"][idx], noise=noise, draws=draws)
                owner.sims += len(idx)
                return self.values(view, p)

            mean, count = halve(judge, li, n, est, first, owner.rng, b.rounds)
            top = count == np.maximum.reduceat(count, np.searchsorted(li, np.arange(n)))[li]
            score = np.where(top & (count > 0), mean + 1e-3 * v0, -np.inf)
        else:  # the env strikes every shot as planned: the noise-free preview is the outcome itself
            mean, count = np.full(len(li), np.nan), np.zeros(len(li), np.int64)
            score = v0 + 1e-6 * est
        o = np.lexsort((-score, li))
        best = o[np.searchsorted(li[o], np.arange(n))]
        value = np.where(count[best] > 0, mean[best], v0[best])
        lp = logp[li, joint]
        rest = logp.copy()
        rest[li, joint] = -np.inf
        top = np.max(rest, axis=1)
        safe_top = np.where(np.isfinite(top), top, 0.0)
        rest_logp = np.where(np.isfinite(top), safe_top + np.log(np.exp(rest - safe_top[:, None]).sum(axis=1)),
                             -np.inf)
        res = SearchResult(c, li, v0, est, mean, count, lp, rest_logp, best, value)
        res.y, res.y_rest = targets(res, b, v_root)
        return res


def targets(res: SearchResult, budget: SearchBudget, v_root=None) -> tuple:
    """(y [m], y_rest [n]): the policy target of a search (module docstring)."""
    li, n = res.li, len(res.rest_logp)
    count = res.count.astype(np.float64)
    if budget.target == "visits" or not np.isfinite(res.logp).all():
        total = np.bincount(li, count, minlength=n)
        y = np.where(total[li] > 0, count / np.maximum(total[li], 1), 0.0)
        y[res.best[total == 0]] = 1.0                           # no samples: the chosen candidate
        return y, np.zeros(n)
    q = np.where(res.count > 0, res.mean, res.est)
    prior = np.exp(res.logp)
    if v_root is None:                                         # the candidates' prior-weighted estimates
        v_root = np.bincount(li, prior * res.est, minlength=n) / np.maximum(np.bincount(li, prior, minlength=n), EPS)
    vis = res.count > 0
    total = np.bincount(li, count, minlength=n)
    p_vis = np.bincount(li, prior * vis, minlength=n)
    q_vis = np.bincount(li, prior * vis * np.nan_to_num(q), minlength=n) / np.maximum(p_vis, EPS)
    v_mix = np.where(total > 0, (np.asarray(v_root, np.float64) + total * q_vis) / (total + 1), v_root)
    lo = np.minimum(np.minimum.reduceat(q, np.searchsorted(li, np.arange(n))), v_mix)
    hi = np.maximum(np.maximum.reduceat(q, np.searchsorted(li, np.arange(n))), v_mix)
    scale = (budget.c_visit + np.maximum.reduceat(count, np.searchsorted(li, np.arange(n)))) * budget.c_scale
    sig = lambda x, r: scale[r] * (x - lo[r]) / np.maximum(hi[r] - lo[r], EPS)
    z_c = res.logp + sig(q, li)
    z_r = res.rest_logp + sig(v_mix, np.arange(n))
    top = np.maximum(np.maximum.reduceat(z_c, np.searchsorted(li, np.arange(n))), z_r)
    e_c, e_r = np.exp(z_c - top[li]), np.where(np.isfinite(z_r), np.exp(z_r - top), 0.0)
    norm = np.bincount(li, e_c, minlength=n) + e_r
    return e_c / norm[li], e_r / norm
