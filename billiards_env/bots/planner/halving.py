"""Successive halving over noisy samples, on common random numbers.

Every candidate of a table gets ``ROUNDS[0]`` noise draws; the better half (by mean value so far) gets
``ROUNDS[1]`` more, and so on: the samples go where the choice is close. Within a table every candidate is
struck with the same draws at the same sample index (``common_draws``), so the comparison between two
candidates is not blurred by their own luck.
"""
from __future__ import annotations

import numpy as np

ROUNDS = (4, 8, 16, 24)   # new noise draws per surviving candidate, round by round
KEEP = 0.5                # the fraction of each table's candidates kept for the next round
MIN_KEEP = 1              # the last survivor keeps drawing: the played shot's value (push-outs, passes) gets precise


def halve(judge, row, n_rows, prior, first_keep, rng, rounds=ROUNDS, keep=KEEP):
    """Successive halving of candidates (their view rows ``row`` [k], local 0..n_rows-1, and a noise-free
    ``prior`` [k] value, which breaks ties and picks the first survivors): ``first_keep`` [k] bool marks
    those judged in the first round. ``judge(idx, draws)`` -> [len(idx)] values of candidates ``idx`` struck
    with standard normal draws [len(idx), 4]. Returns (mean [k] (NaN: never sampled), samples [k])."""
    k = len(row)
    total = np.zeros(k)
    count = np.zeros(k, np.int64)
    alive = np.flatnonzero(first_keep)
    z = rng.normal(size=(n_rows, sum(rounds), 4))          # the draws of each table, by sample index
    s0 = 0
    for r, S in enumerate(rounds):
        if not len(alive):
            break
        idx = np.repeat(alive, S)
        samp = np.tile(np.arange(s0, s0 + S), len(alive))
        v = judge(idx, z[row[idx], samp])
        np.add.at(total, idx, v)
        count[alive] += S
        s0 += S
        if r == len(rounds) - 1:
            break
        mean = total[alive] / count[alive]
        # keep the best fraction of each table's survivors
        order = np.lexsort((-prior[alive], -mean, row[alive]))
        ra = row[alive][order]
        first = np.searchsorted(ra, np.arange(n_rows))
        size = np.bincount(ra, minlength=n_rows)
        rank = np.arange(len(order)) - first[ra]
        quota = np.maximum(np.ceil(size * keep).astype(np.int64), MIN_KEEP)
        alive = np.sort(alive[order][rank < quota[ra]])
    mean = np.where(count > 0, total / np.maximum(count, 1), np.nan)
    return mean, count
