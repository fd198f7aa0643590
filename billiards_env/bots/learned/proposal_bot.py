"""The players of the proposal network (docs/expert_iteration.md), numpy only:

- ``exit-search``: the search over the network's best proposals (``bots.planner.proposals``: champion's
  noise-free previews, one-ply leave and successive halving, run over the ``k`` proposals the network ranks
  highest, the leaves valued partly by the network's value head);
- ``exit-fast``: the distilled network alone: its most probable proposal, decoded and throw-corrected
  (``shot_space.refine``: a few two-ball simulations, the proposal's local refinement), with no search; it passes
  where ``may_pass`` when its value head gives the shooter under 1/2, and never declares a push-out.

Both play the pool games the pool bots play (``games``: the registry's games with pockets and no bots of their own;
9-ball, 8-ball and 10-ball today), each with its own network. Their networks ship beside the ladder as
``bots/learned/ladder/<game>/<name>.npz`` and ``.json`` (``proposal_net.save``; the card also holds the break strike
the search found for the game). ``agents.exit`` trains them (``scripts/expert_iteration.py``); until a game has a
card, asking for the name fails with the command that trains it. ``ProposalPlayer`` also plays a run's snapshots
(``nets=``) or, with no network yet, the hand prior (``nets={game: (None, {})}``: Expert Iteration's first expert).
"""
from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import numpy as np

from ...contract.plan import ShotPlan
from ...rules import GAMES as REGISTRY
from ..game_lookahead import Budget, GameLookahead
from ..planner import leave as LEAVE
from ..planner import proposals as PR
from ..planner import shot_space as SS
from ..planner.bot import CHUNK, HELPER, Champion, PlanRows
from ..planner.breaks import NOMINAL, BreakSearch
from ..serial import serial_act
from . import proposal_net as PN

CARD_DIR = Path(__file__).with_name("ladder")
FAST, SEARCH = "exit-fast", "exit-search"
NAMES = (FAST, SEARCH)
TRAIN = ("python scripts/expert_iteration.py --config configs/exit_{game}.yaml --run runs/exit_{game} --address local"
         "; then python scripts/expert_iteration.py --run runs/exit_{game} --ship")
PASS_BELOW = 0.5          # the fast player hands the shot back where its value of shooting is below this
CARD = "card"             # a budget read from each game's card (``SearchBudget()`` where the card has none)


def games() -> tuple:
    """The registered games a proposal network can learn: those with pockets and no bots of their own (the games
    ``champion`` and ``lookahead`` play), read from the registry (``rules.games``) when called."""
    return tuple(name for name, spec in REGISTRY.items() if spec.words.pockets and not spec.own_bots)


def card_stem(name: str, game: str, root=CARD_DIR) -> Path:
    """Where the network ``name`` of ``game`` is shipped: ``<stem>.npz`` and its card ``<stem>.json``."""
    return Path(root) / game / name


def missing(name: str, game: str, root=CARD_DIR) -> str:
    """The message of a name without a trained network for ``game``."""
    return (f"{name}: no trained network for {game} (no {card_stem(name, game, root)}.npz / .json). Train and ship "
            f"it with: {TRAIN.format(game=game)}")


def shipped_games(name: str, root=CARD_DIR) -> list[str]:
    """The games with a shipped network ``name`` (``exit-search``, ``exit-fast``): the games it plays."""
    return [g for g in games() if card_stem(name, g, root).with_suffix(".json").exists()]


@lru_cache(maxsize=None)
def shipped(name: str, game: str, root: str = str(CARD_DIR)) -> tuple:
    """(network, card) of ``name`` for ``game`` from the package (read once per process)."""
    stem = card_stem(name, game, root)
    if not stem.with_suffix(".json").exists():
        raise ValueError(missing(name, game, root))
    return PN.load(stem)


class ProposalPlayer:
    """A player of the proposal network (module docstring): ``budget`` None plays the network alone
    (``exit-fast``), a ``SearchBudget`` searches over its proposals (``CARD``: the one in the game's card).
    ``nets``: game -> (network or None,
    card) (default: the shipped cards of ``name``); ``searched_break``: without a break strike in the card, search
    one (champion's ``BreakSearch``), else ghost's standard break; ``record``: keep every decision in ``trace``
    (``agents.exit`` learns from it)."""

    plan = Champion.plan

    def __init__(self, name: str = SEARCH, seed: int = 0, nets: dict | None = None, root=CARD_DIR,
                 budget: PR.SearchBudget | str | None = PR.SearchBudget(), searched_break: bool = True,
                 record: bool = False):
        self.name, self.root, self.budget = name, Path(root), budget
        self.rng = np.random.default_rng(seed)
        self.la = GameLookahead(seed=int(self.rng.integers(2 ** 31)), budget=Budget(**HELPER))
        self.nets = dict(nets or {})
        self.breaks = BreakSearch() if searched_break else None
        self.trace = [] if record else None
        self.sims = 0
        self.last_value = self.last_kind = None

    def network(self, game: str) -> tuple:
        if game not in self.nets and game not in games():
            raise ValueError(f"{self.name} plays {', '.join(games())}, not {game}")
        if game not in self.nets:
            self.nets[game] = shipped(self.name, game, str(self.root))
        return self.nets[game]

    def budget_of(self, doc: dict):
        """The search's budget on a game whose card is ``doc`` (None: no search)."""
        if self.budget != CARD:
            return self.budget
        b = doc.get("budget") or {}
        return PR.SearchBudget(**{k: tuple(v) if isinstance(v, list) else v for k, v in b.items()})

    def values(self, view, pv) -> np.ndarray:
        """A previewed shot's value to its mover (the planner's leave): what the break search judges by."""
        return LEAVE.values(view, pv)

    # --- acting -------------------------------------------------------------------------------------------------
    @serial_act
    def act(self, view) -> ShotPlan:
        if not view.table.has_pockets:
            raise ValueError(f"{self.name} pots balls: it cannot play {view.game} on a table without pockets")
        net, doc = self.network(view.game)
        p = PlanRows(view.n)
        brk = np.flatnonzero(view.is_break)
        if len(brk):
            p.breaks(brk, self.la.break_plan(view, brk, np.broadcast_to(self.break_strike(view, brk, doc),
                                                                        (len(brk), 4))))
        play = np.flatnonzero(~view.is_break)
        budget = self.budget_of(doc)
        for lo in range(0, len(play), CHUNK):
            rows = play[lo:lo + CHUNK]
            p.choose(rows, *self.decide(view, rows, net, budget))
        if len(play) and budget is not None:   # push-outs and passes as lookahead declares them
            p.declarations(self.la, view, play)
        elif len(play):
            pas = play[view.may_pass[play] & (p.value[play] < PASS_BELOW)]
            p.declare[pas], p.kind[pas] = True, "pass"
        self.last_value, self.last_kind = p.value, p.kind
        return p.plan(view)

    def break_strike(self, view, rows, doc) -> np.ndarray:
        """The card's break strike for the game, else a searched one (``searched_break``), else ghost's."""
        if doc.get("break") is not None:
            return np.asarray(doc["break"], np.float64)
        return self.breaks.strike(self, view, rows) if self.breaks is not None else np.asarray(NOMINAL)

    def decide(self, view, rows, net, budget):
        """(candidates, the chosen candidate of each row, its value) on view rows ``rows``."""
        layout = SS.Layout(view, rows, self.la)
        g, x = PN.root_globals(view, rows), PN.slot_features(layout)
        if net is None:
            logp, v = PR.log_softmax(PR.hand_logits(layout)), None
        else:
            out, v = net.forward(g, x)
            if budget is None:       # the network alone: its most probable proposal, refined
                c = SS.refine(view, SS.decode(layout, np.arange(len(rows)), PN.best_proposal(out, layout.mask)))
                return c, np.arange(len(rows)), v
            logp = PN.joint_logp(out, layout.mask)
        if budget is None:
            raise ValueError(f"{self.name}: the network alone needs a network")
        leaf = None if net is None else (lambda vw, pv: _leaf_value(net, vw, pv))
        res = PR.ProposalSearch(budget, self, leaf).run(layout, logp, v)
        if self.trace is not None:
            self.trace.append(dict(tables=np.asarray(view.rows)[rows], movers=np.asarray(view.to_move)[rows], g=g,
                                   x=x, mask=layout.mask, li=res.li, joint=res.c["joint"], y=res.y,
                                   y_rest=res.y_rest, chosen=res.c["joint"][res.best], value=res.value,
                                   count=res.count))
        return res.c, res.best, res.value


def _leaf_value(net, view, pv) -> np.ndarray:
    """[k] the value head's value of previewed shots' leaves to the shots' mover."""
    v = net.value(PN.leaf_globals(view, pv))
    return np.where(pv.next.shooter == pv.record.shooter, v, 1.0 - v)


def _shipped_player(name: str, seed: int, **kw) -> ProposalPlayer:
    """``name`` with the shipped cards; a ValueError naming the training command if no game has one."""
    if not shipped_games(name):
        raise ValueError(f"{name}: no trained network is shipped for any game. Train and ship one per game with: "
                         + TRAIN.format(game="<game>") + f" (<game>: {', '.join(games())})")
    return ProposalPlayer(name, seed, **kw)


def exit_fast(seed: int = 0) -> ProposalPlayer:
    """``exit-fast`` (``bots.make_bot("billiards_env.bots.learned.proposal_bot:exit_fast")``): the shipped distilled
    network, no search."""
    return _shipped_player(FAST, seed, budget=None)


def exit_search(seed: int = 0) -> ProposalPlayer:
    """``exit-search``: the search over the shipped Expert Iteration network's proposals."""
    return _shipped_player(SEARCH, seed, budget=CARD)
