"""The proposal network in torch (training only): the layers of ``billiards_env.bots.learned.proposal_net``
(``ProposalNet.forward`` computes the same function in numpy; ``to_numpy`` exports it), and the losses.

Policy loss: the cross-entropy between the search's allocation (each candidate's target and the rest's,
``agents.exit.selfplay``) and the network's distribution, p(candidate) = p(slot) p(turn | slot) p(variant | slot)
and p(rest) = 1 - the candidates' sum. Value loss: binary cross-entropy of the value head against the target
(the game's result, mixed with the search's value by ``value_mix``).
"""
from __future__ import annotations

import numpy as np
import torch
from torch import nn

from billiards_env.bots.learned.proposal_net import STD_FLOOR, ProposalNet

P_FLOOR = 1e-6          # p(rest) is kept at least this in its log (the candidates' sum may round to 1)


class TorchProposalNet(nn.Module):
    """Layers as ``ProposalNet``: table tanh layers ``g``, slot tanh layers ``s`` then the slot outputs, value tanh
    layers then one output; the inputs' statistics as buffers. The output layers start at zero (a uniform policy,
    a value of 1/2)."""

    def __init__(self, G: int, F: int, T: int, V: int, hidden: tuple, stats: tuple):
        super().__init__()
        hg, hs, hv = (list(h) for h in hidden)
        self.T, self.V = T, V
        self.g = nn.ModuleList(nn.Linear(a, b) for a, b in zip([G] + hg[:-1], hg))
        e = hg[-1] if hg else G
        self.s = nn.ModuleList(nn.Linear(a, b) for a, b in zip([F + e] + hs, hs + [1 + T + V]))
        self.v = nn.ModuleList(nn.Linear(a, b) for a, b in zip([e] + hv, hv + [1]))
        for head in (self.s[-1], self.v[-1]):
            nn.init.zeros_(head.weight)
            nn.init.zeros_(head.bias)
        for name, a in zip(("g_mean", "g_std", "s_mean", "s_std"), stats):
            self.register_buffer(name, torch.as_tensor(np.asarray(a, np.float32)))

    def forward(self, g: torch.Tensor, x: torch.Tensor):
        """(slot outputs [n, S, 1 + T + V], value logit [n])."""
        e = (g - self.g_mean) / self.g_std
        for layer in self.g:
            e = torch.tanh(layer(e))
        n, S, _ = x.shape
        h = torch.cat([(x - self.s_mean) / self.s_std, e[:, None].expand(n, S, e.shape[1])], dim=2)
        for layer in self.s[:-1]:
            h = torch.tanh(layer(h))
        out = self.s[-1](h)
        u = e
        for layer in self.v[:-1]:
            u = torch.tanh(layer(u))
        return out, self.v[-1](u)[:, 0]

    def to_numpy(self) -> ProposalNet:
        lay = lambda ms: tuple((m.weight.detach().numpy().astype(np.float32).copy(),
                                m.bias.detach().numpy().astype(np.float32).copy()) for m in ms)
        buf = lambda t: t.detach().numpy().astype(np.float32).copy()
        return ProposalNet(lay(self.g), lay(self.s), lay(self.v), buf(self.g_mean), buf(self.g_std),
                           buf(self.s_mean), buf(self.s_std), self.T, self.V)

    @classmethod
    def from_numpy(cls, net: ProposalNet) -> "TorchProposalNet":
        G, F = net.g_mean.shape[0], net.s_mean.shape[0]
        hidden = (net.hidden["g"], net.hidden["s"], net.hidden["v"])
        m = cls(G, F, net.turns, net.variants, hidden, (net.g_mean, net.g_std, net.s_mean, net.s_std))
        with torch.no_grad():
            for mods, arrs in ((m.g, net.g), (m.s, net.s), (m.v, net.v)):
                for mod, (w, b) in zip(mods, arrs):
                    mod.weight.copy_(torch.as_tensor(w))
                    mod.bias.copy_(torch.as_tensor(b))
        return m


def input_stats(g: np.ndarray, x: np.ndarray) -> tuple:
    """(g_mean, g_std, s_mean, s_std) of training inputs (``x`` over every table's legal and illegal slots)."""
    xf = x.reshape(-1, x.shape[-1]).astype(np.float64)
    g = g.astype(np.float64)
    return (g.mean(0), np.maximum(g.std(0), STD_FLOOR), xf.mean(0), np.maximum(xf.std(0), STD_FLOOR))


def candidate_logp(out: torch.Tensor, mask: torch.Tensor, row: torch.Tensor, joint: torch.Tensor, T: int, V: int):
    """log p of candidates (their decision ``row`` [M] and ``joint`` index [M]) under outputs ``out`` [n, S, 1 + T
    + V] over the legal (slot, turn) pairs ``mask`` [n, S, T]."""
    neg = torch.finfo(out.dtype).min
    slot = torch.log_softmax(torch.where(mask.any(dim=2), out[..., 0], neg), dim=1)
    turn = torch.log_softmax(torch.where(mask, out[..., 1:1 + T], neg), dim=2)
    var = torch.log_softmax(out[..., 1 + T:], dim=2)
    s, t, v = joint // (T * V), (joint // V) % T, joint % V
    return slot[row, s] + turn[row, s, t] + var[row, s, v]


def losses(model: TorchProposalNet, batch: dict) -> tuple:
    """(policy loss, value loss) of a batch (tensors: ``g``, ``x``, ``mask``, ``row``, ``joint``, ``y``,
    ``y_rest``, ``target``)."""
    out, zv = model(batch["g"], batch["x"])
    n = out.shape[0]
    lp = candidate_logp(out, batch["mask"], batch["row"], batch["joint"], model.T, model.V)
    taken = torch.zeros(n, dtype=out.dtype).index_add(0, batch["row"], lp.exp())
    rest = torch.log(torch.clamp(1.0 - taken, min=P_FLOOR))
    ce = -(torch.zeros(n, dtype=out.dtype).index_add(0, batch["row"], batch["y"] * lp) + batch["y_rest"] * rest)
    value = nn.functional.binary_cross_entropy_with_logits(zv, batch["target"])
    return ce.mean(), value
