"""Fitting a value network (``billiards_env.bots.learned.value.ValueNet``) to recorded games, in numpy.

Binary cross-entropy between the network's output and the recorded result of the shooter (1, 0, or 1/2 for a
game cut at the shot cap), minimised by Adam over shuffled minibatches, with L2 weight decay. Inputs are
standardised by the training set's mean and standard deviation (stored with the weights). A new network's
output layer starts at zero, so it starts as the lookahead's hand-made value (``bots.learned.value``).

The samples of one game are strongly correlated (they share the label), so the held-out split (``val_frac``)
holds out whole games (``groups``: a game id per sample; a table and its mirror image share one). The fit
keeps the weights of the epoch with the lowest held-out log loss, the starting weights (epoch 0) included:
a fit that cannot beat the starting value on games it did not see keeps it. The report gives that loss beside
the starting one and the constant predictor's. Seeded: the same data, settings and seed give the same
weights bit for bit.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from billiards_env.bots.learned.value import STD_FLOOR, ValueNet, base_logit

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


def init_net(d: int, hidden, mean, std, rng, ball_eases: bool = False) -> ValueNet:
    """Random hidden layers (normal, 1/sqrt(fan-in)) and a zero output layer."""
    sizes = [d, *hidden, 1]
    ws = [rng.normal(0, 1 / np.sqrt(a), (b, a)) for a, b in zip(sizes[:-1], sizes[1:])]
    ws[-1][:] = 0.0
    ws = tuple(ws)
    bs = tuple(np.zeros(b) for b in sizes[1:])
    return ValueNet(ws, bs, mean, std, ball_eases)


def fit_value(x: np.ndarray, y: np.ndarray, cfg: FitConfig, rng: np.random.Generator,
              init: ValueNet | None = None, groups: np.ndarray | None = None,
              ball_eases: bool = False) -> tuple[ValueNet, dict]:
    """(network, report) fitted to inputs ``x`` [N, D] and results ``y`` [N]; ``init``: start from these
    weights (and its input statistics); ``groups`` [N]: the game of each sample (the
    held-out split keeps games whole; default: every sample its own); ``ball_eases``: ``x`` ends with the
    balls' own eases (``ValueNet.ball_eases``)."""
    x, y = np.asarray(x, np.float64), np.asarray(y, np.float64)
    if len(x) < 2:
        raise ValueError(f"fit_value needs at least 2 samples, got {len(x)}")
    groups = np.arange(len(x)) if groups is None else np.asarray(groups)
    ids = np.unique(groups)
    held = rng.permutation(len(ids))[:int(round(cfg.val_frac * len(ids)))]
    is_val = np.isin(groups, ids[held])
    val, tr = np.nonzero(is_val)[0], np.nonzero(~is_val)[0]
    n_val = len(val)
    mean, std = x[tr].mean(axis=0), np.maximum(x[tr].std(axis=0), STD_FLOOR)
    net = init_net(x.shape[1], cfg.hidden, mean, std, rng, ball_eases)
    if (init is not None and init.in_dim == x.shape[1] and init.hidden == list(cfg.hidden)
            and init.ball_eases == ball_eases):
        net, mean, std = init, init.mean, init.std   # epoch 0 is the starting network exactly
    params = [np.array(a) for a in (*net.weights, *net.biases)]
    L = len(net.weights)
    m = [np.zeros_like(p) for p in params]
    v = [np.zeros_like(p) for p in params]
    b1, b2, t = 0.9, 0.999, 0
    xs = (x[tr] - mean) / std
    base = base_logit(x[tr], ball_eases=ball_eases)
    val_loss = (lambda ps: log_loss(ValueNet(tuple(ps[:L]), tuple(ps[L:]), mean, std, ball_eases)(x[val]),
                                    y[val])) \
        if n_val else (lambda ps: 0.0)
    best, best_loss, best_epoch = [p.copy() for p in params], val_loss(params), 0
    start_loss = best_loss
    for epoch in range(1, cfg.epochs + 1):
        order = rng.permutation(len(tr))
        for lo in range(0, len(order), cfg.batch):
            idx = order[lo:lo + cfg.batch]
            grads = _grads(params, L, xs[idx], y[tr][idx], base[idx], cfg.l2)
            t += 1
            for k, g in enumerate(grads):
                m[k] = b1 * m[k] + (1 - b1) * g
                v[k] = b2 * v[k] + (1 - b2) * g * g
                params[k] -= cfg.lr * (m[k] / (1 - b1 ** t)) / (np.sqrt(v[k] / (1 - b2 ** t)) + ADAM_EPS)
        loss = val_loss(params)
        if n_val and loss < best_loss:
            best, best_loss, best_epoch = [p.copy() for p in params], loss, epoch
    if not n_val:
        best, best_epoch = params, cfg.epochs
    net = ValueNet(tuple(best[:L]), tuple(best[L:]), mean, std, ball_eases)
    rep = dict(samples=int(len(x)), train=int(len(tr)), val=int(n_val), val_games=int(len(held)),
               mean_result=float(y.mean()), best_epoch=best_epoch)
    if n_val:
        rep.update(val_log_loss=best_loss, val_log_loss_start=start_loss,
                   val_log_loss_constant=log_loss(np.full(n_val, y[tr].mean()), y[val]))
    return net, rep


def _grads(params, L, x, y, base, l2):
    """Gradients of the mean cross-entropy (plus ``l2`` |W|^2 / 2) with respect to weights then biases."""
    ws, bs = params[:L], params[L:]
    hs = [x]
    for w, b in zip(ws[:-1], bs[:-1]):
        hs.append(np.tanh(hs[-1] @ w.T + b))
    z = (hs[-1] @ ws[-1].T + bs[-1])[:, 0] + base
    p = 1 / (1 + np.exp(-z))
    d = ((p - y) / len(y))[:, None]
    gw, gb = [None] * L, [None] * L
    for k in range(L - 1, -1, -1):
        gw[k] = d.T @ hs[k] + l2 * ws[k]
        gb[k] = d.sum(axis=0)
        if k:
            d = (d @ ws[k]) * (1 - hs[k] ** 2)
    return gw + gb
