"""Fitting a value network (``billiards_env.bots.learned.value.ValueNet``) to recorded games, in numpy.

Binary cross-entropy between the network's output and the recorded result of the shooter (1, 0, or 1/2 for a
game cut at the shot cap), minimised by Adam over shuffled minibatches, with L2 weight decay. Inputs are
standardised by the training set's mean and standard deviation (stored with the weights). Seeded: the same
data, settings and seed give the same weights bit for bit. A held-out split (``val_frac``) reports the fitted
network's log loss beside the constant predictor's (the data's mean result), so the fit shows what it learned.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from billiards_env.bots.learned.value import STD_FLOOR, ValueNet

ADAM_EPS = 1e-8        # Adam's denominator guard (its paper's default)
P_CLIP = 1e-7          # predicted probabilities kept this far from 0 and 1 in the log loss


@dataclasses.dataclass(frozen=True)
class FitConfig:
    hidden: tuple = (64, 64)
    epochs: int = 30
    batch: int = 256
    lr: float = 1e-3
    l2: float = 1e-4
    val_frac: float = 0.1


def log_loss(p: np.ndarray, y: np.ndarray) -> float:
    p = np.clip(p, P_CLIP, 1 - P_CLIP)
    return float(-(y * np.log(p) + (1 - y) * np.log(1 - p)).mean())


def init_net(d: int, hidden, mean, std, rng) -> ValueNet:
    sizes = [d, *hidden, 1]
    ws = tuple(rng.normal(0, 1 / np.sqrt(a), (b, a)) for a, b in zip(sizes[:-1], sizes[1:]))
    bs = tuple(np.zeros(b) for b in sizes[1:])
    return ValueNet(ws, bs, mean, std)


def fit_value(x: np.ndarray, y: np.ndarray, cfg: FitConfig, rng: np.random.Generator,
              init: ValueNet | None = None) -> tuple[ValueNet, dict]:
    """(network, report) fitted to inputs ``x`` [N, D] and results ``y`` [N]; ``init``: start from these
    weights (its input statistics are replaced by the data's)."""
    x, y = np.asarray(x, np.float64), np.asarray(y, np.float64)
    if len(x) < 2:
        raise ValueError(f"fit_value needs at least 2 samples, got {len(x)}")
    perm = rng.permutation(len(x))
    n_val = int(round(cfg.val_frac * len(x)))
    val, tr = perm[:n_val], perm[n_val:]
    mean, std = x[tr].mean(axis=0), np.maximum(x[tr].std(axis=0), STD_FLOOR)
    net = init_net(x.shape[1], cfg.hidden, mean, std, rng)
    if init is not None and init.in_dim == x.shape[1] and init.hidden == list(cfg.hidden):
        net = ValueNet(init.weights, init.biases, mean, std)
    params = [np.array(a) for a in (*net.weights, *net.biases)]
    L = len(net.weights)
    m = [np.zeros_like(p) for p in params]
    v = [np.zeros_like(p) for p in params]
    b1, b2, t = 0.9, 0.999, 0
    xs = (x[tr] - mean) / std
    for _ in range(cfg.epochs):
        order = rng.permutation(len(tr))
        for lo in range(0, len(order), cfg.batch):
            idx = order[lo:lo + cfg.batch]
            grads = _grads(params, L, xs[idx], y[tr][idx], cfg.l2)
            t += 1
            for k, g in enumerate(grads):
                m[k] = b1 * m[k] + (1 - b1) * g
                v[k] = b2 * v[k] + (1 - b2) * g * g
                params[k] -= cfg.lr * (m[k] / (1 - b1 ** t)) / (np.sqrt(v[k] / (1 - b2 ** t)) + ADAM_EPS)
    net = ValueNet(tuple(params[:L]), tuple(params[L:]), mean, std)
    rep = dict(samples=int(len(x)), train=int(len(tr)), val=int(n_val), mean_result=float(y.mean()))
    if n_val:
        rep.update(val_log_loss=log_loss(net(x[val]), y[val]),
                   val_log_loss_constant=log_loss(np.full(n_val, y[tr].mean()), y[val]))
    return net, rep


def _grads(params, L, x, y, l2):
    """Gradients of the mean cross-entropy (plus ``l2`` |W|^2 / 2) with respect to weights then biases."""
    ws, bs = params[:L], params[L:]
    hs = [x]
    for w, b in zip(ws[:-1], bs[:-1]):
        hs.append(np.tanh(hs[-1] @ w.T + b))
    z = (hs[-1] @ ws[-1].T + bs[-1])[:, 0]
    p = 1 / (1 + np.exp(-z))
    d = ((p - y) / len(y))[:, None]
    gw, gb = [None] * L, [None] * L
    for k in range(L - 1, -1, -1):
        gw[k] = d.T @ hs[k] + l2 * ws[k]
        gb[k] = d.sum(axis=0)
        if k:
            d = (d @ ws[k]) * (1 - hs[k] ** 2)
    return gw + gb
