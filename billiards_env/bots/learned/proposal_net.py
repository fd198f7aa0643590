"""The proposal network in numpy: what it reads, its forward pass, its distribution over the structured shot space
(``bots.planner.shot_space``) and its files (docs/expert_iteration.md). Training is ``agents.exit`` (torch); this
module never imports torch.

Inputs, one row per table in the shooter's frame:

- **the table** (``global_features``): ``bots.learned.value.value_features`` (every ball's position, on-table
  flag and legality, ball in hand, the ease of the shooter's best pot in the planner's window model
  (``planner.leave.leave_ease``) and the balls left) and three flags (a call needed, may pass, push-out allowed):
  the same numbers at the root (a view) and at a previewed leaf (``leaf_globals``), so the value head values both;
- **each slot** (``slot_features``, ``F`` numbers): its kind, whether it is legal, a pot's success estimate and
  cut at each ball-in-hand turn, the distances, the window's half-width, whether the path is open, the speed base,
  the aim's direction, the ball's place and number, the pocket's kind (or the contact line, rail, fan direction)
  and ball in hand.

Network: the table's inputs, standardised, through tanh layers to an embedding ``e``; every slot's inputs,
standardised, with ``e`` through the same tanh layers (one set of weights for all slots: a pot of the 3 and of
the 7 are judged alike) to ``1 + T + V`` outputs: the slot's logit, its turns' and its variants' logits; ``e``
through a tanh layer to one output, the shooter's chance to win (sigmoid). The distribution over proposals
factors as p(slot) p(turn | slot) p(variant | slot), each a softmax over the legal entries (``joint_logp``).

Files: ``<stem>.npz`` (plain arrays, read with ``allow_pickle=False``) and ``<stem>.json``, the card (format,
version, game, sizes, how it was trained); ``save`` / ``load``.
"""
from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import numpy as np

from ...rules import records as RR
from ..planner import leave as LEAVE
from ..planner import shot_space as SS
from .value import value_features

FORMAT = "billiards_env proposal network"
FORMAT_VERSION = 1
N_FLAGS = 3                    # call needed, may pass, push-out allowed
F = 23                         # slot features (slot_features)
STD_FLOOR = 1e-6               # an input's standard deviation is at least this (a constant input is not blown up)


def global_size(n_balls: int) -> int:
    return 4 * n_balls + 5 + N_FLAGS


def _globals(view, pos, on, cons, ease) -> np.ndarray:
    """``value_features`` of tables and the three flags of their shooter's constraints ``cons``."""
    base = value_features(view.game, view.table.width, view.table.length, pos, on, cons.targets, cons.ball_in_hand,
                          ease)
    flags = np.stack([cons.call_needed, cons.may_pass, cons.push_out_allowed], axis=1).astype(np.float64)
    return np.concatenate([base, flags], axis=1).astype(np.float32)


def root_globals(view, rows) -> np.ndarray:
    """[n, global_size] the table inputs of view rows ``rows`` (their shooter to move)."""
    rows = np.asarray(rows, np.int64)
    cons = view.constraints.take(rows)
    ease = LEAVE.leave_ease(view, view.pos[rows], view.on_table[rows], cons.targets, view.in_hand[rows])
    return _globals(view, view.pos[rows], view.on_table[rows], cons, ease)


def leaf_globals(view, pv) -> np.ndarray:
    """[k] the table inputs of previewed shots' leaves, for their next shooter."""
    nxt = pv.next
    ease = LEAVE.leave_ease(view, pv.pos, pv.on_table, nxt.targets, nxt.ball_in_hand != RR.IN_HAND_NONE)
    return _globals(view, pv.pos, pv.on_table, nxt, ease)


def slot_features(layout) -> np.ndarray:
    """[n, S, F] float32 every slot's inputs (module docstring) on a ``shot_space.Layout``."""
    view, sp = layout.view, layout.space
    n, S, T = layout.mask.shape
    W, L, R = view.table.width, view.table.length, view.params.R
    diag = math.hypot(W, L)
    C = SS.CENTRE
    kind = np.eye(4)[sp.kind]                                                       # [S, 4]
    pot = sp.kind == SS.POT
    obj = view.pos[layout.rows][:, np.maximum(sp.ball, 0)]                          # [n, S, 2]
    has_ball = (sp.ball > 0)[None, :]
    side = (np.abs(view.pockets[:, 0] - W / 2) > W / 4) & (np.abs(view.pockets[:, 1] - L / 2) < L / 4)
    line = np.select([pot, sp.kind == SS.SAFE, sp.kind == SS.BANK],
                     [side[np.maximum(sp.pocket, 0)].astype(np.float64),
                      np.asarray(SS.FULLNESS)[np.clip(sp.line, 0, len(SS.FULLNESS) - 1)], sp.line / SS.N_RAILS],
                     sp.line / SS.N_FAN)
    speed = np.where(pot[None], layout.base[:, :, C] / view.params.max_speed, layout.base[:, :, C] / diag)
    cols = [np.broadcast_to(kind, (n, S, 4)),
            layout.mask.any(axis=2)[..., None],
            layout.prob, layout.cut / (np.pi / 2),
            (layout.dcg[:, :, C] / diag)[..., None], (layout.dop[:, :, C] / diag)[..., None],
            (layout.half[:, :, C] / R)[..., None], layout.open_[:, :, C, None],
            np.where(sp.kind == SS.FAN, 0.0, speed)[..., None],
            np.cos(layout.phi[:, :, C])[..., None], np.sin(layout.phi[:, :, C])[..., None],
            np.where(has_ball, obj[..., 0] / W, 0.0)[..., None], np.where(has_ball, obj[..., 1] / L, 0.0)[..., None],
            np.broadcast_to((sp.ball / max(sp.n_balls - 1, 1))[None, :, None], (n, S, 1)),
            np.broadcast_to(line[None, :, None], (n, S, 1)),
            np.broadcast_to(layout.hand[:, None, None], (n, S, 1))]
    x = np.concatenate([np.asarray(c, np.float64) for c in cols], axis=2)
    assert x.shape[2] == F, x.shape
    return x.astype(np.float32)


@dataclasses.dataclass(frozen=True)
class ProposalNet:
    """The network's arrays (float32): ``g`` (table layers), ``s`` (slot layers, the last one the outputs),
    ``v`` (value layers) as tuples of (weight [out, in], bias [out]); the inputs' ``g_mean``, ``g_std``,
    ``s_mean``, ``s_std``; ``turns`` and ``variants``: the output split."""

    g: tuple
    s: tuple
    v: tuple
    g_mean: np.ndarray
    g_std: np.ndarray
    s_mean: np.ndarray
    s_std: np.ndarray
    turns: int
    variants: int

    def __post_init__(self):
        if self.s[-1][0].shape[0] != 1 + self.turns + self.variants or self.v[-1][0].shape[0] != 1:
            raise ValueError("ProposalNet: the slot head must give 1 + T + V outputs and the value head one")

    @property
    def hidden(self) -> dict:
        return dict(g=[w.shape[0] for w, _ in self.g], s=[w.shape[0] for w, _ in self.s[:-1]],
                    v=[w.shape[0] for w, _ in self.v[:-1]])

    def forward(self, g: np.ndarray, x: np.ndarray) -> tuple:
        """(outputs [n, S, 1 + T + V], value [n]) of table inputs ``g`` [n, G] and slot inputs ``x`` [n, S, F]."""
        e = (np.asarray(g, np.float32) - self.g_mean) / self.g_std
        for w, b in self.g:
            e = np.tanh(e @ w.T + b)
        n, S, _ = x.shape
        h = np.concatenate([(np.asarray(x, np.float32) - self.s_mean) / self.s_std,
                            np.broadcast_to(e[:, None], (n, S, e.shape[1]))], axis=2)
        for w, b in self.s[:-1]:
            h = np.tanh(h @ w.T + b)
        out = h @ self.s[-1][0].T + self.s[-1][1]
        u = e
        for w, b in self.v[:-1]:
            u = np.tanh(u @ w.T + b)
        z = (u @ self.v[-1][0].T + self.v[-1][1])[:, 0]
        return out, 1.0 / (1.0 + np.exp(-z.astype(np.float64)))

    def value(self, g: np.ndarray) -> np.ndarray:
        """[n] the value head alone."""
        e = (np.asarray(g, np.float32) - self.g_mean) / self.g_std
        for w, b in self.g:
            e = np.tanh(e @ w.T + b)
        for w, b in self.v[:-1]:
            e = np.tanh(e @ w.T + b)
        z = (e @ self.v[-1][0].T + self.v[-1][1])[:, 0]
        return 1.0 / (1.0 + np.exp(-z.astype(np.float64)))

    def arrays(self) -> dict:
        out = dict(g_mean=self.g_mean, g_std=self.g_std, s_mean=self.s_mean, s_std=self.s_std)
        for part in ("g", "s", "v"):
            for k, (w, b) in enumerate(getattr(self, part)):
                out[f"{part}_w{k}"], out[f"{part}_b{k}"] = w, b
        return out

    @classmethod
    def from_arrays(cls, arrays, turns: int, variants: int) -> "ProposalNet":
        def layers(part):
            n = sum(1 for k in arrays if k.startswith(f"{part}_w"))
            return tuple((np.asarray(arrays[f"{part}_w{k}"], np.float32),
                          np.asarray(arrays[f"{part}_b{k}"], np.float32))
                         for k in range(n))
        std = lambda k: np.maximum(np.asarray(arrays[k], np.float32), STD_FLOOR)
        return cls(layers("g"), layers("s"), layers("v"), np.asarray(arrays["g_mean"], np.float32), std("g_std"),
                   np.asarray(arrays["s_mean"], np.float32), std("s_std"), int(turns), int(variants))

    def save(self, stem, card: dict) -> dict:
        """``<stem>.npz`` and ``<stem>.json`` (``card`` with the format and sizes added); returns the card."""
        stem = Path(stem)
        stem.parent.mkdir(parents=True, exist_ok=True)
        np.savez(stem.with_suffix(".npz"), **self.arrays())
        doc = dict(format=FORMAT, format_version=FORMAT_VERSION, **card, turns=self.turns, variants=self.variants,
                   hidden=self.hidden, global_inputs=int(self.g_mean.shape[0]), slot_inputs=int(self.s_mean.shape[0]))
        stem.with_suffix(".json").write_text(json.dumps(doc, indent=1) + "\n")
        return doc


def load(stem) -> tuple:
    """(network, card) from ``<stem>.npz`` and ``<stem>.json``; a ValueError names what is missing or wrong."""
    stem = Path(stem)
    path = stem.with_suffix(".json")
    if not path.exists() or not stem.with_suffix(".npz").exists():
        raise ValueError(f"no proposal network at {stem} (expected {path.name} and {stem.with_suffix('.npz').name})")
    doc = json.loads(path.read_text())
    if doc.get("format") != FORMAT or int(doc.get("format_version", -1)) > FORMAT_VERSION:
        raise ValueError(f"{path}: not a proposal network card of format {FORMAT!r} version <= {FORMAT_VERSION}")
    with np.load(stem.with_suffix(".npz"), allow_pickle=False) as z:
        net = ProposalNet.from_arrays({k: z[k] for k in z.files}, doc["turns"], doc["variants"])
    if net.hidden != doc["hidden"]:
        raise ValueError(f"{stem}: the weights have hidden sizes {net.hidden}, the card says {doc['hidden']}")
    return net, doc


def joint_logp(out: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """[n, S * T * V] log p(slot) + log p(turn | slot) + log p(variant | slot) of outputs ``out`` [n, S, 1 + T + V]
    over the legal (slot, turn) pairs ``mask`` [n, S, T] (-inf elsewhere)."""
    n, S, T = mask.shape
    out = np.asarray(out, np.float64)
    slot = np.where(mask.any(axis=2), out[..., 0], -np.inf)
    turn = np.where(mask, out[..., 1:1 + T], -np.inf)
    var = out[..., 1 + T:]
    ls = lambda x, ax: x - _logsumexp(x, ax)
    with np.errstate(invalid="ignore"):        # a slot without a legal turn: -inf - -inf, masked below
        lp = ls(slot, 1)[:, :, None, None] + ls(turn, 2)[..., None] + ls(var, 2)[:, :, None, :]
    return np.where(mask[..., None], lp, -np.inf).reshape(n, -1)


def best_proposal(out: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """[n] the most probable legal proposal's joint index, ``argmax(joint_logp(out, mask), axis=1)`` found per
    factor (the best turn and variant of every slot, then the best slot) without the [n, S * T * V] array: the
    fast player's choice."""
    n, S, T = mask.shape
    out = np.asarray(out, np.float64)
    V = out.shape[2] - 1 - T
    legal = mask.any(axis=2)
    ls = lambda x, ax: x - _logsumexp(x, ax)
    with np.errstate(invalid="ignore"):        # a slot without a legal turn: nan, masked below
        lt = ls(np.where(mask, out[..., 1:1 + T], -np.inf), 2)
    lv = ls(out[..., 1 + T:], 2)
    t, v = np.argmax(np.nan_to_num(lt, nan=-np.inf), axis=2), np.argmax(lv, axis=2)
    pick = lambda x, i: np.take_along_axis(x, i[..., None], axis=2)[..., 0]
    score = np.where(legal, ls(np.where(legal, out[..., 0], -np.inf), 1) + pick(lt, t) + pick(lv, v), -np.inf)
    s = np.argmax(score, axis=1)
    r = np.arange(n)
    return (s * T + t[r, s]) * V + v[r, s]


def _logsumexp(x: np.ndarray, axis: int) -> np.ndarray:
    top = np.max(x, axis=axis, keepdims=True)
    top = np.where(np.isfinite(top), top, 0.0)
    with np.errstate(divide="ignore"):
        return top + np.log(np.exp(x - top).sum(axis=axis, keepdims=True))
