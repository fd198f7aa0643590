"""Cheaper sampling inside an RLlib EnvRunner: the parts of RLlib's per-step
cost that can be removed without changing what the Learner receives
(``backend.algo_config(cfg, lean=True)``, the default). Needs
``ray[rllib]``; the backend imports it only when it builds a config or an
EnvRunner's env.

- ``MeanStdFilter``: RLlib's ``MeanStdFilter`` connector (running mean /
  std of the observations, merged across runners) updated once per vector
  step from all tables' observations at once, instead of one Welford push and
  one space conversion per table. Its state (RLlib's ``RunningStat``: count,
  mean, sum of squared deviations and their deltas since the last merge) is
  the same as after pushing the rows one by one, so the driver merges it with
  RLlib's own code. One difference: every observation of a step is scaled
  with the statistics after that whole step (RLlib's filter scales row i with
  the statistics after rows 0..i of the step). It keeps RLlib's class name
  because RLlib files a connector's state under its class name: checkpoints
  of either filter load into the other (resume, ``RLlibPolicy``).
- ``tune_worker_gc``: CPython's cyclic garbage collector in an EnvRunner
  process. RLlib builds several small containers per table per step (one
  episode object each on one-shot tasks), so the default thresholds run a
  young collection every few tables and a full one, traversing the half
  million objects Ray and torch leave in the process, every few samples.
  Freezing the objects that exist after set-up and raising the young
  threshold leaves the collector only the sampling's own garbage.
  ``tuned_gc`` does the same in the driver while it trains (its learner
  handles the same episodes) and restores the collector afterwards.
"""
from __future__ import annotations

import contextlib
import gc

import numpy as np
from ray.rllib.connectors.env_to_module import MeanStdFilter as RLlibMeanStdFilter
from ray.rllib.utils.filter import SMALL_NUMBER

# Young-generation threshold in EnvRunner processes: CPython's default of 700
# net allocations is reached every few tables of a step (several containers per
# one-shot episode); 10,000 collects young objects about 14 times less often
# (the value measured in docs/distributed.md).
WORKER_GC_GEN0_THRESHOLD = 10_000


def tune_worker_gc() -> None:
    """Freeze the objects of this (EnvRunner) process and raise the young
    generation's threshold (``WORKER_GC_GEN0_THRESHOLD``); collection stays
    on, so reference cycles made while sampling are still freed."""
    gc.collect()
    gc.freeze()
    _, gen1, gen2 = gc.get_threshold()
    gc.set_threshold(WORKER_GC_GEN0_THRESHOLD, gen1, gen2)


@contextlib.contextmanager
def tuned_gc():
    """``tune_worker_gc`` for the duration of a ``with`` block (the driver,
    whose learner builds and batches the same episode objects), then the
    collector's thresholds as they were and the frozen objects back in its
    care."""
    threshold = gc.get_threshold()
    tune_worker_gc()
    try:
        yield
    finally:
        gc.unfreeze()
        gc.set_threshold(*threshold)


def push_batch(rs, x: np.ndarray) -> None:
    """Push the rows of ``x`` (``(m,) + rs.shape``) into RLlib's
    ``RunningStat`` ``rs``: the same count, mean, sum of squared deviations
    and deltas since the last merge as ``m`` calls of ``rs.push`` (Chan et
    al.'s pairwise combination of the batch's mean and sum of squares with
    the running ones; the mean delta telescopes to the change of the mean)."""
    m = x.shape[0]
    if m == 0:
        return
    x = np.asarray(x, dtype=np.float64)
    n = rs.num_pushes
    mean_b = x.mean(axis=0)
    ssd_b = ((x - mean_b) ** 2).sum(axis=0)
    old_mean = rs.mean_array.copy()
    total = n + m
    diff = mean_b - old_mean
    new_mean = old_mean + diff * (m / total)
    added_ssd = ssd_b + diff * diff * (n * m / total)
    rs.mean_array[...] = new_mean
    if n == 0:  # RunningStat.push sets the mean delta to the first row, then adds each change of the mean
        rs.mean_delta_array[...] = new_mean
    else:
        rs.mean_delta_array[...] += new_mean - old_mean
    rs.sum_sq_diff_array[...] += added_ssd
    rs.sum_sq_diff_delta_array[...] += added_ssd
    rs.num_pushes = total
    rs.num_pushes_delta += m


class MeanStdFilter(RLlibMeanStdFilter):
    """RLlib's ``MeanStdFilter`` (single agent, Box observations) with one
    batched statistics update (``push_batch``) and one vectorised scaling per
    vector step. State, merging across runners and the output space are
    RLlib's."""

    def __call__(self, *, rl_module, batch, episodes, explore=None, persistent_data=None, **kwargs):
        if self._filters is None:
            self._init_new_filters()
        eps = list(self.single_agent_episode_iterator(episodes))
        if not eps:
            return batch
        filt = self._filters[None]
        raw = np.stack([e.get_observations(indices=-1) for e in eps])
        if self._update_stats:
            push_batch(filt.running_stats, raw)
            push_batch(filt.buffer, raw)
        rs = filt.running_stats
        out = raw
        if filt.demean:
            out = out - rs.mean
        if filt.destd:
            out = out / (rs.std + SMALL_NUMBER)
        if filt.clip:
            out = np.clip(out, -filt.clip, filt.clip)
        out = out.astype(raw.dtype)
        space = self.observation_space
        for e, row in zip(eps, out):
            e.set_observations(at_indices=-1, new_data=row)
            if e.observation_space is not space:  # the setter converts the space: once per episode, not per step
                e.observation_space = space
        return batch
