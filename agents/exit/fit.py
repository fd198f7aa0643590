"""Fitting the proposal network to recorded searches (``agents.exit.selfplay.Data``), resumable bit for bit.

Adam over shuffled minibatches of decisions, minimising the policy loss plus ``value_coef`` times the value loss
(``agents.exit.model.losses``). The split holds out whole games (``val_frac``) for the reported losses; the last
epoch's weights are kept (Expert Iteration's rounds refit on fresh searches, so no epoch is chosen on held-out
games). Every epoch's order comes from a generator seeded by (the run's seed, the fit's key, the epoch), and the
model, the optimiser and the epoch are checkpointed every ``checkpoint_every`` epochs (``<dir>/fit.pt``): a fit
stopped and resumed from its checkpoint ends with the same weights as one that ran through, when torch runs with
the same number of threads.
"""
from __future__ import annotations

import os
import time
from pathlib import Path

import numpy as np
import torch

from billiards_env.bots.planner.shot_space import HEIGHT_BINS, SPEED_BINS

from .config import NetConfig
from .model import TorchProposalNet, input_stats, losses
from .selfplay import Data

CHECKPOINT = "fit.pt"


class Stop(Exception):
    """Raised by a fit's ``stop_after`` hook: the run stops as if killed after that epoch's checkpoint."""


def targets(data: Data, value_mix: float, hard: float = 0.0) -> dict:
    """The fit's targets: each candidate's (``hard`` of it moved to the played candidate: distillation) and the
    rest's, and the value's (the game's result, ``value_mix`` of it the search's value)."""
    a = data.arrays
    row = data.cand_row
    played = (a["cand_joint"] == a["chosen"][row]).astype(np.float64)
    y = (1 - hard) * a["cand_y"] + hard * played
    return dict(y=y.astype(np.float32), y_rest=((1 - hard) * a["y_rest"]).astype(np.float32),
                target=((1 - value_mix) * a["z"] + value_mix * a["value"]).astype(np.float32))


def batch_of(data: Data, t: dict, idx: np.ndarray) -> dict:
    """The tensors of decisions ``idx``."""
    a = data.arrays
    lo, hi = a["cand_ptr"][idx], a["cand_ptr"][idx + 1]
    k = hi - lo
    cand = np.repeat(lo - np.concatenate([[0], np.cumsum(k)[:-1]]), k) + np.arange(k.sum())
    as_t = lambda v, dt=torch.float32: torch.as_tensor(np.ascontiguousarray(v), dtype=dt)
    return dict(g=as_t(a["g"][idx]), x=as_t(a["x"][idx].astype(np.float32)), mask=as_t(a["mask"][idx], torch.bool),
                row=as_t(np.repeat(np.arange(len(idx)), k), torch.int64),
                joint=as_t(a["cand_joint"][cand], torch.int64),
                y=as_t(t["y"][cand]), y_rest=as_t(t["y_rest"][idx]), target=as_t(t["target"][idx]))


def fit(data: Data, cfg: NetConfig, t: dict, key: tuple, folder: Path, init=None, stats=None, log=print,
        stop_after: int | None = None) -> tuple:
    """(numpy ``ProposalNet``, report) fitted to ``data`` with targets ``t`` (``targets``); ``key``: the
    integers seeding it; ``folder``: where its checkpoint lives; ``init``: a ``ProposalNet`` to start from (its
    input statistics kept) when its sizes match ``cfg``, else ``stats`` (``model.input_stats``) or the data's.
    ``stop_after``: raise ``Stop`` after that epoch's checkpoint (a test's interruption)."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    a = data.arrays
    n, S, F = a["x"].shape
    T, V = a["mask"].shape[2], SPEED_BINS * HEIGHT_BINS
    hidden = (tuple(cfg.hidden_g), tuple(cfg.hidden_s), tuple(cfg.hidden_v))
    torch.manual_seed(int(np.random.SeedSequence(list(key)).generate_state(1)[0]))
    same = init is not None and (tuple(init.hidden["g"]), tuple(init.hidden["s"]), tuple(init.hidden["v"])) == hidden
    if same:
        model = TorchProposalNet.from_numpy(init)
    else:
        st = stats or (input_stats(a["g"], a["x"]) if init is None else (init.g_mean, init.g_std, init.s_mean,
                                                                           init.s_std))
        model = TorchProposalNet(a["g"].shape[1], F, T, V, hidden, st)
    opt = torch.optim.Adam(model.parameters(), lr=cfg.lr, weight_decay=cfg.l2)
    games = np.unique(a["game"])
    split = np.random.default_rng(list(key) + [0]).permutation(len(games))[:int(round(cfg.val_frac * len(games)))]
    is_val = np.isin(a["game"], games[split])
    val, tr = np.flatnonzero(is_val), np.flatnonzero(~is_val)
    start, report = 1, dict(samples=int(n), train=int(len(tr)), val=int(len(val)), epochs=[])
    ck = folder / CHECKPOINT
    if ck.exists():
        state = torch.load(ck, weights_only=False)
        model.load_state_dict(state["model"])
        opt.load_state_dict(state["optim"])
        start, report = state["epoch"] + 1, state["report"]
        log(f"    resumed the fit at epoch {start}")
    for epoch in range(start, cfg.epochs + 1):
        t0 = time.perf_counter()
        order = np.random.default_rng(list(key) + [epoch]).permutation(tr)
        tot = np.zeros(2)
        model.train()
        for lo in range(0, len(order), cfg.batch):
            pl, vl = losses(model, batch_of(data, t, order[lo:lo + cfg.batch]))
            loss = pl + cfg.value_coef * vl
            opt.zero_grad()
            loss.backward()
            opt.step()
            tot += [pl.item() * min(cfg.batch, len(order) - lo), vl.item() * min(cfg.batch, len(order) - lo)]
        row = dict(epoch=epoch, policy=float(tot[0] / max(len(tr), 1)), value=float(tot[1] / max(len(tr), 1)),
                   seconds=round(time.perf_counter() - t0, 2))
        if len(val):
            with torch.no_grad():
                pl, vl = losses(model, batch_of(data, t, val))
            row.update(val_policy=float(pl), val_value=float(vl))
        report["epochs"].append(row)
        log(f"    epoch {epoch}/{cfg.epochs}: policy {row['policy']:.4f} value {row['value']:.4f}"
            + (f" (held out: {row['val_policy']:.4f}, {row['val_value']:.4f})" if len(val) else "")
            + f", {row['seconds']:.1f} s")
        if epoch % cfg.checkpoint_every == 0 or epoch == cfg.epochs:
            tmp = folder / (CHECKPOINT + ".tmp")
            torch.save(dict(epoch=epoch, model=model.state_dict(), optim=opt.state_dict(), report=report), tmp)
            os.replace(tmp, ck)
        if stop_after is not None and epoch >= stop_after:
            raise Stop(f"stopped after epoch {epoch}")
    return model.to_numpy(), report

