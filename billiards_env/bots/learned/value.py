"""A learned value of a table for the two-player games, and the lookahead that searches with it.

``ValueNet`` is a small MLP V(table, shooter) -> the probability that the player to shoot wins the game from
here. Its input (``value_features``, one row per table, in the shooter's frame):

- every ball's position as fractions of the table's width and length (0 for a pocketed ball), [B, 2];
- every ball's on-table flag [B] and the shooter's legal targets among them [B] (in 8-ball that is the
  shooter's group, or the 8 when it is on; in 9-ball the lowest ball);
- ball in hand, one-hot over ``rules.IN_HAND_*`` [3];
- the ease of the shooter's best pot (``GameLookahead.leave_ease``: the geometric pot model) and the balls the
  shooter still has to pocket over B - 1 (``game_lookahead.balls_left``);
- optionally (a network with ``ball_eases``), every object ball's own ease [2B]: its best pot with the cue ball
  in hand (how pottable it is from anywhere: 0 for a ball with no open pocket) and from the cue ball where it
  lies (the in-hand ease when the shooter has ball in hand); 0 for the cue ball and pocketed balls
  (``ball_eases``). They say which balls a run must still get position on, which the best pot's ease alone
  does not.

Fouls in a row are not an input: the previewed leaves (``contract.preview.Preview``) carry the next shooter's
constraints but not the fouls count, and the value must be computed the same way at the leaves as in training.

The network is a correction to the lookahead's own leave model: its output is
``sigmoid(logit(position_value(ease)) + f(x))``, where ``position_value`` is ``bots.game_lookahead``'s
(``V_NONE + (V_FULL - V_NONE) ease``) and ``f`` an MLP (tanh hidden layers, one linear output unit) of the
standardised inputs. With ``f``'s output layer at zero it is exactly the hand-made value, which is where the
league's fit starts. It runs in numpy float64. It is stored as an ``.npz`` of plain arrays (``numpy.load`` with
``allow_pickle=False``) beside a JSON card (format, version, game, feature size, hidden sizes, how it was
trained), like the ladder (``bots.learned.ladder``). The shipped values are ``value/<game>.npz`` and ``.json``;
``agents.league`` trains them (docs/league.md).

``ValueLookahead`` (``make_bot("value-lookahead")``) is ``GameLookahead`` with the network in its leaf valuer
(the lookahead's ``leaf_value`` hook): it searches at decision time exactly as ``lookahead`` does (the same
candidates, the same noisy previews). ``LeafValue(where=...)`` says which leaves the network values:

- ``"blind"`` (the default): the leaves where the hand-made value has nothing to say, the tables whose next
  shooter has no open pot (ease 0; ``position_value`` calls every one of them ``V_NONE``, an even safety
  battle); every other leaf keeps ``position_value``. The network tells a good safety from a poor one there;
- ``"all"``: every leaf (measured weaker than ``lookahead``: docs/league.md).
"""
from __future__ import annotations

import dataclasses
import json
from functools import lru_cache
from pathlib import Path

import numpy as np

from ...rules import records as RR
from ..game_lookahead import V_FULL, V_NONE, GameLookahead, balls_left, position_value

VALUE_DIR = Path(__file__).with_name("value")
FORMAT = "billiards_env value network"
FORMAT_VERSION = 2  # 2: ``ball_eases`` in the card (a version-1 card is a network without them)
STD_FLOOR = 1e-6   # an input's standard deviation is at least this (a constant input is not blown up)
BASE_CLIP = 1e-6   # the hand-made value is kept this far from 0 and 1 before its logit
HAND_CODES = (RR.IN_HAND_NONE, RR.IN_HAND_ANYWHERE, RR.IN_HAND_KITCHEN)


def ease_index(n_balls: int) -> int:
    """The column of ``value_features`` that holds the ease."""
    return 4 * n_balls + len(HAND_CODES)


def n_balls_of(dim: int, ball_eases: bool = False) -> int:
    """The balls of tables whose ``value_features`` rows have ``dim`` columns."""
    return (dim - len(HAND_CODES) - 2) // (6 if ball_eases else 4)


def base_logit(x: np.ndarray, v_none: float = V_NONE, v_full: float = V_FULL, ball_eases: bool = False) -> np.ndarray:
    """[N] the logit of the lookahead's ``position_value`` of feature rows ``x`` (from their ease column)."""
    n_balls = n_balls_of(x.shape[1], ball_eases)
    p = np.clip(v_none + (v_full - v_none) * x[:, ease_index(n_balls)], BASE_CLIP, 1 - BASE_CLIP)
    return np.log(p / (1 - p))


def feature_size(n_balls: int, ball_eases: bool = False) -> int:
    """The length of ``value_features`` rows for tables of ``n_balls`` balls."""
    return (6 if ball_eases else 4) * n_balls + len(HAND_CODES) + 2


def ball_eases(geo, view, pos, on, ball_in_hand) -> np.ndarray:
    """[k, 2B] every object ball's ease (module docstring): its best pot's success probability with ball in
    hand, then from the cue ball where it lies; ``geo``: the ``GameLookahead`` whose pot model judges them."""
    pos, on = np.asarray(pos, np.float64), np.asarray(on, bool)
    k = len(on)
    balls = on.copy()
    balls[:, 0] = False
    hand = np.asarray(ball_in_hand) != RR.IN_HAND_NONE
    anywhere = geo.pot_table(view, pos, on, balls, pos[:, 0], np.ones(k, bool))["prob"].max(axis=2)
    from_cue = geo.pot_table(view, pos, on, balls & (on[:, :1] & ~hand[:, None]), pos[:, 0],
                             np.zeros(k, bool))["prob"].max(axis=2)
    return np.concatenate([anywhere, np.where(hand[:, None], anywhere, from_cue)], axis=1)


def value_features(game: str, width: float, length: float, pos, on, targets, ball_in_hand, ease,
                   balls=None) -> np.ndarray:
    """[k, feature_size(B, balls is not None)] float64 inputs of tables (module docstring): ``pos`` [k, B, 2],
    ``on`` and ``targets`` [k, B], ``ball_in_hand`` [k] (``IN_HAND_*``), ``ease`` [k]; ``balls`` [k, 2B]: the
    balls' own eases (``ball_eases``), appended when given."""
    pos, on, targets = np.asarray(pos, np.float64), np.asarray(on, bool), np.asarray(targets, bool)
    k, B = on.shape
    xy = pos / np.array([width, length])
    xy = np.where(on[..., None], xy, 0.0).reshape(k, 2 * B)
    hand = np.stack([np.asarray(ball_in_hand) == c for c in HAND_CODES], axis=1)
    left = balls_left(game, on, targets) / max(B - 1, 1)
    cols = [xy, on, targets & on, hand, np.asarray(ease, np.float64)[:, None], left[:, None]]
    if balls is not None:
        cols.append(np.asarray(balls, np.float64))
    return np.concatenate(cols, axis=1).astype(np.float64)


def mirror_features(x: np.ndarray, n_balls: int) -> np.ndarray:
    """The same tables mirrored across the long axis (x -> width - x): the rules and the table are symmetric
    under it, so a table and its mirror image are worth the same (training data doubled); the balls' eases
    are the same in the mirror image."""
    m = np.array(x, copy=True)
    xs = m[:, 0:2 * n_balls:2]
    on = m[:, 2 * n_balls:3 * n_balls] > 0
    m[:, 0:2 * n_balls:2] = np.where(on, 1.0 - xs, 0.0)
    return m


@dataclasses.dataclass(frozen=True)
class ValueNet:
    """``weights[k]`` [out, in] and ``biases[k]`` [out] (float64) of the tanh hidden layers and the one-unit
    output of the correction ``f``; ``mean`` and ``std`` [D] standardise the inputs; ``ball_eases``: its
    inputs end with the balls' own eases (``value_features``' ``balls``)."""
    weights: tuple
    biases: tuple
    mean: np.ndarray
    std: np.ndarray
    ball_eases: bool = False

    def __post_init__(self):
        if len(self.weights) != len(self.biases) or not self.weights:
            raise ValueError("weights and biases must be non-empty and of the same length")
        if self.weights[-1].shape[0] != 1:
            raise ValueError(f"the output layer must have one unit, got {self.weights[-1].shape[0]}")

    @property
    def in_dim(self) -> int:
        return self.weights[0].shape[1]

    @property
    def hidden(self) -> list:
        return [w.shape[0] for w in self.weights[:-1]]

    def logit(self, x: np.ndarray) -> np.ndarray:
        x = np.asarray(x, np.float64)
        if x.ndim != 2 or x.shape[1] != self.in_dim:
            raise ValueError(f"the value network takes inputs [N, {self.in_dim}], got {list(x.shape)}")
        h = (x - self.mean) / self.std
        for w, b in zip(self.weights[:-1], self.biases[:-1]):
            h = np.tanh(h @ w.T + b)
        return (h @ self.weights[-1].T + self.biases[-1])[:, 0] + base_logit(x, ball_eases=self.ball_eases)

    def __call__(self, x: np.ndarray) -> np.ndarray:
        """[N] the shooter's chance to win."""
        return 1.0 / (1.0 + np.exp(-self.logit(x)))

    def arrays(self) -> dict:
        out = {f"w{k}": w for k, w in enumerate(self.weights)}
        out.update({f"b{k}": b for k, b in enumerate(self.biases)})
        out.update(mean=self.mean, std=self.std)
        return out

    @classmethod
    def from_arrays(cls, arrays, ball_eases: bool = False) -> "ValueNet":
        n = sum(1 for k in arrays if k[0] == "w" and k[1:].isdigit())
        return cls(tuple(np.asarray(arrays[f"w{k}"], np.float64) for k in range(n)),
                   tuple(np.asarray(arrays[f"b{k}"], np.float64) for k in range(n)),
                   np.asarray(arrays["mean"], np.float64), np.maximum(np.asarray(arrays["std"], np.float64), STD_FLOOR),
                   ball_eases)

    def save(self, stem, card: dict) -> None:
        """``<stem>.npz`` (the arrays) and ``<stem>.json`` (``card`` with the format and architecture added)."""
        stem = Path(stem)
        stem.parent.mkdir(parents=True, exist_ok=True)
        np.savez(stem.with_suffix(".npz"), **self.arrays())
        doc = dict(format=FORMAT, format_version=FORMAT_VERSION, **card, in_dim=self.in_dim, hidden=self.hidden,
                   ball_eases=self.ball_eases)
        stem.with_suffix(".json").write_text(json.dumps(doc, indent=2) + "\n")


def load_value(stem) -> tuple[ValueNet, dict]:
    """(network, card) from ``<stem>.npz`` and ``<stem>.json``."""
    stem = Path(stem)
    path = stem.with_suffix(".json")
    if not path.exists():
        raise ValueError(f"no value network at {stem} (expected {path.name} and {stem.with_suffix('.npz').name})")
    doc = json.loads(path.read_text())
    if doc.get("format") != FORMAT or int(doc.get("format_version", -1)) > FORMAT_VERSION:
        raise ValueError(f"{path}: not a value card of format {FORMAT!r} version <= {FORMAT_VERSION}")
    with np.load(stem.with_suffix(".npz"), allow_pickle=False) as z:
        net = ValueNet.from_arrays({k: z[k] for k in z.files}, bool(doc.get("ball_eases", False)))
    if net.hidden != list(doc["hidden"]) or net.in_dim != int(doc["in_dim"]):
        raise ValueError(f"{stem}: the weights are {net.in_dim} -> {net.hidden}, the card says "
                         f"{doc['in_dim']} -> {doc['hidden']}")
    return net, doc


@lru_cache(maxsize=None)
def _shipped(game: str, root: str) -> tuple[ValueNet, dict]:
    return load_value(Path(root) / game)


WHERE = ("blind", "all")


class LeafValue:
    """The lookahead's ``leaf_value`` hook backed by value networks: ``nets`` maps a game to its network, or
    ``root`` (a folder of ``<game>.npz`` / ``.json``) supplies them (read once per process); ``where``: the
    leaves the network values (module docstring), the others keep ``position_value``."""

    def __init__(self, nets: dict | None = None, root=VALUE_DIR, where: str = "blind"):
        if where not in WHERE:
            raise ValueError(f"where must be one of {WHERE}, got {where!r}")
        self.nets, self.root, self.where = dict(nets or {}), Path(root), where
        self.geo = None  # the pot model of the balls' eases (a GameLookahead), made when a network needs them

    def net(self, game: str) -> ValueNet:
        net = self.nets.get(game)
        if net is None:
            if not (self.root / f"{game}.json").exists():
                raise ValueError(f"no value network for {game} in {self.root}")
            net = self.nets[game] = _shipped(game, str(self.root))[0]
        return net

    def values(self, view, pos, on, targets, ball_in_hand, ease) -> np.ndarray:
        """[k] the network's value of every given table."""
        net = self.net(view.game)
        balls = None
        if net.ball_eases:
            self.geo = self.geo or GameLookahead(reply_eval=0, break_search=0)
            balls = ball_eases(self.geo, view, pos, on, ball_in_hand)
        x = value_features(view.game, view.table.width, view.table.length, pos, on, targets, ball_in_hand, ease, balls)
        return net(x)

    def __call__(self, view, pos, on, targets, ball_in_hand, ease) -> np.ndarray:
        if self.where == "all":
            return self.values(view, pos, on, targets, ball_in_hand, ease)
        v = position_value(ease)
        blind = np.nonzero(ease <= 0)[0]
        if len(blind):
            v[blind] = self.values(view, pos[blind], on[blind], targets[blind], np.asarray(ball_in_hand)[blind],
                                   ease[blind])
        return v


class ValueLookahead(GameLookahead):
    """``lookahead`` searching with a learned leaf value (module docstring)."""

    name = "value-lookahead"

    def __init__(self, seed: int = 0, nets: dict | None = None, root=VALUE_DIR, where: str = "blind", **changes):
        super().__init__(seed=seed, leaf_value=LeafValue(nets, root, where), **changes)


def value_lookahead(seed: int = 0, **kw) -> ValueLookahead:
    """The ``value-lookahead`` bot (``bots.make_bot("value-lookahead")``) with the shipped networks."""
    return ValueLookahead(seed=seed, **kw)
