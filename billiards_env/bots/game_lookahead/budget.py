"""What the lookahead searches (``Budget``), the opponent's smaller search
from a leave (``REPLY_BUDGET``) and named budgets (``BUDGETS``)."""
from __future__ import annotations

import dataclasses

from .candidates import HEIGHTS, SPEEDS, THROW
from .pots import SIGMA_MODEL, V_FULL, V_NONE

CHUNK = 128                        # tables decided per batch of previews (memory stays bounded)

# the opponent's reply searched from a leave (Budget.reply_eval > 0): the same machinery at about a sixth of the
# previews per table (3 pots in 9 variants, 12 safeties and kicks, 8 re-judged 8 times under noise), since it runs
# on every leave of the reply_eval x reply_samples outcomes of a table; 4 samples of 6 measured weaker (docs/games.md)
REPLY_BUDGET = dict(n_pots=3, hand_pots=2, n_safe=6, n_kick=2, n_bank=4, n_push=0, n_eval=8, n_eval_safe=2,
                    n_samples=8, throws=(0.0,), speeds=(1.15, 1.8, 2.8), break_search=0, reply_eval=0)


@dataclasses.dataclass(frozen=True)
class Budget:
    """What ``GameLookahead`` searches: candidate counts (pots tried per
    table, and with ball in hand; safeties, kicks, one-rail kicks, push-outs),
    how many candidates are re-judged under noise (pots, safeties) and with
    how many noise samples, the pots' variants (overcuts against throw, speed
    factors, tip heights), and the leave model (``sigma_model``; ``v_none``,
    ``v_full``: see ``position_value``). Off by default, tried
    and measured without a gain: ``reply_keep`` (the mover's own next shot
    searched on the kept tables; docs/league.md). On by default: ``reply_eval`` (two plies: the
    opponent's reply searched from the best candidates' leaves, ``replies``;
    ``reply_eval=0`` is the one-shot leave alone, ``one-ply`` in ``BUDGETS``)."""

    n_pots: int = 6
    hand_pots: int = 3
    n_safe: int = 16
    n_kick: int = 8
    n_bank: int = 16
    n_push: int = 24
    n_eval: int = 32
    n_eval_safe: int = 8
    n_samples: int = 12
    throws: tuple = THROW
    speeds: tuple = SPEEDS
    heights: tuple = HEIGHTS
    sigma_model: float = SIGMA_MODEL
    v_none: float = V_NONE
    v_full: float = V_FULL
    break_search: int = 128    # candidate breaks searched once per game and table (0: ghost's standard break)
    break_racks: int = 16      # the racks (the first breaking rows) each candidate break is judged on
    break_samples: int = 2     # noise samples per candidate and rack
    reply_eval: int = 6        # candidates per table whose turn-passing leaves get the opponent's reply searched
    reply_safe: int = 4        # of them kept for safeties and kicks
    reply_samples: int = 8     # the noisy outcomes (at most n_samples) per candidate whose leaves are searched
    reply: tuple = ()          # (field, value) changes to REPLY_BUDGET, the opponent's search
    reply_keep: bool = False   # also search the mover's own next shot on those outcomes where the mover keeps the table


# smaller search budgets, for measuring strength against compute (``module:factory`` entrants of scripts/match.py)
BUDGETS = dict(fast=dict(n_pots=3, n_eval=8, n_eval_safe=4, n_samples=4, reply_eval=0),
               medium=dict(n_pots=4, n_eval=16, n_eval_safe=4, n_samples=8, reply_eval=0),
               wide=dict(n_eval=64, n_samples=16),
               deep=dict(reply_keep=True),  # the mover's own next shot searched too, where the mover keeps the table
               **{"one-ply": dict(reply_eval=0)})  # without the 2-ply judgement (the default before it)
